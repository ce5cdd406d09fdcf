/* The peer's law and instance (peer.h): the law as it reads on paper. */
#include "peer.h"

#include <math.h>
#include <string.h>

static void rot_diag(double t, double d1, double d2, double R[2][2]) {
    const double c = cos(t), s = sin(t);
    R[0][0] = c * c * d1 + s * s * d2;
    R[1][1] = s * s * d1 + c * c * d2;
    R[0][1] = R[1][0] = c * s * (d1 - d2);
}

static void mul(const double A[2][2], const double B[2][2], double C[2][2]) {
    double T[2][2];
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) T[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j];
    memcpy(C, T, sizeof T);
}

static void inv(const double A[2][2], double C[2][2]) {
    const double d = A[0][0] * A[1][1] - A[0][1] * A[1][0];
    double T[2][2] = {{A[1][1] / d, -A[0][1] / d}, {-A[1][0] / d, A[0][0] / d}};
    memcpy(C, T, sizeof T);
}

static void apply(const double A[2][2], const double x[2], double y[2]) {
    const double y0 = A[0][0] * x[0] + A[0][1] * x[1], y1 = A[1][0] * x[0] + A[1][1] * x[1];
    y[0] = y0;
    y[1] = y1;
}

static double dot(const double a[2], const double b[2]) { return a[0] * b[0] + a[1] * b[1]; }

/* |q|_F = sqrt(q . F q) */
static double fnorm(const double F[2][2], const double q[2]) {
    double Fq[2];
    apply(F, q, Fq);
    return sqrt(dot(q, Fq));
}

void peer_init(peer *P) {
    memset(P, 0, sizeof *P);
    P->mu1 = 0.408;
    P->mu2 = 0.625;
    P->eps1 = 12510.0;
    P->eps2 = 10000.0;
    P->alpha = 1.5707963267948966;
    P->beta = 0.0;
    P->rule = 2;
    P->contact = 1;
    P->phase = PEER_INSTANTIATED;
}

int peer_exit_init(peer *P) {
    if (!(P->mu1 > 0 && P->mu2 > 0 && P->eps1 > 0 && P->eps2 > 0) || P->rule < 1 || P->rule > 3)
        return -1;
    rot_diag(P->alpha, P->eps1, P->eps2, P->B);
    inv(P->B, P->Binv);
    rot_diag(P->beta, 1.0 / (P->mu1 * P->mu1), 1.0 / (P->mu2 * P->mu2), P->F);
    if (P->rule == 1) {
        memcpy(P->G, P->F, sizeof P->G);
    } else { /* G = (B F B)^-1 */
        double BFB[2][2];
        mul(P->B, P->F, BFB);
        mul(BFB, P->B, BFB);
        inv(BFB, P->G);
    }
    mul(P->B, P->G, P->BG);
    /* the contact starts unloaded where the body is */
    P->s[0] = P->u[0];
    P->s[1] = P->u[1];
    P->energy = 0.0;
    P->T[0] = P->T[1] = 0.0;
    P->contact = P->N > 0 ? 1 : 0;
    P->phase = PEER_STEP;
    return 0;
}

int peer_set_real(peer *P, unsigned vr, double v) {
    if (!isfinite(v)) return -1;
    const int params = P->phase == PEER_INSTANTIATED || P->phase == PEER_INIT;
    switch (vr) {
    case OC_VR_mu1: if (!params) return -1; P->mu1 = v; return 0;
    case OC_VR_mu2: if (!params) return -1; P->mu2 = v; return 0;
    case OC_VR_eps1: if (!params) return -1; P->eps1 = v; return 0;
    case OC_VR_eps2: if (!params) return -1; P->eps2 = v; return 0;
    case OC_VR_alpha: if (!params) return -1; P->alpha = v; return 0;
    case OC_VR_beta: if (!params) return -1; P->beta = v; return 0;
    case OC_VR_u1: P->u[0] = v; return 0;
    case OC_VR_u2: P->u[1] = v; return 0;
    case OC_VR_N: P->N = v; return 0;
    default: return -1;
    }
}

int peer_set_int(peer *P, unsigned vr, int v) {
    if (vr != OC_VR_slidingRule || !(P->phase == PEER_INSTANTIATED || P->phase == PEER_INIT)) return -1;
    P->rule = v;
    return 0;
}

