/* FMI 3.0 half of bench_peer.c (bench_peer.h). */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "bench_peer.h"
#include "fmi3Functions.h"
#include "host_support.h"

enum { INST, FREE, ENTER, EXIT, SETF, GETF, SETI64, GETI32, STEP, NFN };
static const char *const NAMES[NFN] = {"fmi3InstantiateCoSimulation",
                                       "fmi3FreeInstance",
                                       "fmi3EnterInitializationMode",
                                       "fmi3ExitInitializationMode",
                                       "fmi3SetFloat64",
                                       "fmi3GetFloat64",
                                       "fmi3SetInt64",
                                       "fmi3GetInt32",
                                       "fmi3DoStep"};

int bench3_open(bench_fmu *f, const char *path) {
    if (!(f->lib = dlopen(path, RTLD_NOW | RTLD_LOCAL))) {
        fprintf(stderr, "cannot load %s: %s\n", path, dlerror());
        return -1;
    }
    for (int i = 0; i < NFN; ++i)
        if (!(f->fn[i] = dlsym(f->lib, NAMES[i]))) {
            fprintf(stderr, "%s does not export %s\n", path, NAMES[i]);
            return -1;
        }
    return 0;
}

double bench3_run(const bench_fmu *f, const char *token, const bench_params *bp, int slip,
                  long steps, double *trace) {
    fmi3SetFloat64TYPE *set_f = (fmi3SetFloat64TYPE *)f->fn[SETF];
    fmi3GetFloat64TYPE *get_f = (fmi3GetFloat64TYPE *)f->fn[GETF];
    fmi3DoStepTYPE *do_step = (fmi3DoStepTYPE *)f->fn[STEP];
    fmi3Instance c = ((fmi3InstantiateCoSimulationTYPE *)f->fn[INST])(
        "bench", token, "", fmi3False, fmi3False, fmi3False, fmi3False, NULL, 0, NULL, host_print3,
        NULL);
    if (!c) return -1;
    const fmi3ValueReference vr_par[6] = {1, 2, 3, 4, 5, 6}, vr_rule = 7;
    const fmi3ValueReference in[3] = {8, 9, 10}, out[2] = {11, 12}, more[3] = {13, 14, 16};
    const fmi3ValueReference vr_state = 15;
    const fmi3Int64 rule = bp->rule;
    double result = 0;
    if (set_f(c, vr_par, 6, bp->p, 6) != fmi3OK ||
        ((fmi3SetInt64TYPE *)f->fn[SETI64])(c, &vr_rule, 1, &rule, 1) != fmi3OK ||
        ((fmi3EnterInitializationModeTYPE *)f->fn[ENTER])(c, fmi3False, 0, 0, fmi3False, 0) !=
            fmi3OK ||
        ((fmi3ExitInitializationModeTYPE *)f->fn[EXIT])(c) != fmi3OK) {
        result = -1;
        goto done;
    }
    double t = 0, h = 1e-4, sink = 0, last;
    fmi3Boolean ev, term, early;
    int bad = 0;
    if (trace) {
        for (long k = 0; k < steps; ++k) {
            double u[3], *row = trace + k * TRACE_COLUMNS;
            fmi3Int32 state;
            bench_inputs(k, slip, u);
            bad |= set_f(c, in, 3, u, 3) | do_step(c, t, h, fmi3True, &ev, &term, &early, &last) |
                   get_f(c, out, 2, row, 2) | get_f(c, more, 3, row + 2, 3) |
                   ((fmi3GetInt32TYPE *)f->fn[GETI32])(c, &vr_state, 1, &state, 1);
            row[5] = state;
            t += h;
        }
    } else {
        const double t0 = now();
        for (long k = 0; k < steps; ++k) {
            double u[3], T[2];
            bench_inputs(k, slip, u);
            bad |= set_f(c, in, 3, u, 3) | do_step(c, t, h, fmi3True, &ev, &term, &early, &last) |
                   get_f(c, out, 2, T, 2);
            t += h;
            sink += T[0];
        }
        result = 1e9 * (now() - t0) / steps;
        fmi3Int32 state;
        ((fmi3GetInt32TYPE *)f->fn[GETI32])(c, &vr_state, 1, &state, 1);
        if (state != (slip ? 2 : 1)) bad = 1;
    }
    if (bad || sink == 12345.6789) result = -1;
done:
    ((fmi3FreeInstanceTYPE *)f->fn[FREE])(c);
    return result;
}
