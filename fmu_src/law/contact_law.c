/* The coupled orthotropic adhesion-friction law (Konyukhov & Schweizerhof):
 * one return-mapping step and its consistent tangent.  The derivations are
 * in docs/explanation/law.md, whose sections these follow; the comments here
 * say why the code takes its shape.
 *
 *   1. Arithmetic: 2x2 products, norms without overflow, power-of-two scales
 *   2. The parameters and the tensors they fix (B, F, the yield coordinates)
 *   3. Slip by the implicit rules: the plastic multiplier on the yield surface
 *   4. Slip by the paper's explicit eq. (20)
 *   5. One step: trial, stick test, return map, commit; many steps at once
 *   6. The consistent tangent
 *   7. A committed state's admissibility
 *
 * Scale: the law is homogeneous (N, eps -> k N, k eps scales forces and
 * energy by k; u, eps -> m u, eps / m scales slip and energy by m).  So
 * every tolerance here is relative, every norm is taken without squaring
 * overflow, and the slip solve works in dimensionless variables. */
#include "law/contact_law.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* ==== 1. Arithmetic: 2x2 products, norms without overflow, power-of-two scales ==== */

/* OC_ALWAYS_INLINE (contact_law.h): inlined even where the compiler would
 * make a call: the slip solve and the parts of a step (sections 3 to 5) are
 * pieces of the step's one body, and as calls they would spill the
 * registers the step keeps live.  gcc inlines them on its own; clang, which
 * builds the shipped binaries, leaves the slip solve a call
 * (docs/benchmarks.md). */

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
        for (int j = 0; j < 2; ++j)
            T[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j];
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

double oc_norm2(double x, double y) { return norm2(x, y); }

/* ==== 2. The parameters and the tensors they fix (B, F, the yield coordinates) ==== */

const char *oc_params_check(const oc_params *p) {
    /* Written as !(x > 0) so that NaN is rejected too. */
    if (!(p->mu1 > 0) || !isfinite(p->mu1)) return "mu1 must be a finite number > 0";
    if (!(p->mu2 > 0) || !isfinite(p->mu2)) return "mu2 must be a finite number > 0";
    if (!(p->eps1 > 0) || !isfinite(p->eps1)) return "eps1 must be a finite number > 0 [N/m]";
    if (!(p->eps2 > 0) || !isfinite(p->eps2)) return "eps2 must be a finite number > 0 [N/m]";
    if (!isfinite(p->alpha)) return "alpha must be finite [rad]";
    if (!isfinite(p->beta)) return "beta must be finite [rad]";
    if (p->rule != OC_RULE_ASSOCIATED && p->rule != OC_RULE_COUPLED && p->rule != OC_RULE_EQ20)
        return "slidingRule must be 1 (associated), 2 (coupled) or 3 (eq. 20)";
    return NULL;
}

/* The elastic tensor B = Q(alpha) diag(eps) Q(alpha)^T, its inverse, and the
 * friction tensor F = Q(beta) diag(1/mu^2) Q(beta)^T of the yield function. */
static void elastic_and_friction_tensors(const oc_params *p, oc_law *L) {
    rotated_diag(p->alpha, p->eps1, p->eps2, L->B);
    rotated_diag(p->alpha, 1.0 / p->eps1, 1.0 / p->eps2, L->Binv);
    rotated_diag(p->beta, 1.0 / (p->mu1 * p->mu1), 1.0 / (p->mu2 * p->mu2), L->F);
}

/* The slip operator S and its eigenbasis V (in the friction axes).
 * With p = F^(1/2) q the slip step reads p = (I + dgamma S)^-1 p_tr for a
 * symmetric positive definite S, whatever the rule:
 * S = F^(1/2) B F^(1/2) (associated) or F^(-1/2) B^-1 F^(-1/2) (coupled).
 * Both are formed in the friction axes, S = Q(beta) S' Q(beta)^T with
 * S' = D Q(gamma) E Q(gamma)^T D, gamma = alpha - beta, D = diag(1/mu) or
 * diag(mu), E = diag(eps) or diag(1/eps): every entry of S' is one product
 * of the parameters with a rotated diagonal, so nothing cancels however
 * different mu1, mu2, eps1, eps2 are.  Formed from rotated factors
 * instead, S loses its small part to the cancellation of its large ones,
 * and its eigenbasis (exactly the shared axes when alpha = beta) comes out
 * off by DBL_EPSILON times the contrast, which then moves the strong-axis
 * part of the force onto the weak axis.  Sets sigma, sigma_ref, sig_hat,
 * kappa; V is the rotation from the eigenbasis to the friction axes. */
static void slip_operator_eigenbasis(const oc_params *p, oc_law *L, double V[2][2]) {
    const int assoc = p->rule == OC_RULE_ASSOCIATED;
    const double gamma = p->alpha - p->beta;
    const double D[2] = {assoc ? 1.0 / p->mu1 : p->mu1, assoc ? 1.0 / p->mu2 : p->mu2};
    double S[2][2];
    rotated_diag(gamma, assoc ? p->eps1 : 1.0 / p->eps1, assoc ? p->eps2 : 1.0 / p->eps2, S);
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) S[i][j] = (D[i] * S[i][j]) * D[j];
    /* One Jacobi rotation diagonalises a symmetric 2x2 matrix exactly,
     * without the cancellation of the characteristic-polynomial formula.  Its
     * angle is taken in [-pi/4, pi/4]: a diagonal S' then gives exactly the
     * identity, not a quarter turn whose cos(pi/2) = 6e-17 would mix the axes. */
    double th = 0.5 * atan2(S[0][1] + S[1][0], S[0][0] - S[1][1]);
    if (th > 0.25 * 3.14159265358979323846) th -= 0.5 * 3.14159265358979323846;
    else if (th < -0.25 * 3.14159265358979323846) th += 0.5 * 3.14159265358979323846;
    const double c = cos(th), s = sin(th);
    V[0][0] = c;
    V[0][1] = -s;
    V[1][0] = s;
    V[1][1] = c;
    L->sigma[0] = c * c * S[0][0] + 2 * c * s * S[0][1] + s * s * S[1][1];
    L->sigma[1] = s * s * S[0][0] - 2 * c * s * S[0][1] + c * c * S[1][1];
    /* The rotation gets the larger eigenvalue to full relative accuracy, the
     * smaller one only to DBL_EPSILON times the larger.  det S is known
     * exactly from the parameters, so the smaller follows from it; the
     * factors are ordered so that no intermediate product overflows. */
    const int big = L->sigma[0] >= L->sigma[1] ? 0 : 1;
    const double mm = p->mu1 * p->mu2, sig_big = L->sigma[big];
    L->sigma[1 - big] = assoc ? ((p->eps1 / mm) / sig_big) * (p->eps2 / mm)
                              : ((mm / p->eps1) / sig_big) * (mm / p->eps2);
    L->sigma_ref = sig_big;
    L->inv_sigma_ref = 1.0 / sig_big;
    L->sig_hat[big] = 1.0;
    L->sig_hat[1 - big] = L->sigma[1 - big] / sig_big;
    L->kappa = sig_big / L->sigma[1 - big];
}

