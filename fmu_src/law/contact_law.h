/*
 * Coupled orthotropic adhesion-friction interface law (Konyukhov & Schweizerhof).
 *
 * This core knows nothing of FMI.  It holds the parameters, the derived
 * tensors, one return-mapping step and its consistent tangent (contact_law.c;
 * the derivations in docs/explanation/law.md).  Conventions
 * (docs/explanation/model-notes.md):
 *   q = B (u - s)  elastic tangential force [N]; the surface acts on the
 *                  body with T = -q.
 *   B = Q(alpha) diag(eps1, eps2) Q(alpha)^T        [N/m]
 *   F = Q(beta)  diag(1/mu1^2, 1/mu2^2) Q(beta)^T   [-]
 *   Phi(q, N) = sqrt(q . F q) - N
 */
#ifndef OC_CONTACT_LAW_H
#define OC_CONTACT_LAW_H

#include <float.h>
#include <math.h>

#include "compiler.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    OC_RULE_ASSOCIATED = 1, /* G = F: classical orthotropic Coulomb */
    OC_RULE_COUPLED = 2,    /* G = (B F B)^-1: Konyukhov-Schweizerhof */
    OC_RULE_EQ20 = 3        /* the paper's explicit eq. (20), step-size dependent */
} oc_rule;

typedef enum { OC_OPEN = 0, OC_STICK = 1, OC_SLIP = 2 } oc_contact;

typedef struct {
    double mu1, mu2;   /* friction coefficients along the friction axes [-] */
    double eps1, eps2; /* tangential stiffnesses along the adhesion axes [N/m] */
    double alpha;      /* adhesion axis 1, counterclockwise from X1 [rad] */
    double beta;       /* friction axis 1, counterclockwise from X1 [rad] */
    int rule;          /* an oc_rule */
} oc_params;

/* Everything a step needs that depends on the parameters only. */
typedef struct {
    oc_params p;
    double B[2][2], Binv[2][2], F[2][2];
    /* Yield coordinates: a = P (u - s) are the components of F^(1/2) q_tr in
     * the eigenbasis of the slip operator S, so that Phi = |a| - N and the
     * slip step decouples into a_i / (1 + dgamma sigma_i). */
    double P[2][2];
    double Minv[2][2]; /* q = Minv a */
    double sigma[2];   /* eigenvalues of S */
    /* eq. (20), q ~ B F q_tr, in the friction axes: with t = diag(1/mu)
     * Q(beta)^T q (so that |t| = |q|_F), t ~ E t_tr for E = diag(1/mu)
     * Q(gamma) diag(eps) Q(gamma)^T diag(1/mu), scaled to max|E| = 1 */
    double E20[2][2];
    double Y[2][2]; /* a = Y q: yield coordinates of a force */
    /* q = Minv a, factored as G R a with the rotation R = Q(beta)^T V and
     * G = Q(beta) diag(mu1, mu2): each friction-axis component of q is then
     * exact to rounding, however different mu1 and mu2 are (the product Minv
     * forms the smaller one by cancelling terms of the size of the larger). */
    double R[2][2], G[2][2];
    double K[2][2];   /* B^-1 G R: the elastic displacement of yield coordinates */
    double sigma_ref; /* the larger sigma: the slip solve works in dgamma sigma_ref */
    double inv_sigma_ref;
    double sig_hat[2]; /* sigma_i / sigma_ref, in (0, 1] */
    double kappa;      /* sigma_max / sigma_min: bounds how far the slip solve reaches */
} oc_law;

/* The internal state committed between steps.  The elastic force is kept
 * in yield coordinates a (with |a| <= N), not recomputed from u - s: a
 * step with held inputs then starts from exactly the force it committed,
 * however anisotropic B and F are, instead of from a difference of large
 * nearly equal displacements amplified by the stiff direction. */
typedef struct {
    double u[2];   /* inputs of the committed step: displacement [m] */
    double N;      /*   and normal force [N] */
    double a[2];   /* yield coordinates of the elastic force q [N] */
    double s[2];   /* slip [m] */
    double energy; /* dissipated energy [J] */
} oc_state;

/* The unloaded state with slip s [m] and dissipated energy [J]. */
oc_state oc_state_unloaded(double s1, double s2, double energy);

