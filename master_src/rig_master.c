/*
 * The compiled master: loads a contact FMU through its FMI 2.0 functions
 * (dlopen of the extracted binary, as any importer does) and runs the
 * carriage/block rig loop for a batch of parameter sets per call.  It is the
 * Python harness's loop (python/orthocontact/rig.py) operation for operation —
 * the same coupling, the same lateral Newton, the same line fit — so the two
 * masters give the same trajectory angles; only the per-step cost differs.
 */
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

typedef struct {
    double mu1, mu2, eps1, eps2, alpha, beta;
    int rule; /* 1 associated, 2 coupled, 3 eq20 */
} rm_contact;

typedef struct {
    double mass, g, f_int, velocity, travel, mu_strip, step, fit_from, c_strip;
    int quasistatic;
} rm_rig;

typedef struct {
    void *lib;
    char *guid, *resources;
    fmi2InstantiateTYPE *instantiate;
    fmi2FreeInstanceTYPE *free_instance;
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter_init;
    fmi2ExitInitializationModeTYPE *exit_init;
    fmi2ResetTYPE *reset;
    fmi2SetRealTYPE *set_real;
    fmi2GetRealTYPE *get_real;
    fmi2SetIntegerTYPE *set_integer;
    fmi2GetIntegerTYPE *get_integer;
    fmi2DoStepTYPE *do_step;
    fmi2GetDirectionalDerivativeTYPE *dir_der;
    fmi2GetFMUstateTYPE *get_state;
    fmi2SetFMUstateTYPE *set_state;
    fmi2FreeFMUstateTYPE *free_state;
    char last[512]; /* the FMU's last logged message */
} rm_master;

/* Value references of OrthotropicContact (its variable table). */
enum { VR_MU1 = 1, VR_RULE = 7, VR_U1 = 8, VR_U2 = 9, VR_N = 10, VR_T1 = 11, VR_T2 = 12, VR_S1 = 13,
       VR_S2 = 14, VR_STATE = 15, VR_ENERGY = 16 };

static void set_err(char *err, size_t n, const char *fmt, ...) {
    if (!err || n == 0) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, n, fmt, ap);
    va_end(ap);
}

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
    (void)name; (void)status; (void)category;
    rm_master *m = env;
    va_list ap;
    va_start(ap, message);
    vsnprintf(m->last, sizeof m->last, message, ap);
    va_end(ap);
}

void rm_close(void *h) {
    rm_master *m = h;
    if (!m) return;
    if (m->lib) dlclose(m->lib);
    free(m->guid);
    free(m->resources);
    free(m);
}

void *rm_open(const char *binary, const char *guid, const char *resources, char *err, size_t n) {
    rm_master *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    m->lib = dlopen(binary, RTLD_NOW | RTLD_LOCAL);
    if (!m->lib) {
        set_err(err, n, "cannot load %s: %s", binary, dlerror());
        rm_close(m);
        return NULL;
    }
#define LOAD(field, name)                                                        \
    if (!(m->field = (void *)dlsym(m->lib, name))) {                             \
        set_err(err, n, "%s does not export %s", binary, name);                 \
        rm_close(m);                                                             \
        return NULL;                                                             \
    }
    LOAD(instantiate, "fmi2Instantiate")
    LOAD(free_instance, "fmi2FreeInstance")
    LOAD(setup, "fmi2SetupExperiment")
    LOAD(enter_init, "fmi2EnterInitializationMode")
    LOAD(exit_init, "fmi2ExitInitializationMode")
    LOAD(reset, "fmi2Reset")
    LOAD(set_real, "fmi2SetReal")
    LOAD(get_real, "fmi2GetReal")
    LOAD(set_integer, "fmi2SetInteger")
    LOAD(get_integer, "fmi2GetInteger")
    LOAD(do_step, "fmi2DoStep")
    LOAD(dir_der, "fmi2GetDirectionalDerivative")
    LOAD(get_state, "fmi2GetFMUstate")
    LOAD(set_state, "fmi2SetFMUstate")
    LOAD(free_state, "fmi2FreeFMUstate")
#undef LOAD
    m->guid = strdup(guid);
    m->resources = strdup(resources);
    return m;
}