/* The maps between forces, displacements and yield coordinates.  The
 * eigenbasis of S is Q(beta) V, so every map is a product of factors with at
 * most one sum of two terms per entry (none when alpha = beta and V = I):
 *   q = G R a,  G = Q(beta) diag(mu), R = V
 *   a = Y q,    Y = V^T diag(1/mu) Q(beta)^T
 *   a = P du,   P = Y B = V^T diag(1/mu) Q(gamma) diag(eps) Q(alpha)^T
 *   B^-1 q = K a, K = Q(alpha) diag(1/eps) Q(gamma)^T diag(mu) V. */
static void yield_coordinate_maps(const oc_params *p, const double V[2][2], oc_law *L) {
    const double gamma = p->alpha - p->beta;
    const double Vt[2][2] = {{V[0][0], V[1][0]}, {V[0][1], V[1][1]}};
    const double ca = cos(p->alpha), sa = sin(p->alpha);
    const double cb = cos(p->beta), sb = sin(p->beta);
    const double cg = cos(gamma), sg = sin(gamma);
    const double Qa[2][2] = {{ca, -sa}, {sa, ca}}, Qat[2][2] = {{ca, sa}, {-sa, ca}};
    L->G[0][0] = cb * p->mu1;
    L->G[0][1] = -sb * p->mu2;
    L->G[1][0] = sb * p->mu1;
    L->G[1][1] = cb * p->mu2;
    memcpy(L->R, V, sizeof L->R);
    matmul(L->G, L->R, L->Minv);
    const double Ymu[2][2] = {{cb / p->mu1, sb / p->mu1}, {-sb / p->mu2, cb / p->mu2}};
    matmul(Vt, Ymu, L->Y);
    const double Pmu[2][2] = {{(cg / p->mu1) * p->eps1, (-sg / p->mu1) * p->eps2},
                              {(sg / p->mu2) * p->eps1, (cg / p->mu2) * p->eps2}};
    matmul(Pmu, Qat, L->P);
    matmul(Vt, L->P, L->P);
    const double Keps[2][2] = {{(cg / p->eps1) * p->mu1, (sg / p->eps1) * p->mu2},
                               {(-sg / p->eps2) * p->mu1, (cg / p->eps2) * p->mu2}};
    matmul(Keps, V, L->K);
    matmul(Qa, L->K, L->K);
}

/* eq. (20)'s matrix E (oc_law.E20).  The rule needs only the direction of
 * E t: E is formed from factors scaled to at most 1 (the C of eps / its
 * largest entry, mu_min / mu_i), so that it can neither overflow nor cancel
 * (every entry is a product), and then scaled to max|E| = 1.  Scaling by a
 * power of two of eps leaves it unchanged bit for bit. */
static void eq20_matrix(const oc_params *p, oc_law *L) {
    double C[2][2];
    rotated_diag(p->alpha - p->beta, p->eps1, p->eps2, C);
    const double cm = fmax(fmax(C[0][0], C[1][1]), fabs(C[0][1]));
    const double mmin = fmin(p->mu1, p->mu2);
    const double f[2] = {mmin / p->mu1, mmin / p->mu2};
    double m = 0.0;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            L->E20[i][j] = ((C[i][j] / cm) * f[i]) * f[j];
            m = fmax(m, fabs(L->E20[i][j]));
        }
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) L->E20[i][j] /= m;
}

int oc_law_init(oc_law *out, const oc_params *p) {
    if (oc_params_check(p)) return -1;
    oc_law L;
    double V[2][2];
    L.p = *p;
    elastic_and_friction_tensors(p, &L);
    slip_operator_eigenbasis(p, &L, V);
    yield_coordinate_maps(p, V, &L);
    eq20_matrix(p, &L);
    /* Parameters far apart enough can still overflow a tensor: refused. */
    if (!all_finite(&L.B[0][0], 4) || !all_finite(&L.Binv[0][0], 4) ||
        !all_finite(&L.F[0][0], 4) || !all_finite(&L.P[0][0], 4) ||
        !all_finite(&L.Minv[0][0], 4) || !all_finite(&L.Y[0][0], 4) || !all_finite(L.sigma, 2) ||
        !all_finite(&L.R[0][0], 4) || !all_finite(&L.G[0][0], 4) || !all_finite(&L.K[0][0], 4) ||
        !all_finite(&L.E20[0][0], 4) || !(L.sigma[0] > 0) || !(L.sigma[1] > 0) ||
        !(L.sig_hat[0] > 0) || !(L.sig_hat[1] > 0) || !isfinite(L.kappa) ||
        !isfinite(L.inv_sigma_ref))
        return -1;
    *out = L;
    return 0;
}

/* q = Minv a: oc_force_of (contact_law.h). */

/* ==== 3. Slip by the implicit rules: the plastic multiplier on the yield surface ==== */

/* Solves sum_i a_i^2 / (1 + y s_i)^2 = rho^2 for y > 0, given |a| = 1 > rho
 * and s_i = sigma_i / sigma_ref in (0, 1] (so y = dgamma sigma_ref is
 * dimensionless).  k(y) = rho / |p(y)| - 1 is a power mean of exponent -2
 * of the affine 1 + y s_i, hence concave and increasing: Newton from the
 * left of the root climbs monotonically to it, and from the right it lands
 * on the left in one step.  The start is the root's series to third order
 * about y = 0 (exact when s_1 = s_2); left of the root the iteration goes on with
 * Halley steps, whose error is the cube of the step, so that a step below
 * 5e-6 y is the last: it is taken to second order in p (remainder below
 * (dy/y)^3 ~ 1e-16).  Typically that is one evaluation after the start.
 * a_raw is the trial (|a_raw|^2 = sq, |a_raw| = n_tr > N).  Returns y and
 * the p (and 1 / |p|) after the last step, p for a_raw / n_tr.
 *
 * The iteration works on g_i = W p_i with W = w_0 w_1, w_i = 1 + y s_i, so
 * that an evaluation costs one square root and one division; its products
 * (up to W^7) stay finite while W < 1e40, which the caller guarantees
 * (W <= kappa / rho^2 at the root); solve_dgamma_far covers the rest.
 *
 * The solve is written once, below, over a lane type T holding one cell's
 * numbers (double, the functions dgamma1_*) or two cells' (v2d, GCC/Clang
 * vector extensions: SSE2 on x86-64, NEON on aarch64; dgamma2_*), so that a
 * batch of cells (oc_law_step_batch) steps two cells by one vector
 * instruction, each lane its cell's own arithmetic bit for bit: a lane
 * operation acts on each lane as the scalar operation does.  Where the
 * iteration branches, both sides are formed and each lane takes its own by
 * a select of one comparison's mask (gcc makes a select by a combined mask,
 * without SSE4.1's blend, lane by lane in integer registers).  The lane
 * helpers: sel (m ? a : b, lane by lane); sel_usual, the same where m is
 * nearly always true (for a double a branch the processor predicts, so that
 * the iteration need not wait for the test: clang, which builds the shipped
 * binaries, otherwise makes the start's test a select); abs, sqrt, max
 * (max2's); not, of a mask (0 or 1 a double's, all ones or zero a vector
 * lane's); splat, a number into every lane. */
