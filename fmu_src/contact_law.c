/* Return mapping for the coupled orthotropic adhesion-friction law.
 * The derivation of the yield coordinates and of the tangent is in
 * docs/law.md; the comments here say why the code takes its shape. */
#include "contact_law.h"

#include <float.h>
#include <math.h>
#include <stddef.h>

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

static int all_finite(const double *v, size_t n) {
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(v[i])) return 0;
    return 1;
}

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

int oc_law_init(oc_law *out, const oc_params *p) {
    if (oc_params_check(p)) return -1;
    oc_law L;
    L.p = *p;
    rotated_diag(p->alpha, p->eps1, p->eps2, L.B);
    rotated_diag(p->alpha, 1.0 / p->eps1, 1.0 / p->eps2, L.Binv);
    rotated_diag(p->beta, 1.0 / (p->mu1 * p->mu1), 1.0 / (p->mu2 * p->mu2), L.F);
    double Fh[2][2], Fhinv[2][2], S[2][2];
    rotated_diag(p->beta, 1.0 / p->mu1, 1.0 / p->mu2, Fh);
    rotated_diag(p->beta, p->mu1, p->mu2, Fhinv);

    /* With p = F^(1/2) q the slip step reads p = (I + dgamma S)^-1 p_tr for a
     * symmetric positive definite S, whatever the rule. */
    if (p->rule == OC_RULE_ASSOCIATED) {
        matmul(Fh, L.B, S);
        matmul(S, Fh, S);
    } else {
        matmul(Fhinv, L.Binv, S);
        matmul(S, Fhinv, S);
    }
    /* One Jacobi rotation diagonalises a symmetric 2x2 matrix exactly,
     * without the cancellation of the characteristic-polynomial formula. */
    const double th = 0.5 * atan2(S[0][1] + S[1][0], S[0][0] - S[1][1]);
    const double c = cos(th), s = sin(th);
    const double V[2][2] = {{c, -s}, {s, c}};
    const double Vt[2][2] = {{c, s}, {-s, c}};
    L.sigma[0] = c * c * S[0][0] + 2 * c * s * S[0][1] + s * s * S[1][1];
    L.sigma[1] = s * s * S[0][0] - 2 * c * s * S[0][1] + c * c * S[1][1];
    /* The rotation gets the larger eigenvalue to full relative accuracy, the
     * smaller one only to DBL_EPSILON times the larger.  det S is known
     * exactly from the parameters, so the smaller follows from it. */
    const double detF = 1.0 / (p->mu1 * p->mu1 * p->mu2 * p->mu2), detB = p->eps1 * p->eps2;
    const double detS = p->rule == OC_RULE_ASSOCIATED ? detF * detB : 1.0 / (detF * detB);
    const int big = L.sigma[0] >= L.sigma[1] ? 0 : 1;
    L.sigma[1 - big] = detS / L.sigma[big];

    double M[2][2];
    matmul(Vt, Fh, M);
    matmul(M, L.B, L.P);
    matmul(Fhinv, V, L.Minv);
    matmul(L.B, L.F, L.BF);
    L.P_norm = fmax(fabs(L.P[0][0]) + fabs(L.P[0][1]), fabs(L.P[1][0]) + fabs(L.P[1][1]));

    if (!all_finite(&L.B[0][0], 4) || !all_finite(&L.Binv[0][0], 4) ||
        !all_finite(&L.F[0][0], 4) || !all_finite(&L.P[0][0], 4) ||
        !all_finite(&L.Minv[0][0], 4) || !all_finite(L.sigma, 2) ||
        !all_finite(&L.BF[0][0], 4) || !(L.sigma[0] > 0) || !(L.sigma[1] > 0))
        return -1;
    *out = L;
    return 0;
}

/* Solves sum_i a_i^2 / (1 + x sigma_i)^2 = rho^2 for x > 0, given |a| = 1 > rho
 * (the caller divides by the trial norm, so that no square under- or
 * overflows).  k(x) = rho / |p(x)| - 1 is a power mean of exponent -2 of the
 * affine 1 + x sigma_i, hence concave and increasing: Newton from the left of
 * the root climbs monotonically to it, and from the right it lands on the
 * left in one step.  The first step is Halley's from x = 0 (cubic, exact
 * when sigma_1 = sigma_2), which leaves typically one Newton step to reach
 * rounding level; that last step is taken to first order (see below).
 * Returns x and the p (and |p|) of the last evaluation. */
