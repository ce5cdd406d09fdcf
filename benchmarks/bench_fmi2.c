/* Benchmark (not a test): ns per step through the FMI calls a master makes,
 * fmi2SetReal(u1, u2, N), fmi2DoStep, fmi2GetReal(T1, T2), for stick and slip
 * steps of each sliding rule.  Prints one line per case. */
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "bench_rules.h"
#include "fmi2Functions.h"
#include "host_support.h"
#include "models/OrthotropicContact/table.h"

/* the heading's words */
#define CALLS "FMI 2.0, ns per step: fmi2SetReal(u1,u2,N) + fmi2DoStep + fmi2GetReal(T1,T2)"

static double run(int rule, int slip, long steps) {
    fmi2Component c =
        fmi2Instantiate("bench", fmi2CoSimulation, FMU_GUID, "", &host_print2_cb, 0, 0);
    const fmi2ValueReference vr_rule = OC_VR_slidingRule;
    const int r = rule;
    fmi2SetInteger(c, &vr_rule, 1, &r);
    fmi2SetupExperiment(c, 0, 0, 0, 0, 0);
    fmi2EnterInitializationMode(c);
    fmi2ExitInitializationMode(c);
    const fmi2ValueReference in[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N}, out[2] = {OC_VR_T1, OC_VR_T2};
    const fmi2ValueReference vr_state = OC_VR_contactState;
    double t = 0, h = 1e-4, sink = 0;
    const double t0 = now();
    for (long k = 0; k < steps; ++k) {
        double u[3];
        bench_inputs(k, slip, u);
        fmi2SetReal(c, in, 3, u);
        fmi2DoStep(c, t, h, fmi2True);
        t += h;
        double T[2];
        fmi2GetReal(c, out, 2, T);
        sink += T[0];
    }
    const double dt = now() - t0;
    int state;
    fmi2GetInteger(c, &vr_state, 1, &state);
    fmi2FreeInstance(c);
    return bench_ns(dt, steps, state, slip, sink);
}

int main(int argc, char **argv) { return bench_rules(argc, argv, CALLS, run); }