#if defined(__GNUC__) || defined(__clang__)
#define OC_USUALLY(c) __builtin_expect(!!(c), 1)
#else
#define OC_USUALLY(c) (c)
#endif
static OC_ALWAYS_INLINE double lane1_sel(int m, double a, double b) { return m ? a : b; }
static OC_ALWAYS_INLINE double lane1_sel_usual(int m, double a, double b) {
    if (OC_USUALLY(m)) return a;
    return b;
}
static OC_ALWAYS_INLINE double lane1_abs(double a) { return fabs(a); }
static OC_ALWAYS_INLINE double lane1_sqrt(double a) { return sqrt(a); }
static OC_ALWAYS_INLINE double lane1_max(double a, double b) { return max2(a, b); }
static OC_ALWAYS_INLINE int lane1_not(int m) { return !m; }
static OC_ALWAYS_INLINE double lane1_splat(double a) { return a; }

#if (defined(__GNUC__) || defined(__clang__)) && !defined(OC_SCALAR_LANES)
#define OC_VECTOR_LANES 1
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
#endif

/* The solve of N lanes of type T with masks of type M:
 *
 * dgammaN_start (no square root, so that it runs beside the caller's):
 * from the trial a_raw = (ar0, ar1), |a_raw|^2 = sq, |a_raw| = n_tr, and
 * N (N_: N names the lanes), the direction a = a_raw / n_tr,
 * rho = N / n_tr and the start x.  Its
 * divisions depend only on the trial, not on its square root: they run
 * beside it.  Moments are taken over a_i^2 / |a|^2.  The start is the
 * root's series in the Newton step h from y = 0, to third order (error
 * O(h^4)), from the moments M_j = sum_i a_i^2 s_i^j: k(0) = rho - 1,
 * k' = rho M1, k''/(2 k') = A2 = 3 (M1^2 - M2) / (2 M1),
 * k'''/(6 k') = A3 = (15 M1^3 - 27 M1 M2 + 12 M3) / (6 M1).  Far from the
 * root the series need not converge: Newton's step then (x > 0 && x < 4 h
 * ? x : h).
 *
 * dgammaN_step: one evaluation at the iterate x, into *E; moves the iterate
 * and returns the mask of the lanes where it was the last (a lane whose
 * evaluation ends it unmoved has dx = 0).  In u_i = W s_i / w_i,
 * k' = rho C / m^3 with C = sum g_i^2 u_i and
 * k'' / k' = -3 (m^2 D2 - C^2) / (W m^2 C), D2 = sum g_i^2 u_i^2.  Left of
 * the root (res > 0): Halley in one division, dx = -(k / k') /
 * (1 - k k'' / (2 k'^2)): k < 0 and k'' <= 0 make the bracket < 1, a step
 * longer than Newton's.  Where the bracket falls below 1/2 (far from the
 * root) the step is held at twice Newton's: overshooting the root is
 * harmless (Newton from the right lands left of it).  Right of it: Newton.
 *
 * dgammaN_root: the root y = x + dx of the evaluation *E, and p there:
 * p_i(x + dx) = p_i / (1 + t_i) with t_i = s_i dx / w_i = u_i dx / W.
 * |p| = rho to rounding then, so 1 / |p| is one Newton step of the inverse
 * square root from 1 / rho: no square root, no division.
 *
 * dgammaN_weights: what the tangent needs of the root y (oc_step.w,
 * inv_wmax): w_i = 1 + y s_i as w_i / max w, and 1 / max w. */
