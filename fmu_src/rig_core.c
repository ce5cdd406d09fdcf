/* The rig once (rig_core.h).  Expressions keep rig.py's order of operations:
 * the tests compare the two bit for bit. */
#include "rig_core.h"

#include <math.h>

/* Python's max(a, b) and min(a, b): the first argument unless the second is
 * strictly larger (smaller); fmax/fmin may differ on signed zeros. */
static double py_max(double a, double b) { return b > a ? b : a; }
static double py_min(double a, double b) { return b < a ? b : a; }

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
    return py_min(mu1, mu2) * N / py_max(eps1, eps2);
}

void rig_lateral_step(double *x2, double *v2, double T1, double T2, double mass, double mu_strip,
                      double damp, double h) {
    const double P = py_max(-T1, 0.0); /* the carriage can only push */
    const double f_max = mu_strip * P, a_free = T2 / mass;
    double v;
    if (f_max > 0.0) {
        /* the strip's friction inside the implicit viscous update, as every
         * force: a steady state balances T2 + f = c_strip v2 exactly */
        const double w = *v2 + h * a_free;
        const double f = -copysign(py_min(f_max, fabs(mass * w / h)), w);
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
    /* math.degrees(x) is x * (180 / pi) */
    return atan((n * f->sxy - f->sx * f->sy) / den) * (180.0 / 3.141592653589793);
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
        const double r = T2 - strip * py_max(-T1, 0.0) - visc * (u2 - u2_ref);
        if (fabs(r) <= tol * py_max(fabs(N), 1e-300)) {
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
            if (!(py_min(lo, hi) < cand && cand < py_max(lo, hi))) cand = 0.5 * (lo + hi);
            /* bracket at rounding level: r jumps across zero */
            if (fabs(hi - lo) <= 4e-16 * py_max(fabs(lo), fabs(hi))) {
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

int rig_run(const rig_setup *r, const rig_contact *c, double scale, rig_observer observe,
            void *observer_ctx, rig_figures *out, double *x1_failed) {
    const double h = r->step, v = r->velocity, m = r->mass, N = r->mass * r->g;
    const long n_steps = rig_step_count(r->travel, v, h);
    if (n_steps < 1) return RIG_BAD_SETUP;
    const double mu_s = r->mu_strip;
    /* the strip's viscous term: implicit in the dynamic rig, a residual term
     * over the step's displacement in the quasi-static one */
    const double damp = 1.0 + h * r->c_strip / m, visc = r->c_strip / h;
    const double x1_fit = rig_fit_start(r, n_steps);
    const double x1_mid = rig_fit_middle(x1_fit, rig_fit_end(r, n_steps));
    double x2 = 0.0, v2 = 0.0, T1 = 0.0, T2 = 0.0;
    rig_line_fit fit = {0}, head = {0}, tail = {0};
    long newton = 0;
    for (long k = 1; k <= n_steps; ++k) {
        const double t = k * h, x1 = v * t;
        if (!r->quasistatic) {
            rig_lateral_step(&x2, &v2, T1, T2, m, mu_s, damp, h);
            if (!c->set_inputs(c->ctx, x1, x2, N) || !c->force(c->ctx, &T1, &T2))
                return RIG_CONTACT_FAILED;
        } else {
            /* The strip holds the block while |T2| <= mu_s P; beyond that the
             * block moves until T2 falls to the strip's limit, iterating from
             * the committed state. */
            if (!c->save(c->ctx) || !c->set_inputs(c->ctx, x1, x2, N) ||
                !c->force(c->ctx, &T1, &T2))
                return RIG_CONTACT_FAILED;
            if (fabs(T2) > mu_s * py_max(-T1, 0.0)) {
                if (!c->restore(c->ctx)) return RIG_CONTACT_FAILED;
                long it = 0;
                const int st = rig_solve_lateral(c, x1, &x2, N, copysign(mu_s, T2), scale, visc, &it);
                newton += it;
                if (st != RIG_OK) {
                    if (x1_failed) *x1_failed = x1;
                    return st;
                }
                if (!c->force(c->ctx, &T1, &T2)) return RIG_CONTACT_FAILED;
            }
        }
        if (!c->commit(c->ctx, h)) return RIG_CONTACT_FAILED;
        const double drive = r->f_int - T1;
        if (x1 >= x1_fit) {
            rig_fit_add(&fit, x1, x2, drive);
            rig_fit_add(x1 >= x1_mid ? &tail : &head, x1, x2, drive);
        }
        if (observe && !observe(observer_ctx, k, n_steps, t, x1, x2, T1, T2, drive))
            return RIG_OBSERVER_FAILED;
    }
    out->phi_deg = rig_fit_angle_deg(&fit);
    out->drive_mean_N = rig_fit_mean_drive(&fit);
    out->phi_head_deg = rig_fit_angle_deg(&head);
    out->phi_tail_deg = rig_fit_angle_deg(&tail);
    out->newton_iterations = newton;
    return RIG_OK;
}
