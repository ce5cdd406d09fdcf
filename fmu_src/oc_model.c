#include "oc_model.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "model_variables.h"

enum { T_Real = 1, T_Integer = 2 };
enum { C_parameter = 1, C_input = 2, C_output = 3 };

typedef struct {
    const char *name;
    int type, causality;
} var_info;

/* Indexed by value reference, straight from the table. */
#define OC_INFO_ENTRY(name, vr, type, caus, ...) [vr] = {#name, T_##type, C_##caus},
static const var_info VARS[OC_VR_COUNT_PLUS_ONE + 1] = {OC_VARIABLES(OC_INFO_ENTRY)};
#undef OC_INFO_ENTRY

static const var_info *lookup(unsigned int vr) {
    if (vr >= sizeof VARS / sizeof VARS[0] || VARS[vr].name == NULL) return NULL;
    return &VARS[vr];
}

const char *oc_variable_name(unsigned int vr) {
    const var_info *v = lookup(vr);
    return v ? v->name : NULL;
}

static oc_status fail(oc_msg *msg, const char *fmt, ...) {
    if (msg) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg->text, sizeof msg->text, fmt, ap);
        va_end(ap);
    }
    return OC_ERR;
}

/* Computes the pending step from the committed state into m, or fails and
 * changes nothing. */
static oc_status evaluate(oc_model *m, const oc_law *law, const double u[2], double N,
                          oc_msg *msg) {
    oc_step st;
    oc_law_step(law, &m->committed, u, N, &st);
    if (!oc_step_is_finite(&st))
        return fail(msg, "inputs u1=%g m, u2=%g m, N=%g N overflow the force or slip", u[0], u[1],
                    N);
    m->law = *law;
    m->u[0] = u[0];
    m->u[1] = u[1];
    m->N = N;
    m->start = m->committed;
    m->result = st;
    m->result_committed = 0;
    return OC_OK;
}

/* Start values, indexed by value reference, straight from the table. */
#define OC_START_ENTRY(name, vr, type, caus, var, init, start, ...) [vr] = start,
static const double START[OC_VR_COUNT_PLUS_ONE + 1] = {OC_VARIABLES(OC_START_ENTRY)};
#undef OC_START_ENTRY

void oc_model_init(oc_model *m) {
    /* memset also zeroes the padding, which the state image copies. */
    memset(m, 0, sizeof *m);
    m->params.mu1 = START[OC_VR_mu1];
    m->params.mu2 = START[OC_VR_mu2];
    m->params.eps1 = START[OC_VR_eps1];
    m->params.eps2 = START[OC_VR_eps2];
    m->params.alpha = START[OC_VR_alpha];
    m->params.beta = START[OC_VR_beta];
    m->params.rule = (int)START[OC_VR_slidingRule];
    m->u[0] = START[OC_VR_u1];
    m->u[1] = START[OC_VR_u2];
    m->N = START[OC_VR_N];
    oc_law_init(&m->law, &m->params);
    oc_law_step(&m->law, &m->committed, m->u, m->N, &m->result);
    m->start = m->committed;
}

static int param_slot(oc_params *p, unsigned int vr, double **slot) {
    switch (vr) {
    case OC_VR_mu1: *slot = &p->mu1; return 1;
    case OC_VR_mu2: *slot = &p->mu2; return 1;
    case OC_VR_eps1: *slot = &p->eps1; return 1;
    case OC_VR_eps2: *slot = &p->eps2; return 1;
    case OC_VR_alpha: *slot = &p->alpha; return 1;
    case OC_VR_beta: *slot = &p->beta; return 1;
    default: return 0;
    }
}

static oc_status check_settable(const var_info *v, unsigned int vr, int want_type, int allow,
                                oc_msg *msg) {
    if (!v) return fail(msg, "unknown value reference %u", vr);
    if (v->type != want_type)
        return fail(msg, "variable %s (vr %u) is not of type %s", v->name, vr,
                    want_type == T_Real ? "Real" : "Integer");
    if (v->causality == C_output) return fail(msg, "variable %s is an output and cannot be set", v->name);
    if (v->causality == C_parameter && !(allow & OC_ALLOW_PARAMETERS))
        return fail(msg, "parameter %s is fixed: it can be set only before "
                         "fmi2ExitInitializationMode (use fmi2Reset to change it)", v->name);
    if (v->causality == C_input && !(allow & OC_ALLOW_INPUTS))
        return fail(msg, "input %s cannot be set in this state", v->name);
    return OC_OK;
}

