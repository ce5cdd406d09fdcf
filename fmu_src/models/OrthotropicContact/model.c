#include "models/OrthotropicContact/model.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "glue/fmu_instance.h"
#include "models/OrthotropicContact/table.h"

/* Where each variable of the table lives: the glue reads and writes them
 * there, and the outputs are kept current by evaluate.  The law's
 * parameters (the table's L rows) live in params under their own names. */
#define LAW_ROW(name, vr, type, caus, var, init, start, lo, hi, unit, ...)                         \
    [vr] = {#name, FMU_T_##type, FMU_C_##caus, FMU_SET_##caus,                                     \
            start, lo,           hi,           offsetof(oc_model, params.name),                    \
            unit},
#define FMU_SLOT_time offsetof(oc_model, time)
#define FMU_SLOT_slidingRule offsetof(oc_model, params.rule)
#define FMU_SLOT_u1 offsetof(oc_model, u[0])
#define FMU_SLOT_u2 offsetof(oc_model, u[1])
#define FMU_SLOT_N offsetof(oc_model, N)
#define FMU_SLOT_T1 offsetof(oc_model, T[0])
#define FMU_SLOT_T2 offsetof(oc_model, T[1])
#define FMU_SLOT_s1 offsetof(oc_model, s[0])
#define FMU_SLOT_s2 offsetof(oc_model, s[1])
#define FMU_SLOT_contactState offsetof(oc_model, contact)
#define FMU_SLOT_dissipatedEnergy offsetof(oc_model, energy)
#define FMU_SLOT_initialSlip offsetof(oc_model, initial_slip)
#define FMU_SLOT_s1Start offsetof(oc_model, s_start[0])
#define FMU_SLOT_s2Start offsetof(oc_model, s_start[1])

enum { FMU_ENUM_TYPES(FMU_ENUM_KIND) OC_ENUM_KINDS_END };

static const fmu_var VARS[OC_VR_COUNT_PLUS_ONE] = {OC_VARIABLES(FMU_VAR_ROW, LAW_ROW)};

static fmu_status derivative(const oc_model *m, const unsigned int unknown[], size_t n_unknown,
                             const unsigned int known[], size_t n_known, const double seed[],
                             double out[], int adjoint, fmu_msg *msg);
static fmu_status exit_init(oc_model *m, fmu_msg *msg);

const fmu_model_info FMU_MODEL_INFO = {FMU_MODEL_IDENTIFIER,
                                       FMU_TOKEN,
                                       FMU_STATE_TAG,
                                       VARS,
                                       OC_VR_COUNT_PLUS_ONE,
                                       sizeof(oc_model),
                                       NULL /* the outputs live in their slots */,
                                       exit_init,
                                       derivative,
                                       NULL /* no arrays */};

static const oc_state *committed(const oc_model *m) {
    return m->result_committed ? &m->steps[m->shown].next : &m->start;
}

/* A number the law has just stored, read on its own.  The law stores its
 * results one by one; a wider load across two of those stores (compilers
 * pair adjacent loads into one) must wait until both have retired, because
 * store forwarding fails (docs/benchmarks.md).  A volatile read is never
 * paired. */
static inline double fresh(const double *p) { return *(const volatile double *)p; }

/* Shows steps[shown]: its outputs into their slots. */
static OC_HOT void show(oc_model *m) {
    const oc_step *st = &m->steps[m->shown];
    /* 0.0 - q rather than -q: an open contact reads +0.0, not -0.0 */
    m->T[0] = 0.0 - fresh(&st->q[0]);
    m->T[1] = 0.0 - fresh(&st->q[1]);
    m->s[0] = fresh(&st->next.s[0]);
    m->s[1] = fresh(&st->next.s[1]);
    m->energy = st->next.energy;
    m->contact = st->contact;
}

/* The committed state before the first step (see models/OrthotropicContact/model.h). */
static oc_state initial_state(const oc_model *m) {
    return m->initial_slip == OC_INITIAL_EXPLICIT
               ? oc_state_unloaded(m->s_start[0], m->s_start[1], 0.0)
               : oc_state_unloaded(m->u[0], m->u[1], 0.0);
}

/* Computes the pending step for the inputs in m from the committed state
 * `from` with `law` into m (which commits neither); or fails and changes
 * nothing. */
static OC_HOT fmu_status evaluate(oc_model *m, const oc_law *law, const oc_state *from,
                                  fmu_msg *msg) {
    /* into the hidden step: `from` (which may be the shown step's state)
     * is read in place, no copy unless it moves */
    oc_step *st = &m->steps[m->shown ^ 1];
    oc_law_step(law, from, m->u, m->N, st);
    /* A stick step keeps `from`'s slip and energy (finite: a committed or
     * initial state always is) and a force inside the yield surface (finite:
     * an infinite or NaN trial fails the stick test); only q = G R a can
     * overflow.  Most steps stick: they check two numbers, not seven. */
    if (st->contact == OC_STICK ? !(isfinite(st->q[0]) && isfinite(st->q[1]))
                                : !oc_step_is_finite(st))
        return fmu_fail(msg, "inputs u1=%g m, u2=%g m, N=%g N overflow the force or slip", m->u[0],
                        m->u[1], m->N);
    if (law != &m->law) m->law = *law;
    if (from != &m->start) m->start = *from;
    m->shown ^= 1;
    show(m);
    m->result_committed = 0;
    return FMU_OK;
}

