/*
 * The part of a model's serialized state (glue/fmu_fields.h) that every
 * model on the cells (cells.h) has, once, as law/law_fields.h is the law's:
 * fields of its struct fmu_model, whose members g (a cells_setup) and cells
 * (a cells_grid) they are.  A model lists them in its field list among its
 * own, in its table's order, the cells' states last (CELLS_STATES_FIELD),
 * and makes its FMU_STATE_FIELDS and head with CELLS_STATE_FIELDS.
 */
#ifndef CELLS_CELLS_FIELDS_H
#define CELLS_CELLS_FIELDS_H

#include "cells/cell_rows.h"
#include "cells/cells.h"
#include "glue/fmu_fields.h"
#include "law/law_fields.h"

/* The value references of the cells' rows (cell_rows.h) and of the law's
 * sliding rule, every such table's. */
#define CELLS_VR_ENTRY(name, vr, ...) CELLS_VR_##name = vr,
enum {
    OC_LAW_RULE_ROW(CELLS_VR_ENTRY) PATCH_INITIAL_SLIP_ROWS(CELLS_VR_ENTRY)
        PATCH_GEOMETRY_ROWS(CELLS_VR_ENTRY) PATCH_MOTION_ROWS(CELLS_VR_ENTRY) CELLS_VR_END
};
#undef CELLS_VR_ENTRY

/* The cells' parameters: the initial slip and the geometry. */
#define CELLS_SETUP_FIELDS                                                                         \
    FMU_U32(struct fmu_model, g.initial_slip, "initialSlip", "the initial slip", RANGE,            \
            CELLS_VR_initialSlip),                                                                 \
        FMU_F64(struct fmu_model, g.s_start[0], "s1Start", "the initial slip", RANGE,              \
                CELLS_VR_s1Start),                                                                 \
        FMU_F64(struct fmu_model, g.s_start[1], "s2Start", "the initial slip", RANGE,              \
                CELLS_VR_s2Start),                                                                 \
        FMU_F64(struct fmu_model, g.length, "length", "the geometry", RANGE, CELLS_VR_length),     \
        FMU_F64(struct fmu_model, g.width, "width", "the geometry", RANGE, CELLS_VR_width),        \
        FMU_U32(struct fmu_model, g.n[0], "n1", "the geometry", RANGE, CELLS_VR_n1),               \
        FMU_U32(struct fmu_model, g.n[1], "n2", "the geometry", RANGE, CELLS_VR_n2)

/* The tangential inputs. */
#define CELLS_MOTION_FIELDS                                                                        \
    FMU_F64(struct fmu_model, g.u[0], "u1", "the inputs", FINITE, 0),                              \
        FMU_F64(struct fmu_model, g.u[1], "u2", "the inputs", FINITE, 0),                          \
        FMU_F64(struct fmu_model, g.theta, "theta", "the inputs", FINITE, 0)

/* The commit flag. */
#define CELLS_COMMITTED_FIELD                                                                      \
    FMU_U32(struct fmu_model, cells.result_committed, "committed",                                 \
            "the commit flag (1: the shown step is committed)", FLAG, 0)

/* Every cell's committed state, those beyond n1 n2 zero (the size is
 * fixed): the last field.  The model writes and reads the cells itself
 * (cells_state_write, cells_state_read): their states lie where its steps
 * left them (cells_start_of). */
#define CELLS_STATES_FIELD                                                                         \
    FMU_RECORDS(struct fmu_model, cells.start, &OC_STATE_FIELDS, PATCH_MAX_CELLS,                  \
                "the cells' committed states (cell c = i + n1 j)")

/* FMU_STATE_FIELDS from the model's field list `list`, and its head
 * CELLS_HEAD_FIELDS: all but the cells. */
#define CELLS_STATE_FIELDS(list)                                                                   \
    static const fmu_fields FMU_STATE_FIELDS = FMU_FIELDS(list, struct fmu_model);                 \
    static const fmu_fields CELLS_HEAD_FIELDS = {list, sizeof list / sizeof list[0] - 1,           \
                                                 sizeof(struct fmu_model)}

#endif
