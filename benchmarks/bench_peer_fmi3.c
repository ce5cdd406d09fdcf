/* FMI 3.0 half of bench_peer.c (bench_peer.h). */
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "bench_peer.h"
#include "fmi3Functions.h"
#include "host_support.h"

/* The calls a run makes (bench_peer_run.h), each without its prefix fmi3 */
/* clang-format off */
#define BENCH_CALLS(F) F(InstantiateCoSimulation) F(FreeInstance) F(EnterInitializationMode) \
    F(ExitInitializationMode) F(SetFloat64) F(GetFloat64) F(SetInt64) F(GetInt32) F(DoStep)
/* clang-format on */
#define BENCH_FMI 3
typedef fmi3Instance fmu_t;
#include "bench_peer_run.h"

static inline void stop(const bench_fmu *f, fmu_t c) { CALL(FreeInstance)(c); }

static inline fmu_t start(const bench_fmu *f, const char *token, const bench_params *bp) {
    fmu_t c = CALL(InstantiateCoSimulation)("bench", token, "", fmi3False, fmi3False, fmi3False,
                                            fmi3False, NULL, 0, NULL, host_print3, NULL);
    const fmi3Int64 rule = bp->rule;
    if (c && (CALL(SetFloat64)(c, BENCH_VR_PARAMS, 6, bp->p, 6) != fmi3OK ||
              CALL(SetInt64)(c, &BENCH_VR_RULE, 1, &rule, 1) != fmi3OK ||
              CALL(EnterInitializationMode)(c, fmi3False, 0, 0, fmi3False, 0) != fmi3OK ||
              CALL(ExitInitializationMode)(c) != fmi3OK)) {
        stop(f, c);
        return NULL;
    }
    return c;
}

static inline int step(const bench_fmu *f, fmu_t c, double t, double h, const double u[3],
                       double T[2]) {
    fmi3Boolean ev, term, early;
    double last;
    int st = CALL(SetFloat64)(c, BENCH_VR_IN, 3, u, 3);
    st |= CALL(DoStep)(c, t, h, fmi3True, &ev, &term, &early, &last);
    return st | CALL(GetFloat64)(c, BENCH_VR_T, 2, T, 2);
}

static inline int state(const bench_fmu *f, fmu_t c) {
    fmi3Int32 s;
    return CALL(GetInt32)(c, &BENCH_VR_STATE, 1, &s, 1) == fmi3OK ? s : -1;
}

static inline int more(const bench_fmu *f, fmu_t c, double *row) {
    const int s = state(f, c);
    row[5] = s;
    return CALL(GetFloat64)(c, BENCH_VR_MORE, 3, row + 2, 3) | (s < 0);
}
