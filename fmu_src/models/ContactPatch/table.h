/*
 * The one table of the ContactPatch FMU (glue/fmu_table.h says what a
 * table holds): a rectangle length x width of a rigid body on a flat
 * surface, divided into n1 x n2 equal cells, each cell the law
 * (law/contact_law.h) at its centre with its own slip state; the law's rows
 * (law/law_table.h) are the patch's.
 *
 * Geometry (cells/cells.h and model.c say how each number is
 * formed):
 *   - a cell centre r = (xi length, eta width) in body coordinates, xi, eta
 *     the midpoints of n1 (n2) equal parts of [-1/2, 1/2];
 *   - its displacement relative to the surface d = u + (R(theta) - I) r;
 *   - its normal force N_c = N w (1 + p1 x / S1 + p2 y / S2), (x, y) = r,
 *     w = 1/(n1 n2) its share of the area, S1 = sum of w x^2 over the cells
 *     = length^2 (1 - 1/n1^2)/12 (likewise S2): the grid's linear pressure,
 *     whose resultant is N and first moment N (p1, p2) exactly (the
 *     continuum's sampled at the centres, 12 p1 x / length^2, falls short by
 *     the factor 1 - 1/n1^2).  One cell along an axis (S = 0) cannot carry
 *     p along it: with N > 0 that p must be 0, as (p1, p2) must lie in the
 *     kern; with N <= 0 (open) every cell gets N w and p is not looked at;
 *   - its stiffness eps w: the patch in uniform translation is exactly as
 *     stiff as the point.
 *   - the texture's axes (alpha, beta) are the surface's, shared by every cell.
 * Outputs: T = sum of the cells' -q, Mz = sum of (R r) x (-q) about the patch
 * centre, both in the surface frame, on the body.
 */
#ifndef PATCH_VARIABLES_H
#define PATCH_VARIABLES_H

#include "cells/cell_rows.h"
#include "glue/fmu_table.h"
#include "law/law_table.h"

/* A table's rows and lists keep their own layout. */
/* clang-format off */

#define FMU_MODEL_NAME "ContactPatch"
#define FMU_MODEL_IDENTIFIER "ContactPatch"
#ifndef FMU_GENERATOR
#include "fmu_token.h"
#endif
#define FMU_STATE_TAG {'O', 'C', 'P', 'T'}
#define FMU_DESCRIPTION                                                                        \
    "Rectangular contact patch of a rigid body on a flat textured surface: n1 x n2 cells, each " \
    "the coupled orthotropic adhesion-friction law (Konyukhov and Schweizerhof 2007) at its "    \
    "centre with its own slip; force and torque from the body's displacement and rotation"
#define FMU_SOURCES(S)                                                                          \
    S(law/contact_law.c) S(cells/cells.c) S(models/ContactPatch/model.c)
/* The model: its struct and its serialized state's field list (FMU_STATE_FIELDS). */
#define FMU_MODEL_HEADER "models/ContactPatch/model.h"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"1\" stepSize=\"0.001\""

#ifdef FMU_GENERATOR
/* The patch, for documentation/index.html. */
static const char FMU_DOC_HTML[] =
    "<h2>The patch</h2>\n<ul>\n"
    "<li>A rigid rectangle length &times; width on a flat surface, n1 &times; n2 equal cells. "
    "Each cell is the point law (the OrthotropicContact FMU's) at its centre r (body "
    "coordinates) with its own slip: displacement d = u + (R(theta) - I) r, normal force "
    "N w (1 + p1 x/S1 + p2 y/S2) with w = 1/(n1 n2) and S1 = length<sup>2</sup> (1 - "
    "1/n1<sup>2</sup>)/12, S2 likewise (the mean of x<sup>2</sup>, y<sup>2</sup> over the "
    "cells), so that the cells' normal forces have resultant N and first moment N (p1, p2) "
    "exactly on every grid; stiffness (eps1, eps2) times the cell's share of the area.  The "
    "texture's axes alpha, beta are the surface's.</li>\n"
    "<li>T1, T2: the sum of the cells' forces on the body; Mz: their moment about the patch "
    "centre, sum of (R r) &times; T<sub>cell</sub>, counterclockwise; all in the surface "
    "frame.</li>\n"
    "<li>With N &gt; 0 the centre of pressure must lie in the kern, |p1|/length + |p2|/width "
    "&le; 1/6 (no corner in tension), and be 0 along a side of one cell (p1 = 0 if n1 = 1: "
    "its cells cannot carry it); with N &le; 0 the contact is open and p is not looked at.  "
    "The pending step is computed when inputs are set, so the set call that leaves N, p1, p2 "
    "otherwise is refused (an error status, the reason logged, nothing changed), as is any "
    "value that would make an output not finite: set N, p1, p2 in one call.</li>\n"
    "<li>Not modelled: rolling, a curved surface, a pressure other than linear, the body's "
    "deformation.</li>\n</ul>\n"
    "<h2>Step semantics</h2>\n<p>As the point FMU: setting inputs computes every cell's step "
    "from the committed state without committing it; @DOSTEP@ commits all cells at once, or "
    "none.  @DIRDER@ gives the derivatives of T1, T2, Mz, dissipatedEnergy with respect to u1, "
    "u2, theta, N, p1, p2: the sum of the cells' consistent tangents through the kinematics."
    "</p>\n";
