/*
 * The one table of the ContactPad FMU (glue/fmu_table.h says what a table
 * holds): the contact patch's cells (cells/cells.h: a
 * rectangle length x width of a rigid body, n1 x n2 cells each the law at
 * its centre with its own slip; the law's rows and the cells' rows are the
 * patch's) on a Winkler foundation, whose pressure follows the pad's pose:
 *
 *   - a point of the pad at (X, Y) in the surface frame (its body position
 *     turned by theta) approaches the surface by delta = d + phi2 X - phi1 Y
 *     (d the approach of the pad centre, > 0 pressed; phi1, phi2 small tilts
 *     about the surface's X1, X2, right-handed; X3 the outward normal);
 *   - the pressure there is p = kn delta + dn delta' where delta > 0 (the
 *     layer presses only where it touches), clipped at 0 (it never
 *     pulls), delta' the approach's rate over the communication step
 *     (models/ContactPad/model.c: over the previous step's size, none before
 *     the first step);
 *   - each cell's normal force is the exact integral of p over its
 *     rectangle (models/ContactPad/pressure.h), a cell wholly lifted is
 *     open as the point law opens;
 *   - Fn, M1, M2: the pressure's resultant on the body and its moments about
 *     the pad centre's X1, X2 axes (a force +X3 at (X, Y) has the moment
 *     (Y F, -X F)): exact integrals, restoring against a tilt.
 * T1, T2, Mz as the patch's: the cells' forces, each at its cell's centre.
 */
#ifndef PAD_VARIABLES_H
#define PAD_VARIABLES_H

#include "cells/cell_rows.h"
#include "glue/fmu_table.h"
#include "law/law_table.h"

/* A table's rows and lists keep their own layout. */
/* clang-format off */

#define FMU_MODEL_NAME "ContactPad"
#define FMU_MODEL_IDENTIFIER "ContactPad"
#ifndef FMU_GENERATOR
#include "fmu_token.h"
#endif
#define FMU_STATE_TAG {'O', 'C', 'P', 'D'}
#define FMU_DESCRIPTION                                                                        \
    "Rectangular pad of a rigid body on a Winkler foundation under a flat textured surface: "  \
    "n1 x n2 cells, each the coupled orthotropic adhesion-friction law (Konyukhov and "        \
    "Schweizerhof 2007) with its own slip, pressed by the foundation under the pad's pose; "   \
    "the six-component wrench from the body's displacement, rotation, approach and tilts, the "  \
    "body's surface rolling through the pad at vr (a brush)"
#define FMU_SOURCES(S)                                                                          \
    S(law/contact_law.c) S(cells/cells.c) S(cells/transport.c) S(models/ContactPad/pressure.c)  \
    S(models/ContactPad/model.c)
/* The model: its struct and its serialized state's field list (FMU_STATE_FIELDS). */
#define FMU_MODEL_HEADER "models/ContactPad/model.h"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"1\" stepSize=\"0.001\""

