/* The carriage/block rig as a model of the shared FMI glue (fmu_model.h): a
 * second model beside the contact, with its own table (rig_variables.h). */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "fmu_bytes.h"
#include "fmu_model.h"
#include "rig_variables.h"

enum { N_PAR = 6 }; /* mass, g, fInt, velocity, muStrip, cStrip: vr 1..6 */

struct fmu_model {
    double par[N_PAR]; /* indexed by value reference - 1 */
    double T[2];       /* force of the mat on the block [N] */
    double x2, v2;     /* lateral position [m] and velocity [m/s] */
    double time;       /* [s]; x1 = velocity time */
    double x1, N, drive_force; /* outputs that follow from the above (refresh) */
};

/* Where each variable of the table lives (the glue reads and writes them). */
#define FMU_SLOT_time offsetof(struct fmu_model, time)
#define FMU_SLOT_mass offsetof(struct fmu_model, par[RIG_VR_mass - 1])
#define FMU_SLOT_g offsetof(struct fmu_model, par[RIG_VR_g - 1])
#define FMU_SLOT_fInt offsetof(struct fmu_model, par[RIG_VR_fInt - 1])
#define FMU_SLOT_velocity offsetof(struct fmu_model, par[RIG_VR_velocity - 1])
#define FMU_SLOT_muStrip offsetof(struct fmu_model, par[RIG_VR_muStrip - 1])
#define FMU_SLOT_cStrip offsetof(struct fmu_model, par[RIG_VR_cStrip - 1])
#define FMU_SLOT_T1 offsetof(struct fmu_model, T[0])
#define FMU_SLOT_T2 offsetof(struct fmu_model, T[1])
#define FMU_SLOT_u1 offsetof(struct fmu_model, x1)
#define FMU_SLOT_u2 offsetof(struct fmu_model, x2)
#define FMU_SLOT_N offsetof(struct fmu_model, N)
#define FMU_SLOT_x1 offsetof(struct fmu_model, x1)
#define FMU_SLOT_x2 offsetof(struct fmu_model, x2)
#define FMU_SLOT_driveForce offsetof(struct fmu_model, drive_force)

static const fmu_var VARS[RIG_VR_COUNT_PLUS_ONE] = {FMU_VARIABLES(FMU_VAR_ROW)};

static void refresh(fmu_model *m) {
    m->x1 = m->par[RIG_VR_velocity - 1] * m->time;
    m->N = m->par[RIG_VR_mass - 1] * m->par[RIG_VR_g - 1];
    m->drive_force = m->par[RIG_VR_fInt - 1] - m->T[0];
}

/* No derivatives (providesDirectionalDerivative = false): the glue's default. */
const fmu_model_info FMU_MODEL_INFO = {FMU_MODEL_IDENTIFIER, FMU_TOKEN, FMU_STATE_TAG, VARS,
                                       RIG_VR_COUNT_PLUS_ONE, sizeof(struct fmu_model), refresh,
                                       NULL, NULL};

/* Every value the glue checked against the table is admissible. */
fmu_status fmu_model_update(fmu_model *m, int changed, int allow, fmu_msg *msg) {
    (void)m; (void)changed; (void)allow; (void)msg;
    return FMU_OK;
}

/* One step with T held, as the Python harness's dynamic rig: symplectic
 * Euler; the strip's Coulomb force opposes the lateral motion and may stop
 * the block within the step but never reverse it; the viscous term is
 * implicit, so any step is stable (with cStrip = 0 the update is the
 * harness's, operation for operation). */
fmu_status fmu_model_do_step(fmu_model *m, double h, fmu_msg *msg) {
    const double mass = m->par[RIG_VR_mass - 1], mu_s = m->par[RIG_VR_muStrip - 1];
    const double c = m->par[RIG_VR_cStrip - 1];
    const double P = fmax(-m->T[0], 0.0), T2 = m->T[1];
    const double f_max = mu_s * P, a_free = T2 / mass, damp = 1.0 + h * c / mass;
    double v2;
    if (f_max > 0.0) {
        const double v_free = (m->v2 + h * a_free) / damp;
        const double f = v_free != 0.0 ? -copysign(fmin(f_max, fabs(mass * v_free / h)), v_free)
                                       : -copysign(fmin(f_max, fabs(T2)), T2);
        v2 = v_free + h * f / mass;
    } else {
        v2 = (m->v2 + h * a_free) / damp;
    }
    const double x2 = m->x2 + h * v2;
    if (!isfinite(v2) || !isfinite(x2))
        return fmu_fail(msg, "the lateral motion overflows (T2 = %g N, h = %g s)", T2, h);
    m->v2 = v2;
    m->x2 = x2;
    return FMU_OK;
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
        if (fmu_model_check_range((unsigned)i + 1, t.par[i], "serialized state", msg) != FMU_OK)
            return FMU_ERR;
    }
    p = fmu_get_f64(p, &t.T[0]);
    p = fmu_get_f64(p, &t.T[1]);
    p = fmu_get_f64(p, &t.x2);
    fmu_get_f64(p, &t.v2);
    if (!isfinite(t.T[0]) || !isfinite(t.T[1]) || !isfinite(t.x2) || !isfinite(t.v2))
        return fmu_fail(msg, "serialized state: a value is not finite");
    *m = t;
    return FMU_OK;
}
