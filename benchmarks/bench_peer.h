/* bench_peer.c's two halves: one FMU binary of either FMI version, loaded
 * with dlopen as an importer loads it, driven through the calls a master
 * makes every step (bench_peer_fmi2.c, bench_peer_fmi3.c). */
#ifndef BENCH_PEER_H
#define BENCH_PEER_H

/* mu1, mu2, eps1, eps2, alpha, beta */
typedef struct {
    double p[6];
    int rule;
} bench_params;

/* The contact's value references the runs use (its table's; the peer has
 * the same): the law's parameters, the sliding rule, the inputs u1, u2, N,
 * the outputs T1, T2, then s1, s2, dissipatedEnergy, and contactState. */
static const unsigned int BENCH_VR_PARAMS[6] = {1, 2, 3, 4, 5, 6}, BENCH_VR_RULE = 7,
                          BENCH_VR_IN[3] = {8, 9, 10}, BENCH_VR_T[2] = {11, 12},
                          BENCH_VR_MORE[3] = {13, 14, 16}, BENCH_VR_STATE = 15;

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
