/*
 * The law's arithmetic (contact_law.c's section 1): 2x2 products, norms
 * without overflow, power-of-two scales.  Part of contact_law.c's unit
 * (it alone includes this): static functions, inlined where they are used.
 *
 * Scale: the law is homogeneous, so every norm is taken without squaring
 * overflow, and exact power-of-two scalings (which commute with rounding)
 * bring the numbers a computation works on to about 1.
 */
#ifndef OC_LAW_ARITH_H
#define OC_LAW_ARITH_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* Q(t) diag(d1, d2) Q(t)^T */
static void rotated_diag(double t, double d1, double d2, double R[2][2]) {
    const double c = cos(t), s = sin(t);
    R[0][0] = d1 * c * c + d2 * s * s;
    R[1][1] = d1 * s * s + d2 * c * c;
    R[0][1] = R[1][0] = (d1 - d2) * s * c;
}

static void matmul(const double A[2][2], const double B[2][2], double C[2][2]) {
    double T[2][2];
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) T[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j];
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) C[i][j] = T[i][j];
}

static void matvec(const double A[2][2], const double x[2], double y[2]) {
    const double y0 = A[0][0] * x[0] + A[0][1] * x[1];
    const double y1 = A[1][0] * x[0] + A[1][1] * x[1];
    y[0] = y0;
    y[1] = y1;
}

/* fmax, NaN handling included (the other argument), without the libm call
 * it compiles to on x86-64 (a call in the middle of the slip solve's
 * arithmetic).  Zeros of both signs tie differently, which no caller meets
 * (they compare positive numbers). */
static inline double max2(double a, double b) { return a > b || b != b ? a : b; }

static int all_finite(const double *v, size_t n) {
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(v[i])) return 0;
    return 1;
}

/* 2^-e and 2^e for the binary exponent e of |x| (x finite, normal and
 * nonzero), from the bits.  Scaling by them is exact, and exact power-of-two
 * scaling commutes with rounding: whatever is computed on scaled values is
 * the same, bit for bit, in any power-of-two units. */
static double pow2_of(double x, double *inverse) {
    uint64_t b;
    memcpy(&b, &x, 8);
    const uint64_t e = (b >> 52) & 0x7ff; /* biased exponent, 1..2046 */
    const uint64_t p = e << 52, r = (2046 - e) << 52;
    double out, inv;
    memcpy(&out, &p, 8);
    memcpy(&inv, &r, 8);
    /* At the top exponent the inverse 2^-1023 is subnormal (biased exponent
     * 0, which the bits above would read as +0.0); it is still exact. */
    *inverse = e == 2046 ? 0x1p-1023 : inv;
    return out;
}

/* 2^-floor(e / 2) for the binary exponent e of x (x normal and positive):
 * for x = |a|^2 it scales |a| to [1, 2) as pow2_of(|a|) does, up to a factor
 * 2 where the square's rounding crosses a power of four.  Where nothing
 * under- or overflows, results computed on a trial scaled either way are
 * the same bit for bit (the scale is exact), and it needs no square root.
 * floor, not truncation: it moves with x's exponent, so that results stay
 * the same in any power-of-two units. */
static inline double pow2_root_inverse(double x) {
    uint64_t b;
    memcpy(&b, &x, 8);
    const int e = (int)((b >> 52) & 0x7ff) - 1023;
    const int k = e >= 0 ? e / 2 : -((1 - e) / 2);
    const uint64_t r = (uint64_t)(1023 - k) << 52;
    double out;
    memcpy(&out, &r, 8);
    return out;
}

/* The power of two that scales a trial of norm n_tr = sqrt(sq) to about
 * [1, 2): from sq's exponent where sq is normal (the slip's work that needs
 * only the scaled trial then starts while the square root is under way),
 * else from n_tr itself. */
static inline double trial_scale(double sq, double n_tr) {
    if (sq >= 0x1p-900 && sq <= 0x1p1000) return pow2_root_inverse(sq);
    double sc;
    pow2_of(n_tr, &sc);
    return sc;
}

/* The general case of oc_norm2: no square may under- or overflow. */
static double norm2_scaled(double x, double y) {
    const double ax = fabs(x), ay = fabs(y);
    const double big = ax > ay ? ax : ay;
    if (!(big >= DBL_MIN) || !isfinite(big)) {
        /* 0, subnormal, inf or NaN */
        if (!(big > 0) || !isfinite(big)) return big + (ax > ay ? ay : ax);
        const double r = (ax > ay ? ay : ax) / big;
        return big * sqrt(1.0 + r * r);
    }
    double inv;
    const double p = pow2_of(big, &inv), xs = x * inv, ys = y * inv;
    return sqrt(xs * xs + ys * ys) * p;
}

/* No square under- or overflows in the first branch, so it gives what the
 * scaled form gives, bit for bit (a square too small to matter is absorbed). */
static inline double norm2(double x, double y) {
    const double sq = x * x + y * y;
    return sq >= 0x1p-900 && sq <= 0x1p1000 ? sqrt(sq) : norm2_scaled(x, y);
}

#endif