/* Applies new parameters (if changed) and inputs at once, or nothing. */
static oc_status apply(oc_model *m, const oc_params *p, int params_changed, const double u[2],
                       double N, oc_msg *msg) {
    if (!params_changed) return evaluate(m, &m->law, u, N, msg);
    const char *why = oc_params_check(p);
    if (why) return fail(msg, "%s", why);
    oc_law law;
    if (oc_law_init(&law, p) != 0)
        return fail(msg, "parameters mu=(%g, %g) eps=(%g, %g) give non-finite tensors", p->mu1,
                    p->mu2, p->eps1, p->eps2);
    if (evaluate(m, &law, u, N, msg) != OC_OK) return OC_ERR;
    m->params = *p;
    return OC_OK;
}

oc_status oc_model_set_real(oc_model *m, const unsigned int vr[], size_t n, const double v[],
                            int allow, oc_msg *msg) {
    oc_params p = m->params;
    int params_changed = 0;
    double u[2] = {m->u[0], m->u[1]}, N = m->N;
    for (size_t i = 0; i < n; ++i) {
        const var_info *info = lookup(vr[i]);
        if (check_settable(info, vr[i], T_Real, allow, msg) != OC_OK) return OC_ERR;
        if (!isfinite(v[i]))
            return fail(msg, "%s = %g rejected: values must be finite", info->name, v[i]);
        double *slot;
        if (param_slot(&p, vr[i], &slot)) {
            *slot = v[i];
            params_changed = 1;
        } else if (vr[i] == OC_VR_u1) u[0] = v[i];
        else if (vr[i] == OC_VR_u2) u[1] = v[i];
        else if (vr[i] == OC_VR_N) N = v[i];
    }
    return apply(m, &p, params_changed, u, N, msg);
}

oc_status oc_model_set_integer(oc_model *m, const unsigned int vr[], size_t n, const int v[],
                               int allow, oc_msg *msg) {
    oc_params p = m->params;
    for (size_t i = 0; i < n; ++i) {
        if (check_settable(lookup(vr[i]), vr[i], T_Integer, allow, msg) != OC_OK) return OC_ERR;
        p.rule = v[i]; /* slidingRule is the only settable Integer */
    }
    return apply(m, &p, n > 0, m->u, m->N, msg);
}

/* The error of a get with a value reference that is not of the asked type. */
static oc_status not_of_type(unsigned int vr, const char *type, oc_msg *msg) {
    const var_info *info = lookup(vr);
    if (info) return fail(msg, "variable %s (vr %u) is not of type %s", info->name, vr, type);
    return fail(msg, "unknown value reference %u", vr);
}

oc_status oc_model_get_real(const oc_model *m, const unsigned int vr[], size_t n, double v[],
                            oc_msg *msg) {
    for (size_t i = 0; i < n; ++i) {
        switch (vr[i]) {
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
        default: return not_of_type(vr[i], "Real", msg);
        }
    }
    return OC_OK;
}

oc_status oc_model_get_integer(const oc_model *m, const unsigned int vr[], size_t n, int v[],
                               oc_msg *msg) {
    for (size_t i = 0; i < n; ++i) {
        switch (vr[i]) {
        case OC_VR_slidingRule: v[i] = m->params.rule; break;
        case OC_VR_contactState: v[i] = m->result.contact; break;
        default: return not_of_type(vr[i], "Integer", msg);
        }
    }
    return OC_OK;
}