#ifdef FMU_GENERATOR
/* The pad, for documentation/index.html. */
static const char FMU_DOC_HTML[] =
    "<h2>The pad</h2>\n<ul>\n"
    "<li>The ContactPatch FMU's cells (a rigid rectangle length &times; width, n1 &times; n2 "
    "cells, each the point law at its centre with its own slip, displaced by u + (R(theta) - "
    "I) r, stiffness (eps1, eps2) shared by area) on a Winkler foundation: a point of the pad "
    "at (X, Y) in the surface frame approaches by delta = d + phi2 X - phi1 Y and is pressed "
    "where it touches (delta &gt; 0) by kn delta + dn delta', clipped at 0 (the pressure "
    "never pulls; a point above the layer carries nothing, however fast it comes).  d &gt; 0 "
    "presses; "
    "phi1, phi2 are small tilts about the surface's X1, X2 (right-handed, X3 the outward "
    "normal).</li>\n"
    "<li>Each cell's normal force is the exact integral of that pressure over its rectangle: "
    "a cell wholly pressed gets its area times the pressure at its centre, one the lift-off "
    "line crosses the integral over the part that presses, one wholly lifted none (it is "
    "open: its slip follows the body).  Fn and the moments M1, M2 about the pad centre's "
    "X1, X2 axes are those integrals' sums, exact on every grid (Fn = kn A d and M2 = "
    "-kn phi2 width length<sup>3</sup>/12 in full contact at theta = 0).</li>\n"
    "<li>delta' is the approach's rate over the previous communication step: (delta - "
    "delta<sub>prev</sub>)/h<sub>prev</sub> of each point of the body, where delta<sub>prev"
    "</sub> is its approach at the last committed step and h<sub>prev</sub> that step's size; "
    "none before the first step (the step size is known at @DOSTEP@ only, the pending step "
    "is computed when inputs are set): the backward difference over the step that brought "
    "the inputs, set at each step's start.  dissipatedEnergy counts the damper's work on the "
    "body besides the cells' friction.</li>\n"
    "<li>T1, T2, Mz: the cells' forces on the body and their moment about the pad centre, "
    "each cell's force at its centre, in the surface frame.</li>\n"
    "<li>Rolling: vr is the speed at which the body's surface passes through the pad along "
    "its axis 1 (vr &gt; 0: it enters at x = +length/2, unloaded, and leaves at -length/2). "
    "Each step moves the cells' elastic states with the material by the previous step's vr "
    "h (exactly for a whole number of cells, else by linear upwind interpolation); each cell "
    "keeps its dissipated energy.  A creep u1 = xi vr t is the longitudinal creepage xi.</li>\n"
    "<li>Not modelled: large tilts (the approach is linearised in them), a curved surface, "
    "coupling between neighbouring points of the foundation, the inertia of the rolling "
    "material, a carcass behind it.</li>\n</ul>\n"
    "<h2>Step semantics</h2>\n<p>As the point FMU: setting inputs computes every cell's step "
    "from the committed state without committing it; @DOSTEP@ commits all cells at once, or "
    "none.  @DIRDER@ gives the derivatives of T1, T2, Mz, Fn, M1, M2, dissipatedEnergy with "
    "respect to u1, u2, theta, d, phi1, phi2: the cells' consistent tangents through the "
    "kinematics and the foundation's exact integrals.</p>\n";
#endif

#define FMU_ENUM_TYPES(T) T(SlidingRule, OC_SLIDING_RULE_ITEMS) T(InitialSlip, PATCH_INITIAL_SLIP_ITEMS)
#define PAD_KNOWNS_NO_RULE OC_LAW_NAMES PATCH_CELL_KNOWNS " kn d phi1 phi2"
#define PAD_KNOWNS PAD_KNOWNS_NO_RULE " slidingRule"
#define PAD_INPUTS "u1 u2 theta d phi1 phi2"
/* the normal force and its moments follow from the pose and the foundation alone */
#define PAD_NORMAL_INPUTS "theta d phi1 phi2"
#define PAD_NORMAL_KNOWNS "length width n1 n2 kn " PAD_NORMAL_INPUTS
#define FMU_DEPENDENCIES(D)                                                                      \
    D(T1, PAD_INPUTS, PAD_KNOWNS) D(T2, PAD_INPUTS, PAD_KNOWNS) D(Mz, PAD_INPUTS, PAD_KNOWNS)    \
    D(Fn, PAD_NORMAL_INPUTS, PAD_NORMAL_KNOWNS) D(M1, PAD_NORMAL_INPUTS, PAD_NORMAL_KNOWNS)      \
    D(M2, PAD_NORMAL_INPUTS, PAD_NORMAL_KNOWNS) D(dissipatedEnergy, PAD_INPUTS, PAD_KNOWNS)      \
    D(contactFraction, PAD_NORMAL_INPUTS, "length width n1 n2 " PAD_NORMAL_INPUTS)               \
    D(slipFraction, PAD_INPUTS, PAD_KNOWNS_NO_RULE)                                              \
    D(contactState, PAD_INPUTS, PAD_KNOWNS_NO_RULE)

