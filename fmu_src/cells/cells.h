/*
 * The cells of a rectangle length x width on a flat surface, n1 x n2 equal
 * cells each the law (law/contact_law.h) at its centre with its own slip:
 * their kinematics, their steps and sums, the pending/committed step logic
 * and their part of the serialized state, once for every model whose body
 * rests on them (ContactPatch: a given linear pressure; ContactPad: a
 * Winkler foundation).  A model gives each cell its normal force; the cells
 * give back the tangential force and moment.  No FMI in it.
 *
 * Geometry: a cell centre r = (xi length, eta width) in body coordinates,
 * xi, eta the midpoints of n1 (n2) equal parts of [-1/2, 1/2]; its
 * displacement relative to the surface d = u + (R(theta) - I) r; its
 * stiffness eps w, w = 1/(n1 n2) its share of the area, so that the cells
 * in uniform translation are exactly as stiff as the point.  The texture's
 * axes (alpha, beta) are the surface's.  T = the sum of the cells' -q,
 * Mz = the sum of (R r) x (-q) about the centre, both in the surface frame,
 * on the body.
 *
 * Storage is fixed (the glue allocates sizeof(struct fmu_model) and
 * serializes a fixed number of bytes): PATCH_MAX_CELLS cells, of which the
 * first n1 n2 are used, cell c = i + n1 j for i < n1 along length, j < n2
 * along width.
 */
#ifndef CELLS_CELLS_H
#define CELLS_CELLS_H

#include "cells/cell_rows.h"
#include "glue/fmu_model.h"
#include "law/contact_law.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The values of the parameter initialSlip (cells/cell_rows.h). */
enum { PATCH_INITIAL_AT_INPUTS = 1, PATCH_INITIAL_EXPLICIT = 2 };

/* What the cells' kinematics follow from: the geometry, the initial slip
 * and the tangential inputs (the tables' slots). */
typedef struct {
    double length, width; /* [m] */
    int n[2];             /* cells along length, width */
    int initial_slip;     /* PATCH_INITIAL_* */
    double s_start[2];    /* explicit initial slip [m] */
    double u[2], theta;   /* inputs [m], [rad] */
} cells_setup;

/* The sums the outputs are. */
typedef struct {
    double T[2], Mz, energy, slip_fraction;
    int contact; /* 0 open (no cell pressed), 1 every pressed cell sticks, 2 some slip, 3 all */
} cells_sums;

/* The cells' steps: the law, and the shown step of every cell with the
 * committed states it was computed from. */
typedef struct {
    oc_law law; /* the cells' law: the parameters with eps times the cell's share of the area */
    int shown;  /* the shown step of every cell is steps[shown][c] */
    /* The states the shown step was computed from (its start): the steps
     * steps[from - 1][c].next a doStep committed, where they lie, or start[c]
     * (from = 0, as a zeroed model has it: initial or restored states,
     * which no step holds), or moved[c] (from = -1: committed states a
     * model moved, cells/transport.h). */
    int from;
    int result_committed; /* 0: pending, committed states = the start; 1: = steps[shown][c].next */
    oc_state start[PATCH_MAX_CELLS];
    /* Moved states are written into whichever of start and moved the shown
     * step does not start from (cells_move_target), so that a step refused
     * changes nothing, and a step starts from them where they lie. */
    oc_state moved[PATCH_MAX_CELLS];
    /* The shown step, its start's, and one free: a new step is computed
     * into the buffer that is neither, so that a refused one changes nothing. */
    oc_step steps[3][PATCH_MAX_CELLS];
} cells_grid;

static inline int cells_count(const cells_setup *g) { return g->n[0] * g->n[1]; }

/* (2i + 1 - n) / (2n): mirror cells get exactly opposite coordinates */
static inline double cells_coordinate(int i, int n) {
    return (double)(2 * i + 1 - n) / (double)(2 * n);
}

/* One cell's kinematics: its relative coordinates xi, eta in (-1/2, 1/2),
 * its centre r [m] in body coordinates, R r in the surface frame and its
 * displacement d [m]. */
typedef struct {
    double xi, eta, r[2], Rr[2], d[2];
} cells_cell;
cells_cell cells_cell_of(const cells_setup *g, int c);

/* Where each cell's committed state comes from. */
typedef enum {
    CELLS_FROM_INITIAL,
    CELLS_FROM_ARRAY,
    CELLS_FROM_STEPS,
    CELLS_FROM_BYTES
} cells_kind;
typedef struct {
    cells_kind kind;
    const oc_state *array;      /* FROM_ARRAY: cell c's state is array[c] */
    const oc_step *steps;       /* FROM_STEPS: steps[c].next, */
    int buffer;                 /*   steps = the grid's steps[buffer] */
    const unsigned char *bytes; /* FROM_BYTES: serialized */
} cells_source;

