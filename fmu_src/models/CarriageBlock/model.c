/* The carriage/block rig as a model of the shared FMI glue (model.h). */
#include "models/CarriageBlock/model.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "rig/rig_core.h"

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

/* x1 = velocity time is the output that can overflow from values each
 * inside its range (1e6 m/s, 1e303 s); N and driveForce are checked alike
 * rather than argued from today's ranges. */
static fmu_status refresh(fmu_model *m, fmu_msg *msg) {
    const double velocity = m->par[RIG_VR_velocity - 1];
    const double x1 = velocity * m->time;
    const double N = m->par[RIG_VR_mass - 1] * m->par[RIG_VR_g - 1];
    const double drive_force = m->par[RIG_VR_fInt - 1] - m->T[0];
    if (!isfinite(x1))
        return fmu_fail(msg, "x1 = u1 = velocity time = %g m/s * %g s overflows", velocity,
                        m->time);
    if (!isfinite(N)) return fmu_fail(msg, "N = mass g overflows");
    if (!isfinite(drive_force)) return fmu_fail(msg, "driveForce = fInt - T1 overflows");
    m->x1 = x1;
    m->N = N;
    m->drive_force = drive_force;
    return FMU_OK;
}

/* No derivatives (providesDirectionalDerivative = false): the glue's default. */
const fmu_model_info FMU_MODEL_INFO = {
    FMU_MODEL_IDENTIFIER,     FMU_TOKEN, FMU_STATE_TAG, VARS, RIG_VR_COUNT_PLUS_ONE,
    sizeof(struct fmu_model), refresh,   NULL,          NULL, NULL /* no arrays */};

/* One step with T held: the rig's lateral step (rig_core.h), refused
 * unchanged if the motion overflows.  x2 and v2 are the outputs this keeps;
 * the rest follow from the time (already the step's end) through refresh. */
fmu_status fmu_model_do_step(fmu_model *m, double h, fmu_msg *msg) {
    const double mass = m->par[RIG_VR_mass - 1], mu_s = m->par[RIG_VR_muStrip - 1];
    const double c = m->par[RIG_VR_cStrip - 1];
    double x2 = m->x2, v2 = m->v2;
    rig_lateral_step(&x2, &v2, m->T[0], m->T[1], mass, mu_s, 1.0 + h * c / mass, h);
    if (!isfinite(v2) || !isfinite(x2))
        return fmu_fail(msg, "the lateral motion overflows (T2 = %g N, h = %g s)", m->T[1], h);
    m->x2 = x2;
    m->v2 = v2;
    return FMU_OK;
}

/* The rest is the glue's: no update (every value the glue checked against
 * the table is admissible), the serialized state of model.h's field list. */
#include "glue/fmu_model_defaults.inc"