#define OC_DGAMMA_SOLVE(N, T, M)                                                           \
    typedef struct {                                                                       \
        T a0, a1;       /* the trial's direction a_raw / n_tr */                           \
        T rho, inv_rho; /* N / n_tr and its inverse */                                     \
        T x;            /* the iterate y */                                                \
        T it;           /* evaluations made */                                             \
    } dgamma##N##_solve;                                                                   \
    typedef struct {                                                                       \
        T x, dx, W, g0, g1, u0, u1;                                                        \
    } dgamma##N##_eval;                                                                    \
                                                                                           \
    static OC_ALWAYS_INLINE void dgamma##N##_start(T ar0, T ar1, T sq, T n_tr, T N_,       \
                                                   const double sh[2],                     \
                                                   dgamma##N##_solve *S) {                 \
        const T A0 = ar0 * ar0, A1 = ar1 * ar1;                                            \
        const double s0 = sh[0], s1 = sh[1];                                               \
        const T R1 = A0 * s0 + A1 * s1;                                                    \
        const T inv_sq = 1.0 / sq, inv_R1 = 1.0 / R1, inv_N = 1.0 / N_;                    \
        const T inv_ntr = n_tr * inv_sq, rho = N_ * inv_ntr, inv_rho = n_tr * inv_N;       \
        S->a0 = ar0 * inv_ntr;                                                             \
        S->a1 = ar1 * inv_ntr;                                                             \
        S->rho = rho;                                                                      \
        S->inv_rho = inv_rho;                                                              \
        const T M1 = R1 * inv_sq, M2 = (A0 * s0 * s0 + A1 * s1 * s1) * inv_sq;             \
        const T M3 = (A0 * s0 * s0 * s0 + A1 * s1 * s1 * s1) * inv_sq;                     \
        const T inv_M1 = sq * inv_R1;                                                      \
        const T h = (1.0 - rho) * inv_rho * inv_M1;                                        \
        const T A2 = 1.5 * (M1 * M1 - M2) * inv_M1;                                        \
        const T A3 =                                                                       \
            (15.0 * M1 * M1 * M1 - 27.0 * M1 * M2 + 12.0 * M3) * inv_M1 * (1.0 / 6.0);     \
        const T x = h * (1.0 - A2 * h + (2.0 * A2 * A2 - A3) * h * h);                     \
        S->x = lane##N##_sel_usual((M)(x < 4.0 * h),                                       \
                                   lane##N##_sel_usual((M)(x > 0.0), x, h), h);            \
        S->it = lane##N##_splat(0.0);                                                      \
    }                                                                                      \
                                                                                           \
    static OC_ALWAYS_INLINE M dgamma##N##_step(dgamma##N##_solve *S, const double sh[2],   \
                                               dgamma##N##_eval *E) {                      \
        const T x = S->x, rho = S->rho, inv_rho = S->inv_rho;                              \
        const T w0x = 1.0 + x * sh[0], w1x = 1.0 + x * sh[1], W = w0x * w1x;               \
        const T g0 = S->a0 * w1x, g1 = S->a1 * w0x;                                        \
        const T G0 = g0 * g0, G1 = g1 * g1, m2 = G0 + G1, m = lane##N##_sqrt(m2);          \
        const T res = m - rho * W;                                                         \
        const T u0 = sh[0] * w1x, u1 = sh[1] * w0x;                                        \
        const M far = (M)(lane##N##_abs(res) > 2 * DBL_EPSILON * rho * W);                 \
        const M more = (M)(S->it < 100.0);                                                 \
        const M left = (M)(res > 0.0);                                                     \
        const T C = G0 * u0 + G1 * u1;                                                     \
        const T D2 = G0 * u0 * u0 + G1 * u1 * u1, nC2 = rho * W * C * C;                   \
        const T num = lane##N##_sel(left, res * m2 * W * C, res * m2 * inv_rho);           \
        const T den = lane##N##_sel(                                                       \
            left, lane##N##_max(nC2 - 1.5 * res * (m2 * D2 - C * C), 0.5 * nC2), C);       \
        const T zero = lane##N##_splat(0.0);                                               \
        const T dx = lane##N##_sel(more, lane##N##_sel(far, num / den, zero), zero);       \
        const M small = (M)(lane##N##_abs(dx) <= lane##N##_sel(left, 5e-6 * x, 1e-8 * x)); \
        E->x = x;                                                                          \
        E->dx = dx;                                                                        \
        E->W = W;                                                                          \
        E->g0 = g0;                                                                        \
        E->g1 = g1;                                                                        \
        E->u0 = u0;                                                                        \
        E->u1 = u1;                                                                        \
        S->x = lane##N##_max(x + dx, zero);                                                \
        S->it = S->it + 1.0;                                                               \
        return lane##N##_not(far & more) | small;                                          \
    }                                                                                      \
                                                                                           \
    static OC_ALWAYS_INLINE void dgamma##N##_root(const dgamma##N##_solve *S,              \
                                                  const dgamma##N##_eval *E, T *p0, T *p1, \
                                                  T *inv_norm, T *root) {                  \
        const T invW = 1.0 / E->W, inv_rho = S->inv_rho;                                   \
        const T t0 = E->u0 * E->dx * invW, t1 = E->u1 * E->dx * invW;                      \
        *p0 = E->g0 * invW * (1.0 - t0 + t0 * t0);                                         \
        *p1 = E->g1 * invW * (1.0 - t1 + t1 * t1);                                         \
        const T pp = *p0 * *p0 + *p1 * *p1;                                                \
        *inv_norm = inv_rho * (1.5 - 0.5 * pp * inv_rho * inv_rho);                        \
        *root = E->x + E->dx;                                                              \
    }                                                                                      \
                                                                                           \
    static OC_ALWAYS_INLINE void dgamma##N##_weights(T y, const double sh[2], T *w0, T *w1, \
                                                     T *inv_wmax) {                        \
        const T v0 = 1.0 + y * sh[0], v1 = 1.0 + y * sh[1], wmax = lane##N##_max(v0, v1);  \
        *w0 = v0 / wmax;                                                                   \
        *w1 = v1 / wmax;                                                                   \
        *inv_wmax = 1.0 / wmax;                                                            \
    }

OC_DGAMMA_SOLVE(1, double, int)
#ifdef OC_VECTOR_LANES
OC_DGAMMA_SOLVE(2, v2d, v2m)
#endif

/* One cell's solve (dgamma1_*, section 3's opening comment): y, and p (and
 * 1 / |p|) there. */
static OC_ALWAYS_INLINE double solve_dgamma(const double a_raw[2], double sq, double n_tr,
                                             double N, const double sh[2], double p[2],
                                             double *inv_norm) {
    dgamma1_solve S;
    dgamma1_eval E;
    dgamma1_start(a_raw[0], a_raw[1], sq, n_tr, N, sh, &S);
    while (!dgamma1_step(&S, sh, &E)) {
    }
    double y;
    dgamma1_root(&S, &E, &p[0], &p[1], inv_norm, &y);
    return y;
}

/* The same root for a trial far outside the yield surface or a large
 * kappa, in v = y rho: with wt_i = rho + v s_i (= rho w_i) the yield
 * condition reads |b| = 1 for b_i = a_i / wt_i, and 1 / |b| - 1 is concave and
 * increasing in v (as k is in y), so Newton from the left climbs to the root
 * and from the right lands left of it.  The root lies in [1 - rho, |a / s|]
 * (s_i <= 1 and wt_i >= v s_i): v is bounded however small rho is, even
 * subnormal, where y = v / rho overflows.  b is kept as c = wmin b (|c| <= 1)
 * so that nothing overflows.  Returns v; p = c with *inv_norm = 1 / |c|. */
static double solve_dgamma_far(const double a[2], const double sh[2], double rho, double p[2],
                               double *inv_norm) {
    const double vmax = oc_norm2(a[0] / sh[0], a[1] / sh[1]);
    double v = rho < 1.0 ? 1.0 - rho : 0.0, c0 = a[0], c1 = a[1], n = 1.0;
    for (int it = 0; it < 200; ++it) {
        const double w0 = rho + v * sh[0], w1 = rho + v * sh[1], wmin = fmin(w0, w1);
        c0 = a[0] * (wmin / w0);
        c1 = a[1] * (wmin / w1);
        n = oc_norm2(c0, c1);
        const double r0 = c0 / n, r1 = c1 / n;
        /* Newton: dv = (|b| - 1) / kp, kp = sum_i r_i^2 s_i / wt_i */
        const double kp = r0 * r0 * (sh[0] / w0) + r1 * r1 * (sh[1] / w1);
        double dv = (n / wmin - 1.0) / kp;
        if (!(fabs(dv) > 1e-15 * v)) break; /* stalls at the root (or NaN: stop) */
        if (!(v + dv <= vmax)) dv = vmax - v; /* also for dv = inf */
        if (dv == 0.0) break;
        v += dv;
    }
    p[0] = c0;
    p[1] = c1;
    *inv_norm = 1.0 / n;
    return v;
}

/* The return map of the implicit rules (associated, coupled): the slipped
 * force a = a_tr / (1 + dgamma sigma) on the yield surface |a| = N, as the
 * direction p and the radial scale with a = p scale; yp = y a as the
 * dissipation needs it (y = dgamma sigma_ref), and what the tangent needs
 * (oc_step.dgamma, w, inv_wmax).  The trial a (|a| = n_tr, |a|^2 = sq) lies
 * outside the surface. */