/* The initial states (initialSlip) and the committed ones: the start
 * before a commit, the shown step's after. */
cells_source cells_initial(void);
cells_source cells_committed(const cells_grid *G);
/* Cell c's start of the shown step. */
const oc_state *cells_start_of(const cells_grid *G, int c);
/* Where to write committed states moved (cells/transport.h) for a step
 * from them (a source CELLS_FROM_ARRAY of it): start or moved, whichever
 * the shown step does not start from. */
oc_state *cells_move_target(cells_grid *G);

/* The cells' law: the parameters with the stiffness shared by area. */
fmu_status cells_law(const oc_params *p, const cells_setup *g, oc_law *law, fmu_msg *msg);

/* Steps every cell c with `law` from `src` and its normal force Nc[c] [N]
 * (N <= 0: open) into out[] and sums the outputs.  Returns -1 if every
 * result and sum is finite, else the first cell whose result is not (in
 * the order c = i + n1 j), or n1 n2 if only a sum is not: then nothing but
 * out[] was written, and the model says why. */
int cells_step(const oc_law *law, const cells_setup *g, const double Nc[], const cells_source *src,
               oc_step out[], cells_sums *S);

/* The pending step of every cell for g and Nc from `src` with `law`,
 * which commits nothing: into the free buffer, then shown; or (a cell or
 * sum not finite: cells_step's index returned) nothing changed. */
int cells_evaluate(cells_grid *G, const oc_law *law, const cells_setup *g, const double Nc[],
                   const cells_source *src, cells_sums *S);

/* The derivatives of T1, T2, Mz, dissipatedEnergy (rows) with respect to
 * u1, u2, theta and three inputs of the normal forces (columns) of the
 * shown step: each cell's consistent tangent through its kinematics and
 * its normal force, whose derivatives dNc/d(theta, load 1, load 2, load 3)
 * normal(model, c, dN) gives; Mz's own turning adds -(R r) . T_c to
 * dMz/dtheta. */
enum { CELLS_JAC_ROWS = 4, CELLS_JAC_COLS = 6 };
typedef void (*cells_normal_tangent)(const void *model, int c, double dN[4]);
void cells_jacobian(const cells_grid *G, const cells_setup *g, cells_normal_tangent normal,
                    const void *model, double P[CELLS_JAC_ROWS][CELLS_JAC_COLS]);

/* FMI 3.0's arrays of the cells: element [i][j] (row-major, shape (n1,
 * n2)) is cell c = i + n1 j of the shown step; what = 0, 1 its force along
 * X1, X2 as the sums take it (0.0 - q), 2 its normal force (double), 3 its
 * state (int32_t). */
enum { CELLS_ARRAY_T1, CELLS_ARRAY_T2, CELLS_ARRAY_N, CELLS_ARRAY_STATE };
void cells_array(const cells_grid *G, const cells_setup *g, int what, void *out);

/* The serialized cells: every cell's committed state (the start of the
 * shown step), those beyond n1 n2 zero. */
size_t cells_state_size(void);
void cells_state_write(const cells_grid *G, const cells_setup *g, unsigned char *p);
/* Checks the serialized cells at p against `law` and the grid g (each a
 * state the law can have committed, those beyond n1 n2 zero): FMU_OK, or
 * FMU_ERR with why (msg). */
fmu_status cells_state_check(const oc_law *law, const cells_setup *g, const unsigned char *p,
                             fmu_msg *msg);
/* The law serialized cells at p are read with (cells_state_read), and
 * the cells checked against it (cells_state_check).  A master that saves
 * and restores every step restores the parameters it already has: while
 * `params` and the grid g are those G's law was made for (`was`, was_g:
 * bit patterns, not ==, since -0.0 and +0.0 give tensors that differ in the
 * sign of zero entries, and a restored state must continue bit for bit)
 * it is G's, kept; else computed.  FMU_OK, or FMU_ERR with why (msg). */
fmu_status cells_restored_law(const cells_grid *G, const oc_params *was, const cells_setup *was_g,
                              const oc_params *params, const cells_setup *g, const unsigned char *p,
                              oc_law *law, fmu_msg *msg);
/* Takes checked serialized cells at p as the committed states: the shown
 * step recomputed from them with `law` and Nc into the free buffer, as
 * cells_evaluate; -1, or cells_step's index and nothing changed. */
int cells_state_read(cells_grid *G, const oc_law *law, const cells_setup *g, const double Nc[],
                     const unsigned char *p, cells_sums *S);
/* The buffer a new step is computed into: neither the shown step's nor
 * its start's. */
int cells_free_buffer(const cells_grid *G);

#ifdef __cplusplus
}
#endif
#endif