/* The streaming least-squares line of rig.LineFit, sums about the first point. */
typedef struct {
    long n;
    double x0, y0, sx, sy, sxx, sxy, sf;
} line_fit;

static void fit_add(line_fit *f, double x1, double x2, double drive) {
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

static double fit_angle_deg(const line_fit *f) {
    const double n = (double)f->n, den = n * f->sxx - f->sx * f->sx;
    if (f->n < 2 || den <= 0) return NAN;
    return atan((n * f->sxy - f->sx * f->sy) / den) * (180.0 / 3.141592653589793);
}

typedef struct {
    rm_master *m;
    fmi2Component c;
    double time;
    fmi2ValueReference in_vr[3], T_vr[2], known_u2;
} fmu_t;

static int set_inputs(fmu_t *F, double u1, double u2, double N) {
    const double v[3] = {u1, u2, N};
    return F->m->set_real(F->c, F->in_vr, 3, v) <= fmi2Warning;
}

static int force(fmu_t *F, double *T1, double *T2) {
    double T[2];
    if (F->m->get_real(F->c, F->T_vr, 2, T) > fmi2Warning) return 0;
    *T1 = T[0];
    *T2 = T[1];
    return 1;
}

/* Python's max(a, b): the first argument unless the second is larger. */
static double pymax(double a, double b) { return b > a ? b : a; }
static double pymin(double a, double b) { return b < a ? b : a; }

/* rig.solve_lateral: u2 with T2 - strip * max(-T1, 0) - visc * (u2 - u2_ref)
 * = 0, from u2_ref = *u2p; *iters as the harness counts them.  0 on failure. */
static int solve_lateral(fmu_t *F, double u1, double *u2p, double N, double strip, double scale,
                         double visc, long *iters) {
    const double tol = 1e-12, u2_ref = *u2p;
    double u2 = *u2p, lo = 0, hi = 0, grow = scale;
    int have_lo = 0, have_hi = 0;
    for (int it = 1; it <= 200; ++it) {
        double T1, T2;
        *iters = it;
        if (!set_inputs(F, u1, u2, N) || !force(F, &T1, &T2)) return 0;
        const double r = T2 - strip * pymax(-T1, 0.0) - visc * (u2 - u2_ref);
        if (fabs(r) <= tol * pymax(fabs(N), 1e-300)) {
            *u2p = u2;
            return 1;
        }
        if (r > 0) {
            lo = u2;
            have_lo = 1;
        } else {
            hi = u2;
            have_hi = 1;
        }
        const double one = 1.0;
        double dT[2];
        if (F->m->dir_der(F->c, F->T_vr, 2, &F->known_u2, 1, &one, dT) > fmi2Warning) return 0;
        const double d = dT[1] + (T1 < 0 ? strip * dT[0] : 0.0) - visc;
        double cand = d < 0 ? u2 - r / d : NAN;
        if (have_lo && have_hi) {
            if (!(pymin(lo, hi) < cand && cand < pymax(lo, hi))) cand = 0.5 * (lo + hi);
            if (fabs(hi - lo) <= 4e-16 * pymax(fabs(lo), fabs(hi))) {
                *u2p = u2;
                return 1;
            }
        } else if (!isfinite(cand) || fabs(cand - u2) > grow) {
            cand = u2 + copysign(grow, r);
            grow *= 4;
        }
        u2 = cand;
    }
    return 0;
}

/* What a recorded run keeps every `every` steps (and at the last), as
 * rig.RigResult's columns: t, x1, x2, T1, T2, s1, s2, state, energy, drive. */
enum { REC_COLUMNS = 10 };
typedef struct {
    long every, capacity, rows, newton;
    double *data; /* capacity x REC_COLUMNS, row-major */
} recording;

static int record_row(fmu_t *F, recording *rec, double t, double x1, double x2, double T1, double T2,
                      double drive) {
    if (rec->rows >= rec->capacity) return 0;
    const fmi2ValueReference vr[3] = {VR_S1, VR_S2, VR_ENERGY}, vr_state = VR_STATE;
    double o[3];
    fmi2Integer state;
    if (F->m->get_real(F->c, vr, 3, o) > fmi2Warning ||
        F->m->get_integer(F->c, &vr_state, 1, &state) > fmi2Warning)
        return 0;
    double *row = rec->data + rec->rows * REC_COLUMNS;
    row[0] = t, row[1] = x1, row[2] = x2, row[3] = T1, row[4] = T2;
    row[5] = o[0], row[6] = o[1], row[7] = (double)state, row[8] = o[2], row[9] = drive;
    rec->rows += 1;
    return 1;
}

/* One run of rig._simulate on an initialized instance; rec may be NULL. */
static int simulate(fmu_t *F, const rm_contact *p, const rm_rig *r, double *phi, double *drive_mean,
                    recording *rec, char *err, size_t n) {
    const double h = r->step, v = r->velocity, m = r->mass, N = r->mass * r->g;
    const long n_steps = (long)ceil(r->travel / (v * h) - 1e-9);
    const double scale = pymin(p->mu1, p->mu2) * N / pymax(p->eps1, p->eps2);
    const double mu_s = r->mu_strip;
    /* the strip's viscous term: implicit in the dynamic rig (damp is exactly 1
     * without it), a residual term in the quasi-static one */
    const double damp = 1.0 + h * r->c_strip / m, visc = r->c_strip / h;
    double x2 = 0.0, v2 = 0.0, T1 = 0.0, T2 = 0.0;
    line_fit fit = {0};
    const double x1_fit = r->fit_from * v * n_steps * h;
    fmi2FMUstate snapshot = NULL;
    for (long k = 1; k <= n_steps; ++k) {
        const double t = k * h, x1 = v * t;
        const double P = pymax(-T1, 0.0);
        if (!r->quasistatic) {
            const double f_max = mu_s * P, a_free = T2 / m;
            if (f_max > 0.0) {
                const double v_free = (v2 + h * a_free) / damp;
                const double f = v_free != 0.0
                                     ? -copysign(pymin(f_max, fabs(m * v_free / h)), v_free)
                                     : -copysign(pymin(f_max, fabs(T2)), T2);
                v2 = v_free + h * f / m;
            } else {
                v2 = (v2 + h * a_free) / damp;
            }
            x2 += h * v2;
            if (!set_inputs(F, x1, x2, N) || !force(F, &T1, &T2)) goto fail;
        } else {
            if (F->m->get_state(F->c, &snapshot) > fmi2Warning) goto fail;
            if (!set_inputs(F, x1, x2, N) || !force(F, &T1, &T2)) goto fail;
            if (fabs(T2) > mu_s * pymax(-T1, 0.0)) {
                if (F->m->set_state(F->c, snapshot) > fmi2Warning) goto fail;
                long it = 0;
                const int ok = solve_lateral(F, x1, &x2, N, copysign(mu_s, T2), scale, visc, &it);
                if (rec) rec->newton += it;
                if (!ok) {
                    set_err(err, n, "lateral equilibrium not reached at x1 = %g m", x1);
                    goto fail_quiet;
                }
                if (!force(F, &T1, &T2)) goto fail;
            }
        }
        if (F->m->do_step(F->c, F->time, h, fmi2True) > fmi2Warning) goto fail;
        F->time += h;
        if (x1 >= x1_fit) fit_add(&fit, x1, x2, r->f_int - T1);
        if (rec && (k % rec->every == 0 || k == n_steps) &&
            !record_row(F, rec, t, x1, x2, T1, T2, r->f_int - T1)) {
            if (rec->rows >= rec->capacity) {
                set_err(err, n, "recording buffer of %ld rows is full", rec->capacity);
                goto fail_quiet;
            }
            goto fail;
        }
    }
    if (snapshot) F->m->free_state(F->c, &snapshot);
    *phi = fit_angle_deg(&fit);
    *drive_mean = fit.n ? fit.sf / (double)fit.n : NAN;
    return 1;
fail:
    set_err(err, n, "FMU call failed: %s", F->m->last);
fail_quiet:
    if (snapshot) F->m->free_state(F->c, &snapshot);
    return 0;
}

/* Runs n parameter sets on one instance (reset between runs, as the harness's
 * workers do).  phi [deg], drive [N] per set; the first set recorded into rec
 * if rec is not NULL.  0, or -1 with err. */
static int run_sets(void *h, int count, const rm_contact *p, const rm_rig *r, double *phi,
                    double *drive, recording *rec, char *err, size_t n) {
    rm_master *m = h;
    const fmi2CallbackFunctions cb = {logger, calloc, free, NULL, m};
    fmu_t F = {m, NULL, 0.0, {VR_U1, VR_U2, VR_N}, {VR_T1, VR_T2}, VR_U2};
    F.c = m->instantiate("cmaster", fmi2CoSimulation, m->guid, m->resources, &cb, fmi2False, fmi2False);
    if (!F.c) {
        set_err(err, n, "fmi2Instantiate failed: %s", m->last);
        return -1;
    }
    int status = 0;
    for (int i = 0; i < count && status == 0; ++i) {
        const fmi2ValueReference vr[6] = {VR_MU1, VR_MU1 + 1, VR_MU1 + 2, VR_MU1 + 3, VR_MU1 + 4,
                                          VR_MU1 + 5};
        const double v[6] = {p[i].mu1, p[i].mu2, p[i].eps1, p[i].eps2, p[i].alpha, p[i].beta};
        const fmi2ValueReference vr_rule = VR_RULE;
        const fmi2Integer rule = p[i].rule;
        if ((i > 0 && m->reset(F.c) > fmi2Warning) || m->set_real(F.c, vr, 6, v) > fmi2Warning ||
            m->set_integer(F.c, &vr_rule, 1, &rule) > fmi2Warning ||
            m->setup(F.c, fmi2False, 0.0, 0.0, fmi2False, 0.0) > fmi2Warning ||
            m->enter_init(F.c) > fmi2Warning || m->exit_init(F.c) > fmi2Warning) {
            set_err(err, n, "set %d: initialization failed: %s", i, m->last);
            status = -1;
            break;
        }
        F.time = 0.0;
        if (!simulate(&F, &p[i], &r[i], &phi[i], &drive[i], i == 0 ? rec : NULL, err, n))
            status = -1;
    }
    m->free_instance(F.c);
    return status;
}

int rm_run(void *h, int count, const rm_contact *p, const rm_rig *r, double *phi, double *drive,
           char *err, size_t n) {
    return run_sets(h, count, p, r, phi, drive, NULL, err, n);
}

/* One run, recorded every `every` steps into rows (capacity x 10, the
 * columns of rig.RigResult); *n_rows rows written, *newton lateral Newton
 * iterations.  0, or -1 with err. */
int rm_record(void *h, const rm_contact *p, const rm_rig *r, long every, double *rows, long capacity,
              long *n_rows, double *phi, double *drive, long *newton, char *err, size_t n) {
    if (every < 1) {
        set_err(err, n, "record every %ld steps: expected >= 1", every);
        return -1;
    }
    recording rec = {every, capacity, 0, 0, rows};
    const int status = run_sets(h, 1, p, r, phi, drive, &rec, err, n);
    *n_rows = rec.rows;
    *newton = rec.newton;
    return status;
}
