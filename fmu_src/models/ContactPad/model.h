/*
 * The contact pad as a model of the shared FMI glue (fmu_model.h): the
 * variables of models/ContactPad/table.h, the patch's cells
 * (cells/cells.h) pressed by a Winkler foundation under the
 * pad's pose (models/ContactPad/pressure.h), and the serialized state.
 *
 * Step semantics as the patch's: setting inputs computes every cell's
 * normal force and step from the committed states without committing them;
 * the outputs read that pending result; a doStep commits all cells.  A
 * step in which any cell, sum, force or moment would not be finite is
 * refused and changes nothing.
 *
 * The approach's rate (the foundation's damping dn) is taken over the
 * previous communication step: against the pose a step starts from (the
 * pose of the last committed step, `ref`) and the size of that step; the
 * pending step knows no other (the step size reaches the model at doStep
 * only).  Before the first doStep there is none (ref.h = 0).
 *
 * Rolling likewise (cells/transport.h): a step from the committed result
 * starts from the committed states moved with the material by the
 * committed step's vr h (commit.vr, commit.h), so that vr acts from the
 * next step on; a step at the same time again starts from that moved
 * start.  vr h = 0 moves nothing: the pad without rolling, bit for bit.
 */
#ifndef PAD_MODEL_H
#define PAD_MODEL_H

#include "cells/cells.h"
#include "cells/cells_fields.h"
#include "glue/fmu_fields.h"
#include "glue/fmu_model.h"
#include "law/contact_law.h"
#include "law/law_fields.h"
#include "models/ContactPad/table.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A pose of the pad, its rolling speed and the step size its rate is taken
 * over. */
typedef struct {
    double d, phi[2], theta; /* [m], [rad], [rad] */
    double h;                /* [s]; 0: no rate */
    double vr;               /* [m/s]: the material moves by vr h over the step */
} pad_pose;

struct fmu_model {
    oc_params params; /* the table's law parameters: eps1, eps2 the whole pad's */
    cells_setup g;    /* the geometry, the initial slip, u1, u2, theta */
    double kn, dn;    /* the foundation [N/m^3], [N s/m^3] */
    double d, phi[2]; /* the pose's inputs [m], [rad] */
    double vr;        /* the rolling speed [m/s] (cells/transport.h) */
    /* The shown step's outputs, where the table reads them: */
    cells_sums out;
    double Fn, M[2], contact_fraction;
    double time;
    /* The pose the shown step's rate is taken against (the start's), and
     * that of the shown step with the size of the doStep that committed it
     * (while cells.result_committed): the next step's reference. */
    pad_pose ref, commit;
    /* The damper's work on the body [J]: up to the shown step's start, and
     * in the shown step (dissipatedEnergy counts both, with the cells'). */
    double damper, damper_step;
    cells_grid cells;
};
typedef struct fmu_model pad_model;

/* The model's part of the serialized state (glue/fmu_fields.h): the head,
 * then every cell's committed state (cells_fields.h).  The shown result is
 * not stored but recomputed from the committed states, the inputs and the
 * rate's reference. */
#define PAD_POSE_FIELDS(member, group)                                                             \
    FMU_F64(pad_model, member.d, "d", group, FINITE, 0),                                           \
        FMU_F64(pad_model, member.phi[0], "phi1", group, FINITE, 0),                               \
        FMU_F64(pad_model, member.phi[1], "phi2", group, FINITE, 0),                               \
        FMU_F64(pad_model, member.theta, "theta", group, FINITE, 0),                               \
        FMU_F64(pad_model, member.h, "h", group, FINITE, 0),                                       \
        FMU_F64(pad_model, member.vr, "vr", group, FINITE, 0)
static const fmu_field PAD_MODEL_FIELD_LIST[] = {
    FMU_RECORD(pad_model, params, &OC_PARAMS_FIELDS,
               "the law's parameters (eps1, eps2 the whole pad's)"),
    CELLS_SETUP_FIELDS,
    FMU_F64(pad_model, kn, "kn", "the foundation", RANGE, PAD_VR_kn),
    FMU_F64(pad_model, dn, "dn", "the foundation", RANGE, PAD_VR_dn),
    CELLS_MOTION_FIELDS,
    FMU_F64(pad_model, d, "d", "the inputs", FINITE, 0),
    FMU_F64(pad_model, phi[0], "phi1", "the inputs", FINITE, 0),
    FMU_F64(pad_model, phi[1], "phi2", "the inputs", FINITE, 0),
    FMU_F64(pad_model, vr, "vr", "the inputs", FINITE, 0),
    CELLS_COMMITTED_FIELD,
    PAD_POSE_FIELDS(ref, "the pose the shown step's rate is taken against, and over what step "
                         "[s] (0: none)"),
    PAD_POSE_FIELDS(commit, "the shown step's pose and the size [s] of the doStep that committed "
                            "it (while committed)"),
    FMU_F64(pad_model, damper, "damper", "the damper's work up to the shown step's start [J]",
            FINITE, 0),
    CELLS_STATES_FIELD};
CELLS_STATE_FIELDS(PAD_MODEL_FIELD_LIST);
/* What model.c writes itself (glue/fmu_model_defaults.inc the rest): its
 * update, its state's writer (cells/cells_model.inc: the cells where its
 * steps left them) and reader. */
#define FMU_HAS_UPDATE 1
#define FMU_HAS_STATE_WRITE 1
#define FMU_HAS_STATE_READ 1

#ifdef __cplusplus
}
#endif
#endif
