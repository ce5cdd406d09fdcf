/*
 * The carriage/block rig of the paper's experiment, once, in C: the block's
 * lateral step with the strip's Coulomb and viscous terms, the quasi-static
 * lateral solve, the streaming line fit of the trajectory angle, the step
 * count and the rig's run loop over any contact.  The CarriageBlock FMU
 * (models/CarriageBlock/model.c) takes its step from here, the compiled master
 * (master_src/rig_master.c) its whole loop.  No FMI in it: the contact is
 * reached through rig_contact's functions.
 *
 * The fmpy harness (python/orthocontact/rig/harness.py) runs the same rig
 * in Python, and tests/rig/test_compiled.py holds the two to the same
 * numbers bit for bit.  That asks nothing of this code: both write each
 * formula the plain way, and IEEE arithmetic without fused multiply-adds
 * (OC_C_FLAGS in CMakeLists.txt) rounds the same operations alike.
 */
#ifndef RIG_CORE_H
#define RIG_CORE_H

#include <math.h>

#include "compiler.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Structs are declared through field lists (type, name) so that the
 * compiled master can describe their layout to its Python caller
 * (rm_layout in master_src/rig_master.h) from the same list; the lists
 * keep their own layout (clang-format off). */
#define RIG_DECLARE_FIELD(type, name) type name;

/* The carriage's push on the block, P = max(-T1, 0) [N] for the mat's force
 * T1 on the block [N]: the carriage can only push, so where the mat pulls
 * the block along (T1 > 0) it pushes nothing.  (A comparison, not fmax:
 * that is a libm call on x86-64, and this runs every step.) */
static inline double rig_push(double T1) { return T1 > 0.0 ? 0.0 : -T1; }

/* The rig, as orthocontact.rig.Rig.  kg, m/s^2, N, m/s, m, s, N s/m;
 * quasistatic: 0 dynamic, 1 quasi-static. */
/* clang-format off */
#define RIG_SETUP_FIELDS(F)                                                                  \
    F(double, mass) F(double, g) F(double, f_int) F(double, velocity) F(double, travel)     \
    F(double, mu_strip) F(double, step) F(double, fit_from) F(double, c_strip)              \
    F(int, quasistatic)
/* clang-format on */
typedef struct {
    RIG_SETUP_FIELDS(RIG_DECLARE_FIELD)
} rig_setup;

/* What a run measures: the trajectory angle fitted over the fitted range
 * [x1_fit, x1_end] and over each half of it (split at x1_mid), the mean
 * driving force over the range, the lateral Newton iterations. */
/* clang-format off */
#define RIG_FIGURES_FIELDS(F)                                                                \
    F(double, phi_deg) F(double, drive_mean_N) F(double, phi_head_deg) F(double, phi_tail_deg) \
    F(long, newton_iterations)
/* clang-format on */
typedef struct {
    RIG_FIGURES_FIELDS(RIG_DECLARE_FIELD)
} rig_figures;

/* Steps of a run: ceil(travel / (velocity step) - 1e-9), the tolerance
 * absorbing the rounding of travels meant as whole multiples of a step. */
long rig_step_count(double travel, double velocity, double step);

/* Where the fit starts, where the run ends, where the halves meet [m]. */
double rig_fit_start(const rig_setup *r, long n_steps);
double rig_fit_end(const rig_setup *r, long n_steps);
double rig_fit_middle(double x1_fit, double x1_end);

/* One lateral step of the dynamic rig with the mat's force T held over h:
 * symplectic Euler, the strip's Coulomb force |f| <= mu_strip max(-T1, 0)
 * opposing the lateral motion and never reversing it within the step, the
 * viscous term implicit (damp = 1 + h c_strip / mass, so any step is stable;
 * with c_strip = 0 damp is exactly 1).  Updates *x2 [m], *v2 [m/s]. */
void rig_lateral_step(double *x2, double *v2, double T1, double T2, double mass, double mu_strip,
                      double damp, double h);

/* The streaming least-squares line x2 = a + b x1 and mean driving force;
 * sums about the first point to avoid cancellation. */
typedef struct {
    long n;
    double x0, y0, sx, sy, sxx, sxy, sf;
} rig_line_fit;

void rig_fit_add(rig_line_fit *f, double x1, double x2, double drive);
double rig_fit_angle_deg(const rig_line_fit *f);  /* NaN with fewer than 2 distinct x1 */
double rig_fit_mean_drive(const rig_line_fit *f); /* NaN without points */

/* The contact as the rig sees it.  Each function returns 1 on success, 0 on
 * failure (the caller knows why).  set_inputs makes a pending step at
 * (u1, u2, N); force reads its T; force_du2 its derivative along u2;
 * save/restore the committed state; commit ends the step of h [s]. */
typedef struct {
    void *ctx;
    int (*set_inputs)(void *ctx, double u1, double u2, double N);
    int (*force)(void *ctx, double *T1, double *T2);
    int (*force_du2)(void *ctx, double *dT1, double *dT2);
    int (*save)(void *ctx);
    int (*restore)(void *ctx);
    int (*commit)(void *ctx, double h);
} rig_contact;

/* The quasi-static lateral solve: u2 with r(u2) = T2 - strip max(-T1, 0) -
 * visc (u2 - u2_ref) = 0 from u2_ref = *u2, strip the strip's signed friction
 * coefficient, visc = c_strip / h [N/m].  r falls with u2 (the return map is
 * monotone), so every evaluation tightens a bracket; Newton steps with the
 * contact's tangent are taken when they stay inside it, bisection otherwise;
 * before a bracket exists steps are limited to a growing multiple of `scale`
 * [m].  Tolerance 1e-12 relative to N, at most 200 iterations.  Leaves the
 * contact's pending step at the solution.  RIG_OK, RIG_CONTACT_FAILED or
 * RIG_NOT_CONVERGED; *iterations as rig.solve_lateral counts them. */
