/*
 * The rows of a variable table (glue/fmu_table.h) that every model on the
 * cells (cells/cells.h) has: the initial slip, the
 * rectangle's geometry and the tangential motion, value references 16 to
 * 25 after the law's block (law/law_table.h: OC_LAW_VR_END); and the sums'
 * rows and the cells' arrays, whose value references each table gives (the
 * first of a group, the others following), since its own rows come
 * between.  ContactPatch's and ContactPad's tables list them; what they
 * add follows from 26 on.
 */
#ifndef CELLS_CELL_ROWS_H
#define CELLS_CELL_ROWS_H

/* A table's rows and lists keep their own layout. */
/* clang-format off */

/* The largest grid: the model's storage and its serialized state are fixed
 * in size (fmu_model.h), so they hold PATCH_MAX_CELLS cells whatever n1, n2
 * are: each side at most PATCH_MAX_SIDE (the rows' range), n1 n2 at most
 * PATCH_MAX_CELLS (64 along the rolling axis for a rolling pad, 16 across).
 * PATCH_TEXT(x): a macro's value as a string, for the rows' descriptions. */
#define PATCH_MAX_SIDE 64
#define PATCH_MAX_CELLS 1024
#define PATCH_TEXT_OF(x) #x
#define PATCH_TEXT(x) PATCH_TEXT_OF(x)

#define PATCH_INITIAL_SLIP_ITEMS(E)                                                              \
    E(atInputs, 1, "every cell's slip is its displacement at the end of initialization: no "     \
      "force until the body moves")                                                              \
    E(explicit, 2, "every cell's slip is (s1Start, s2Start): the rest pose is that "             \
      "translation at theta = 0")

#define PATCH_INITIAL_SLIP_ROWS(X)                                                               \
    X(initialSlip, 16, InitialSlip, parameter, fixed, exact, 1, 1, 2, "", "",                    \
      "Initial slip: 1 atInputs (every cell unloaded where the inputs put it when "              \
      "initialization ends), 2 explicit (every cell's slip (s1Start, s2Start))")                 \
    X(s1Start, 17, Float64, parameter, fixed, exact, 0.0, -1e300, 1e300, "m", "",                \
      "Initial slip of every cell along X1 when initialSlip = explicit")                         \
    X(s2Start, 18, Float64, parameter, fixed, exact, 0.0, -1e300, 1e300, "m", "",                \
      "Initial slip of every cell along X2 when initialSlip = explicit")

#define PATCH_GEOMETRY_ROWS(X)                                                                   \
    X(length, 19, Float64, parameter, fixed, exact, 0.1, 1e-100, 1e100, "m", "",                 \
      "Side of the patch along the body's axis 1 (X1 at theta = 0)")                             \
    X(width, 20, Float64, parameter, fixed, exact, 0.1, 1e-100, 1e100, "m", "",                  \
      "Side of the patch along the body's axis 2 (X2 at theta = 0)")                             \
    X(n1, 21, Int32, parameter, fixed, exact, 8, 1, PATCH_MAX_SIDE, "", "",                      \
      "Number of cells along length (at most " PATCH_TEXT(PATCH_MAX_SIDE) ", and n1 n2 at most "  \
      PATCH_TEXT(PATCH_MAX_CELLS) ")")                                                            \
    X(n2, 22, Int32, parameter, fixed, exact, 8, 1, PATCH_MAX_SIDE, "", "",                      \
      "Number of cells along width (at most " PATCH_TEXT(PATCH_MAX_SIDE) ", and n1 n2 at most "   \
      PATCH_TEXT(PATCH_MAX_CELLS) ")")

#define PATCH_MOTION_ROWS(X)                                                                     \
    X(u1, 23, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "m", "",                        \
      "Displacement of the patch centre relative to the surface along X1")                       \
    X(u2, 24, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "m", "",                        \
      "Displacement of the patch centre relative to the surface along X2")                       \
    X(theta, 25, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "rad", "deg",                \
      "Rotation of the body relative to the surface, counterclockwise about the normal")

/* The sums' rows from value reference vr on: the force and moment on the
 * body, `body` its name in the descriptions ("patch"); its dissipated
 * energy; the share of it that slips and the step's state. */
#define PATCH_RESULTANT_ROWS(X, vr, body)                                                        \
    X(T1, vr, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "N", "",             \
      "Tangential force of the surface on the body along X1 (sum over the cells)")               \
    X(T2, vr + 1, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "N", "",         \
      "Tangential force of the surface on the body along X2 (sum over the cells)")               \
    X(Mz, vr + 2, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "N.m", "",       \
      "Moment of the surface on the body about the normal through the " body " centre, "         \
      "counterclockwise")

#define PATCH_ENERGY_ROW(X, vr)                                                                  \
    X(dissipatedEnergy, vr, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "J",   \
      "", "Frictional energy dissipated by all cells over the committed steps")

#define PATCH_SLIP_ROWS(X, vr, body)                                                             \
    X(slipFraction, vr, Float64, output, continuous, calculated, 0.0, 0.0, 1.0, "1", "",         \
      "Share of the " body "'s area whose cells slip in this step")                              \
    X(contactState, vr + 1, Int32, output, discrete, calculated, 0, 0, 3, "", "",                \
      "State of the step: 0 open (no cell pressed), 1 every pressed cell sticks, 2 some slip, "  \
      "3 every pressed cell slips")

/* FMI 3.0 only (a table's FMU_ARRAYS): the cells' tangential forces from
 * value reference vr on, and their states, with their structural
 * parameters n1, n2. */
#define PATCH_FORCE_ARRAYS(A, vr)                                                                \
    A(cellT1, vr, Float64, "N", T1,                                                              \
      "Tangential force of the surface on the body at each cell along X1 (they sum to T1)")      \
    A(cellT2, vr + 1, Float64, "N", T2,                                                          \
      "Tangential force of the surface on the body at each cell along X2 (they sum to T2)")
#define PATCH_STATE_ARRAY(A, vr)                                                                 \
    A(cellState, vr, Int32, "", contactState,                                                    \
      "State of each cell in this step: 0 open, 1 stick, 2 slip")
#define FMU_STRUCTURAL_PARAMETERS "n1 n2"

/* The rows' names, for the tables' lists of knowns. */
#define PATCH_CELL_KNOWNS "initialSlip s1Start s2Start length width n1 n2 u1 u2 theta"

/* clang-format on */
#endif