static double solve_dgamma(const double a[2], const double sigma[2], double rho, double p[2],
                           double *norm) {
    const double inv_rho = 1.0 / rho, delta = 1.0 - rho;
    /* k(0) = -delta, k'(0) = rho m1, k''(0) = -3 rho v: the moments of sigma
     * under the weights a_i^2 (which sum to 1). */
    const double wt0 = a[0] * a[0], wt1 = a[1] * a[1];
    const double m1 = wt0 * sigma[0] + wt1 * sigma[1];
    const double d0 = sigma[0] - m1, d1 = sigma[1] - m1;
    const double v = wt0 * d0 * d0 + wt1 * d1 * d1;
    const double den = 2 * rho * m1 * m1 - 3 * delta * v;
    /* Far from the root Halley's denominator can vanish: take Newton's step. */
    double x = den > rho * m1 * m1 ? 2 * delta * m1 / den : delta * inv_rho / m1;
    /* Iterate on g_i = W p_i with W = w_0 w_1, w_i = 1 + x sigma_i, so that
     * an iteration costs one square root and one division:
     * m = W |p|, residual m - rho W, Newton step (m - rho W) m^2 / (rho C)
     * with C = g_0^2 sigma_0 w_1 + g_1^2 sigma_1 w_0. */
    double p0, p1, n;
    for (int it = 0;; ++it) {
        const double w0x = 1.0 + x * sigma[0], w1x = 1.0 + x * sigma[1], W = w0x * w1x;
        const double g0 = a[0] * w1x, g1 = a[1] * w0x;
        const double m = sqrt(g0 * g0 + g1 * g1);
        const double res = m - rho * W;
        double dx = 0.0;
        if (fabs(res) > 2 * DBL_EPSILON * rho * W && it < 100) {
            const double C = g0 * g0 * sigma[0] * w1x + g1 * g1 * sigma[1] * w0x;
            dx = res * m * m * inv_rho / C;
            if (fabs(dx) > 1e-8 * x) {
                x = fmax(x + dx, 0.0);
                continue;
            }
        }
        /* Converged, or one step short of it: both the Newton error after
         * that step and the Taylor remainder of p are below (dx/x)^2 <= 1e-16
         * relative, so the step is taken to first order. */
        const double invW = 1.0 / W;
        p0 = g0 * invW * (1.0 - sigma[0] * w1x * invW * dx);
        p1 = g1 * invW * (1.0 - sigma[1] * w0x * invW * dx);
        n = dx == 0.0 ? m * invW : sqrt(p0 * p0 + p1 * p1);
        x += dx;
        break;
    }
    p[0] = p0;
    p[1] = p1;
    *norm = n;
    return x;
}

void oc_law_step(const oc_law *L, const oc_state *start, const double u[2], double N,
                 oc_step *out) {
    out->dgamma = 0.0;
    out->w[0] = out->w[1] = 1.0;
    out->next = *start;

    if (!(N > 0)) {
        /* Open: no force, and the slip follows the body so that a new contact
         * starts unloaded.  Released elastic energy is not dissipation. */
        out->contact = OC_OPEN;
        out->q[0] = out->q[1] = 0.0;
        out->a[0] = out->a[1] = 0.0;
        out->next.s[0] = u[0];
        out->next.s[1] = u[1];
        return;
    }

    const double e[2] = {u[0] - start->s[0], u[1] - start->s[1]};
    double a[2];
    matvec(L->P, e, a);
    double n_tr = sqrt(a[0] * a[0] + a[1] * a[1]);
    if (!isfinite(n_tr)) n_tr = hypot(a[0], a[1]); /* squares overflowed */
    /* u - s is computed with an absolute rounding error of order
     * DBL_EPSILON (|u| + |s|); a trial within that distance of the yield
     * surface cannot be told from one on it, and must stick, or held inputs
     * after a slip step would slip again by rounding noise. */
    const double mag = fmax(fabs(u[0]), fabs(u[1])) + fmax(fabs(start->s[0]), fabs(start->s[1]));
    const double tol = 16 * DBL_EPSILON * (N + L->P_norm * mag);

    if (n_tr <= N + tol) {
        out->contact = OC_STICK;
        matvec(L->B, e, out->q);
        out->a[0] = a[0];
        out->a[1] = a[1];
        return;
    }

    out->contact = OC_SLIP;
    if (L->p.rule == OC_RULE_EQ20) {
        double qtr[2], y[2], Fy[2];
        matvec(L->B, e, qtr);
        matvec(L->BF, qtr, y);
        matvec(L->F, y, Fy);
        const double ny = sqrt(y[0] * Fy[0] + y[1] * Fy[1]);
        out->q[0] = N * y[0] / ny;
        out->q[1] = N * y[1] / ny;
        out->a[0] = out->a[1] = 0.0; /* unused by the eq. (20) tangent */
    } else {
        const double inv_ntr = 1.0 / n_tr;
        const double an[2] = {a[0] * inv_ntr, a[1] * inv_ntr};
        double ap[2], n_p;
        const double x = solve_dgamma(an, L->sigma, N * inv_ntr, ap, &n_p);
        out->dgamma = x;
        out->w[0] = 1.0 + x * L->sigma[0];
        out->w[1] = 1.0 + x * L->sigma[1];
        /* Newton stops within an ulp or two of the yield surface; the radial
         * scaling puts the force on it to rounding of one product. */
        const double scale = N / n_p;
        ap[0] *= scale;
        ap[1] *= scale;
        out->a[0] = ap[0];
        out->a[1] = ap[1];
        matvec(L->Minv, ap, out->q);
    }
    /* The slip follows from the elastic relation rather than from
     * s_n + dgamma G q, so that held inputs reproduce q exactly next step. */
    double e_new[2];
    matvec(L->Binv, out->q, e_new);
    out->next.s[0] = u[0] - e_new[0];
    out->next.s[1] = u[1] - e_new[1];
    out->next.energy = start->energy + out->q[0] * (out->next.s[0] - start->s[0]) +
                       out->q[1] * (out->next.s[1] - start->s[1]);
}