#endif

#define FMU_ENUM_TYPES(T) T(SlidingRule, OC_SLIDING_RULE_ITEMS) T(InitialSlip, PATCH_INITIAL_SLIP_ITEMS)
#define PATCH_KNOWNS_NO_RULE OC_LAW_NAMES PATCH_CELL_KNOWNS " N p1 p2"
#define PATCH_KNOWNS PATCH_KNOWNS_NO_RULE " slidingRule"
#define PATCH_INPUTS "u1 u2 theta N p1 p2"
#define FMU_DEPENDENCIES(D)                                                                      \
    D(T1, PATCH_INPUTS, PATCH_KNOWNS) D(T2, PATCH_INPUTS, PATCH_KNOWNS)                          \
    D(Mz, PATCH_INPUTS, PATCH_KNOWNS) D(dissipatedEnergy, PATCH_INPUTS, PATCH_KNOWNS)            \
    D(slipFraction, PATCH_INPUTS, PATCH_KNOWNS_NO_RULE)                                          \
    D(contactState, PATCH_INPUTS, PATCH_KNOWNS_NO_RULE)

/* The variables: time, the law's rows (its block, value references 1 to 15:
 * law/law_table.h), the cells' rows (16 to 25: cells/cell_rows.h), then: */
#define PATCH_LOAD_ROWS(X)                                                                       \
    X(N, 26, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "N", "",                         \
      "Total normal force pressing the body on the surface (N <= 0: open contact)")              \
    X(p1, 27, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "m", "",                        \
      "Centre of pressure along the body's axis 1 (0: uniform pressure); while N > 0, "          \
      "|p1|/length + |p2|/width <= 1/6 and p1 = 0 if n1 = 1")                                    \
    X(p2, 28, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "m", "",                        \
      "Centre of pressure along the body's axis 2 (0: uniform pressure); while N > 0, "          \
      "|p1|/length + |p2|/width <= 1/6 and p2 = 0 if n2 = 1")

#define PATCH_VARIABLES(X, L)                                                                    \
    X(time, 0, Float64, independent, continuous, , 0.0, NO_MIN, NO_MAX, "s", "",                 \
      "Simulation time")                                                                         \
    OC_LAW_ROWS(L, X) PATCH_INITIAL_SLIP_ROWS(X) PATCH_GEOMETRY_ROWS(X) PATCH_MOTION_ROWS(X)     \
    PATCH_LOAD_ROWS(X) PATCH_RESULTANT_ROWS(X, 29, "patch") PATCH_ENERGY_ROW(X, 32)              \
    PATCH_SLIP_ROWS(X, 33, "patch")

/* FMI 3.0 only: the cells' forces and states as arrays of shape (n1, n2),
 * element [i][j] the cell i along length, j along width (row-major, j
 * fastest), and n1, n2 their structural parameters (FMI 2.0 has neither:
 * there n1, n2 are parameters): cells/cell_rows.h. */
#define FMU_ARRAYS(A) PATCH_FORCE_ARRAYS(A, 35) PATCH_STATE_ARRAY(A, 37)

/* The table's tail, every table's (glue/fmu_table_tail.inc): FMU_VARIABLES,
 * the law's group and the value references PATCH_VR_*. */
#define FMU_TABLE_ROWS PATCH_VARIABLES
#define FMU_VR_PREFIX PATCH_VR_
#include "glue/fmu_table_tail.inc"

/* clang-format on */
#endif