static OC_ALWAYS_INLINE void return_map_implicit(const oc_law *L, const double a[2], double sq,
                                                 double n_tr, double N, double p[2],
                                                 double *scale_out, double yp[2], oc_step *out) {
    /* The fast solve needs W <= kappa / rho^2 < 1e40.  It runs on the
     * trial scaled by the power of two that brings |a| to [1, 2): the
     * same numbers in any units, down to which squares of a small
     * component underflow (scaled only where |a|^2 left a range, the
     * units decided whether a_i^2 was subnormal). */
    double inv_np, scale;
    if (L->kappa <= 1e20 && n_tr <= 1e10 * N && n_tr >= DBL_MIN) {
        const double sc = trial_scale(sq, n_tr);
        const double as[2] = {a[0] * sc, a[1] * sc};
        const double y = solve_dgamma(as, as[0] * as[0] + as[1] * as[1], n_tr * sc, N * sc,
                                      L->sig_hat, p, &inv_np);
        dgamma1_weights(y, L->sig_hat, &out->w[0], &out->w[1], &out->inv_wmax);
        scale = N * inv_np;
        /* y a_i with a = p scale, as the energy needs it */
        yp[0] = y * (p[0] * scale);
        yp[1] = y * (p[1] * scale);
        out->dgamma = y * L->inv_sigma_ref;
    } else {
        const double an[2] = {a[0] / n_tr, a[1] / n_tr}, rho = N / n_tr;
        const double v = solve_dgamma_far(an, L->sig_hat, rho, p, &inv_np);
        /* wt_i = rho w_i; y a_i = v (p_i / |p|) n_tr, without y = v / rho */
        const double w0 = rho + v * L->sig_hat[0], w1 = rho + v * L->sig_hat[1];
        const double wmax = max2(w0, w1);
        out->w[0] = w0 / wmax;
        out->w[1] = w1 / wmax;
        out->inv_wmax = rho / wmax;
        scale = N * inv_np;
        yp[0] = v * (p[0] * inv_np) * n_tr;
        yp[1] = v * (p[1] * inv_np) * n_tr;
        out->dgamma = (v / rho) * L->inv_sigma_ref;
    }
    *scale_out = scale;
}

/* The energy the implicit rules dissipate in a slip to the force ap:
 * dgamma q.Gq = sum_i dgamma c_i a_i^2 with c_i = 1 (associated) or
 * sigma_i^2 (coupled): a sum of products of equal signs, so it is >= 0 by
 * construction, in an order that does not overflow where the result does
 * not: (dgamma c_i a_i), of the size of the slip in yield coordinates,
 * times a_i, the force. */
static OC_ALWAYS_INLINE double dissipation_implicit(const oc_law *L, const double yp[2],
                                                    const double ap[2]) {
    if (L->p.rule == OC_RULE_ASSOCIATED)
        return (yp[0] * L->inv_sigma_ref) * ap[0] + (yp[1] * L->inv_sigma_ref) * ap[1];
    return ((L->sig_hat[0] * yp[0]) * L->sigma[0]) * ap[0] +
           ((L->sig_hat[1] * yp[1]) * L->sigma[1]) * ap[1];
}

/* ==== 4. Slip by the paper's explicit eq. (20) ==== */

/* The return map of eq. (20): t = N z / |z|, z = E t_tr, t_tr = R a (see
 * oc_law.E20), as the direction p (in yield coordinates) and the scale that
 * puts it exactly on the yield surface, like the implicit rules' states.
 * No multiplier: the tangent differentiates the formula itself. */
static OC_ALWAYS_INLINE void return_map_eq20(const oc_law *L, const double a[2], double sq,
                                             double n_tr, double N, double p[2], double *scale,
                                             oc_step *out) {
    out->dgamma = 0.0;
    out->w[0] = out->w[1] = out->inv_wmax = 1.0;
    /* On a trial scaled to |t_tr| in [1, 2) by a power of two: the direction
     * of z is the same in any units.  Back in yield coordinates, p = R^T z. */
    const double sc = trial_scale(sq, n_tr);
    const double as[2] = {a[0] * sc, a[1] * sc};
    double t[2], z[2];
    matvec(L->R, as, t);
    matvec(L->E20, t, z);
    p[0] = L->R[0][0] * z[0] + L->R[1][0] * z[1];
    p[1] = L->R[0][1] * z[0] + L->R[1][1] * z[1];
    *scale = N / norm2(p[0], p[1]);
}

/* The energy eq. (20) dissipates in a slip from the trial a to the force ap
 * (q in global axes).  The rule is not derived from a dissipation potential,
 * yet its q . ds is positive (docs/explanation/law.md: Cauchy-Schwarz, since
 * N < |t| when it slides); the clip only catches rounding.  ds = B^-1 (q_tr - q) =
 * K (a_tr - a), formed from yield coordinates rather than as a difference
 * of slips, which may be large and nearly equal. */
static OC_ALWAYS_INLINE double dissipation_eq20(const oc_law *L, const double a[2],
                                                const double ap[2], const double q[2]) {
    const double da[2] = {a[0] - ap[0], a[1] - ap[1]};
    double ds[2];
    matvec(L->K, da, ds);
    const double dE = q[0] * ds[0] + q[1] * ds[1];
    return dE > 0 ? dE : 0.0;
}

/* ==== 5. One step: trial, stick test, return map, commit ==== */

/* Open, the trial and stick: oc_step_open, oc_trial, oc_step_stick
 * (contact_law.h), inline there for oc_law_step_quick. */

/* The slipped force in yield coordinates, p scale, inside the stick test:
 * near the subnormal range it is rounded to a multiple of 2^-1074, which can
 * put it a unit outside, so that the state would slip again with held
 * inputs (and be refused on restore): it is then shrunk to inside, a unit
 * at a time. */
static OC_ALWAYS_INLINE void on_yield_surface(const double p[2], double scale, double N,
                                              double ap[2]) {
    ap[0] = p[0] * scale;
    ap[1] = p[1] * scale;
    if (N < 0x1p-1016) {
        while (norm2(ap[0], ap[1]) > N * (1.0 + 8 * DBL_EPSILON)) {
            const int i = fabs(ap[0]) >= fabs(ap[1]) ? 0 : 1;
            ap[i] = nextafter(ap[i], 0.0);
        }
    }
}

/* Slip: commits the force ap on the yield surface, the slip that leaves
 * the elastic displacement B^-1 q = K ap, and the dissipated energy. */
static OC_ALWAYS_INLINE void step_slip(const oc_law *L, const oc_state *start, const double u[2],
                                       const double a[2], const double ap[2], const double yp[2],
                                       oc_step *out) {
    /* The elastic displacement from the committed force, not from p: K p
     * is a product of a scale-dependent K with a scale-free p, whose small
     * terms underflow in some units only. */
    double ge[2];
    matvec(L->K, ap, ge);
    out->next.a[0] = ap[0];
    out->next.a[1] = ap[1];
    /* The force exactly as a stick step from this committed state forms it,
     * so that held inputs reproduce it bit for bit. */
    oc_force_of(L, ap, out->q);
    out->next.s[0] = u[0] - ge[0];
    out->next.s[1] = u[1] - ge[1];
    out->next.energy = start->energy + (L->p.rule != OC_RULE_EQ20
                                            ? dissipation_implicit(L, yp, ap)
                                            : dissipation_eq20(L, a, ap, out->q));
}

