/* Benchmark (not a test): ns per step through the FMI 3.0 calls a master
 * makes, fmi3SetFloat64(u1, u2, N), fmi3DoStep, fmi3GetFloat64(T1, T2), for
 * stick and slip steps of each sliding rule.  Prints one line per case. */
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "fmi3Functions.h"
#include "host_support.h"
#include "models/OrthotropicContact/table.h"

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
    if (state != (slip ? 2 : 1)) fprintf(stderr, "unexpected contact state %d\n", state);
    fmi3FreeInstance(c);
    if (sink == 12345.6789) printf(" ");
    return 1e9 * dt / steps;
}

/* The sliding rules by their numbers, from the table's enumeration. */
#define RULE_NAME(name, value, description) [value] = #name,
#define RULE_COUNT(name, value, description) +1
static const char *const RULE_NAMES[] = {OC_SLIDING_RULE_ITEMS(RULE_NAME)};
enum { N_RULES = 0 OC_SLIDING_RULE_ITEMS(RULE_COUNT) };

int main(int argc, char **argv) {
    const long steps = argc > 1 ? atol(argv[1]) : 500000;
    printf("# FMI 3.0, ns per step: fmi3SetFloat64(u1,u2,N) + fmi3DoStep + fmi3GetFloat64(T1,T2), "
           "%ld steps\n",
           steps);
    printf("%-11s %10s %10s %8s\n", "rule", "stick_ns", "slip_ns", "ratio");
    for (int rule = 1; rule <= N_RULES; ++rule) {
        double stick = 1e30, slipv = 1e30;
        for (int rep = 0; rep < 7;
             ++rep) { /* stick and slip interleaved; the least disturbed of 7 */
            const double a = run(rule, 0, steps), b = run(rule, 1, steps);
            if (a < stick) stick = a;
            if (b < slipv) slipv = b;
        }
        printf("%-11s %10.1f %10.1f %8.2f\n", RULE_NAMES[rule], stick, slipv, slipv / stick);
    }
    return 0;
}
