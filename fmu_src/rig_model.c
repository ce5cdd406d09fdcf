/* The carriage/block rig as a model of the shared FMI glue (fmu_model.h): a
 * second model beside the contact, with its own table (rig_variables.h). */
#include <math.h>
#include <string.h>

#include "fmu_bytes.h"
#include "fmu_model.h"
#include "rig_core.h"
#include "rig_variables.h"

const fmu_model_info FMU_MODEL_INFO = {FMU_MODEL_IDENTIFIER, FMU_GUID, FMU_STATE_TAG};

enum { C_independent = 1, C_parameter, C_input, C_output };
enum { N_PAR = 6 }; /* mass, g, fInt, velocity, muStrip, cStrip: vr 1..6 */

typedef struct {
    const char *name;
    int causality;
    double start, min, max;
} var_info;

#define RIG_INFO_ENTRY(name, vr, type, caus, var, init, start, lo, hi, ...) \
    [vr] = {#name, C_##caus, start, lo, hi},
static const var_info VARS[RIG_VR_COUNT_PLUS_ONE] = {FMU_VARIABLES(RIG_INFO_ENTRY)};
#undef RIG_INFO_ENTRY

struct fmu_model {
    double par[N_PAR]; /* indexed by value reference - 1 */
    double T[2];       /* force of the mat on the block [N] */
    double x2, v2;     /* lateral position [m] and velocity [m/s] */
    double time;       /* [s]; x1 = velocity time */
};

static const var_info *lookup(unsigned int vr) {
    if (vr >= sizeof VARS / sizeof VARS[0] || VARS[vr].name == NULL) return NULL;
    return &VARS[vr];
}

const char *fmu_model_variable_name(unsigned int vr) {
    const var_info *v = lookup(vr);
    return v ? v->name : NULL;
}

size_t fmu_model_size(void) { return sizeof(struct fmu_model); }
double *fmu_model_time(fmu_model *m) { return &m->time; }

/* Every output is finite: each change of the time, a parameter, an input or
 * the state passes here before it is kept.  x1 = velocity time is the one
 * that can overflow from values each inside its range (1e6 m/s, 1e303 s). */
static fmu_status outputs_finite(const struct fmu_model *m, fmu_msg *msg) {
    const double x1 = m->par[RIG_VR_velocity - 1] * m->time;
    if (!isfinite(x1))
        return fmu_fail(msg, "x1 = u1 = velocity time = %g m/s * %g s overflows",
                        m->par[RIG_VR_velocity - 1], m->time);
    if (!isfinite(m->x2)) return fmu_fail(msg, "x2 = u2 = %g m is not finite", m->x2);
    if (!isfinite(m->par[RIG_VR_mass - 1] * m->par[RIG_VR_g - 1]))
        return fmu_fail(msg, "N = mass g overflows");
    if (!isfinite(m->par[RIG_VR_fInt - 1] - m->T[0]))
        return fmu_fail(msg, "driveForce = fInt - T1 overflows");
    return FMU_OK;
}

fmu_status fmu_model_check(const fmu_model *m, fmu_msg *msg) { return outputs_finite(m, msg); }

void fmu_model_init(fmu_model *m) {
    memset(m, 0, sizeof *m);
    for (int i = 0; i < N_PAR; ++i) m->par[i] = VARS[i + 1].start;
    m->T[0] = VARS[RIG_VR_T1].start;
    m->T[1] = VARS[RIG_VR_T2].start;
    m->time = VARS[RIG_VR_time].start;
}

fmu_status fmu_model_set_float64(fmu_model *m, const unsigned int vr[], size_t n, const double v[],
                                 int allow, fmu_msg *msg) {
    struct fmu_model next = *m;
    for (size_t i = 0; i < n; ++i) {
        const var_info *info = lookup(vr[i]);
        if (!info) return fmu_fail(msg, "unknown value reference %u", vr[i]);
        if (info->causality == C_output || info->causality == C_independent)
            return fmu_fail(msg, "variable %s cannot be set", info->name);
        if (info->causality == C_parameter && !(allow & FMU_ALLOW_PARAMETERS))
            return fmu_fail(msg, "parameter %s is fixed: it can be set only before the end of "
                                 "initialization (reset the FMU to change it)", info->name);
        if (info->causality == C_input && !(allow & FMU_ALLOW_INPUTS))
            return fmu_fail(msg, "input %s cannot be set in this state", info->name);
        if (!isfinite(v[i]))
            return fmu_fail(msg, "%s = %g rejected: values must be finite", info->name, v[i]);
        if (v[i] < info->min || v[i] > info->max)
            return fmu_fail(msg, "%s = %g rejected: outside [%g, %g]", info->name, v[i], info->min,
                            info->max);
        if (vr[i] >= 1 && vr[i] <= N_PAR) next.par[vr[i] - 1] = v[i];
        else next.T[vr[i] - RIG_VR_T1] = v[i];
    }
    if (outputs_finite(&next, msg) != FMU_OK) return FMU_ERR;
    *m = next;
    return FMU_OK;
}

fmu_status fmu_model_get_float64(const fmu_model *m, const unsigned int vr[], size_t n, double v[],
                                 fmu_msg *msg) {
    const double mass = m->par[RIG_VR_mass - 1], g = m->par[RIG_VR_g - 1];
    const double x1 = m->par[RIG_VR_velocity - 1] * m->time;
    for (size_t i = 0; i < n; ++i) {
        switch (vr[i]) {
        case RIG_VR_time: v[i] = m->time; break;
        case RIG_VR_T1: v[i] = m->T[0]; break;
        case RIG_VR_T2: v[i] = m->T[1]; break;
        case RIG_VR_u1: case RIG_VR_x1: v[i] = x1; break;
        case RIG_VR_u2: case RIG_VR_x2: v[i] = m->x2; break;
        case RIG_VR_N: v[i] = mass * g; break;
        case RIG_VR_driveForce: v[i] = m->par[RIG_VR_fInt - 1] - m->T[0]; break;
        default:
            if (vr[i] >= 1 && vr[i] <= N_PAR) {
                v[i] = m->par[vr[i] - 1];
                break;
            }
            return fmu_fail(msg, "unknown value reference %u", vr[i]);
        }
    }
    return FMU_OK;
}

fmu_status fmu_model_set_int(fmu_model *m, const unsigned int vr[], size_t n, const void *v,
                             size_t width, int kinds, int allow, fmu_msg *msg) {
    (void)m; (void)v; (void)width; (void)kinds; (void)allow;
    if (n == 0) return FMU_OK;
    return fmu_fail(msg, "unknown value reference %u (this FMU has no integer variables)", vr[0]);
}

fmu_status fmu_model_get_int(const fmu_model *m, const unsigned int vr[], size_t n, void *v,
                             size_t width, int kinds, fmu_msg *msg) {
    (void)m; (void)v; (void)width; (void)kinds;
    if (n == 0) return FMU_OK;
    return fmu_fail(msg, "unknown value reference %u (this FMU has no integer variables)", vr[0]);
}

/* One step with T held: the rig's lateral step (rig_core.h), refused
 * unchanged if the motion overflows or an output at the step's end (the
 * glue has moved the time there) is not finite. */
fmu_status fmu_model_do_step(fmu_model *m, double h, fmu_msg *msg) {
    const double mass = m->par[RIG_VR_mass - 1], mu_s = m->par[RIG_VR_muStrip - 1];
    const double c = m->par[RIG_VR_cStrip - 1];
    struct fmu_model next = *m;
    rig_lateral_step(&next.x2, &next.v2, m->T[0], m->T[1], mass, mu_s, 1.0 + h * c / mass, h);
    if (!isfinite(next.v2) || !isfinite(next.x2))
        return fmu_fail(msg, "the lateral motion overflows (T2 = %g N, h = %g s)", m->T[1], h);
    if (outputs_finite(&next, msg) != FMU_OK) return FMU_ERR;
    *m = next;
    return FMU_OK;
}

fmu_status fmu_model_derivative(const fmu_model *m, const unsigned int unknown[], size_t n_unknown,
                                const unsigned int known[], size_t n_known, const double seed[],
                                double out[], int adjoint, fmu_msg *msg) {
    (void)m; (void)unknown; (void)n_unknown; (void)known; (void)n_known; (void)seed; (void)out;
    (void)adjoint;
    return fmu_fail(msg, "this FMU provides no derivatives (providesDirectionalDerivative = false)");
}

/* Serialized: the six parameters, T1, T2, x2, v2: little-endian doubles. */
enum { N_STATE = N_PAR + 4 };
size_t fmu_model_state_size(void) { return 8 * N_STATE; }

void fmu_model_state_write(const fmu_model *m, unsigned char *p) {
    for (int i = 0; i < N_PAR; ++i) p = fmu_put_f64(p, m->par[i]);
    p = fmu_put_f64(p, m->T[0]);
    p = fmu_put_f64(p, m->T[1]);
    p = fmu_put_f64(p, m->x2);
    fmu_put_f64(p, m->v2);
}

fmu_status fmu_model_state_read(fmu_model *m, const unsigned char *p, fmu_msg *msg) {
    struct fmu_model t = *m;
    for (int i = 0; i < N_PAR; ++i) {
        p = fmu_get_f64(p, &t.par[i]);
        const var_info *v = &VARS[i + 1];
        if (!(t.par[i] >= v->min && t.par[i] <= v->max))
            return fmu_fail(msg, "serialized state: parameter %s = %g is outside [%g, %g]", v->name,
                            t.par[i], v->min, v->max);
    }
    p = fmu_get_f64(p, &t.T[0]);
    p = fmu_get_f64(p, &t.T[1]);
    p = fmu_get_f64(p, &t.x2);
    fmu_get_f64(p, &t.v2);
    if (!isfinite(t.T[0]) || !isfinite(t.T[1]) || !isfinite(t.x2) || !isfinite(t.v2))
        return fmu_fail(msg, "serialized state: a value is not finite");
    if (outputs_finite(&t, msg) != FMU_OK) {
        fmu_msg why = *msg;
        return fmu_fail(msg, "serialized state at t = %g s: %s", t.time, why.text);
    }
    *m = t;
    return FMU_OK;
}