oc_status oc_model_do_step(oc_model *m, double t, double h, oc_msg *msg) {
    if (!isfinite(t) || !isfinite(h) || !(h > 0))
        return fail(msg, "doStep(currentCommunicationPoint=%g, communicationStepSize=%g): the step "
                         "size must be finite and > 0", t, h);
    /* Masters that count time as t0 + k h differ from a sum of steps by
     * rounding only; anything beyond that is a master error. */
    if (fabs(t - m->time) > 1e-9 * (1.0 + fabs(m->time)))
        return fail(msg, "doStep: currentCommunicationPoint=%.17g but the FMU is at time %.17g", t,
                    m->time);
    if (m->result_committed && evaluate(m, &m->law, m->u, m->N, msg) != OC_OK) return OC_ERR;
    m->committed = m->result.next;
    m->result_committed = 1;
    m->time = t + h;
    return OC_OK;
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

oc_status oc_model_directional_derivative(const oc_model *m, const unsigned int unknown[],
                                          size_t n_unknown, const unsigned int known[],
                                          size_t n_known, const double dv_known[],
                                          double dv_unknown[], oc_msg *msg) {
    for (size_t j = 0; j < n_known; ++j) {
        if (jac_col(known[j]) < 0)
            return fail(msg, "directional derivative: known vr %u (%s) is not an input u1, u2, N",
                        known[j], oc_variable_name(known[j]) ? oc_variable_name(known[j]) : "unknown");
        if (!isfinite(dv_known[j]))
            return fail(msg, "directional derivative: seed for vr %u is not finite", known[j]);
    }
    for (size_t i = 0; i < n_unknown; ++i)
        if (jac_row(unknown[i]) < 0)
            return fail(msg, "directional derivative: unknown vr %u (%s) is not a Real output "
                             "T1, T2, s1, s2, dissipatedEnergy",
                        unknown[i],
                        oc_variable_name(unknown[i]) ? oc_variable_name(unknown[i]) : "unknown");
    double J[OC_JAC_ROWS][OC_JAC_COLS];
    oc_law_jacobian(&m->law, &m->start, m->u, m->N, &m->result, J);
    for (size_t i = 0; i < n_unknown; ++i) {
        const int r = jac_row(unknown[i]);
        double acc = 0.0;
        for (size_t j = 0; j < n_known; ++j) acc += J[r][jac_col(known[j])] * dv_known[j];
        dv_unknown[i] = acc;
    }
    return OC_OK;
}

/* Image layout: magic, format version, payload size, then the model struct
 * (plain doubles and ints, no pointers).  Bit-exact within one platform. */
static const unsigned char IMAGE_MAGIC[4] = {'O', 'C', 'S', 'T'};
enum { IMAGE_VERSION = 1, IMAGE_HEADER = 12 };

size_t oc_model_image_size(void) { return IMAGE_HEADER + sizeof(oc_model); }

void oc_model_write_image(const oc_model *m, unsigned char *buf) {
    const unsigned int version = IMAGE_VERSION, size = (unsigned int)sizeof(oc_model);
    memcpy(buf, IMAGE_MAGIC, 4);
    memcpy(buf + 4, &version, 4);
    memcpy(buf + 8, &size, 4);
    memcpy(buf + IMAGE_HEADER, m, sizeof *m);
}

oc_status oc_model_read_image(oc_model *m, const unsigned char *buf, size_t size, oc_msg *msg) {
    unsigned int version, payload;
    if (!buf || size != oc_model_image_size())
        return fail(msg, "serialized state has %zu bytes, expected %zu", size, oc_model_image_size());
    memcpy(&version, buf + 4, 4);
    memcpy(&payload, buf + 8, 4);
    if (memcmp(buf, IMAGE_MAGIC, 4) != 0 || version != IMAGE_VERSION || payload != sizeof(oc_model))
        return fail(msg, "serialized state is not an OrthotropicContact state of format %d",
                    IMAGE_VERSION);
    oc_model tmp;
    memcpy(&tmp, buf + IMAGE_HEADER, sizeof tmp);
    const char *why = oc_params_check(&tmp.params);
    if (why) return fail(msg, "serialized state holds invalid parameters: %s", why);
    /* Derive the tensors again rather than trust the image's copy. */
    if (oc_law_init(&tmp.law, &tmp.params) != 0)
        return fail(msg, "serialized state holds parameters that give non-finite tensors");
    const double nums[] = {tmp.u[0], tmp.u[1], tmp.N, tmp.committed.s[0], tmp.committed.s[1],
                           tmp.committed.energy, tmp.start.s[0], tmp.start.s[1],
                           tmp.start.energy, tmp.time};
    for (size_t i = 0; i < sizeof nums / sizeof nums[0]; ++i)
        if (!isfinite(nums[i])) return fail(msg, "serialized state holds non-finite values");
    if (!oc_step_is_finite(&tmp.result)) return fail(msg, "serialized state holds non-finite values");
    *m = tmp;
    return OC_OK;
}
