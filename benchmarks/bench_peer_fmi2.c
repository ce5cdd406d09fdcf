/* FMI 2.0 half of bench_peer.c (bench_peer.h). */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "bench_peer.h"
#include "fmi2Functions.h"
#include "host_support.h"

enum { INST, FREE, SETUP, ENTER, EXIT, SETR, GETR, SETI, GETI, STEP, NFN };
static const char *const NAMES[NFN] = {"fmi2Instantiate",
                                       "fmi2FreeInstance",
                                       "fmi2SetupExperiment",
                                       "fmi2EnterInitializationMode",
                                       "fmi2ExitInitializationMode",
                                       "fmi2SetReal",
                                       "fmi2GetReal",
                                       "fmi2SetInteger",
                                       "fmi2GetInteger",
                                       "fmi2DoStep"};

int bench2_open(bench_fmu *f, const char *path) {
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

double bench2_run(const bench_fmu *f, const char *token, const bench_params *bp, int slip,
                  long steps, double *trace) {
    fmi2SetRealTYPE *set_real = (fmi2SetRealTYPE *)f->fn[SETR];
    fmi2GetRealTYPE *get_real = (fmi2GetRealTYPE *)f->fn[GETR];
    fmi2DoStepTYPE *do_step = (fmi2DoStepTYPE *)f->fn[STEP];
    fmi2Component c = ((fmi2InstantiateTYPE *)f->fn[INST])("bench", fmi2CoSimulation, token, "",
                                                           &host_print2_cb, fmi2False, fmi2False);
    if (!c) return -1;
    const fmi2ValueReference vr_par[6] = {1, 2, 3, 4, 5, 6}, vr_rule = 7;
    const fmi2ValueReference in[3] = {8, 9, 10}, out[2] = {11, 12}, more[3] = {13, 14, 16};
    const fmi2ValueReference vr_state = 15;
    const fmi2Integer rule = bp->rule;
    double result = 0;
    if (set_real(c, vr_par, 6, bp->p) != fmi2OK ||
        ((fmi2SetIntegerTYPE *)f->fn[SETI])(c, &vr_rule, 1, &rule) != fmi2OK ||
        ((fmi2SetupExperimentTYPE *)f->fn[SETUP])(c, fmi2False, 0, 0, fmi2False, 0) != fmi2OK ||
        ((fmi2EnterInitializationModeTYPE *)f->fn[ENTER])(c) != fmi2OK ||
        ((fmi2ExitInitializationModeTYPE *)f->fn[EXIT])(c) != fmi2OK) {
        result = -1;
        goto done;
    }
    double t = 0, h = 1e-4, sink = 0;
    int bad = 0;
    if (trace) {
        for (long k = 0; k < steps; ++k) {
            double u[3], *row = trace + k * TRACE_COLUMNS;
            fmi2Integer state;
            bench_inputs(k, slip, u);
            bad |= set_real(c, in, 3, u) | do_step(c, t, h, fmi2True) | get_real(c, out, 2, row) |
                   get_real(c, more, 3, row + 2) |
                   ((fmi2GetIntegerTYPE *)f->fn[GETI])(c, &vr_state, 1, &state);
            row[5] = state;
            t += h;
        }
    } else {
        const double t0 = now();
        for (long k = 0; k < steps; ++k) {
            double u[3], T[2];
            bench_inputs(k, slip, u);
            bad |= set_real(c, in, 3, u) | do_step(c, t, h, fmi2True) | get_real(c, out, 2, T);
            t += h;
            sink += T[0];
        }
        result = 1e9 * (now() - t0) / steps;
        fmi2Integer state;
        ((fmi2GetIntegerTYPE *)f->fn[GETI])(c, &vr_state, 1, &state);
        if (state != (slip ? 2 : 1)) bad = 1;
    }
    if (bad || sink == 12345.6789) result = -1;
done:
    ((fmi2FreeInstanceTYPE *)f->fn[FREE])(c);
    return result;
}