void oc_law_step(const oc_law *L, const oc_state *start, const double u_in[2], double N,
                 oc_step *out) {
    /* The caller has typically just stored the inputs, one value at a time
     * (a master's set call).  Read as a pair, as clang vectorizes the
     * difference in trial(), the load waits until both stores have retired
     * (store forwarding fails).  A volatile read is never paired. */
    const double u[2] = {*(const volatile double *)&u_in[0], *(const volatile double *)&u_in[1]};
    /* Each field of the result is written once, by the part that knows it:
     * a stick step, most steps, writes 10 numbers, not a copy of the start
     * followed by the fields that change. */
    out->next.u[0] = u[0];
    out->next.u[1] = u[1];
    out->next.N = N;
    /* The steps of docs/explanation/law.md, "One step".  1: open. */
    if (!(N > 0)) {
        oc_step_open(start, u, out);
        return;
    }
    /* 2: the elastic trial, and the stick test. */
    double a[2];
    oc_trial(L, start, u, a);

    /* The stick test |a_tr| <= N, i.e. Phi(q_tr, N) <= 0.  A committed force
     * lies on or inside the yield surface to a few rounding errors of N;
     * such a trial sticks, so held inputs stick: n_tr <= lim.  Most steps
     * stick well inside, which the squares tell without the square root:
     * sq <= lim^2 exactly implies sqrt(sq) <= lim after rounding, and the
     * factor (1 - 4 eps) covers the two roundings of lim2c, which is normal
     * wherever sq >= 2^-900 passes.  Within it the decision is the square
     * root's, bit for bit (sq is what norm2 takes the root of in this
     * range), and is taken by it everywhere else.  (Written out here, not
     * as a function of its own: so gcc keeps the trial in registers on the
     * way to a stick.) */
    const double lim = N * (1.0 + 8 * DBL_EPSILON);
    const double sq = a[0] * a[0] + a[1] * a[1];
    const double lim2c = (lim * lim) * (1.0 - 4 * DBL_EPSILON);
    const int surely_inside = sq <= lim2c && sq >= 0x1p-900 && sq <= 0x1p1000;
    const double n_tr = surely_inside ? 0.0 : norm2(a[0], a[1]);
    if (surely_inside || n_tr <= lim) {
        oc_step_stick(L, start, a, out);
        return;
    }

    /* 3: slip, the return map onto the yield surface by the rule, and the
     * state it commits. */
    out->contact = OC_SLIP;
    double p[2], scale, yp[2] = {0.0, 0.0}, ap[2];
    if (L->p.rule == OC_RULE_EQ20)
        return_map_eq20(L, a, sq, n_tr, N, p, &scale, out);
    else
        return_map_implicit(L, a, sq, n_tr, N, p, &scale, yp, out);
    on_yield_surface(p, scale, N, ap);
    step_slip(L, start, u, a, ap, yp, out);
}

/* ==== 5b. Many steps with one law: the slipping cells' solves interleaved ==== */

/* The implicit rules' slip from the trial a, given the solve's root y, p,
 * 1 / |p| and w_i / max w, 1 / max w (w_i = 1 + y sig_hat_i):
 * return_map_implicit's first branch after its solve, on_yield_surface and
 * step_slip, in their order. */
static OC_ALWAYS_INLINE void slip_implicit_finish(const oc_law *L, const oc_state *start,
                                                  const double u[2], const double a[2], double N,
                                                  double y, const double p[2], double inv_np,
                                                  double w0, double w1, double inv_wmax,
                                                  oc_step *out) {
    out->contact = OC_SLIP;
    double yp[2], ap[2];
    const double scale = N * inv_np;
    yp[0] = y * (p[0] * scale);
    yp[1] = y * (p[1] * scale);
    out->dgamma = y * L->inv_sigma_ref;
    out->w[0] = w0;
    out->w[1] = w1;
    out->inv_wmax = inv_wmax;
    on_yield_surface(p, scale, N, ap);
    step_slip(L, start, u, a, ap, yp, out);
}

/* A slipping cell of oc_law_step_rest: its trial's norm and scale. */
typedef struct {
    const oc_rest *r;
    double n_tr, sc;
} slip_cell;

/* The cell's step once its solve gave y, p and 1 / |p|. */
static OC_ALWAYS_INLINE void slip_cell_finish(const oc_law *L, const slip_cell *c, double y,
                                              const double p[2], double inv_np, double w0,
                                              double w1, double inv_wmax) {
    oc_step *o = c->r->out;
    const double uk[2] = {o->next.u[0], o->next.u[1]};
    slip_implicit_finish(L, c->r->start, uk, c->r->a, o->next.N, y, p, inv_np, w0, w1, inv_wmax,
                         o);
}

#ifdef OC_VECTOR_LANES
/* Two cells in the two lanes of a vector (dgamma2_*): one vector division
 * serves two cells, and the divisions are what the slip's time goes to (the
 * square roots stay one a lane: sqrt may set errno).  A lane done goes on
 * being evaluated (harmlessly: nothing traps) until the other is; its
 * results are those of the evaluation that ended it. */
typedef struct {
    dgamma2_solve s;
    int done[2];
    double p0[2], p1[2], inv_norm[2], root[2]; /* a lane's, once done */
} dgamma_pair;

/* One evaluation of both lanes: 1 when both are done. */
static OC_ALWAYS_INLINE int dgamma_pair_step(dgamma_pair *S, const double sh[2]) {
    dgamma2_eval E;
    const v2m end = dgamma2_step(&S->s, sh, &E);
    v2d p0, p1, inv_norm, root;
    dgamma2_root(&S->s, &E, &p0, &p1, &inv_norm, &root);
    for (int l = 0; l < 2; ++l)
        if (!S->done[l] && end[l]) {
            S->done[l] = 1;
            S->p0[l] = p0[l];
            S->p1[l] = p1[l];
            S->inv_norm[l] = inv_norm[l];
            S->root[l] = root[l];
        }
    return S->done[0] && S->done[1];
}

/* Solves and finishes n <= OC_LANES slipping cells, two a vector, the
 * vectors' evaluations in turn (independent chains of square roots and
 * divisions, which the processor overlaps).  An odd cell out fills both
 * lanes of its vector. */