int rig_solve_lateral(const rig_contact *c, double u1, double *u2, double N, double strip,
                      double scale, double visc, long *iterations);

/* Called after every committed step k of n_steps (t = k h), if given; 0
 * stops the run with RIG_OBSERVER_FAILED. */
typedef int (*rig_observer)(void *ctx, long k, long n_steps, double t, double x1, double x2,
                            double T1, double T2, double drive);

enum { RIG_OK = 0, RIG_CONTACT_FAILED, RIG_NOT_CONVERGED, RIG_OBSERVER_FAILED, RIG_BAD_SETUP };

/* The lateral solve's first step [m]: the elastic displacement
 * min(mu1, mu2) N / max(eps1, eps2) of the contact. */
double rig_lateral_scale(double mu1, double mu2, double eps1, double eps2, double N);

/* One run of the rig over r->travel on an initialized contact, `scale` from
 * rig_lateral_scale.  RIG_BAD_SETUP if its step count is not a whole number
 * in [1, 2^53].  On RIG_NOT_CONVERGED *x1_failed is where.  Figures
 * are written on RIG_OK only.  rig_start + rig_advance until rig_done +
 * rig_finish, in one call. */
int rig_run(const rig_setup *r, const rig_contact *c, double scale, rig_observer observe,
            void *observer_ctx, rig_figures *out, double *x1_failed);

/* The same run a step at a time, so that a caller can advance several
 * independent runs in turn: a rig step waits on the contact's result (the
 * lateral step needs the force, the next contact step the position), and
 * two runs stepped alternately let the processor work on one while the
 * other waits.  Each run's numbers are those of rig_run, bit for bit. */
typedef struct {
    const rig_setup *r;
    const rig_contact *c;
    double h, v, m, N, mu_s, damp, visc, scale, x1_fit, x1_mid;
    long n_steps, k, newton;
    double x2, v2, T1, T2;
    rig_line_fit fit, head, tail;
} rig_runner;

/* RIG_OK, or RIG_BAD_SETUP (nothing to step).  r and c must outlive the run. */
int rig_start(rig_runner *run, const rig_setup *r, const rig_contact *c, double scale);
/* 1 once every step is taken. */
static inline int rig_done(const rig_runner *run) { return run->k > run->n_steps; }
/* The next step (rig_run's loop body): RIG_OK or an error as rig_run's. */
int rig_advance(rig_runner *run, rig_observer observe, void *observer_ctx, double *x1_failed);
/* The same with the contact given by value: where the caller's contact
 * functions are known at compile time, the compiler calls them directly
 * (or inlines them) instead of through the pointers.  Always inlined: gcc
 * -O2 leaves it a call at a second call site, which then calls through the
 * pointers again (docs/benchmarks.md, the compiled master). */
static OC_ALWAYS_INLINE int rig_advance_on(rig_runner *s, const rig_contact contact,
                                           rig_observer observe, void *observer_ctx,
                                           double *x1_failed) {
    const rig_contact *c = &contact;
    const double h = s->h, N = s->N, mu_s = s->mu_s;
    const long k = s->k;
    const double t = k * h, x1 = s->v * t;
    double x2 = s->x2, T1 = s->T1, T2 = s->T2;
    if (!s->r->quasistatic) {
        rig_lateral_step(&x2, &s->v2, T1, T2, s->m, mu_s, s->damp, h);
        if (!c->set_inputs(c->ctx, x1, x2, N) || !c->force(c->ctx, &T1, &T2))
            return RIG_CONTACT_FAILED;
    } else {
        /* The strip holds the block while |T2| <= mu_s P; beyond that the
         * block moves until T2 falls to the strip's limit, iterating from
         * the committed state. */
        if (!c->save(c->ctx) || !c->set_inputs(c->ctx, x1, x2, N) || !c->force(c->ctx, &T1, &T2))
            return RIG_CONTACT_FAILED;
        if (fabs(T2) > mu_s * rig_push(T1)) {
            if (!c->restore(c->ctx)) return RIG_CONTACT_FAILED;
            long it = 0;
            const int st =
                rig_solve_lateral(c, x1, &x2, N, copysign(mu_s, T2), s->scale, s->visc, &it);
            s->newton += it;
            if (st != RIG_OK) {
                if (x1_failed) *x1_failed = x1;
                return st;
            }
            if (!c->force(c->ctx, &T1, &T2)) return RIG_CONTACT_FAILED;
        }
    }
    if (!c->commit(c->ctx, h)) return RIG_CONTACT_FAILED;
    s->x2 = x2;
    s->T1 = T1;
    s->T2 = T2;
    s->k = k + 1;
    const double drive = s->r->f_int - T1;
    if (x1 >= s->x1_fit) {
        rig_fit_add(&s->fit, x1, x2, drive);
        rig_fit_add(x1 >= s->x1_mid ? &s->tail : &s->head, x1, x2, drive);
    }
    if (observe && !observe(observer_ctx, k, s->n_steps, t, x1, x2, T1, T2, drive))
        return RIG_OBSERVER_FAILED;
    return RIG_OK;
}

/* The figures of a finished run. */
void rig_finish(const rig_runner *run, rig_figures *out);

#ifdef __cplusplus
}
#endif
#endif