void oc_law_jacobian(const oc_law *L, const oc_state *start, const double u[2], double N,
                     const oc_step *st, double J[OC_JAC_ROWS][OC_JAC_COLS]) {
    (void)u;
    double dq_du[2][2] = {{0, 0}, {0, 0}};
    double dq_dN[2] = {0, 0};
    double ds_du[2][2] = {{0, 0}, {0, 0}};
    double ds_dN[2] = {0, 0};

    if (st->contact == OC_OPEN) {
        ds_du[0][0] = ds_du[1][1] = 1.0;
    } else if (st->contact == OC_STICK) {
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j) dq_du[i][j] = L->B[i][j];
    } else {
        if (L->p.rule == OC_RULE_EQ20) {
            /* q = N y / |y|_F with y = B F B (u - s_n). */
            const double e[2] = {u[0] - start->s[0], u[1] - start->s[1]};
            double qtr[2], y[2], Fy[2], BFB[2][2];
            matvec(L->B, e, qtr);
            matvec(L->BF, qtr, y);
            matvec(L->F, y, Fy);
            matmul(L->BF, L->B, BFB);
            const double ny = sqrt(y[0] * Fy[0] + y[1] * Fy[1]);
            double D[2][2];
            for (int i = 0; i < 2; ++i)
                for (int j = 0; j < 2; ++j)
                    D[i][j] = N * ((i == j ? 1.0 : 0.0) / ny - y[i] * Fy[j] / (ny * ny * ny));
            matmul(D, BFB, dq_du);
            dq_dN[0] = y[0] / ny;
            dq_dN[1] = y[1] / ny;
        } else {
            /* a_i(final) = a_tr,i / w_i with |a| = N: differentiating the
             * constraint gives d dgamma = (g . da_tr - N dN) / c, with
             * g_i = a_i / w_i, v_i = sigma_i a_i / w_i, c = a . v. */
            const double *a = st->a, *w = st->w;
            const double g[2] = {a[0] / w[0], a[1] / w[1]};
            const double v[2] = {L->sigma[0] * a[0] / w[0], L->sigma[1] * a[1] / w[1]};
            const double c = a[0] * v[0] + a[1] * v[1];
            double Da[2][2];
            for (int i = 0; i < 2; ++i)
                for (int j = 0; j < 2; ++j)
                    Da[i][j] = (i == j ? 1.0 / w[i] : 0.0) - v[i] * g[j] / c;
            double T[2][2];
            matmul(Da, L->P, T);
            matmul(L->Minv, T, dq_du);
            const double daN[2] = {v[0] * N / c, v[1] * N / c};
            matvec(L->Minv, daN, dq_dN);
        }
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

    /* energy = E_n + q . (s - s_n) */
    const double ds[2] = {st->next.s[0] - start->s[0], st->next.s[1] - start->s[1]};
    for (int j = 0; j < 2; ++j) {
        J[0][j] = -dq_du[0][j];
        J[1][j] = -dq_du[1][j];
        J[2][j] = ds_du[0][j];
        J[3][j] = ds_du[1][j];
        J[4][j] = dq_du[0][j] * ds[0] + dq_du[1][j] * ds[1] + st->q[0] * ds_du[0][j] +
                  st->q[1] * ds_du[1][j];
    }
    J[0][2] = -dq_dN[0];
    J[1][2] = -dq_dN[1];
    J[2][2] = ds_dN[0];
    J[3][2] = ds_dN[1];
    J[4][2] = dq_dN[0] * ds[0] + dq_dN[1] * ds[1] + st->q[0] * ds_dN[0] + st->q[1] * ds_dN[1];
}

int oc_step_is_finite(const oc_step *st) {
    return all_finite(st->q, 2) && all_finite(st->next.s, 2) && isfinite(st->next.energy) &&
           isfinite(st->dgamma);
}