/* The variables: time, the law's rows (its block, value references 1 to 15:
 * law/law_table.h), the cells' rows (16 to 25: cells/cell_rows.h), then: */
#define PAD_FOUNDATION_ROWS(X)                                                                   \
    X(kn, 26, Float64, parameter, fixed, exact, 1e7, 1e-100, 1e100, "N/m3", "",                  \
      "Foundation stiffness: pressure per unit approach")                                        \
    X(dn, 27, Float64, parameter, fixed, exact, 0.0, 0.0, 1e100, "N.s/m3", "",                   \
      "Foundation damping: pressure per unit approach rate, the rate taken over the previous "   \
      "communication step (none before the first)")

#define PAD_POSE_ROWS(X)                                                                         \
    X(d, 28, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "m", "",                         \
      "Approach of the pad centre into the surface along -X3 (> 0 pressed)")                     \
    X(phi1, 29, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "rad", "deg",                 \
      "Tilt of the pad about the surface's X1 axis (small; right-handed: +Y lifts)")             \
    X(phi2, 30, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "rad", "deg",                 \
      "Tilt of the pad about the surface's X2 axis (small; right-handed: +X presses)")            \
    X(vr, 41, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "m/s", "",                      \
      "Rolling speed: the body's surface passes through the pad along its axis 1, entering at "  \
      "x = +length/2 (vr > 0) and leaving at -length/2; it moves the cells' states from the "    \
      "next step on")

#define PAD_WRENCH_ROWS(X)                                                                       \
    X(Fn, 34, Float64, output, continuous, calculated, 0.0, 0.0, NO_MAX, "N", "",                \
      "Normal force of the foundation on the body along X3 (>= 0)")                              \
    X(M1, 35, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "N.m", "",           \
      "Moment of the pressure on the body about the pad centre's X1 axis")                       \
    X(M2, 36, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "N.m", "",           \
      "Moment of the pressure on the body about the pad centre's X2 axis")

#define PAD_CONTACT_ROW(X)                                                                       \
    X(contactFraction, 38, Float64, output, continuous, calculated, 0.0, 0.0, 1.0, "1", "",      \
      "Share of the pad's area that presses in this step")

#define PAD_VARIABLES(X, L)                                                                      \
    X(time, 0, Float64, independent, continuous, , 0.0, NO_MIN, NO_MAX, "s", "",                 \
      "Simulation time")                                                                         \
    OC_LAW_ROWS(L, X) PATCH_INITIAL_SLIP_ROWS(X) PATCH_GEOMETRY_ROWS(X) PATCH_MOTION_ROWS(X)     \
    PAD_FOUNDATION_ROWS(X) PAD_POSE_ROWS(X) PATCH_RESULTANT_ROWS(X, 31, "pad")                   \
    PAD_WRENCH_ROWS(X) PATCH_ENERGY_ROW(X, 37) PAD_CONTACT_ROW(X) PATCH_SLIP_ROWS(X, 39, "pad")

/* FMI 3.0 only: the cells' forces, normal forces and states as arrays of
 * shape (n1, n2), element [i][j] the cell i along length, j along width
 * (row-major, j fastest), and n1, n2 their structural parameters (FMI 2.0
 * has neither: there n1, n2 are parameters): cells/cell_rows.h.
 * Columns: name, value reference, type, unit, the scalar output whose
 * dependencies each element has, description. */
#define FMU_ARRAYS(A)                                                                            \
    PATCH_FORCE_ARRAYS(A, 42)                                                                    \
    A(cellFn, 44, Float64, "N", Fn,                                                              \
      "Normal force of the foundation on the body at each cell (they sum to Fn)")                \
    PATCH_STATE_ARRAY(A, 45)

/* The table's tail, every table's (glue/fmu_table_tail.inc): FMU_VARIABLES,
 * the law's group and the value references PAD_VR_*. */
#define FMU_TABLE_ROWS PAD_VARIABLES
#define FMU_VR_PREFIX PAD_VR_
#include "glue/fmu_table_tail.inc"

/* clang-format on */
#endif
