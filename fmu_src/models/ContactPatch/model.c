#include "models/ContactPatch/model.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

/* Where each of the patch's own variables lives (cells/cells_model.inc has the
 * law's, the cells' and their sums'). */
#define FMU_SLOT_N offsetof(patch_model, N)
#define FMU_SLOT_p1 offsetof(patch_model, p[0])
#define FMU_SLOT_p2 offsetof(patch_model, p[1])

/* The Jacobian: rows T1, T2, Mz, dissipatedEnergy; columns u1, u2, theta,
 * N, p1, p2. */
#define MODEL_JAC_ROWS CELLS_JAC_ROWS
#define MODEL_JAC_COLS CELLS_JAC_COLS
#define MODEL_JAC_OUTPUTS PATCH_VR_T1, PATCH_VR_T2, PATCH_VR_Mz, PATCH_VR_dissipatedEnergy
#define MODEL_JAC_INPUTS                                                                           \
    PATCH_VR_u1, PATCH_VR_u2, PATCH_VR_theta, PATCH_VR_N, PATCH_VR_p1, PATCH_VR_p2

#include "cells/cells_model.inc"

/* ---- the cells' normal forces ------------------------------------------ */

/* The cells' normal forces N_c = N w (1 + p1 x/S1 + p2 y/S2), S1 = sum of
 * w x^2 over the cells = length^2 (1 - 1/n1^2)/12 (likewise S2): resultant N
 * and first moment N (p1, p2) on the grid exactly (the continuum's pressure
 * sampled at the centres, 12 p1 x/length^2, has N p1 (1 - 1/n1^2)).  Per unit
 * xi = x/length that is 12 n1^2/(n1^2 - 1) (p1/length) xi.  One cell along an
 * axis has S = 0 and carries no p along it (check_pressure refuses one), nor
 * does an open contact (N <= 0): there the slopes are 0 and every cell gets
 * N w <= 0, whatever p is. */
static double pressure_slope(int n, double N) {
    const double nn = (double)n * (double)n;
    return n > 1 && N > 0.0 ? 12.0 * nn / (nn - 1.0) : 0.0;
}

/* What every cell's normal force shares. */
typedef struct {
    double w;    /* a cell's share of the area, 1/(n1 n2) */
    double c[2]; /* the pressure's slope per unit xi (eta) and unit p1/length (p2/width) */
    double k[2]; /* c[0] p1/length, c[1] p2/width: the pressure's slopes per unit xi, eta */
} patch_frame;

static patch_frame frame_of(const patch_model *m) {
    const cells_setup *g = &m->g;
    const double c0 = pressure_slope(g->n[0], m->N), c1 = pressure_slope(g->n[1], m->N);
    patch_frame f = {1.0 / ((double)g->n[0] * (double)g->n[1]),
                     {c0, c1},
                     {c0 * (m->p[0] / g->length), c1 * (m->p[1] / g->width)}};
    return f;
}

/* Every cell's normal force, N (w ((1 + k0 xi) + k1 eta)) in that order. */
static void normal_forces(const patch_model *m, double Nc[]) {
    const patch_frame f = frame_of(m);
    const int n1 = m->g.n[0], n2 = m->g.n[1];
    double p0[PATCH_MAX_SIDE], p1[PATCH_MAX_SIDE];
    for (int i = 0; i < n1; ++i) p0[i] = 1.0 + f.k[0] * cells_coordinate(i, n1);
    for (int j = 0; j < n2; ++j) p1[j] = f.k[1] * cells_coordinate(j, n2);
    for (int j = 0, c = 0; j < n2; ++j)
        for (int i = 0; i < n1; ++i, ++c) Nc[c] = m->N * (f.w * (p0[i] + p1[j]));
}

/* The centre of pressure of a closed contact (N > 0; an open one has no
 * pressure, and p is not looked at): in the kern, where the linear pressure
 * of resultant N at (p1, p2) is >= 0 at every corner (and so every cell's
 * N_c is > 0), with a few roundings of slack so that p1 = length/6 typed
 * as such is in; and 0 along an axis of one cell, whose cells all lie on
 * the other axis and cannot move the resultant off it. */
static fmu_status check_pressure(const patch_model *m, fmu_msg *msg) {
    const cells_setup *g = &m->g;
    if (!(m->N > 0.0)) return FMU_OK;
    const double e = fabs(m->p[0]) / g->length + fabs(m->p[1]) / g->width;
    if (!(6.0 * e <= 1.0 + 8 * DBL_EPSILON))
        return fmu_fail(msg,
                        "centre of pressure p1=%g m, p2=%g m outside the kern of the %g m x %g m "
                        "patch: |p1|/length + |p2|/width = %g > 1/6, where a linear pressure "
                        "would pull at a corner (no-tension pressure is not modelled)",
                        m->p[0], m->p[1], g->length, g->width, e);
    for (int a = 0; a < 2; ++a)
        if (g->n[a] == 1 && m->p[a] != 0.0)
            return fmu_fail(msg,
                            "centre of pressure p%d=%g m off the axis of a grid with n%d = 1: "
                            "one cell along %s has its centre on that axis and cannot carry a "
                            "centre of pressure off it (set p%d = 0, or n%d >= 2)",
                            a + 1, m->p[a], a + 1, a ? "width" : "length", a + 1, a + 1);
    return FMU_OK;
}

/* Why a step was refused: cells_step's index `bad`, the first cell whose
 * force or slip would not be finite, or n1 n2 for a sum. */