/* The result of one step, and what the tangent needs of it. */
typedef struct {
    double q[2];   /* elastic force [N]; T = -q */
    oc_state next; /* state after the step (next.a: yield coordinates of q) */
    int contact;   /* an oc_contact */
    /* What the tangent needs of a slip: w_i = 1 + dgamma sigma_i, kept as
     * w_i / max w and 1 / max w, which stay representable where dgamma and
     * w overflow (a trial far outside a tiny yield surface).  Not outputs:
     * nothing here may refuse a step.  Written by a slip step only (an open
     * or stick step leaves them as they were: its tangent needs none). */
    double dgamma;   /* plastic multiplier of the slip step (0 for eq. 20; may be inf) */
    double w[2];     /* (1 + dgamma sigma_i) / max_j (1 + dgamma sigma_j), in (0, 1] */
    double inv_wmax; /* 1 / max_j (1 + dgamma sigma_j), in [0, 1] */
} oc_step;

/* NULL if the parameters are admissible, otherwise why not. */
const char *oc_params_check(const oc_params *p);

/* Computes the derived tensors; returns 0, or -1 (and leaves law untouched)
 * if the parameters are inadmissible or lead to non-finite tensors. */
int oc_law_init(oc_law *law, const oc_params *p);

/* One return-mapping step from the committed state `start` with the inputs
 * u [m] and N [N].  Pure: it changes nothing but *out.  Homogeneous: the
 * result does not depend on the units (no absolute tolerance anywhere). */
void oc_law_step(const oc_law *law, const oc_state *start, const double u[2], double N,
                 oc_step *out);

/* ---- oc_law_step's open and stick steps, inline: contact_law.c steps by
 * these, and a caller stepping many cells (the patch) begins each cell's
 * step in its own loop (oc_law_step_begin) and leaves those that may slip
 * to oc_law_step_finish. ---- */

/* q = Minv a in its factored form (see oc_law.R): a rotation, then
 * G = Q(beta) diag(mu), whose entries never mix mu1 with mu2. */
static OC_ALWAYS_INLINE void oc_force_of(const oc_law *L, const double a[2], double q[2]) {
    const double r0 = L->R[0][0] * a[0] + L->R[0][1] * a[1];
    const double r1 = L->R[1][0] * a[0] + L->R[1][1] * a[1];
    q[0] = L->G[0][0] * r0 + L->G[0][1] * r1;
    q[1] = L->G[1][0] * r0 + L->G[1][1] * r1;
}

/* Open (N <= 0): no force, and the slip follows the body so that a new
 * contact starts unloaded.  Released elastic energy is not dissipation. */
static OC_ALWAYS_INLINE void oc_step_open(const oc_state *start, const double u[2], oc_step *out) {
    out->contact = OC_OPEN;
    out->q[0] = out->q[1] = 0.0;
    out->next.a[0] = out->next.a[1] = 0.0;
    out->next.s[0] = u[0];
    out->next.s[1] = u[1];
    out->next.energy = start->energy;
}

/* The trial in yield coordinates: the committed force plus the elastic
 * response to the change of the inputs, a_tr = a_n + P (u - u_n). */
static OC_ALWAYS_INLINE void oc_trial(const oc_law *L, const oc_state *start, const double u[2],
                                      double a[2]) {
    const double du[2] = {u[0] - start->u[0], u[1] - start->u[1]};
    const double y0 = L->P[0][0] * du[0] + L->P[0][1] * du[1];
    const double y1 = L->P[1][0] * du[0] + L->P[1][1] * du[1];
    a[0] = y0 + start->a[0];
    a[1] = y1 + start->a[1];
}

/* Stick: the trial is the force; the slip and the energy stay. */
static OC_ALWAYS_INLINE void oc_step_stick(const oc_law *L, const oc_state *start,
                                           const double a[2], oc_step *out) {
    out->contact = OC_STICK;
    oc_force_of(L, a, out->q);
    out->next.a[0] = a[0];
    out->next.a[1] = a[1];
    out->next.s[0] = start->s[0];
    out->next.s[1] = start->s[1];
    out->next.energy = start->energy;
}

/* The stick test |a_tr| <= N, i.e. Phi(q_tr, N) <= 0, in two parts.  A
 * committed force lies on or inside the yield surface to a few rounding
 * errors of N; such a trial sticks, so held inputs stick: |a_tr| <= lim =
 * N (1 + 8 eps).  Most steps stick well inside, which the squares tell
 * without the square root (oc_sticks_surely): sq = |a_tr|^2 <= lim^2
 * exactly implies sqrt(sq) <= lim after rounding, and the factor (1 - 4
 * eps) covers the two roundings of lim2c, which is normal wherever sq >=
 * 2^-900 passes.  Within it the decision is the square root's, bit for bit
 * (sq is what norm2 takes the root of in this range), and is taken by it
 * everywhere else (oc_sticks_by_root, n_tr = |a_tr|). */
