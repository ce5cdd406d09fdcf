/*
 * The carriage/block rig as a model of the shared FMI glue (fmu_model.h):
 * a second model beside the contact, with its own table
 * (models/CarriageBlock/table.h); its step is the C rig's (rig/rig_core.h).
 */
#ifndef RIG_MODEL_H
#define RIG_MODEL_H

#include "glue/fmu_fields.h"
#include "glue/fmu_model.h"
#include "models/CarriageBlock/table.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { N_PAR = 6 }; /* mass, g, fInt, velocity, muStrip, cStrip: vr 1..6 */

struct fmu_model {
    double par[N_PAR];         /* indexed by value reference - 1 */
    double T[2];               /* force of the mat on the block [N] */
    double x2, v2;             /* lateral position [m] and velocity [m/s] */
    double time;               /* [s]; x1 = velocity time */
    double x1, N, drive_force; /* outputs that follow from the above (refresh) */
};

/* The model's part of the serialized state (glue/fmu_fields.h); the rest
 * follows from it and the time. */
#define RIG_PARAMETER_FIELD(name, vr, ...)                                                         \
    FMU_F64(struct fmu_model, par[vr - 1], #name, "the parameters", RANGE, vr),
static const fmu_field RIG_MODEL_FIELD_LIST[] = {
    RIG_PARAMETER_ROWS(RIG_PARAMETER_FIELD)
        FMU_F64(struct fmu_model, T[0], "T1", "the inputs", FINITE, 0),
    FMU_F64(struct fmu_model, T[1], "T2", "the inputs", FINITE, 0),
    FMU_F64(struct fmu_model, x2, "x2", "the lateral motion", FINITE, 0),
    FMU_F64(struct fmu_model, v2, "v2", "the lateral motion", FINITE, 0)};
#undef RIG_PARAMETER_FIELD
static const fmu_fields FMU_STATE_FIELDS = FMU_FIELDS(RIG_MODEL_FIELD_LIST, struct fmu_model);

#ifdef __cplusplus
}
#endif
#endif
