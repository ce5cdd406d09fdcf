/* What bench_fmi2.c and bench_fmi3.c share: the end of a run and the main,
 * ns per step of each sliding rule (the contact's table's enumeration),
 * stick and slip runs interleaved, the least disturbed of 7, with `run` the
 * version's run of `steps` steps and `calls` the calls it makes. */
#ifndef BENCH_RULES_H
#define BENCH_RULES_H
#include <stdio.h>
#include <stdlib.h>

#include "models/OrthotropicContact/table.h"

#define RULE_NAME(name, value, description) [value] = #name,
#define RULE_COUNT(name, value, description) +1
static const char *const RULE_NAMES[] = {OC_SLIDING_RULE_ITEMS(RULE_NAME)};
enum { N_RULES = 0 OC_SLIDING_RULE_ITEMS(RULE_COUNT) };

/* ns per step of a run that took dt [s] for `steps` steps of path `slip`
 * (bench_common.h), ending in contact state `state`: a state that is not
 * the path's (1 stick, 2 slip) is said on stderr.  sink: the outputs'
 * sum, which the compiler must not drop. */
static double bench_ns(double dt, long steps, int state, int slip, double sink) {
    if (state != (slip ? 2 : 1)) fprintf(stderr, "unexpected contact state %d\n", state);
    if (sink == 12345.6789) printf(" ");
    return 1e9 * dt / steps;
}

static int bench_rules(int argc, char **argv, const char *calls,
                       double (*run)(int rule, int slip, long steps)) {
    const long steps = argc > 1 ? atol(argv[1]) : 500000;
    printf("# %s, %ld steps\n", calls, steps);
    printf("%-11s %10s %10s %8s\n", "rule", "stick_ns", "slip_ns", "ratio");
    for (int rule = 1; rule <= N_RULES; ++rule) {
        double stick = 1e30, slipv = 1e30;
        for (int rep = 0; rep < 7; ++rep) {
            const double a = run(rule, 0, steps), b = run(rule, 1, steps);
            if (a < stick) stick = a;
            if (b < slipv) slipv = b;
        }
        printf("%-11s %10.1f %10.1f %8.2f\n", RULE_NAMES[rule], stick, slipv, slipv / stick);
    }
    return 0;
}
#endif
