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

#include "cells/cells.h"
#include "cells/cells_fields.h"
#include "glue/fmu_fields.h"
#include "glue/fmu_model.h"
#include "law/contact_law.h"
#include "law/law_fields.h"
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
 * then every cell's committed state (cells_fields.h).  The shown result is
 * not stored but recomputed from the committed states and the inputs. */
static const fmu_field PATCH_MODEL_FIELD_LIST[] = {
    FMU_RECORD(patch_model, params, &OC_PARAMS_FIELDS,
               "the law's parameters (eps1, eps2 the whole patch's)"),
    CELLS_SETUP_FIELDS,
    CELLS_MOTION_FIELDS,
    FMU_F64(patch_model, N, "N", "the inputs", FINITE, 0),
    FMU_F64(patch_model, p[0], "p1", "the inputs", FINITE, 0),
    FMU_F64(patch_model, p[1], "p2", "the inputs", FINITE, 0),
    CELLS_COMMITTED_FIELD,
    CELLS_STATES_FIELD};
CELLS_STATE_FIELDS(PATCH_MODEL_FIELD_LIST);
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
