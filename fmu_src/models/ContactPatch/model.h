/*
 * The contact patch as a model of the shared FMI glue (fmu_model.h): the
 * variables of models/ContactPatch/table.h, its cells (cells.h: n1 x n2
 * cells each stepped by the point law, called, not copied, with its own
 * committed state) pressed by the grid's linear pressure of resultant N at
 * the centre of pressure (p1, p2), and the serialized state.
 *
 * Step semantics as the point's: setting inputs computes every cell's step
 * from the committed states without committing them; the outputs read that
 * pending result; a doStep commits all cells.  A step in which any cell or
 * sum would not be finite is refused and changes nothing.
 */
#ifndef PATCH_MODEL_H
#define PATCH_MODEL_H

#include "glue/fmu_fields.h"
#include "glue/fmu_model.h"
#include "law/contact_law.h"
#include "law/law_fields.h"
#include "models/ContactPatch/cells.h"
#include "models/ContactPatch/table.h"

#ifdef __cplusplus
extern "C" {
#endif

struct fmu_model {
    oc_params params; /* the table's law parameters: eps1, eps2 the whole patch's */
    cells_setup g;    /* the geometry, the initial slip, u1, u2, theta */
    double N, p[2];   /* normal force [N], centre of pressure [m], body coordinates */
    cells_sums out;   /* the shown step's outputs, where the table reads them */
    double time;
    cells_grid cells;
};
typedef struct fmu_model patch_model;

/* The model's part of the serialized state (glue/fmu_fields.h): the head,
 * then every cell's committed state, those beyond n1 n2 zero (the size is
 * fixed).  The model writes and reads the cells itself (cells.h): their
 * states lie where its steps left them (cells_start_of).  The shown result is not stored
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
    FMU_F64(patch_model, N, "N", "the inputs", FINITE, 0),
    FMU_F64(patch_model, p[0], "p1", "the inputs", FINITE, 0),
    FMU_F64(patch_model, p[1], "p2", "the inputs", FINITE, 0),
    FMU_U32(patch_model, cells.result_committed, "committed",
            "the commit flag (1: the shown step is committed)", FLAG, 0),
    FMU_RECORDS(patch_model, cells.start, &OC_STATE_FIELDS, PATCH_MAX_CELLS,
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
