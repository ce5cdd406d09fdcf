/*
 * The lanes the implicit slip solve (law/slip_solve.inc) is written over:
 * one cell's numbers in a double (lane1_*), or two cells' in a vector of
 * two doubles (lane2_*, GCC/Clang vector extensions: SSE2 on x86-64, NEON
 * on aarch64; no intrinsics, no -march), each vector operation beside its
 * plain twin.  A lane operation acts on each lane as the scalar operation
 * does, so that a lane's numbers are its cell's own arithmetic bit for bit.
 * Part of contact_law.c's unit (it alone includes this).
 *
 *   sel(m, a, b)        m ? a : b, lane by lane (a vector's by one
 *                       comparison's mask: gcc makes a select by a combined
 *                       mask, without SSE4.1's blend, lane by lane in
 *                       integer registers)
 *   sel_usual(m, a, b)  the same where m is nearly always true: for a
 *                       double a branch the processor predicts (OC_LIKELY)
 *   abs, sqrt, max      fabs, sqrt, max2 (law/arith.h)
 *   not(m)              of a mask: 0 or 1 a double's, all ones or zero a
 *                       vector lane's
 *   splat(a)            a number into every lane
 *   make(a, b)          the lanes of two cells (a double takes a)
 *   get(x, l), mask_get(m, l)  lane l (macros: see lane2_get)
 * Without the vector extensions (OC_VECTORS 0: compiler.h) the batch's
 * lanes are the doubles' (OC_LANE_WIDTH: 2 or 1).
 */
#ifndef OC_LAW_LANES_H
#define OC_LAW_LANES_H

#include <math.h>

#include "compiler.h"
#include "law/arith.h"

static OC_ALWAYS_INLINE double lane1_sel(int m, double a, double b) { return m ? a : b; }
static OC_ALWAYS_INLINE double lane1_sel_usual(int m, double a, double b) {
    if (OC_LIKELY(m)) return a;
    return b;
}
static OC_ALWAYS_INLINE double lane1_abs(double a) { return fabs(a); }
static OC_ALWAYS_INLINE double lane1_sqrt(double a) { return sqrt(a); }
static OC_ALWAYS_INLINE double lane1_max(double a, double b) { return max2(a, b); }
static OC_ALWAYS_INLINE int lane1_not(int m) { return !m; }
static OC_ALWAYS_INLINE double lane1_splat(double a) { return a; }
static OC_ALWAYS_INLINE double lane1_make(double a, double b) {
    (void)b;
    return a;
}
#define lane1_get(x, l) (x)
#define lane1_mask_get(m, l) (m)

#if OC_VECTORS
typedef double v2d __attribute__((vector_size(16)));
typedef long long v2m __attribute__((vector_size(16))); /* a lane all ones or zero */
static OC_ALWAYS_INLINE v2d lane2_sel(v2m m, v2d a, v2d b) {
    return (v2d)(((v2m)a & m) | ((v2m)b & ~m));
}
static OC_ALWAYS_INLINE v2d lane2_abs(v2d a) {
    const v2m mag = {0x7fffffffffffffffLL, 0x7fffffffffffffffLL};
    return (v2d)((v2m)a & mag);
}
static OC_ALWAYS_INLINE v2d lane2_sqrt(v2d a) {
    const v2d r = {sqrt(a[0]), sqrt(a[1])};
    return r;
}
static OC_ALWAYS_INLINE v2d lane2_max(v2d a, v2d b) { /* max2's: a > b || b != b ? a : b */
    return lane2_sel((v2m)(b != b), a, lane2_sel((v2m)(a > b), a, b));
}
static OC_ALWAYS_INLINE v2d lane2_sel_usual(v2m m, v2d a, v2d b) { return lane2_sel(m, a, b); }
static OC_ALWAYS_INLINE v2m lane2_not(v2m m) { return ~m; }
static OC_ALWAYS_INLINE v2d lane2_splat(double a) {
    const v2d r = {a, a};
    return r;
}
static OC_ALWAYS_INLINE v2d lane2_make(double a, double b) {
    const v2d r = {a, b};
    return r;
}
/* Lane l of a vector by indexing it in place: a function taking the vector
 * would copy it to memory first (1.7 % of a batch of slipping cells). */
#define lane2_get(x, l) ((x)[l])
#define lane2_mask_get(m, l) ((m)[l])
#define OC_LANE_WIDTH 2
#else
#define OC_LANE_WIDTH 1
#endif

#endif
