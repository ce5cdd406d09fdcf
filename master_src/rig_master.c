/*
 * The compiled master (rig_master.h): loads a contact FMU through its FMI 2.0
 * functions (dlopen of the extracted binary, as any importer does) and runs
 * the rig of fmu_src/rig/rig_core.c on it for a batch of parameter sets per call.
 * The rig itself is not here: this file only gives it the contact's FMI 2.0
 * functions and records what a caller asks for.
 */
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "models/OrthotropicContact/table.h"
#include "rig_master.h"

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

static void set_err(char *err, size_t n, const char *fmt, ...) {
    if (!err || n == 0) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, n, fmt, ap);
    va_end(ap);
}

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
    (void)name;
    (void)status;
    (void)category;
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
#define LOAD(field, name)                                                                          \
    if (!(m->field = (void *)dlsym(m->lib, name))) {                                               \
        set_err(err, n, "%s does not export %s", binary, name);                                    \
        rm_close(m);                                                                               \
        return NULL;                                                                               \
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

int rm_layout(char *buf, size_t n) {
    size_t used = 0;
    int total = 0;
#define RM_PUT(...)                                                                                \
    do {                                                                                           \
        const int k =                                                                              \
            snprintf(buf ? buf + used : NULL, buf && used < n ? n - used : 0, __VA_ARGS__);        \
        if (k < 0) return -1;                                                                      \
        total += k;                                                                                \
        used = (size_t)total < n ? (size_t)total : n;                                              \
    } while (0)
#define RM_STRUCT(S) RM_PUT("struct %s %zu\n", #S, sizeof(S));
#define RM_FIELD_OF(S) RM_FIELD_##S
#define RM_FIELD(S, type, name) RM_PUT("%s %zu %s\n", #name, offsetof(S, name), #type);
#define RM_FIELD_rig_setup(type, name) RM_FIELD(rig_setup, type, name)
#define RM_FIELD_rig_figures(type, name) RM_FIELD(rig_figures, type, name)
#define RM_LAW_LAYOUT(name, ...) RM_FIELD(rm_contact, double, name)
    /* a struct's line, then its fields' */
    /* clang-format off */
    RM_STRUCT(rm_contact) OC_LAW_PARAMETERS(RM_LAW_LAYOUT) RM_FIELD(rm_contact, int, rule)
    RM_STRUCT(rig_setup) RIG_SETUP_FIELDS(RM_FIELD_rig_setup)
    RM_STRUCT(rig_figures) RIG_FIGURES_FIELDS(RM_FIELD_rig_figures)
    /* clang-format on */
#undef RM_PUT
#undef RM_STRUCT
#undef RM_FIELD_OF
#undef RM_FIELD
#undef RM_LAW_LAYOUT
#undef RM_FIELD_rig_setup
#undef RM_FIELD_rig_figures
                return total;
}

/* The contact FMU as rig_core's rig_contact. */
typedef struct {
    rm_master *m;
    fmi2Component c;
    double time;
    fmi2FMUstate snapshot;
} fmu_contact;

static const fmi2ValueReference VR_INPUTS[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
static const fmi2ValueReference VR_FORCE[2] = {OC_VR_T1, OC_VR_T2};
static const fmi2ValueReference VR_U2 = OC_VR_u2;

static int fc_set_inputs(void *ctx, double u1, double u2, double N) {
    fmu_contact *F = ctx;
    const double v[3] = {u1, u2, N};
    return F->m->set_real(F->c, VR_INPUTS, 3, v) <= fmi2Warning;
}

static int fc_force(void *ctx, double *T1, double *T2) {
    fmu_contact *F = ctx;
    double T[2];
    if (F->m->get_real(F->c, VR_FORCE, 2, T) > fmi2Warning) return 0;
    *T1 = T[0];
    *T2 = T[1];
    return 1;
}

static int fc_force_du2(void *ctx, double *dT1, double *dT2) {
    fmu_contact *F = ctx;
    const double one = 1.0;
    double dT[2];
    if (F->m->dir_der(F->c, VR_FORCE, 2, &VR_U2, 1, &one, dT) > fmi2Warning) return 0;
    *dT1 = dT[0];
    *dT2 = dT[1];
    return 1;
}

static int fc_save(void *ctx) {
    fmu_contact *F = ctx;
    return F->m->get_state(F->c, &F->snapshot) <= fmi2Warning;
}

static int fc_restore(void *ctx) {
    fmu_contact *F = ctx;
    return F->m->set_state(F->c, F->snapshot) <= fmi2Warning;
}

static int fc_commit(void *ctx, double h) {
    fmu_contact *F = ctx;
    if (F->m->do_step(F->c, F->time, h, fmi2True) > fmi2Warning) return 0;
    F->time += h;
    return 1;
}

/* What a recorded run keeps every `every` steps (and at the last). */
typedef struct {
    fmu_contact *F;
    long every, capacity, rows;
    double *data; /* capacity x RM_RECORD_COLUMNS, row-major */
    int full;
} recording;

static int record_row(void *ctx, long k, long n_steps, double t, double x1, double x2, double T1,
                      double T2, double drive) {
    recording *rec = ctx;
    if (!(k % rec->every == 0 || k == n_steps)) return 1;
    if (rec->rows >= rec->capacity) {
        rec->full = 1;
        return 0;
    }
    static const fmi2ValueReference vr[3] = {OC_VR_s1, OC_VR_s2, OC_VR_dissipatedEnergy};
    static const fmi2ValueReference vr_state = OC_VR_contactState;
    double o[3];
    fmi2Integer state;
    if (rec->F->m->get_real(rec->F->c, vr, 3, o) > fmi2Warning ||
        rec->F->m->get_integer(rec->F->c, &vr_state, 1, &state) > fmi2Warning)
        return 0;
    double *row = rec->data + rec->rows * RM_RECORD_COLUMNS;
    row[0] = t, row[1] = x1, row[2] = x2, row[3] = T1, row[4] = T2;
    row[5] = o[0], row[6] = o[1], row[7] = (double)state, row[8] = o[2], row[9] = drive;
    rec->rows += 1;
    return 1;
}

/* Why a run stopped with rig status st, into err. */
static void run_error(const fmu_contact *F, int st, const rig_setup *r, const recording *rec,
                      double x1_failed, char *err, size_t n) {
    switch (st) {
    case RIG_NOT_CONVERGED:
        set_err(err, n, "lateral equilibrium not reached at x1 = %g m", x1_failed);
        break;
    case RIG_BAD_SETUP:
        set_err(err, n,
                "travel %g m at %g m/s in steps of %g s is not a whole number of steps "
                "in [1, 2^53]",
                r->travel, r->velocity, r->step);
        break;
    default:
        if (st == RIG_OBSERVER_FAILED && rec && rec->full)
            set_err(err, n, "recording buffer of %ld rows is full", rec->capacity);
        else /* a call of the run or of its recorder */
            set_err(err, n, "FMU call failed: %s", F->m->last);
    }
}

/* A run in progress on its own contact instance.  run_sets advances up to
 * LANES runs in turn, a step each: one rig step waits on its contact's
 * result, and the other run's step fills that wait (rig_runner, rig_core.h;
 * the gain in docs/benchmarks.md).  Each run is alone on its instance, so
 * its numbers do not depend on the lanes. */
enum { LANES = 2 };
typedef struct {
    fmu_contact F;
    rig_contact contact;
    rig_runner run;
    int set;  /* the set it runs, -1 if idle */
    int used; /* the instance has run a set: reset before the next */
} lane;

/* Starts set i on lane L: the instance reset and initialized with the set's
 * parameters.  1, or 0 with err. */
static int lane_start(lane *L, int i, const rm_contact *p, const rig_setup *r, char *err,
                      size_t n) {
    rm_master *m = L->F.m;
#define LAW_VR(name, vr, ...) vr,
#define LAW_VALUE(name, ...) p[i].name,
    static const fmi2ValueReference vr[] = {OC_LAW_PARAMETERS(LAW_VR)};
    static const fmi2ValueReference vr_rule = OC_VR_slidingRule;
    const double v[] = {OC_LAW_PARAMETERS(LAW_VALUE)};
#undef LAW_VR
#undef LAW_VALUE
    const fmi2Integer rule = p[i].rule;
    fmi2Component c = L->F.c;
    if ((L->used && m->reset(c) > fmi2Warning) ||
        m->set_real(c, vr, sizeof vr / sizeof vr[0], v) > fmi2Warning ||
        m->set_integer(c, &vr_rule, 1, &rule) > fmi2Warning ||
        m->setup(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) > fmi2Warning ||
        m->enter_init(c) > fmi2Warning || m->exit_init(c) > fmi2Warning) {
        set_err(err, n, "set %d: initialization failed: %s", i, m->last);
        return 0;
    }
    L->used = 1;
    L->F.time = 0.0;
    L->set = i;
    const double scale =
        rig_lateral_scale(p[i].mu1, p[i].mu2, p[i].eps1, p[i].eps2, r[i].mass * r[i].g);
    const int st = rig_start(&L->run, &r[i], &L->contact, scale);
    if (st != RIG_OK) {
        run_error(&L->F, st, &r[i], NULL, NAN, err, n);
        return 0;
    }
    return 1;
}

static int run_sets(void *h, int count, const rm_contact *p, const rig_setup *r, rig_figures *out,
                    recording *rec, char *err, size_t n) {
    rm_master *m = h;
    const fmi2CallbackFunctions cb = {logger, calloc, free, NULL, m};
    /* a recorded run has one observer, on one lane */
    const int lanes = rec || count < LANES ? 1 : LANES;
    lane L[LANES];
    int status = 0, next = 0, active = 0;
    for (int k = 0; k < lanes; ++k) {
        L[k] = (lane){{m, NULL, 0.0, NULL}, {0}, {0}, -1, 0};
        L[k].contact = (rig_contact){&L[k].F, fc_set_inputs, fc_force, fc_force_du2,
                                     fc_save, fc_restore,    fc_commit};
        L[k].F.c = m->instantiate("cmaster", fmi2CoSimulation, m->guid, m->resources, &cb,
                                  fmi2False, fmi2False);
        if (!L[k].F.c) {
            set_err(err, n, "fmi2Instantiate failed: %s", m->last);
            status = -1;
        }
    }
    if (rec) rec->F = &L[0].F;
    for (int k = 0; k < lanes && status == 0 && next < count; ++k, ++active)
        if (!lane_start(&L[k], next++, p, r, err, n)) status = -1;
    while (status == 0 && active > 0) {
        for (int k = 0; k < lanes && status == 0; ++k) {
            lane *a = &L[k];
            if (a->set < 0) continue;
            double x1_failed = NAN;
            /* the contact's functions as constants (not a->contact, which
             * holds the same in memory): so they are called directly */
            const int st =
                rig_advance_on(&a->run,
                               (rig_contact){&a->F, fc_set_inputs, fc_force, fc_force_du2, fc_save,
                                             fc_restore, fc_commit},
                               rec ? record_row : NULL, rec, &x1_failed);
            if (st != RIG_OK) {
                run_error(&a->F, st, &r[a->set], rec, x1_failed, err, n);
                status = -1;
                break;
            }
            if (!rig_done(&a->run)) continue;
            rig_finish(&a->run, &out[a->set]);
            if (a->F.snapshot) m->free_state(a->F.c, &a->F.snapshot);
            a->F.snapshot = NULL;
            a->set = -1;
            active -= 1;
            if (next < count) {
                if (!lane_start(a, next++, p, r, err, n))
                    status = -1;
                else
                    active += 1;
            }
        }
    }
    for (int k = 0; k < lanes; ++k) {
        if (!L[k].F.c) continue;
        if (L[k].F.snapshot) m->free_state(L[k].F.c, &L[k].F.snapshot);
        m->free_instance(L[k].F.c);
    }
    return status;
}

int rm_run(void *h, int count, const rm_contact *p, const rig_setup *r, rig_figures *out, char *err,
           size_t n) {
    return run_sets(h, count, p, r, out, NULL, err, n);
}

int rm_record(void *h, const rm_contact *p, const rig_setup *r, long every, double *rows,
              long capacity, long *n_rows, rig_figures *out, char *err, size_t n) {
    if (every < 1) {
        set_err(err, n, "record every %ld steps: expected >= 1", every);
        return -1;
    }
    recording rec = {NULL, every, capacity, 0, rows, 0};
    const int status = run_sets(h, 1, p, r, out, &rec, err, n);
    *n_rows = rec.rows;
    return status;
}
