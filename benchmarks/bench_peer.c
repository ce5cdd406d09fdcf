/* Benchmark (not a test) and, with --check, the peer's agreement test.
 *
 * The shipped FMU (the host binaries CMake builds, loaded with dlopen as an
 * importer loads them) against the peer (benchmarks/peer/: the same law
 * written the plain way, with a minimal FMI layer), both driven through the
 * same loop of set inputs + doStep + get (T1, T2), FMI 2.0 and 3.0, every
 * sliding rule, stick and slip paths (bench_common.h).  Runs are interleaved
 * (ours and the peer one after the other, stick then slip, `rounds` rounds),
 * each figure the least disturbed of its rounds; the ratio is ours / peer of
 * those, with the range of the rounds' own ratios beside it.  Targets (issue
 * 16): stick <= 1.0x the peer, slip <= 0.5x.
 *
 *   bench_peer [steps [rounds]]       ns per step and ratios
 *   bench_peer --check [steps]        exit 1 unless both agree to 1e-9
 *                                     relative on the benchmark's paths
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_peer.h"
#include "fmu_token.h"

typedef struct {
    const char *name;
    int (*open)(bench_fmu *, const char *);
    double (*run)(const bench_fmu *, const char *, const bench_params *, int, long, double *);
    const char *ours_path, *peer_path;
    bench_fmu ours, peer;
} version;

static const char *const RULES[4] = {"", "associated", "coupled", "eq20"};

/* The FMU's default parameters (the aged mat: axes at 90 deg to each other)
 * and a set whose axes are neither aligned nor perpendicular. */
static bench_params params(int set, int rule) {
    bench_params b = {{0.408, 0.625, 12510.0, 10000.0, 1.5707963267948966, 0.0}, rule};
    if (set == 1) {
        const double p[6] = {0.3, 0.55, 24000.0, 30000.0, 0.4, -0.25};
        memcpy(b.p, p, sizeof p);
    }
    return b;
}

/* Largest |a - b| / max(|a|, |b|) over the vectors of columns [c0, c0 + n)
 * of the rows, and whether the contact states agree. */
static double worst(const double *a, const double *b, long rows, int c0, int n, int *states_differ) {
    double w = 0;
    for (long k = 0; k < rows; ++k) {
        const double *x = a + k * TRACE_COLUMNS, *y = b + k * TRACE_COLUMNS;
        double d = 0, m = 0;
        for (int j = c0; j < c0 + n; ++j) {
            d = fmax(d, fabs(x[j] - y[j]));
            m = fmax(m, fmax(fabs(x[j]), fabs(y[j])));
        }
        const double r = d == 0 ? 0 : d / m;
        if (!(r <= w)) w = r; /* NaN propagates */
        if (x[5] != y[5]) *states_differ = 1;
    }
    return w;
}

static int check(version *v, int nv, long steps) {
    double *a = malloc(sizeof(double) * TRACE_COLUMNS * steps);
    double *b = malloc(sizeof(double) * TRACE_COLUMNS * steps);
    int failed = 0;
    printf("# ours against the peer, %ld steps a path: max relative difference\n", steps);
    printf("%-8s %-11s %-4s %-5s %10s %10s %10s %s\n", "FMI", "rule", "set", "path", "T", "s",
           "energy", "states");
    for (int i = 0; i < nv; ++i)
        for (int rule = 1; rule <= 3; ++rule)
            for (int set = 0; set < 2; ++set)
                for (int slip = 0; slip < 2; ++slip) {
                    const bench_params bp = params(set, rule);
                    if (v[i].run(&v[i].ours, FMU_TOKEN, &bp, slip, steps, a) < 0 ||
                        v[i].run(&v[i].peer, FMU_TOKEN, &bp, slip, steps, b) < 0) {
                        printf("%s %s: an FMI call failed\n", v[i].name, RULES[rule]);
                        failed = 1;
                        continue;
                    }
                    int differ = 0;
                    const double wT = worst(a, b, steps, 0, 2, &differ);
                    const double ws = worst(a, b, steps, 2, 2, &differ);
                    const double wE = worst(a, b, steps, 4, 1, &differ);
                    const int ok = wT <= 1e-9 && ws <= 1e-9 && wE <= 1e-9 && !differ;
                    printf("%-8s %-11s %-4d %-5s %10.1e %10.1e %10.1e %s%s\n", v[i].name,
                           RULES[rule], set, slip ? "slip" : "stick", wT, ws, wE,
                           differ ? "differ" : "agree", ok ? "" : "   <-- FAILED (> 1e-9)");
                    failed |= !ok;
                }
    free(a);
    free(b);
    printf(failed ? "FAILED\n" : "all within 1e-9\n");
    return failed;
}

static void bench(version *v, int nv, long steps, int rounds) {
    printf("# ns per step through the FMI calls (set u1, u2, N + doStep + get T1, T2), %ld steps "
           "a run,\n# ours and the peer interleaved, least disturbed of %d rounds; ratio = ours / "
           "peer [range over rounds]\n", steps, rounds);
    printf("%-8s %-11s %-5s %9s %9s %7s %15s %s\n", "FMI", "rule", "path", "ours_ns", "peer_ns",
           "ratio", "round ratios", "target");
    for (int i = 0; i < nv; ++i)
        for (int rule = 1; rule <= 3; ++rule) {
            const bench_params bp = params(0, rule);
            double best[2][2] = {{1e30, 1e30}, {1e30, 1e30}}, lo[2] = {1e30, 1e30}, hi[2] = {0, 0};
            int failed = 0;
            for (int r = 0; r < rounds; ++r)
                for (int slip = 0; slip < 2; ++slip) {
                    const double o = v[i].run(&v[i].ours, FMU_TOKEN, &bp, slip, steps, NULL);
                    const double p = v[i].run(&v[i].peer, FMU_TOKEN, &bp, slip, steps, NULL);
                    if (o < 0 || p < 0) failed = 1;
                    best[slip][0] = fmin(best[slip][0], o);
                    best[slip][1] = fmin(best[slip][1], p);
                    lo[slip] = fmin(lo[slip], o / p);
                    hi[slip] = fmax(hi[slip], o / p);
                }
            for (int slip = 0; slip < 2; ++slip) {
                const double ratio = best[slip][0] / best[slip][1], target = slip ? 0.5 : 1.0;
                printf("%-8s %-11s %-5s %9.1f %9.1f %7.2f %7.2f-%-7.2f <= %.1f %s\n", v[i].name,
                       RULES[rule], slip ? "slip" : "stick", best[slip][0], best[slip][1], ratio,
                       lo[slip], hi[slip], target,
                       failed ? "(a call failed)" : ratio <= target ? "met" : "NOT MET");
            }
        }
}

int main(int argc, char **argv) {
    int do_check = argc > 1 && strcmp(argv[1], "--check") == 0;
    const int a0 = do_check ? 2 : 1;
    const long steps = argc > a0 ? atol(argv[a0]) : (do_check ? 20000 : 200000);
    const int rounds = argc > a0 + 1 ? atoi(argv[a0 + 1]) : 9;
    version v[2] = {{"FMI 2.0", bench2_open, bench2_run, OURS_FMI2, PEER_FMI2, {0}, {0}},
                    {"FMI 3.0", bench3_open, bench3_run, OURS_FMI3, PEER_FMI3, {0}, {0}}};
    for (int i = 0; i < 2; ++i)
        if (v[i].open(&v[i].ours, v[i].ours_path) || v[i].open(&v[i].peer, v[i].peer_path))
            return 2;
    if (do_check) return check(v, 2, steps);
    bench(v, 2, steps, rounds);
    return 0;
}
