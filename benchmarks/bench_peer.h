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

/* What a traced step records: T1, T2, s1, s2, dissipatedEnergy, contactState. */
enum { TRACE_COLUMNS = 6 };

typedef struct {
    void *lib;
    void *fn[16];
} bench_fmu;

/* 0, or -1 with a message on stderr. */
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
