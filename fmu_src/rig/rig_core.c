/* The carriage/block rig of the paper's experiment (rig_core.h). */
#include "rig/rig_core.h"

#include <math.h>

/* fmax and fmin of two numbers, without the libm calls these compile to on
 * x86-64 (no NaN reaches them: the contact refuses a non-finite force). */
static inline double larger(double a, double b) { return b > a ? b : a; }
static inline double smaller(double a, double b) { return b < a ? b : a; }

long rig_step_count(double travel, double velocity, double step) {
    const double n = ceil(travel / (velocity * step) - 1e-9);
    /* beyond 2^53 steps the count is not a whole number any more, and no
     * run is that long: refused, as a NaN would be */
    if (!(n >= 1.0 && n <= 9007199254740992.0)) return -1;
    return (long)n;
}

double rig_fit_start(const rig_setup *r, long n_steps) {
    return r->fit_from * r->velocity * (double)n_steps * r->step;
}

double rig_fit_end(const rig_setup *r, long n_steps) {
    return r->velocity * (double)n_steps * r->step;
}

double rig_fit_middle(double x1_fit, double x1_end) { return x1_fit + 0.5 * (x1_end - x1_fit); }

double rig_lateral_scale(double mu1, double mu2, double eps1, double eps2, double N) {
    return smaller(mu1, mu2) * N / larger(eps1, eps2);
}

void rig_lateral_step(double *x2, double *v2, double T1, double T2, double mass, double mu_strip,
                      double damp, double h) {
    const double f_max = mu_strip * rig_push(T1), a_free = T2 / mass;
    double v;
    if (f_max > 0.0) {
        /* the strip's friction inside the implicit viscous update, as every
         * force: a steady state balances T2 + f = c_strip v2 exactly.  It
         * opposes the motion and at most stops the block within the step. */
        const double w = *v2 + h * a_free, f_stop = fabs(mass * w / h);
        const double f = -copysign(f_stop < f_max ? f_stop : f_max, w);
        v = (w + h * f / mass) / damp;
    } else {
        v = (*v2 + h * a_free) / damp;
    }
    *v2 = v;
    *x2 += h * v;
}

void rig_fit_add(rig_line_fit *f, double x1, double x2, double drive) {
    if (f->n == 0) {
        f->x0 = x1;
        f->y0 = x2;
    }
    const double dx = x1 - f->x0, dy = x2 - f->y0;
    f->n += 1;
    f->sx += dx;
    f->sy += dy;
    f->sxx += dx * dx;
    f->sxy += dx * dy;
    f->sf += drive;
}

double rig_fit_angle_deg(const rig_line_fit *f) {
    const double n = (double)f->n, den = n * f->sxx - f->sx * f->sx;
    if (f->n < 2 || den <= 0) return NAN;
    return atan((n * f->sxy - f->sx * f->sy) / den) * (180.0 / 3.141592653589793); /* degrees */
}

double rig_fit_mean_drive(const rig_line_fit *f) { return f->n ? f->sf / (double)f->n : NAN; }

int rig_solve_lateral(const rig_contact *c, double u1, double *u2p, double N, double strip,
                      double scale, double visc, long *iterations) {
    const double tol = 1e-12, u2_ref = *u2p;
    double u2 = *u2p, lo = 0, hi = 0, grow = scale;
    int have_lo = 0, have_hi = 0;
    for (int it = 1; it <= 200; ++it) {
        double T1, T2;
        *iterations = it;
        if (!c->set_inputs(c->ctx, u1, u2, N) || !c->force(c->ctx, &T1, &T2))
            return RIG_CONTACT_FAILED;
        const double r = T2 - strip * rig_push(T1) - visc * (u2 - u2_ref);
        if (fabs(r) <= tol * larger(fabs(N), 1e-300)) {
            *u2p = u2;
            return RIG_OK;
        }
        if (r > 0) {
            lo = u2;
            have_lo = 1;
        } else {
            hi = u2;
            have_hi = 1;
        }
        double dT1, dT2;
        if (!c->force_du2(c->ctx, &dT1, &dT2)) return RIG_CONTACT_FAILED;
        const double d = dT2 + (T1 < 0 ? strip * dT1 : 0.0) - visc;
        double cand = d < 0 ? u2 - r / d : NAN;
        if (have_lo && have_hi) {
            if (!(smaller(lo, hi) < cand && cand < larger(lo, hi))) cand = 0.5 * (lo + hi);
            /* bracket at rounding level: r jumps across zero */
            if (fabs(hi - lo) <= 4e-16 * larger(fabs(lo), fabs(hi))) {
                *u2p = u2;
                return RIG_OK;
            }
        } else if (!isfinite(cand) || fabs(cand - u2) > grow) {
            cand = u2 + copysign(grow, r); /* r > 0: T2 too big, increase u2 */
            grow *= 4;
        }
        u2 = cand;
    }
    return RIG_NOT_CONVERGED;
}

int rig_start(rig_runner *run, const rig_setup *r, const rig_contact *c, double scale) {
    const double h = r->step, v = r->velocity, m = r->mass;
    const long n_steps = rig_step_count(r->travel, v, h);
    if (n_steps < 1) return RIG_BAD_SETUP;
    rig_runner s = {0};
    s.r = r;
    s.c = c;
    s.h = h;
    s.v = v;
    s.m = m;
    s.N = r->mass * r->g;
    s.mu_s = r->mu_strip;
    /* the strip's viscous term: implicit in the dynamic rig, a residual term
     * over the step's displacement in the quasi-static one */
    s.damp = 1.0 + h * r->c_strip / m;
    s.visc = r->c_strip / h;
    s.scale = scale;
    s.x1_fit = rig_fit_start(r, n_steps);
    s.x1_mid = rig_fit_middle(s.x1_fit, rig_fit_end(r, n_steps));
    s.n_steps = n_steps;
    s.k = 1;
    *run = s;
    return RIG_OK;
}

int rig_advance(rig_runner *s, rig_observer observe, void *observer_ctx, double *x1_failed) {
    return rig_advance_on(s, *s->c, observe, observer_ctx, x1_failed);
}

void rig_finish(const rig_runner *s, rig_figures *out) {
    out->phi_deg = rig_fit_angle_deg(&s->fit);
    out->drive_mean_N = rig_fit_mean_drive(&s->fit);
    out->phi_head_deg = rig_fit_angle_deg(&s->head);
    out->phi_tail_deg = rig_fit_angle_deg(&s->tail);
    out->newton_iterations = s->newton;
}

int rig_run(const rig_setup *r, const rig_contact *c, double scale, rig_observer observe,
            void *observer_ctx, rig_figures *out, double *x1_failed) {
    rig_runner run;
    int st = rig_start(&run, r, c, scale);
    while (st == RIG_OK && !rig_done(&run))
        st = rig_advance(&run, observe, observer_ctx, x1_failed);
    if (st == RIG_OK) rig_finish(&run, out);
    return st;
}
