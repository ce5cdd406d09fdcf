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

#include "law/contact_law.h"
#include "glue/fmu_model.h"
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
    int shown;            /* the shown step of every cell is steps[shown][c] */
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

#ifdef __cplusplus
}
#endif
#endif
