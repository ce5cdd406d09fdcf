/* The coupled orthotropic adhesion-friction law (Konyukhov & Schweizerhof):
 * one return-mapping step and its consistent tangent.  The derivations are
 * in docs/explanation/law.md, whose sections these follow; the comments here
 * say why the code takes its shape.
 *
 *   1. Arithmetic: 2x2 products, norms without overflow, power-of-two scales
 *      (law/arith.h)
 *   2. The parameters and the tensors they fix (B, F, the yield coordinates)
 *   3. Slip by the implicit rules: the plastic multiplier on the yield surface
 *      (its solve: law/slip_solve.inc, over the lanes of law/lanes.h)
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

#include "compiler.h"
#include "law/arith.h"
#include "law/lanes.h"

/* ==== 1. Arithmetic: law/arith.h ==== */

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
    if (th > 0.25 * 3.14159265358979323846)
        th -= 0.5 * 3.14159265358979323846;
    else if (th < -0.25 * 3.14159265358979323846)
        th += 0.5 * 3.14159265358979323846;
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
    if (!all_finite(&L.B[0][0], 4) || !all_finite(&L.Binv[0][0], 4) || !all_finite(&L.F[0][0], 4) ||
        !all_finite(&L.P[0][0], 4) || !all_finite(&L.Minv[0][0], 4) || !all_finite(&L.Y[0][0], 4) ||
        !all_finite(L.sigma, 2) || !all_finite(&L.R[0][0], 4) || !all_finite(&L.G[0][0], 4) ||
        !all_finite(&L.K[0][0], 4) || !all_finite(&L.E20[0][0], 4) || !(L.sigma[0] > 0) ||
        !(L.sigma[1] > 0) || !(L.sig_hat[0] > 0) || !(L.sig_hat[1] > 0) || !isfinite(L.kappa) ||
        !isfinite(L.inv_sigma_ref))
        return -1;
    *out = L;
    return 0;
}

/* ==== 3. Slip by the implicit rules: the plastic multiplier on the yield surface ==== */

/* The slip solve (law/slip_solve.inc: what it solves and how), over the lanes
 * of law/lanes.h: for one cell (dgamma1_*, oc_law_step's) and, where the
 * batch's cells go two to a vector, for two (dgamma2_*).  Its second
 * inclusion also gives the batch's lanes (slip_lanes), which solve and
 * finish the slipping cells of section 5b: */
typedef struct {
    const oc_unfinished *r;
    double n_tr, sc; /* the trial's norm and its power-of-two scale */
} slip_cell;
static OC_ALWAYS_INLINE void slip_cell_finish(const oc_law *L, const slip_cell *c, double y,
                                              const double p[2], double inv_np, double w0,
                                              double w1, double inv_wmax);
#define OC_SLIP_LANES 1
#include "law/slip_solve.inc"
#if OC_VECTORS
#define OC_SLIP_LANES 2
#include "law/slip_solve.inc"
#endif

/* One cell's solve (dgamma1_*, section 3's opening comment): y, and p (and
 * 1 / |p|) there. */
static OC_ALWAYS_INLINE double solve_dgamma(const double a_raw[2], double sq, double n_tr, double N,
                                            const double sh[2], double p[2], double *inv_norm) {
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
        if (!(fabs(dv) > 1e-15 * v)) break;   /* stalls at the root (or NaN: stop) */
        if (!(v + dv <= vmax)) dv = vmax - v; /* also for dv = inf */
        if (dv == 0.0) break;
        v += dv;
    }
    p[0] = c0;
    p[1] = c1;
    *inv_norm = 1.0 / n;
    return v;
}

/* The fast solve's gate, once: it needs W <= kappa / rho^2 < 1e40 at the
 * root (law/slip_solve.inc), which the law's part (fast_law, the same for
 * every cell) and the trial's part (fast_trial: not far outside the yield
 * surface, and of normal size to scale) guarantee.  Otherwise the far
 * solve. */