int peer_get_real(const peer *P, unsigned vr, double *v) {
    switch (vr) {
    case OC_VR_mu1: *v = P->mu1; return 0;
    case OC_VR_mu2: *v = P->mu2; return 0;
    case OC_VR_eps1: *v = P->eps1; return 0;
    case OC_VR_eps2: *v = P->eps2; return 0;
    case OC_VR_alpha: *v = P->alpha; return 0;
    case OC_VR_beta: *v = P->beta; return 0;
    case OC_VR_u1: *v = P->u[0]; return 0;
    case OC_VR_u2: *v = P->u[1]; return 0;
    case OC_VR_N: *v = P->N; return 0;
    case OC_VR_T1: *v = P->T[0]; return 0;
    case OC_VR_T2: *v = P->T[1]; return 0;
    case OC_VR_s1: *v = P->s[0]; return 0;
    case OC_VR_s2: *v = P->s[1]; return 0;
    case OC_VR_dissipatedEnergy: *v = P->energy; return 0;
    default: return -1;
    }
}

int peer_get_int(const peer *P, unsigned vr, int *v) {
    if (vr == OC_VR_contactState) *v = P->contact;
    else if (vr == OC_VR_slidingRule) *v = P->rule;
    else return -1;
    return 0;
}

/* q(dg) = (I + dg B G)^-1 q_tr */
static void q_at(const peer *P, double dg, const double qtr[2], double q[2], double Minv[2][2]) {
    const double M[2][2] = {{1.0 + dg * P->BG[0][0], dg * P->BG[0][1]},
                            {dg * P->BG[1][0], 1.0 + dg * P->BG[1][1]}};
    inv(M, Minv);
    apply(Minv, qtr, q);
}

/* Safeguarded Newton on f(dg) = |q(dg)|_F - N, f(0) > 0, f falling to -N:
 * the bracket [lo, hi] tightens with every evaluation; a Newton step that
 * leaves it is replaced by bisection (or by growth before hi is known). */
static double solve_dgamma(const peer *P, const double qtr[2], double N, double q[2]) {
    double lo = 0.0, hi = INFINITY, dg = 0.0;
    for (int it = 0; it < 100; ++it) {
        double Minv[2][2];
        q_at(P, dg, qtr, q, Minv);
        const double n = fnorm(P->F, q), f = n - N;
        if (fabs(f) <= 1e-15 * N) break;
        if (f > 0) lo = dg;
        else hi = dg;
        double BGq[2], dq[2], Fq[2];
        apply(P->BG, q, BGq);
        apply(Minv, BGq, dq); /* dq/ddg = -Minv B G q */
        apply(P->F, q, Fq);
        const double fp = -dot(Fq, dq) / n;
        double next = dg - f / fp;
        if (!(next > lo && next < hi))
            next = isfinite(hi) ? 0.5 * (lo + hi) : (lo > 0 ? 4.0 * lo : 1.0 / fabs(P->BG[0][0] + P->BG[1][1]));
        if (fabs(next - dg) <= 1e-16 * dg) {
            dg = next;
            q_at(P, dg, qtr, q, Minv);
            break;
        }
        dg = next;
    }
    return dg;
}

void peer_step(peer *P) {
    const double N = P->N;
    double q[2] = {0.0, 0.0};
    if (!(N > 0)) {
        P->contact = 0;
        P->s[0] = P->u[0];
        P->s[1] = P->u[1];
    } else {
        const double e[2] = {P->u[0] - P->s[0], P->u[1] - P->s[1]};
        double qtr[2];
        apply(P->B, e, qtr);
        if (fnorm(P->F, qtr) <= N) {
            P->contact = 1;
            q[0] = qtr[0];
            q[1] = qtr[1];
        } else {
            P->contact = 2;
            double dE;
            if (P->rule == 3) {
                double Fq[2], z[2];
                apply(P->F, qtr, Fq);
                apply(P->B, Fq, z);
                const double k = N / fnorm(P->F, z);
                q[0] = k * z[0];
                q[1] = k * z[1];
                const double dq[2] = {qtr[0] - q[0], qtr[1] - q[1]};
                double ds[2];
                apply(P->Binv, dq, ds);
                dE = fmax(dot(q, ds), 0.0);
            } else {
                const double dg = solve_dgamma(P, qtr, N, q);
                double Gq[2];
                apply(P->G, q, Gq);
                dE = dg * dot(q, Gq);
            }
            double Bq[2];
            apply(P->Binv, q, Bq);
            P->s[0] = P->u[0] - Bq[0];
            P->s[1] = P->u[1] - Bq[1];
            P->energy += dE;
        }
    }
    P->T[0] = 0.0 - q[0];
    P->T[1] = 0.0 - q[1];
}
