#include "oc_model.h"

#include <math.h>
#include <string.h>

#include "fmu_bytes.h"
#include "model_variables.h"

const fmu_model_info FMU_MODEL_INFO = {FMU_MODEL_IDENTIFIER, FMU_GUID, FMU_STATE_TAG};

enum { T_Float64 = 1, T_Int32 = 2, T_Enum = 3 };
enum { C_independent = 1, C_parameter, C_input, C_output };

typedef struct {
    const char *name;
    int type, causality;
    double start, min, max;
} var_info;

/* Indexed by value reference, straight from the table. */
#define OC_INFO_ENTRY(name, vr, type, caus, var, init, start, lo, hi, ...) \
    [vr] = {#name, T_##type, C_##caus, start, lo, hi},
static const var_info VARS[OC_VR_COUNT_PLUS_ONE] = {FMU_VARIABLES(OC_INFO_ENTRY)};
#undef OC_INFO_ENTRY

static const var_info *lookup(unsigned int vr) {
    if (vr >= sizeof VARS / sizeof VARS[0] || VARS[vr].name == NULL) return NULL;
    return &VARS[vr];
}

const char *fmu_model_variable_name(unsigned int vr) {
    const var_info *v = lookup(vr);
    return v ? v->name : NULL;
}

size_t fmu_model_size(void) { return sizeof(oc_model); }
double *fmu_model_time(fmu_model *m) { return &m->time; }

/* The contact's outputs do not depend on the time, and every change of its
 * inputs, parameters or state checks them. */
fmu_status fmu_model_check(const fmu_model *m, fmu_msg *msg) {
    (void)m; (void)msg;
    return FMU_OK;
}

static const oc_state *committed(const oc_model *m) {
    return m->result_committed ? &m->result.next : &m->start;
}

/* Computes the pending step from the committed state into m, or fails and
 * changes nothing. */
static fmu_status evaluate(oc_model *m, const oc_law *law, const double u[2], double N,
                           fmu_msg *msg) {
    oc_step st;
    const oc_state from = *committed(m);
    oc_law_step(law, &from, u, N, &st);
    if (!oc_step_is_finite(&st))
        return fmu_fail(msg, "inputs u1=%g m, u2=%g m, N=%g N overflow the force or slip", u[0],
                        u[1], N);
    if (law != &m->law) m->law = *law;
    m->u[0] = u[0];
    m->u[1] = u[1];
    m->N = N;
    m->start = from;
    m->result = st;
    m->result_committed = 0;
    return FMU_OK;
}

void fmu_model_init(oc_model *m) {
    memset(m, 0, sizeof *m);
    m->params.mu1 = VARS[OC_VR_mu1].start;
    m->params.mu2 = VARS[OC_VR_mu2].start;
    m->params.eps1 = VARS[OC_VR_eps1].start;
    m->params.eps2 = VARS[OC_VR_eps2].start;
    m->params.alpha = VARS[OC_VR_alpha].start;
    m->params.beta = VARS[OC_VR_beta].start;
    m->params.rule = (int)VARS[OC_VR_slidingRule].start;
    m->u[0] = VARS[OC_VR_u1].start;
    m->u[1] = VARS[OC_VR_u2].start;
    m->N = VARS[OC_VR_N].start;
    m->time = VARS[OC_VR_time].start;
    oc_law_init(&m->law, &m->params);
    oc_law_step(&m->law, &m->start, m->u, m->N, &m->result);
}

static double *param_slot(oc_params *p, unsigned int vr) {
    switch (vr) {
    case OC_VR_mu1: return &p->mu1;
    case OC_VR_mu2: return &p->mu2;
    case OC_VR_eps1: return &p->eps1;
    case OC_VR_eps2: return &p->eps2;
    case OC_VR_alpha: return &p->alpha;
    case OC_VR_beta: return &p->beta;
    default: return NULL;
    }
}

static const char *type_name(int type) {
    return type == T_Float64 ? "Float64 (Real)" : type == T_Int32 ? "Int32 (Integer)"
                                                                 : "Enumeration (Integer)";
}

/* Whether v may be set now to `value`: type, causality, phase, range. */
static fmu_status check_settable(const var_info *v, unsigned int vr, int type_ok, double value,
                                 int allow, fmu_msg *msg) {
    if (!v) return fmu_fail(msg, "unknown value reference %u", vr);
    if (!type_ok)
        return fmu_fail(msg, "variable %s (vr %u) is of type %s", v->name, vr, type_name(v->type));
    if (v->causality == C_output)
        return fmu_fail(msg, "variable %s is an output and cannot be set", v->name);
    if (v->causality == C_independent)
        return fmu_fail(msg, "variable %s is the independent variable: doStep advances it", v->name);
    if (v->causality == C_parameter && !(allow & FMU_ALLOW_PARAMETERS))
        return fmu_fail(msg, "parameter %s is fixed: it can be set only before the end of "
                             "initialization (reset the FMU to change it)", v->name);
    if (v->causality == C_input && !(allow & FMU_ALLOW_INPUTS))
        return fmu_fail(msg, "input %s cannot be set in this state", v->name);
    if (!isfinite(value))
        return fmu_fail(msg, "%s = %g rejected: values must be finite", v->name, value);
    if (value < v->min || value > v->max)
        return fmu_fail(msg, "%s = %g rejected: outside [%g, %g]", v->name, value, v->min, v->max);
    return FMU_OK;
}

/* Applies new parameters (if changed) and inputs at once, or nothing. */
static fmu_status apply(oc_model *m, const oc_params *p, int params_changed, const double u[2],
                        double N, fmu_msg *msg) {
    if (!params_changed) return evaluate(m, &m->law, u, N, msg);
    const char *why = oc_params_check(p);
    if (why) return fmu_fail(msg, "%s", why);
    oc_law law;
    if (oc_law_init(&law, p) != 0)
        return fmu_fail(msg, "parameters mu=(%g, %g) eps=(%g, %g) give non-finite tensors",
                        p->mu1, p->mu2, p->eps1, p->eps2);
    if (evaluate(m, &law, u, N, msg) != FMU_OK) return FMU_ERR;
    m->params = *p;
    return FMU_OK;
}

fmu_status fmu_model_set_float64(oc_model *m, const unsigned int vr[], size_t n, const double v[],
                                 int allow, fmu_msg *msg) {
    oc_params p = m->params;
    int params_changed = 0;
    double u[2] = {m->u[0], m->u[1]}, N = m->N;
    for (size_t i = 0; i < n; ++i) {
        const var_info *info = lookup(vr[i]);
        if (check_settable(info, vr[i], info && info->type == T_Float64, v[i], allow, msg) != FMU_OK)
            return FMU_ERR;
        double *slot = param_slot(&p, vr[i]);
        if (slot) {
            *slot = v[i];
            params_changed = 1;
        } else if (vr[i] == OC_VR_u1) u[0] = v[i];
        else if (vr[i] == OC_VR_u2) u[1] = v[i];
        else if (vr[i] == OC_VR_N) N = v[i];
    }
    return apply(m, &p, params_changed, u, N, msg);
}

static int int_kind(const var_info *v) {
    return !v ? 0 : v->type == T_Int32 ? FMU_INT32 : v->type == T_Enum ? FMU_ENUM : 0;
}

fmu_status fmu_model_set_int(oc_model *m, const unsigned int vr[], size_t n, const void *v,
                             size_t width, int kinds, int allow, fmu_msg *msg) {
    oc_params p = m->params;
    for (size_t i = 0; i < n; ++i) {
        const var_info *info = lookup(vr[i]);
        const int64_t x = fmu_int_at(v, width, i);
        if (check_settable(info, vr[i], (int_kind(info) & kinds) != 0, (double)x, allow, msg) !=
            FMU_OK)
            return FMU_ERR;
        p.rule = (int)x; /* slidingRule is the only settable integer */
    }
    return apply(m, &p, n > 0, m->u, m->N, msg);
}

static fmu_status not_of_type(unsigned int vr, const char *asked, fmu_msg *msg) {
    const var_info *info = lookup(vr);
    if (info)
        return fmu_fail(msg, "variable %s (vr %u) is of type %s, not %s", info->name, vr,
                        type_name(info->type), asked);
    return fmu_fail(msg, "unknown value reference %u", vr);
}

fmu_status fmu_model_get_float64(const oc_model *m, const unsigned int vr[], size_t n, double v[],
                                 fmu_msg *msg) {
    for (size_t i = 0; i < n; ++i) {
        switch (vr[i]) {
        case OC_VR_time: v[i] = m->time; break;
        case OC_VR_mu1: v[i] = m->params.mu1; break;
        case OC_VR_mu2: v[i] = m->params.mu2; break;
        case OC_VR_eps1: v[i] = m->params.eps1; break;
        case OC_VR_eps2: v[i] = m->params.eps2; break;
        case OC_VR_alpha: v[i] = m->params.alpha; break;
        case OC_VR_beta: v[i] = m->params.beta; break;
        case OC_VR_u1: v[i] = m->u[0]; break;
        case OC_VR_u2: v[i] = m->u[1]; break;
        case OC_VR_N: v[i] = m->N; break;
        /* 0.0 - q rather than -q: an open contact reads +0.0, not -0.0 */
        case OC_VR_T1: v[i] = 0.0 - m->result.q[0]; break;
        case OC_VR_T2: v[i] = 0.0 - m->result.q[1]; break;
        case OC_VR_s1: v[i] = m->result.next.s[0]; break;
        case OC_VR_s2: v[i] = m->result.next.s[1]; break;
        case OC_VR_dissipatedEnergy: v[i] = m->result.next.energy; break;
        default: return not_of_type(vr[i], "Float64 (Real)", msg);
        }
    }
    return FMU_OK;
}

fmu_status fmu_model_get_int(const oc_model *m, const unsigned int vr[], size_t n, void *v,
                             size_t width, int kinds, fmu_msg *msg) {
    for (size_t i = 0; i < n; ++i) {
        const var_info *info = lookup(vr[i]);
        if (!(int_kind(info) & kinds))
            return not_of_type(vr[i], kinds == FMU_ENUM ? "Enumeration (Int64)"
                                      : kinds == FMU_INT32 ? "Int32" : "Integer", msg);
        fmu_int_put(v, width, i, vr[i] == OC_VR_slidingRule ? m->params.rule : m->result.contact);
    }
    return FMU_OK;
}

fmu_status fmu_model_do_step(oc_model *m, double h, fmu_msg *msg) {
    (void)h; /* rate-independent: the step size does not enter the law */
    if (m->result_committed && evaluate(m, &m->law, m->u, m->N, msg) != FMU_OK) return FMU_ERR;
    m->result_committed = 1;
    return FMU_OK;
}

static int jac_row(unsigned int vr) {
    switch (vr) {
    case OC_VR_T1: return 0;
    case OC_VR_T2: return 1;
    case OC_VR_s1: return 2;
    case OC_VR_s2: return 3;
    case OC_VR_dissipatedEnergy: return 4;
    default: return -1;
    }
}

static int jac_col(unsigned int vr) {
    switch (vr) {
    case OC_VR_u1: return 0;
    case OC_VR_u2: return 1;
    case OC_VR_N: return 2;
    default: return -1;
    }
}

static const char *name_or_unknown(unsigned int vr) {
    const char *n = fmu_model_variable_name(vr);
    return n ? n : "unknown";
}

fmu_status fmu_model_derivative(const oc_model *m, const unsigned int unknown[], size_t n_unknown,
                                const unsigned int known[], size_t n_known, const double seed[],
                                double out[], int adjoint, fmu_msg *msg) {
    for (size_t j = 0; j < n_known; ++j)
        if (jac_col(known[j]) < 0)
            return fmu_fail(msg, "known vr %u (%s) is not an input u1, u2, N", known[j],
                            name_or_unknown(known[j]));
    for (size_t i = 0; i < n_unknown; ++i)
        if (jac_row(unknown[i]) < 0)
            return fmu_fail(msg, "unknown vr %u (%s) is not a Float64 output T1, T2, s1, s2, "
                                 "dissipatedEnergy", unknown[i], name_or_unknown(unknown[i]));
    const size_t n_seed = adjoint ? n_unknown : n_known;
    for (size_t k = 0; k < n_seed; ++k)
        if (!isfinite(seed[k])) return fmu_fail(msg, "seed %zu is not finite", k);
    double J[OC_JAC_ROWS][OC_JAC_COLS];
    oc_law_jacobian(&m->law, &m->start, m->u, m->N, &m->result, J);
    const size_t n_out = adjoint ? n_known : n_unknown;
    for (size_t k = 0; k < n_out; ++k) {
        double acc = 0.0;
        if (adjoint)
            for (size_t i = 0; i < n_unknown; ++i) acc += J[jac_row(unknown[i])][jac_col(known[k])] * seed[i];
        else
            for (size_t j = 0; j < n_known; ++j) acc += J[jac_row(unknown[k])][jac_col(known[j])] * seed[j];
        if (!isfinite(acc)) return fmu_fail(msg, "the derivative overflows");
        out[k] = acc;
    }
    return FMU_OK;
}

/* ---- serialized state: field by field, little-endian --------------------- */

enum { N_PARAM_F64 = 6, N_STATE_F64 = 8 };
static size_t state_bytes(void) { return 8 * N_PARAM_F64 + 4 + 8 * 3 + 8 * N_STATE_F64 + 4; }
size_t fmu_model_state_size(void) { return state_bytes(); }

static unsigned char *put_state(unsigned char *p, const oc_state *s) {
    const double f[N_STATE_F64] = {s->u[0], s->u[1], s->N, s->a[0], s->a[1], s->s[0], s->s[1],
                                   s->energy};
    for (int i = 0; i < N_STATE_F64; ++i) p = fmu_put_f64(p, f[i]);
    return p;
}

static const unsigned char *get_state(const unsigned char *p, oc_state *s) {
    double f[N_STATE_F64];
    for (int i = 0; i < N_STATE_F64; ++i) p = fmu_get_f64(p, &f[i]);
    *s = (oc_state){{f[0], f[1]}, f[2], {f[3], f[4]}, {f[5], f[6]}, f[7]};
    return p;
}

void fmu_model_state_write(const oc_model *m, unsigned char *p) {
    const oc_params *q = &m->params;
    const double pf[N_PARAM_F64] = {q->mu1, q->mu2, q->eps1, q->eps2, q->alpha, q->beta};
    for (int i = 0; i < N_PARAM_F64; ++i) p = fmu_put_f64(p, pf[i]);
    p = fmu_put_u32(p, (uint32_t)q->rule);
    p = fmu_put_f64(p, m->u[0]);
    p = fmu_put_f64(p, m->u[1]);
    p = fmu_put_f64(p, m->N);
    p = put_state(p, &m->start);
    fmu_put_u32(p, (uint32_t)m->result_committed);
}

fmu_status fmu_model_state_read(oc_model *m, const unsigned char *p, fmu_msg *msg) {
    oc_model t;
    memset(&t, 0, sizeof t);
    double pf[N_PARAM_F64];
    uint32_t rule, done;
    for (int i = 0; i < N_PARAM_F64; ++i) p = fmu_get_f64(p, &pf[i]);
    p = fmu_get_u32(p, &rule);
    p = fmu_get_f64(p, &t.u[0]);
    p = fmu_get_f64(p, &t.u[1]);
    p = fmu_get_f64(p, &t.N);
    p = get_state(p, &t.start);
    fmu_get_u32(p, &done);
    t.params = (oc_params){pf[0], pf[1], pf[2], pf[3], pf[4], pf[5], (int)rule};
    static const unsigned pvr[N_PARAM_F64] = {OC_VR_mu1, OC_VR_mu2, OC_VR_eps1, OC_VR_eps2,
                                              OC_VR_alpha, OC_VR_beta};
    for (int i = 0; i < N_PARAM_F64; ++i) {
        const var_info *v = &VARS[pvr[i]];
        if (!(pf[i] >= v->min && pf[i] <= v->max))
            return fmu_fail(msg, "serialized state: parameter %s = %g is outside [%g, %g]", v->name,
                            pf[i], v->min, v->max);
    }
    if (rule < 1 || rule > 3)
        return fmu_fail(msg, "serialized state: slidingRule = %u is not 1, 2 or 3", (unsigned)rule);
    /* A master that saves and restores every step restores the parameters
     * it already has: keep their tensors instead of recomputing them. */
    /* Bit patterns, not ==: -0.0 and +0.0 give tensors that differ in the
     * sign of zero entries, and a restored state must continue bit for bit. */
    const double mine[N_PARAM_F64] = {m->law.p.mu1, m->law.p.mu2, m->law.p.eps1, m->law.p.eps2,
                                      m->law.p.alpha, m->law.p.beta};
    const int same = memcmp(mine, pf, sizeof mine) == 0 && m->law.p.rule == t.params.rule;
    if (same) t.law = m->law;
    else if (oc_law_init(&t.law, &t.params) != 0)
        return fmu_fail(msg, "serialized state: the parameters give non-finite tensors");
    if (!isfinite(t.u[0]) || !isfinite(t.u[1]) || !isfinite(t.N))
        return fmu_fail(msg, "serialized state: an input is not finite");
    const char *why = oc_state_check(&t.law, &t.start);
    if (why) return fmu_fail(msg, "serialized state: %s", why);
    if (done > 1) return fmu_fail(msg, "serialized state: commit flag %u is not 0 or 1", (unsigned)done);
    /* The shown result is not stored but recomputed: the law is a function
     * of the committed state and the inputs, so nothing derived can
     * disagree with what it derives from. */
    oc_law_step(&t.law, &t.start, t.u, t.N, &t.result);
    if (!oc_step_is_finite(&t.result))
        return fmu_fail(msg, "serialized state: its inputs overflow the force or slip");
    t.result_committed = (int)done;
    t.time = m->time; /* the glue restores the time */
    *m = t;
    return FMU_OK;
}
