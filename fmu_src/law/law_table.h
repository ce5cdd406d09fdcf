/*
 * The law's part of a model's table (glue/fmu_table.h), written once:
 * the rows of its parameters and of its sliding rule, and the rules'
 * enumeration.  Every model that carries the law (OrthotropicContact,
 * ContactPatch, ContactPad) includes this and puts OC_LAW_ROWS(L, X) among
 * its variables, in the law's block of value references, 1 to
 * OC_LAW_VR_END - 1 (1 to 7 taken): L for the law's Float64 parameters,
 * oc_params' fields of the same names (law/contact_law.h) in this order,
 * which a table marks as the group "law" (the package's manifest lists
 * them so), X for the sliding rule (oc_params.rule).  A model's own rows
 * start at OC_LAW_VR_END, so that a new row of the law takes the next
 * value reference of the block and moves none of them.  Each description
 * reads right for a point and for a patch of cells.
 */
#ifndef OC_LAW_TABLE_H
#define OC_LAW_TABLE_H

#include "glue/fmu_table.h"

/* The law's block of value references ends before this: every model's own
 * rows start here. */
#define OC_LAW_VR_END 16

/* A table's rows and lists keep their own layout. */
/* clang-format off */

/* Friction coefficients [-] along the friction axes. */
#define OC_LAW_FRICTION_ROWS(L)                                                                \
    L(mu1, 1, Float64, parameter, fixed, exact, 0.408, 1e-150, 1e150, "1", "",                 \
      "Friction coefficient along friction axis 1 (at angle beta)")                            \
    L(mu2, 2, Float64, parameter, fixed, exact, 0.625, 1e-150, 1e150, "1", "",                 \
      "Friction coefficient along friction axis 2 (at angle beta + 90 deg)")

/* Tangential stiffnesses [N/m] along the adhesion axes. */
#define OC_LAW_STIFFNESS_ROWS(L)                                                               \
    L(eps1, 3, Float64, parameter, fixed, exact, 12510.0, 1e-300, 1e300, "N/m", "",            \
      "Tangential (adhesion) stiffness along adhesion axis 1 (at angle alpha); a patch "       \
      "shares it among its cells by area")                                                     \
    L(eps2, 4, Float64, parameter, fixed, exact, 10000.0, 1e-300, 1e300, "N/m", "",            \
      "Tangential (adhesion) stiffness along adhesion axis 2 (at angle alpha + 90 deg); a "    \
      "patch shares it among its cells by area")

/* The texture's axes [rad], the surface's. */
#define OC_LAW_AXES_ROWS(L)                                                                    \
    L(alpha, 5, Float64, parameter, fixed, exact, 1.5707963267948966, -12.566370614359172,     \
      12.566370614359172, "rad", "deg",                                                        \
      "Angle of adhesion axis 1, counterclockwise from X1 (fixed to the surface)")             \
    L(beta, 6, Float64, parameter, fixed, exact, 0.0, -12.566370614359172, 12.566370614359172, \
      "rad", "deg", "Angle of friction axis 1, counterclockwise from X1 (fixed to the surface)")

/* The sliding rule: an oc_rule (law/contact_law.h), of the type SlidingRule. */
#define OC_LAW_RULE_ROW(X)                                                                     \
    X(slidingRule, 7, SlidingRule, parameter, fixed, exact, 2, 1, 3, "", "",                   \
      "Sliding rule: 1 associated (G = F), 2 coupled (G = (B F B)^-1), "                       \
      "3 literal eq. (20) of the paper (step-size dependent, for reproduction only)")

#define OC_LAW_ROWS(L, X)                                                                      \
    OC_LAW_FRICTION_ROWS(L) OC_LAW_STIFFNESS_ROWS(L) OC_LAW_AXES_ROWS(L) OC_LAW_RULE_ROW(X)

/* Every row of the law lies in its block (a negative array size fails to
 * compile). */
#define OC_LAW_IN_BLOCK(name, vr, ...)                                                         \
    typedef char oc_law_block_##name[(vr) < OC_LAW_VR_END ? 1 : -1];
OC_LAW_ROWS(OC_LAW_IN_BLOCK, OC_LAW_IN_BLOCK)
#undef OC_LAW_IN_BLOCK

/* The law's parameters alone (its L rows), and their names as a list of
 * knowns ("mu1 mu2 ... beta "). */
#define OC_LAW_PARAMETERS(L) OC_LAW_ROWS(L, FMU_NO_ROW)
#define OC_LAW_NAMES OC_LAW_PARAMETERS(FMU_NAME_SPACE)

/* The enumeration type SlidingRule, E(name, value, description): oc_rule's
 * values. */
#define OC_SLIDING_RULE_ITEMS(E)                                                               \
    E(associated, 1, "G = F: classical orthotropic Coulomb friction (paper Case 1)")           \
    E(coupled, 2, "G = (B F B)^-1: the coupled law of Konyukhov and Schweizerhof")             \
    E(eq20, 3, "the paper's explicit eq. (20), step-size dependent: for reproduction only")

/* clang-format on */
#endif