static OC_ALWAYS_INLINE double oc_stick_limit(double N) { return N * (1.0 + 8 * DBL_EPSILON); }
static OC_ALWAYS_INLINE int oc_sticks_surely(double sq, double N) {
    const double lim = oc_stick_limit(N);
    const double lim2c = (lim * lim) * (1.0 - 4 * DBL_EPSILON);
    return sq <= lim2c && sq >= 0x1p-900 && sq <= 0x1p1000;
}
static OC_ALWAYS_INLINE int oc_sticks_by_root(double n_tr, double N) {
    return n_tr <= oc_stick_limit(N);
}

/* The first part of oc_law_step: the inputs into out->next, then an open
 * step, or a trial whose squares say it sticks: out is then
 * oc_law_step(law, start, u, N) bit for bit, and 1 is returned.  Otherwise
 * 0, with the trial in a: oc_law_step_finish finishes the step. */
static OC_ALWAYS_INLINE int oc_law_step_begin(const oc_law *L, const oc_state *start,
                                              const double u[2], double N, oc_step *out,
                                              double a[2]) {
    out->next.u[0] = u[0];
    out->next.u[1] = u[1];
    out->next.N = N;
    if (!(N > 0)) {
        oc_step_open(start, u, out);
        return 1;
    }
    oc_trial(L, start, u, a);
    if (oc_sticks_surely(a[0] * a[0] + a[1] * a[1], N)) {
        oc_step_stick(L, start, a, out);
        return 1;
    }
    return 0;
}

/* A step that oc_law_step_begin left unfinished: its start, its result
 * (whose next.u and next.N hold the inputs, as begin wrote them) and the
 * trial. */
typedef struct {
    const oc_state *start;
    oc_step *out;
    double a[2];
} oc_unfinished;

/* Finishes n steps that oc_law_step_begin left (in chunks of OC_BATCH_MAX):
 * each pending[k].out is then, bit for bit, what oc_law_step gives: a stick
 * by the square root or a slip.  The cells that slip by an implicit rule's
 * fast solve are solved OC_LANES at a time, their evaluations interleaved
 * and two cells a vector where the compiler has vectors (the cells share
 * the law's tensors and slip eigenbasis); the others as oc_law_step steps
 * them.  No out may overlap a start. */
enum { OC_BATCH_MAX = 64, OC_LANES = 8 };
void oc_law_step_finish(const oc_law *law, const oc_unfinished pending[], int n);

/* n steps with one law (in chunks of OC_BATCH_MAX): out[k] is, bit for bit, what
 * oc_law_step(law, start[k], u[k], N[k], &out[k]) gives (oc_law_step_begin
 * on each, then oc_law_step_finish on those it left).  No out[k] may overlap
 * a start or an input. */
void oc_law_step_batch(const oc_law *law, const oc_state *const start[], const double u[][2],
                       const double N[], oc_step out[], int n);

/* Jacobian of the outputs y = (T1, T2, s1, s2, energy) with respect to
 * x = (u1, u2, N) for the step `st` computed from `start` with (u, N). */
enum { OC_JAC_ROWS = 5, OC_JAC_COLS = 3 };
void oc_law_jacobian(const oc_law *law, const oc_state *start, const double u[2], double N,
                     const oc_step *st, double J[OC_JAC_ROWS][OC_JAC_COLS]);

/* 1 if every output and committed number of the step is finite (q, the
 * committed state); the tangent's internals (dgamma, w) are not checked.
 * Inline: it runs on every step, right after the law stored these field by
 * field.  One at a time on purpose: read in pairs (as compilers vectorize a
 * branch-free form) each 16-byte load waits for both 8-byte stores to
 * retire, because store forwarding fails. */
static inline int oc_step_is_finite(const oc_step *st) {
    return isfinite(st->q[0]) && isfinite(st->q[1]) && isfinite(st->next.a[0]) &&
           isfinite(st->next.a[1]) && isfinite(st->next.s[0]) && isfinite(st->next.s[1]) &&
           isfinite(st->next.energy);
}

/* NULL if `st` can be a committed state of `law` (finite, energy >= 0,
 * open contact unloaded, force inside the yield surface up to rounding),
 * otherwise why not. */
const char *oc_state_check(const oc_law *law, const oc_state *st);

/* Euclidean norm of (x, y) without overflow or underflow of the squares
 * (hypot, without needing a recent libm). */
double oc_norm2(double x, double y);

#ifdef __cplusplus
}
#endif
#endif
