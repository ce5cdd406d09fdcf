/* Benchmark (not a test): ns per step through the FMI 3.0 calls a master
 * makes, fmi3SetFloat64(u1, u2, N), fmi3DoStep, fmi3GetFloat64(T1, T2), for
 * stick and slip steps of each sliding rule.  Prints one line per case. */
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "bench_rules.h"
#include "fmi3Functions.h"
#include "host_support.h"
#include "models/OrthotropicContact/table.h"

/* the heading's words */
#define CALLS "FMI 3.0, ns per step: fmi3SetFloat64(u1,u2,N) + fmi3DoStep + fmi3GetFloat64(T1,T2)"

static double run(int rule, int slip, long steps) {
    fmi3Instance c = fmi3InstantiateCoSimulation("bench", FMU_GUID, "", 0, 0, 0, 0, NULL, 0, NULL,
                                                 host_print3, NULL);
    const fmi3ValueReference vr_rule = OC_VR_slidingRule;
    const fmi3Int64 r = rule;
    fmi3SetInt64(c, &vr_rule, 1, &r, 1);
    fmi3EnterInitializationMode(c, 0, 0, 0, 0, 0);
    fmi3ExitInitializationMode(c);
    const fmi3ValueReference in[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N}, out[2] = {OC_VR_T1, OC_VR_T2};
    const fmi3ValueReference vr_state = OC_VR_contactState;
    double t = 0, h = 1e-4, sink = 0, last;
    fmi3Boolean ev, term, early;
    const double t0 = now();
    for (long k = 0; k < steps; ++k) {
        double u[3];
        bench_inputs(k, slip, u);
        fmi3SetFloat64(c, in, 3, u, 3);
        fmi3DoStep(c, t, h, fmi3True, &ev, &term, &early, &last);
        t += h;
        double T[2];
        fmi3GetFloat64(c, out, 2, T, 2);
        sink += T[0];
    }
    const double dt = now() - t0;
    fmi3Int32 state;
    fmi3GetInt32(c, &vr_state, 1, &state, 1);
    fmi3FreeInstance(c);
    return bench_ns(dt, steps, state, slip, sink);
}

int main(int argc, char **argv) { return bench_rules(argc, argv, CALLS, run); }