static void slip_lanes(const oc_law *L, const slip_cell c[], int n) {
    enum { PAIRS = (OC_LANES + 1) / 2 };
    const int pairs = (n + 1) / 2;
    dgamma_pair S[PAIRS];
    for (int v = 0; v < pairs; ++v) {
        const slip_cell *c0 = &c[2 * v], *c1 = 2 * v + 1 < n ? &c[2 * v + 1] : c0;
        const v2d sc = {c0->sc, c1->sc};
        const v2d ar0 = (v2d){c0->r->a[0], c1->r->a[0]} * sc;
        const v2d ar1 = (v2d){c0->r->a[1], c1->r->a[1]} * sc;
        const v2d n_tr = (v2d){c0->n_tr, c1->n_tr} * sc;
        const v2d N = (v2d){c0->r->out->next.N, c1->r->out->next.N} * sc;
        dgamma2_start(ar0, ar1, ar0 * ar0 + ar1 * ar1, n_tr, N, L->sig_hat, &S[v].s);
        S[v].done[0] = S[v].done[1] = 0;
    }
    for (int left = pairs; left > 0;)
        for (int v = 0; v < pairs; ++v)
            if (!(S[v].done[0] && S[v].done[1]) && dgamma_pair_step(&S[v], L->sig_hat)) --left;
    for (int v = 0; v < pairs; ++v) {
        const v2d y = {S[v].root[0], S[v].root[1]};
        v2d w0, w1, inv_wmax;
        dgamma2_weights(y, L->sig_hat, &w0, &w1, &inv_wmax);
        for (int l = 0; l < 2 && 2 * v + l < n; ++l) {
            const double p[2] = {S[v].p0[l], S[v].p1[l]};
            slip_cell_finish(L, &c[2 * v + l], y[l], p, S[v].inv_norm[l], w0[l], w1[l],
                             inv_wmax[l]);
        }
    }
}
#else
/* Without vector extensions: the lanes as scalars, the functions of
 * oc_law_step's own solve (dgamma1_*), evaluations in turn. */
static void slip_lanes(const oc_law *L, const slip_cell c[], int n) {
    dgamma1_solve S[OC_LANES];
    double p[OC_LANES][2], inv_np[OC_LANES], y[OC_LANES];
    int done[OC_LANES];
    for (int l = 0; l < n; ++l) {
        const double as0 = c[l].r->a[0] * c[l].sc, as1 = c[l].r->a[1] * c[l].sc;
        dgamma1_start(as0, as1, as0 * as0 + as1 * as1, c[l].n_tr * c[l].sc,
                      c[l].r->out->next.N * c[l].sc, L->sig_hat, &S[l]);
        done[l] = 0;
    }
    for (int left = n; left > 0;)
        for (int l = 0; l < n; ++l) {
            dgamma1_eval E;
            if (!done[l] && dgamma1_step(&S[l], L->sig_hat, &E)) {
                dgamma1_root(&S[l], &E, &p[l][0], &p[l][1], &inv_np[l], &y[l]);
                done[l] = 1;
                --left;
            }
        }
    for (int l = 0; l < n; ++l) {
        double w0, w1, inv_wmax;
        dgamma1_weights(y[l], L->sig_hat, &w0, &w1, &inv_wmax);
        slip_cell_finish(L, &c[l], y[l], p[l], inv_np[l], w0, w1, inv_wmax);
    }
}
#endif

void oc_law_step_rest(const oc_law *L, const oc_rest rest[], int n) {
    /* 1: what oc_law_step does after its first stick test: a trial whose
     * square is normal sticks by its square root; a cell that slips by an
     * implicit rule where oc_law_step takes its fast solve waits for 2; any
     * other is oc_law_step's own.  A larger n goes in chunks: the cells are
     * independent, and slip[] holds OC_BATCH_MAX. */
    for (; n > OC_BATCH_MAX; n -= OC_BATCH_MAX, rest += OC_BATCH_MAX)
        oc_law_step_rest(L, rest, OC_BATCH_MAX);
    slip_cell slip[OC_BATCH_MAX];
    int n_slip = 0;
    const int fast = L->p.rule != OC_RULE_EQ20 && L->kappa <= 1e20;
    for (int k = 0; k < n; ++k) {
        oc_step *o = rest[k].out;
        const oc_state *start = rest[k].start;
        const double *a = rest[k].a, Nk = o->next.N;
        const double lim = Nk * (1.0 + 8 * DBL_EPSILON);
        const double sq = a[0] * a[0] + a[1] * a[1];
        const int normal = sq >= 0x1p-900 && sq <= 0x1p1000;
        const double n_tr = normal ? sqrt(sq) : 0.0; /* norm2's, sq being normal */
        if (normal && n_tr <= lim) {
            oc_step_stick(L, start, a, o);
            continue;
        }
        if (!normal || !fast || !(n_tr <= 1e10 * Nk)) {
            const double uk[2] = {o->next.u[0], o->next.u[1]};
            oc_law_step(L, start, uk, Nk, o);
            continue;
        }
        slip_cell *c = &slip[n_slip++];
        c->r = &rest[k];
        c->n_tr = n_tr;
        c->sc = pow2_root_inverse(sq); /* trial_scale's, sq being normal */
    }
    /* 2: the slipping cells OC_LANES at a time. */
    for (int first = 0; first < n_slip; first += OC_LANES) {
        const int lanes = n_slip - first < OC_LANES ? n_slip - first : OC_LANES;
        if (lanes == 1) { /* nothing to interleave: the cell's own step, in registers */
            const oc_rest *r = slip[first].r;
            const double uk[2] = {r->out->next.u[0], r->out->next.u[1]};
            oc_law_step(L, r->start, uk, r->out->next.N, r->out);
            break;
        }
        slip_lanes(L, &slip[first], lanes);
    }
}

void oc_law_step_batch(const oc_law *L, const oc_state *const start[], const double u[][2],
                       const double N[], oc_step out[], int n) {
    for (; n > OC_BATCH_MAX; n -= OC_BATCH_MAX) { /* in chunks: rest[] holds OC_BATCH_MAX */
        oc_law_step_batch(L, start, u, N, out, OC_BATCH_MAX);
        start += OC_BATCH_MAX, u += OC_BATCH_MAX, N += OC_BATCH_MAX, out += OC_BATCH_MAX;
    }
    oc_rest rest[OC_BATCH_MAX];
    int n_rest = 0;
    for (int k = 0; k < n; ++k) {
        const double uk[2] = {u[k][0], u[k][1]};
        oc_rest *r = &rest[n_rest];
        if (!oc_law_step_quick(L, start[k], uk, N[k], &out[k], r->a)) {
            r->start = start[k];
            r->out = &out[k];
            ++n_rest;
        }
    }
    oc_law_step_rest(L, rest, n_rest);
}

/* ==== 6. The consistent tangent ==== */

/* dq/du and dq/dN of an eq. (20) slip: q = G t, t = N z / |z|, z = E t_tr,
 * t_tr = R a_tr, a_tr = P du + a_start (see oc_law.E20): dq/du = G D E R P
 * with D = N (I - zh zh^T) / |z|, zh = z / |z|, and dq/dN = G zh.  D E is
 * homogeneous of degree 0 in the scale of E and -1 in t_tr: it is formed at
 * t_tr scaled to [1, 2) and then divided by that scale.  Returns 1 where the
 * step's energy increment was clipped to 0 (its derivative is then 0). */
