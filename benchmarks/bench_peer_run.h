/* What bench_peer_fmi2.c and bench_peer_fmi3.c share, written once: a
 * template each includes (no include guard) after defining
 *   BENCH_FMI       its FMI version, 2 or 3;
 *   BENCH_CALLS(F)  the calls a run makes, F(name) each, named without
 *                   the version's prefix fmi<v>;
 *   fmu_t           the version's instance type.
 * It defines CALL(name), the call as its type from bench_fmu.fn, and
 * bench<v>_open and bench<v>_run (bench_peer.h); the run is made of these,
 * which the includer defines after it on its version's calls:
 *   start(f, token, bp)   an instance with bp's parameters and rule,
 *                         initialized; NULL if a call failed (freed);
 *   step(f, c, t, h, u, T)  u1, u2, N set from u, doStep(t, h), T1, T2
 *                         into T; the calls' statuses or'ed (0: all OK);
 *   more(f, c, row)       s1, s2, dissipatedEnergy and contactState into
 *                         row[2..5]; likewise;
 *   state(f, c)           contactState, -1 if the call failed;
 *   stop(f, c)            the instance freed. */
#define BENCH_CAT_(a, b, c) a##b##c
#define BENCH_CAT(a, b, c) BENCH_CAT_(a, b, c)
#define BENCH_STR_(x) #x
#define BENCH_STR(x) BENCH_STR_(x)
#define BENCH_INDEX(name) I_##name,
#define BENCH_NAME(name) "fmi" BENCH_STR(BENCH_FMI) #name,
#define CALL(name) ((BENCH_CAT(fmi, BENCH_FMI, name##TYPE) *)f->fn[I_##name])

enum { BENCH_CALLS(BENCH_INDEX) N_CALLS };
static const char *const NAMES[N_CALLS] = {BENCH_CALLS(BENCH_NAME)};

int BENCH_CAT(bench, BENCH_FMI, _open)(bench_fmu *f, const char *path) {
    return bench_open(f, path, NAMES, N_CALLS);
}

static inline fmu_t start(const bench_fmu *f, const char *token, const bench_params *bp);
static inline int step(const bench_fmu *f, fmu_t c, double t, double h, const double u[3],
                       double T[2]);
static inline int more(const bench_fmu *f, fmu_t c, double *row);
static inline int state(const bench_fmu *f, fmu_t c);
static inline void stop(const bench_fmu *f, fmu_t c);

double BENCH_CAT(bench, BENCH_FMI, _run)(const bench_fmu *f, const char *token,
                                         const bench_params *bp, int slip, long steps,
                                         double *trace) {
    fmu_t c = start(f, token, bp);
    if (!c) return -1;
    double t = 0, h = 1e-4, sink = 0, result = 0;
    int bad = 0;
    if (trace) {
        for (long k = 0; k < steps; ++k) {
            double u[3], *row = trace + k * TRACE_COLUMNS;
            bench_inputs(k, slip, u);
            bad |= step(f, c, t, h, u, row);
            bad |= more(f, c, row);
            t += h;
        }
    } else {
        const double t0 = now();
        for (long k = 0; k < steps; ++k) {
            double u[3], T[2];
            bench_inputs(k, slip, u);
            bad |= step(f, c, t, h, u, T);
            t += h;
            sink += T[0];
        }
        result = 1e9 * (now() - t0) / steps;
        if (state(f, c) != (slip ? 2 : 1)) bad = 1;
    }
    if (bad || sink == 12345.6789) result = -1;
    stop(f, c);
    return result;
}