OC_HOT fmu_status fmu_model_update(oc_model *m, int changed, int allow, fmu_msg *msg) {
    /* Before the end of initialization the start follows the inputs or the
     * explicit slip; afterwards it is whatever was committed. */
    oc_state init;
    const oc_state *from = committed(m);
    if (allow & FMU_ALLOW_PARAMETERS) {
        init = initial_state(m);
        from = &init;
    }
    if (!(changed & FMU_CHANGED_PARAMETERS)) return evaluate(m, &m->law, from, msg);
    const char *why = oc_params_check(&m->params);
    if (why) return fmu_fail(msg, "%s", why);
    oc_law law;
    if (oc_law_init(&law, &m->params) != 0)
        return fmu_fail(msg, "parameters mu=(%g, %g) eps=(%g, %g) give non-finite tensors",
                        m->params.mu1, m->params.mu2, m->params.eps1, m->params.eps2);
    return evaluate(m, &law, from, msg);
}

/* Every set in initialization already derived the start from the values it
 * left; deriving it once more here makes the end of initialization the
 * moment that counts, whatever was restored before it. */
static fmu_status exit_init(oc_model *m, fmu_msg *msg) {
    const oc_state init = initial_state(m);
    return evaluate(m, &m->law, &init, msg);
}

/* A further step with held inputs: rare (a master sets inputs before a
 * step), so kept out of doStep, whose every call would otherwise pay for
 * the registers the law needs. */
static OC_NOINLINE fmu_status step_again(oc_model *m, fmu_msg *msg) {
    return evaluate(m, &m->law, &m->steps[m->shown].next, msg);
}

OC_HOT fmu_status fmu_model_do_step(oc_model *m, double h, fmu_msg *msg) {
    (void)h; /* rate-independent: the step size does not enter the law */
    if (m->result_committed && step_again(m, msg) != FMU_OK) return FMU_ERR;
    m->result_committed = 1;
    return FMU_OK;
}

/* The Jacobian's rows and columns, in their order in oc_law_jacobian */
static const unsigned int JAC_OUTPUTS[] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2,
                                           OC_VR_dissipatedEnergy};
static const unsigned int JAC_INPUTS[] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
typedef char jacobian_listed[sizeof JAC_OUTPUTS / sizeof *JAC_OUTPUTS == OC_JAC_ROWS &&
                                     sizeof JAC_INPUTS / sizeof *JAC_INPUTS == OC_JAC_COLS
                                 ? 1
                                 : -1];

static void partials(const oc_model *m, double *J) {
    oc_law_jacobian(&m->law, &m->start, m->u, m->N, &m->steps[m->shown], (double(*)[OC_JAC_COLS])J);
}

/* J fits the glue's buffer (a negative size fails to compile) */
typedef char jacobian_fits[OC_JAC_ROWS * OC_JAC_COLS <= FMU_JACOBIAN_MAX ? 1 : -1];
static const fmu_jacobian JACOBIAN = {OC_JAC_ROWS, OC_JAC_COLS, JAC_OUTPUTS, JAC_INPUTS, partials};

static fmu_status derivative(const oc_model *m, const unsigned int unknown[], size_t n_unknown,
                             const unsigned int known[], size_t n_known, const double seed[],
                             double out[], int adjoint, fmu_msg *msg) {
    return fmu_jacobian_derivative(&JACOBIAN, m, unknown, n_unknown, known, n_known, seed, out,
                                   adjoint, msg);
}

/* ---- serialized state: the field list of model.h ------------------------ */

/* Its reader (FMU_HAS_STATE_READ): the glue's writer and size
 * (glue/fmu_model_defaults.inc, at the end). */
fmu_status fmu_model_state_read(oc_model *m, const unsigned char *p, fmu_msg *msg) {
    oc_model t;
    memset(&t, 0, sizeof t);
    if (fmu_fields_read(&FMU_STATE_FIELDS, &t, &p, msg) != FMU_OK) return FMU_ERR;
    /* A master that saves and restores every step restores the parameters
     * it already has: keep their tensors instead of recomputing them. */
    /* Bit patterns, not ==: -0.0 and +0.0 give tensors that differ in the
     * sign of zero entries, and a restored state must continue bit for bit. */
    const int same = fmu_fields_same(&OC_PARAMS_FIELDS, &m->law.p, &t.params);
    if (same)
        t.law = m->law;
    else if (oc_law_init(&t.law, &t.params) != 0)
        return fmu_fail(msg, "serialized state: the parameters give non-finite tensors");
    const char *why = oc_state_check(&t.law, &t.start);
    if (why) return fmu_fail(msg, "serialized state: %s", why);
    /* The shown result is not stored but recomputed: the law is a function
     * of the committed state and the inputs, so nothing derived can
     * disagree with what it derives from. */
    t.shown = 0;
    oc_law_step(&t.law, &t.start, t.u, t.N, &t.steps[0]);
    if (!oc_step_is_finite(&t.steps[0]))
        return fmu_fail(msg, "serialized state: its inputs overflow the force or slip");
    show(&t);
    t.time = m->time; /* the glue restores the time */
    *m = t;
    return FMU_OK;
}

#include "glue/fmu_model_defaults.inc"