static int tangent_eq20(const oc_law *L, const oc_state *start, const double u[2], double N,
                        const oc_step *st, double dq_du[2][2], double dq_dN[2]) {
    double a[2], t[2], z[2];
    oc_trial(L, start, u, a);
    double sc;
    pow2_of(oc_norm2(a[0], a[1]), &sc);
    a[0] *= sc;
    a[1] *= sc;
    matvec(L->R, a, t);
    matvec(L->E20, t, z);
    const double nz = oc_norm2(z[0], z[1]);
    const double zh[2] = {z[0] / nz, z[1] / nz};
    double D[2][2], M[2][2];
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            D[i][j] = ((i == j ? 1.0 : 0.0) - zh[i] * zh[j]) * ((N * sc) / nz);
    matmul(D, L->E20, M);
    matmul(M, L->R, M);
    matmul(M, L->P, M);
    matmul(L->G, M, dq_du);
    dq_dN[0] = L->G[0][0] * zh[0] + L->G[0][1] * zh[1];
    dq_dN[1] = L->G[1][0] * zh[0] + L->G[1][1] * zh[1];
    const double dE = st->q[0] * (st->next.s[0] - start->s[0]) +
                      st->q[1] * (st->next.s[1] - start->s[1]);
    return !(dE > 0);
}

/* dq/du and dq/dN of an implicit rule's slip.  a_i(final) = a_tr,i / w_i
 * with |a| = N: differentiating the constraint gives d dgamma = (g . da_tr -
 * N dN) / c, with g_i = a_i / w_i, v_i = sigma_i a_i / w_i, c = a . v, so
 * dq/du = Minv (W^-1 - v g^T / c) P and dq/dN = Minv v N / c.  v g^T / c and
 * v N / c are homogeneous of degree 0 in sigma and in a, so they are formed
 * from sig_hat and a / N: no overflow.  W^-1 - v g^T / c is homogeneous of
 * degree -1 in w: formed from w / max w and multiplied by 1 / max w (see
 * oc_step.w). */
static void tangent_implicit(const oc_law *L, double N, const oc_step *st, double dq_du[2][2],
                             double dq_dN[2]) {
    const double *w = st->w, *sh = L->sig_hat;
    const double ah[2] = {st->next.a[0] / N, st->next.a[1] / N};
    const double g[2] = {ah[0] / w[0], ah[1] / w[1]};
    const double v[2] = {sh[0] * ah[0] / w[0], sh[1] * ah[1] / w[1]};
    const double c = ah[0] * v[0] + ah[1] * v[1];
    double Da[2][2];
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            Da[i][j] = ((i == j ? 1.0 / w[i] : 0.0) - (v[i] / c) * g[j]) * st->inv_wmax;
    double T[2][2];
    matmul(Da, L->P, T);
    matmul(L->Minv, T, dq_du);
    const double daN[2] = {v[0] / c, v[1] / c};
    matvec(L->Minv, daN, dq_dN);
}

void oc_law_jacobian(const oc_law *L, const oc_state *start, const double u[2], double N,
                     const oc_step *st, double J[OC_JAC_ROWS][OC_JAC_COLS]) {
    double dq_du[2][2] = {{0, 0}, {0, 0}};
    double dq_dN[2] = {0, 0};
    double ds_du[2][2] = {{0, 0}, {0, 0}};
    double ds_dN[2] = {0, 0};
    int eq20_clamped = 0;

    if (st->contact == OC_OPEN) {
        /* no force; the slip follows the body */
        ds_du[0][0] = ds_du[1][1] = 1.0;
    } else if (st->contact == OC_STICK) {
        /* q = B (u - s) with s held */
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j) dq_du[i][j] = L->B[i][j];
    } else {
        if (L->p.rule == OC_RULE_EQ20)
            eq20_clamped = tangent_eq20(L, start, u, N, st, dq_du, dq_dN);
        else
            tangent_implicit(L, N, st, dq_du, dq_dN);
        /* s = u - B^-1 q */
        double Bi_dq[2][2];
        matmul(L->Binv, dq_du, Bi_dq);
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j) ds_du[i][j] = (i == j ? 1.0 : 0.0) - Bi_dq[i][j];
        double Bi_dqN[2];
        matvec(L->Binv, dq_dN, Bi_dqN);
        ds_dN[0] = -Bi_dqN[0];
        ds_dN[1] = -Bi_dqN[1];
    }

    /* The outputs: T = -q, s, and energy = E_n + q . (s - s_n), whose
     * derivative is the dissipation increment's (the step computes the same
     * increment in a sign-safe form). */
    const double ds[2] = {st->next.s[0] - start->s[0], st->next.s[1] - start->s[1]};
    for (int j = 0; j < 2; ++j) {
        J[0][j] = -dq_du[0][j];
        J[1][j] = -dq_du[1][j];
        J[2][j] = ds_du[0][j];
        J[3][j] = ds_du[1][j];
        J[4][j] = eq20_clamped ? 0.0
                               : dq_du[0][j] * ds[0] + dq_du[1][j] * ds[1] +
                                     st->q[0] * ds_du[0][j] + st->q[1] * ds_du[1][j];
    }
    J[0][2] = -dq_dN[0];
    J[1][2] = -dq_dN[1];
    J[2][2] = ds_dN[0];
    J[3][2] = ds_dN[1];
    J[4][2] = eq20_clamped ? 0.0
                           : dq_dN[0] * ds[0] + dq_dN[1] * ds[1] + st->q[0] * ds_dN[0] +
                                 st->q[1] * ds_dN[1];
}

/* ==== 7. A committed state's admissibility ==== */

oc_state oc_state_unloaded(double s1, double s2, double energy) {
    oc_state st = {{s1, s2}, 0.0, {0.0, 0.0}, {s1, s2}, energy};
    return st;
}

const char *oc_state_check(const oc_law *L, const oc_state *st) {
    (void)L;
    const double v[] = {st->u[0], st->u[1], st->N,    st->a[0],
                        st->a[1], st->s[0], st->s[1], st->energy};
    if (!all_finite(v, sizeof v / sizeof v[0])) return "a committed value is not finite";
    if (!(st->energy >= 0)) return "the dissipated energy is negative";
    if (!(st->N > 0)) {
        if (st->a[0] != 0 || st->a[1] != 0) return "an open contact carries a force";
        if (st->s[0] != st->u[0] || st->s[1] != st->u[1])
            return "an open contact's slip does not follow the body";
        return NULL;
    }
    if (!(oc_norm2(st->a[0], st->a[1]) <= st->N * (1.0 + 64 * DBL_EPSILON)))
        return "the committed force lies outside the yield surface";
    return NULL;
}
