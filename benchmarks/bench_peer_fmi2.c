/* FMI 2.0 half of bench_peer.c (bench_peer.h). */
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "bench_peer.h"
#include "fmi2Functions.h"
#include "host_support.h"

/* The calls a run makes (bench_peer_run.h), each without its prefix fmi2 */
/* clang-format off */
#define BENCH_CALLS(F) F(Instantiate) F(FreeInstance) F(SetupExperiment) F(EnterInitializationMode) \
    F(ExitInitializationMode) F(SetReal) F(GetReal) F(SetInteger) F(GetInteger) F(DoStep)
/* clang-format on */
#define BENCH_FMI 2
typedef fmi2Component fmu_t;
#include "bench_peer_run.h"

static inline void stop(const bench_fmu *f, fmu_t c) { CALL(FreeInstance)(c); }

static inline fmu_t start(const bench_fmu *f, const char *token, const bench_params *bp) {
    fmu_t c = CALL(Instantiate)("bench", fmi2CoSimulation, token, "", &host_print2_cb, fmi2False,
                                fmi2False);
    const fmi2Integer rule = bp->rule;
    if (c &&
        (CALL(SetReal)(c, BENCH_VR_PARAMS, 6, bp->p) != fmi2OK ||
         CALL(SetInteger)(c, &BENCH_VR_RULE, 1, &rule) != fmi2OK ||
         CALL(SetupExperiment)(c, fmi2False, 0, 0, fmi2False, 0) != fmi2OK ||
         CALL(EnterInitializationMode)(c) != fmi2OK || CALL(ExitInitializationMode)(c) != fmi2OK)) {
        stop(f, c);
        return NULL;
    }
    return c;
}

static inline int step(const bench_fmu *f, fmu_t c, double t, double h, const double u[3],
                       double T[2]) {
    int st = CALL(SetReal)(c, BENCH_VR_IN, 3, u);
    st |= CALL(DoStep)(c, t, h, fmi2True);
    return st | CALL(GetReal)(c, BENCH_VR_T, 2, T);
}

static inline int state(const bench_fmu *f, fmu_t c) {
    fmi2Integer s;
    return CALL(GetInteger)(c, &BENCH_VR_STATE, 1, &s) == fmi2OK ? s : -1;
}

static inline int more(const bench_fmu *f, fmu_t c, double *row) {
    const int s = state(f, c);
    row[5] = s;
    return CALL(GetReal)(c, BENCH_VR_MORE, 3, row + 2) | (s < 0);
}