static fmu_status overflow(const patch_model *m, int bad, fmu_msg *msg) {
    const cells_setup *g = &m->g;
    if (bad < cells_count(g))
        return fmu_fail(msg,
                        "inputs u1=%g m, u2=%g m, theta=%g rad, N=%g N overflow the force or "
                        "slip of cell (%d, %d)",
                        g->u[0], g->u[1], g->theta, m->N, bad % g->n[0] + 1, bad / g->n[0] + 1);
    return fmu_fail(msg,
                    "inputs u1=%g m, u2=%g m, theta=%g rad, N=%g N overflow the patch's "
                    "force, moment or energy",
                    g->u[0], g->u[1], g->theta, m->N);
}

/* Computes the pending step of every cell for the inputs in m from `src`
 * with `law` (which commits nothing); or fails and changes nothing. */
static fmu_status evaluate(patch_model *m, const oc_law *law, const cells_source *src,
                           fmu_msg *msg) {
    double Nc[PATCH_MAX_CELLS];
    normal_forces(m, Nc);
    cells_sums S;
    const int bad = cells_evaluate(&m->cells, law, &m->g, Nc, src, &S);
    if (bad >= 0) return overflow(m, bad, msg);
    m->out = S;
    return FMU_OK;
}

fmu_status fmu_model_update(patch_model *m, int changed, int allow, fmu_msg *msg) {
    if (check_pressure(m, msg) != FMU_OK) return FMU_ERR;
    oc_law law;
    const oc_law *use = law_for(m, changed, &law, msg);
    if (!use) return FMU_ERR;
    /* Before the end of initialization the cells start where the inputs or
     * the explicit slip put them; afterwards from what was committed. */
    const cells_source src =
        (allow & FMU_ALLOW_PARAMETERS) ? cells_initial() : cells_committed(&m->cells);
    return evaluate(m, use, &src, msg);
}

/* Every set in initialization already derived the start from the values it
 * left; deriving it once more here makes the end of initialization the
 * moment that counts, whatever was restored before it. */
static fmu_status exit_init(patch_model *m, fmu_msg *msg) {
    const cells_source init = cells_initial();
    return evaluate(m, &m->cells.law, &init, msg);
}

/* A further step with held inputs steps every cell again from what the
 * last doStep committed. */
fmu_status fmu_model_do_step(patch_model *m, double h, fmu_msg *msg) {
    (void)h; /* rate-independent: the step size does not enter the law */
    if (m->cells.result_committed) {
        const cells_source src = cells_committed(&m->cells);
        if (evaluate(m, &m->cells.law, &src, msg) != FMU_OK) return FMU_ERR;
    }
    m->cells.result_committed = 1;
    return FMU_OK;
}

/* ---- directional derivatives ------------------------------------------------ */

/* Cell c's dN_c/d(theta, N, p1, p2) = (0, nu, N w c0 xi / length, N w c1 eta
 * / width) for N_c = N nu(p), nu = w (1 + k0 xi + k1 eta). */
static void normal_tangent(const void *model, int c, double dN[4]) {
    const patch_model *m = model;
    const cells_setup *g = &m->g;
    const patch_frame f = frame_of(m);
    const double xi = cells_coordinate(c % g->n[0], g->n[0]);
    const double eta = cells_coordinate(c / g->n[0], g->n[1]);
    dN[0] = 0.0;
    dN[1] = f.w * (1.0 + f.k[0] * xi + f.k[1] * eta);
    dN[2] = m->N * f.w * f.c[0] * xi / g->length;
    dN[3] = m->N * f.w * f.c[1] * eta / g->width;
}

/* The patch's Jacobian of the shown step: the cells' (cells_jacobian). */
static void partials(const patch_model *m, double *J) {
    cells_jacobian(&m->cells, &m->g, normal_tangent, m, (double(*)[CELLS_JAC_COLS])J);
}

/* ---- serialized state: the field list of model.h ------------------------ */

/* What the serialized head reads into m, kept to be put back. */
typedef struct {
    oc_params params;
    cells_setup g;
    double N, p[2];
    int result_committed;
} patch_head;

/* fmu_model_state_read once the head is in m: the cells checked where they
 * lie in the buffer, then the shown result recomputed (into the free
 * buffer, which nothing reads) from the committed states and the inputs,
 * of which it is a function.  `was` holds the head before. */
static fmu_status read_cells(patch_model *m, const patch_head *was, const unsigned char *cells,
                             fmu_msg *msg) {
    if (check_pressure(m, msg) != FMU_OK) return FMU_ERR;
    oc_law law;
    if (cells_restored_law(&m->cells, &was->params, &was->g, &m->params, &m->g, cells, &law, msg) !=
        FMU_OK)
        return FMU_ERR;
    double Nc[PATCH_MAX_CELLS];
    normal_forces(m, Nc);
    return restored_cells(m, &law, Nc, cells, msg);
}

/* Reads the head into m, checked field by field, and the cells; a refused
 * state puts the head back and changes nothing else. */
fmu_status fmu_model_state_read(patch_model *m, const unsigned char *p, fmu_msg *msg) {
    const patch_head head = {m->params, m->g, m->N, {m->p[0], m->p[1]}, m->cells.result_committed};
    fmu_status st = fmu_fields_read(&CELLS_HEAD_FIELDS, m, &p, msg);
    if (st == FMU_OK) st = read_cells(m, &head, p, msg);
    if (st != FMU_OK) {
        m->params = head.params;
        m->g = head.g;
        m->N = head.N;
        m->p[0] = head.p[0];
        m->p[1] = head.p[1];
        m->cells.result_committed = head.result_committed;
    }
    return st;
}

#include "glue/fmu_model_defaults.inc"
