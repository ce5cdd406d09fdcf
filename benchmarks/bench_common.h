/* What the FMI 2.0 and 3.0 step benchmarks share: the clock and the input
 * paths, so that both measure exactly the same steps. */
#ifndef BENCH_COMMON_H
#define BENCH_COMMON_H
#include <time.h>

static inline double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts); /* not the time others take the core */
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Step k of the path: slip = 0, the body oscillates inside the sticking
 * ellipse; slip = 1, it is pushed steadily (0.244 m/s, 0.1 ms steps) and every
 * step slips.  u = (u1 [m], u2 [m], N [N]). */
static inline void bench_inputs(long k, int slip, double u[3]) {
    if (slip) {
        u[0] = 2.44e-5 * k;
        u[1] = 0.3 * u[0];
    } else {
        u[0] = 1e-4 * ((k & 7) - 3.5) / 3.5;
        u[1] = 5e-5 * ((k & 3) - 1.5) / 1.5;
    }
    u[2] = 18.39;
}
#endif
