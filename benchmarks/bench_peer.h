/* bench_peer.c's two halves: one FMU binary of either FMI version, loaded
 * with dlopen as an importer loads it, driven through the calls a master
 * makes every step (bench_peer_fmi2.c, bench_peer_fmi3.c). */
#ifndef BENCH_PEER_H
#define BENCH_PEER_H

#include "models/OrthotropicContact/table.h"

/* mu1, mu2, eps1, eps2, alpha, beta */
typedef struct {
    double p[6];
    int rule;
} bench_params;

/* The contact's value references the runs use (its table's; the peer has
 * the same): the law's parameters, the sliding rule, the inputs u1, u2, N,
 * the outputs T1, T2, then s1, s2, dissipatedEnergy, and contactState. */
#define BENCH_VR_OF(name, vr, ...) vr,
static const unsigned int BENCH_VR_PARAMS[6] = {OC_LAW_PARAMETERS(BENCH_VR_OF)},
                          BENCH_VR_RULE = OC_VR_slidingRule,
                          BENCH_VR_IN[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N},
                          BENCH_VR_T[2] = {OC_VR_T1, OC_VR_T2},
                          BENCH_VR_MORE[3] = {OC_VR_s1, OC_VR_s2, OC_VR_dissipatedEnergy},
                          BENCH_VR_STATE = OC_VR_contactState;
#undef BENCH_VR_OF

/* What a traced step records: T1, T2, s1, s2, dissipatedEnergy, contactState. */
enum { TRACE_COLUMNS = 6 };

typedef struct {
    void *lib;
    void *fn[16];
} bench_fmu;

/* 0, or -1 with a message on stderr: the library at path loaded, its
 * functions names[0..n) into f->fn (bench_peer.c); each half's with the
 * names of its version's calls. */
int bench_open(bench_fmu *f, const char *path, const char *const names[], int n);
int bench2_open(bench_fmu *f, const char *path);
int bench3_open(bench_fmu *f, const char *path);
/* ns per step of `steps` steps on path `slip` (bench_common.h); with
 * trace != NULL, no timing: the outputs of every step into trace
 * (steps x TRACE_COLUMNS).  A negative value: a call failed. */
double bench2_run(const bench_fmu *f, const char *token, const bench_params *bp, int slip,
                  long steps, double *trace);
double bench3_run(const bench_fmu *f, const char *token, const bench_params *bp, int slip,
                  long steps, double *trace);

#endif