static OC_ALWAYS_INLINE int fast_law(const oc_law *L) { return L->kappa <= 1e20; }
static OC_ALWAYS_INLINE int fast_trial(double n_tr, double N) {
    return n_tr <= 1e10 * N && n_tr >= DBL_MIN;
}

/* The fast solve's slip from its root, once (a cell of oc_law_step and a
 * lane of the batch): from y = dgamma sigma_ref, p and 1 / |p|, and the
 * weights w_i / max w, 1 / max w (w_i = 1 + y sig_hat_i), the scale that
 * puts p on the yield surface, yp = y a as the energy needs it (a = p
 * scale), and what the tangent needs (oc_step.dgamma, w, inv_wmax). */
static OC_ALWAYS_INLINE void slip_of_root(const oc_law *L, double y, const double p[2],
                                          double inv_np, double N, double w0, double w1,
                                          double inv_wmax, double *scale, double yp[2],
                                          oc_step *out) {
    out->w[0] = w0;
    out->w[1] = w1;
    out->inv_wmax = inv_wmax;
    *scale = N * inv_np;
    yp[0] = y * (p[0] * *scale);
    yp[1] = y * (p[1] * *scale);
    out->dgamma = y * L->inv_sigma_ref;
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
    /* The fast solve runs on the trial scaled by the power of two that
     * brings |a| to [1, 2): the same numbers in any units, down to which
     * squares of a small component underflow (scaled only where |a|^2 left
     * a range, the units decided whether a_i^2 was subnormal). */
    double inv_np, scale;
    if (fast_law(L) && fast_trial(n_tr, N)) {
        const double sc = trial_scale(sq, n_tr);
        const double as[2] = {a[0] * sc, a[1] * sc};
        const double y = solve_dgamma(as, as[0] * as[0] + as[1] * as[1], n_tr * sc, N * sc,
                                      L->sig_hat, p, &inv_np);
        double w0, w1, inv_wmax;
        dgamma1_weights(y, L->sig_hat, &w0, &w1, &inv_wmax);
        slip_of_root(L, y, p, inv_np, N, w0, w1, inv_wmax, &scale, yp, out);
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

/* Open, the trial, the stick test and the stick step: oc_step_open,
 * oc_trial, oc_sticks_surely and oc_sticks_by_root, oc_step_stick
 * (contact_law.h), inline there for oc_law_step_begin. */

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
    out->next.energy =
        start->energy + (L->p.rule != OC_RULE_EQ20 ? dissipation_implicit(L, yp, ap)
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

    /* The stick test (contact_law.h): the squares', else the root's. */
    const double sq = a[0] * a[0] + a[1] * a[1];
    const int surely = oc_sticks_surely(sq, N);
    const double n_tr = surely ? 0.0 : norm2(a[0], a[1]);
    if (surely || oc_sticks_by_root(n_tr, N)) {
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

/* A slipping cell of the batch once its lane of the solve gave y, p, 1 / |p|
 * and the weights: the slip as oc_law_step's implicit rule finishes it. */
static OC_ALWAYS_INLINE void slip_cell_finish(const oc_law *L, const slip_cell *c, double y,
                                              const double p[2], double inv_np, double w0,
                                              double w1, double inv_wmax) {
    oc_step *o = c->r->out;
    const double uk[2] = {o->next.u[0], o->next.u[1]};
    const double N = o->next.N;
    const oc_state *start = c->r->start;
    const double *a = c->r->a;
    o->contact = OC_SLIP;
    double yp[2], ap[2], scale;
    slip_of_root(L, y, p, inv_np, N, w0, w1, inv_wmax, &scale, yp, o);
    on_yield_surface(p, scale, N, ap);
    step_slip(L, start, uk, a, ap, yp, o);
}

void oc_law_step_finish(const oc_law *L, const oc_unfinished pending[], int n) {
    /* 1: what oc_law_step does after the squares' stick test: a trial whose
     * square is normal sticks by its square root; a cell that slips by an
     * implicit rule where oc_law_step takes its fast solve waits for 2; any
     * other is oc_law_step's own.  The law's part of the gate is the same
     * for every cell.  A larger n goes in chunks: the cells are
     * independent, and slip[] holds OC_BATCH_MAX. */
    for (; n > OC_BATCH_MAX; n -= OC_BATCH_MAX, pending += OC_BATCH_MAX)
        oc_law_step_finish(L, pending, OC_BATCH_MAX);
    slip_cell slip[OC_BATCH_MAX];
    int n_slip = 0;
    const int fast = L->p.rule != OC_RULE_EQ20 && fast_law(L);
    for (int k = 0; k < n; ++k) {
        oc_step *o = pending[k].out;
        const oc_state *start = pending[k].start;
        const double *a = pending[k].a, Nk = o->next.N;
        const double sq = a[0] * a[0] + a[1] * a[1];
        const int normal = sq >= 0x1p-900 && sq <= 0x1p1000;
        const double n_tr = normal ? sqrt(sq) : 0.0; /* norm2's, sq being normal */
        if (normal && oc_sticks_by_root(n_tr, Nk)) {
            oc_step_stick(L, start, a, o);
            continue;
        }
        if (!normal || !fast || !fast_trial(n_tr, Nk)) {
            const double uk[2] = {o->next.u[0], o->next.u[1]};
            oc_law_step(L, start, uk, Nk, o);
            continue;
        }
        slip_cell *c = &slip[n_slip++];
        c->r = &pending[k];
        c->n_tr = n_tr;
        c->sc = pow2_root_inverse(sq); /* trial_scale's, sq being normal */
    }
    /* 2: the slipping cells OC_LANES at a time, in the batch's lanes
     * (law/slip_solve.inc's slip_lanes). */
    for (int first = 0; first < n_slip; first += OC_LANES) {
        const int lanes = n_slip - first < OC_LANES ? n_slip - first : OC_LANES;
        if (lanes == 1) { /* nothing to interleave: the cell's own step, in registers */
            const oc_unfinished *r = slip[first].r;
            const double uk[2] = {r->out->next.u[0], r->out->next.u[1]};
            oc_law_step(L, r->start, uk, r->out->next.N, r->out);
            break;
        }
        slip_lanes(L, &slip[first], lanes);
    }
}

void oc_law_step_batch(const oc_law *L, const oc_state *const start[], const double u[][2],
                       const double N[], oc_step out[], int n) {
    for (; n > OC_BATCH_MAX; n -= OC_BATCH_MAX) { /* in chunks: pending[] holds OC_BATCH_MAX */
        oc_law_step_batch(L, start, u, N, out, OC_BATCH_MAX);
        start += OC_BATCH_MAX, u += OC_BATCH_MAX, N += OC_BATCH_MAX, out += OC_BATCH_MAX;
    }
    oc_unfinished pending[OC_BATCH_MAX];
    int n_pending = 0;
    for (int k = 0; k < n; ++k) {
        const double uk[2] = {u[k][0], u[k][1]};
        oc_unfinished *r = &pending[n_pending];
        if (!oc_law_step_begin(L, start[k], uk, N[k], &out[k], r->a)) {
            r->start = start[k];
            r->out = &out[k];
            ++n_pending;
        }
    }
    oc_law_step_finish(L, pending, n_pending);
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
    const double dE =
        st->q[0] * (st->next.s[0] - start->s[0]) + st->q[1] * (st->next.s[1] - start->s[1]);
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
    J[4][2] = eq20_clamped
                  ? 0.0
                  : dq_dN[0] * ds[0] + dq_dN[1] * ds[1] + st->q[0] * ds_dN[0] + st->q[1] * ds_dN[1];
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
