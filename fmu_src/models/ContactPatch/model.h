/*
 * The contact patch as a model of the shared FMI glue (fmu_model.h): the
 * variables of models/ContactPatch/table.h, n1 x n2 cells each stepped by the point
 * law (contact_law.h, called, not copied) with its own committed state, the
 * pending/committed step logic of the point model (models/OrthotropicContact/model.h) for all
 * cells at once, and the serialized state.
 *
 * Step semantics as the point's: setting inputs computes every cell's step
 * from the committed states without committing them; the outputs read that
 * pending result; a doStep commits all cells.  A step in which any cell or
 * sum would not be finite is refused and changes nothing.
 *
 * Storage is fixed (the glue allocates sizeof(struct fmu_model) and
 * serializes a fixed number of bytes): PATCH_MAX_SIDE^2 cells, of which the
 * first n1 n2 are used, cell c = i + n1 j for i < n1 along length, j < n2
 * along width.
 */
#ifndef PATCH_MODEL_H
#define PATCH_MODEL_H

#include "glue/fmu_fields.h"
#include "glue/fmu_model.h"
#include "law/contact_law.h"
#include "law/law_fields.h"
#include "models/ContactPatch/table.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { PATCH_MAX_CELLS = PATCH_MAX_SIDE * PATCH_MAX_SIDE };

/* The values of the parameter initialSlip (models/ContactPatch/table.h). */
enum { PATCH_INITIAL_AT_INPUTS = 1, PATCH_INITIAL_EXPLICIT = 2 };

/* Everything the cells' kinematics and loads follow from: the geometry,
 * the initial slip and the inputs (the table's slots). */
typedef struct {
    double length, width;  /* [m] */
    int n[2];              /* cells along length, width */
    int initial_slip;      /* PATCH_INITIAL_* */
    double s_start[2];     /* explicit initial slip [m] */
    double u[2], theta, N; /* inputs [m], [rad], [N] */
    double p[2];           /* centre of pressure [m], body coordinates */
} patch_setup;

struct fmu_model {
    oc_params params; /* the table's law parameters: eps1, eps2 the whole patch's */
    oc_law law;       /* the cells' law: params with eps times the cell's share of the area */
    patch_setup g;
    /* The shown result's outputs, where the table reads them: */
    double T[2], Mz, energy, slip_fraction;
    int contact;
    int shown; /* the shown step of every cell is steps[shown][c] */
    /* The states the shown step was computed from (its start): the steps
     * steps[from - 1][c].next a doStep committed, where they lie, or start[c]
     * (from = 0, as a zeroed model has it: initial or restored states,
     * which no step holds). */
    int from;
    int result_committed; /* 0: pending, committed states = the start; 1: = steps[shown][c].next */
    double time;
    oc_state start[PATCH_MAX_CELLS];
    /* The shown step, its start's, and one free: a new step is computed
     * into the buffer that is neither, so that a refused one changes nothing. */
    oc_step steps[3][PATCH_MAX_CELLS];
};
typedef struct fmu_model patch_model;

/* The model's part of the serialized state (glue/fmu_fields.h): the head,
 * then every cell's committed state, those beyond n1 n2 zero (the size is
 * fixed).  The model writes and reads the cells itself: their states lie
 * where its steps left them (start_of).  The shown result is not stored
 * but recomputed from the committed states and the inputs. */
static const fmu_field PATCH_MODEL_FIELD_LIST[] = {
    FMU_RECORD(patch_model, params, &OC_PARAMS_FIELDS,
               "the law's parameters (eps1, eps2 the whole patch's)"),
    FMU_U32(patch_model, g.initial_slip, "initialSlip", "the initial slip", RANGE,
            PATCH_VR_initialSlip),
    FMU_F64(patch_model, g.s_start[0], "s1Start", "the initial slip", RANGE, PATCH_VR_s1Start),
    FMU_F64(patch_model, g.s_start[1], "s2Start", "the initial slip", RANGE, PATCH_VR_s2Start),
    FMU_F64(patch_model, g.length, "length", "the geometry", RANGE, PATCH_VR_length),
    FMU_F64(patch_model, g.width, "width", "the geometry", RANGE, PATCH_VR_width),
    FMU_U32(patch_model, g.n[0], "n1", "the geometry", RANGE, PATCH_VR_n1),
    FMU_U32(patch_model, g.n[1], "n2", "the geometry", RANGE, PATCH_VR_n2),
    FMU_F64(patch_model, g.u[0], "u1", "the inputs", FINITE, 0),
    FMU_F64(patch_model, g.u[1], "u2", "the inputs", FINITE, 0),
    FMU_F64(patch_model, g.theta, "theta", "the inputs", FINITE, 0),
    FMU_F64(patch_model, g.N, "N", "the inputs", FINITE, 0),
    FMU_F64(patch_model, g.p[0], "p1", "the inputs", FINITE, 0),
    FMU_F64(patch_model, g.p[1], "p2", "the inputs", FINITE, 0),
    FMU_U32(patch_model, result_committed, "committed",
            "the commit flag (1: the shown step is committed)", FLAG, 0),
    FMU_RECORDS(patch_model, start, &OC_STATE_FIELDS, PATCH_MAX_CELLS,
                "the cells' committed states (cell c = i + n1 j)")};
enum { PATCH_MODEL_FIELDS = sizeof PATCH_MODEL_FIELD_LIST / sizeof PATCH_MODEL_FIELD_LIST[0] };
static const fmu_fields FMU_STATE_FIELDS = FMU_FIELDS(PATCH_MODEL_FIELD_LIST, patch_model);
/* The head: all but the cells. */
static const fmu_fields PATCH_HEAD_FIELDS = {PATCH_MODEL_FIELD_LIST, PATCH_MODEL_FIELDS - 1,
                                             sizeof(patch_model)};

#ifdef __cplusplus
}
#endif
#endif
