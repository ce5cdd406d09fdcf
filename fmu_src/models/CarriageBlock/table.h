/*
 * The one table of the CarriageBlock FMU (glue/fmu_table.h says what a
 * table holds): the carriage/block rig of the paper's experiment (sec. 2),
 * to be coupled with OrthotropicContact.  A block of mass m on the mat is pushed
 * along X1 at constant velocity by a carriage through a strip; laterally it
 * is free but for the strip's Coulomb friction (muStrip on the push) and
 * viscous term (cStrip).  It takes the mat's force T on the block and gives
 * the contact its displacement u = x and normal force N = m g.
 */
#ifndef RIG_VARIABLES_H
#define RIG_VARIABLES_H

#include "glue/fmu_table.h"

/* A table's rows and lists keep their own layout. */
/* clang-format off */

#define FMU_MODEL_NAME "CarriageBlock"
#define FMU_MODEL_IDENTIFIER "CarriageBlock"
/* The guid / instantiationToken is a hash of the generated model
 * descriptions (gen_model_description writes it into fmu_token.h as
 * FMU_TOKEN, alias FMU_GUID): it changes whenever the description does, and
 * the binary and the description agree by construction.  The version is the
 * build's (CMake, from the file VERSION). */
#ifndef FMU_GENERATOR
#include "fmu_token.h"
#endif
#define FMU_STATE_TAG {'C', 'B', 'S', 'T'}
#define FMU_DESCRIPTION                                                                      \
    "Carriage/block rig of Konyukhov and Schweizerhof's experiment: a block pushed along X1 " \
    "at constant velocity, laterally free but for a strip's friction; couple its u1, u2, N " \
    "to OrthotropicContact's inputs and T1, T2 back"
/* Sources of the binary besides the glue's (glue/fmu_table.h's
 * FMU_GLUE_SOURCES and the version's; CMake's fmu_add reads the list from
 * here). */
#define FMU_SOURCES(S) S(models/CarriageBlock/model.c) S(rig/rig_core.c)
/* The model: its struct and its serialized state's field list (FMU_STATE_FIELDS). */
#define FMU_MODEL_HEADER "models/CarriageBlock/model.h"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"2.05\" stepSize=\"0.0002\""
#define FMU_PROVIDES_DERIVATIVES 0
#ifdef FMU_GENERATOR
/* The rig, for documentation/index.html. */
static const char FMU_DOC_HTML[] =
    "<h2>The rig</h2>\n<ul>\n"
    "<li>x1 = velocity t (the carriage drives the block); u1 = x1, u2 = x2, N = mass g.</li>\n"
    "<li>mass x2'' = T2 - cStrip x2' + f, with the strip's Coulomb force |f| <= muStrip P, "
    "P = max(-T1, 0) the push, opposing the lateral motion and never reversing it.</li>\n"
    "<li>driveForce = fInt - T1: what the force sensor reads.</li>\n"
    "<li>Each step integrates with T held: symplectic Euler, the viscous term implicit "
    "(stable for any step).</li>\n"
    "<li>Coupled with OrthotropicContact by the explicit loop (the rig steps with T held), "
    "the lateral motion on a stuck contact is a mass on a spring of stiffness up to "
    "max(eps1, eps2): stable only for h &lt; 2 sqrt(mass / max(eps1, eps2)), 24.5 ms for the "
    "defaults (the contact's documentation says why and what to do otherwise).</li>\n</ul>\n";
#endif

/* What each output depends on (ModelStructure, both FMI versions; columns
 * as in glue/fmu_table.h).  u1, u2, N, x1, x2 follow from the state and the
 * time, not from an input: no direct feedthrough, so a master needs no
 * iteration; driveForce = fInt - T1 reads the input T1 with the factor -1.
 * In initialization x1 = velocity * startTime, x2 = 0, N = mass g. */
#define FMU_DEPENDENCIES(D)                                                                    \
    D(u1, "", "time velocity") D(u2, "", "") D(N, "", "mass g")                                \
    D(x1, "", "time velocity") D(x2, "", "")                                                    \
    D(driveForce, "T1:constant", "fInt:constant T1:constant")

#define RIG_PARAMETER_ROWS(X)                                                                  \
    X(mass, 1, Float64, parameter, fixed, exact, 1.875, 1e-12, 1e12, "kg", "",                 \
      "Mass of the block")                                                                     \
    X(g, 2, Float64, parameter, fixed, exact, 9.806, 0.0, 1e3, "m/s2", "",                     \
      "Gravitational acceleration")                                                            \
    X(fInt, 3, Float64, parameter, fixed, exact, 5.0, 0.0, 1e12, "N", "",                      \
      "Internal resistance of the carriage, added to the push in the sensor's reading")        \
    X(velocity, 4, Float64, parameter, fixed, exact, 0.244, 1e-12, 1e6, "m/s", "",             \
      "Driving velocity of the carriage along X1")                                             \
    X(muStrip, 5, Float64, parameter, fixed, exact, 0.0, 0.0, 10.0, "1", "",                   \
      "Coulomb friction coefficient of the strip between carriage and block (on the push)")   \
    X(cStrip, 6, Float64, parameter, fixed, exact, 0.0, 0.0, 1e12, "N.s/m", "",                \
      "Lateral viscous coefficient of the strip")

#define RIG_INPUT_ROWS(X)                                                                      \
    X(T1, 7, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "N", "",                       \
      "Force of the mat on the block along X1 (OrthotropicContact.T1)")                        \
    X(T2, 8, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "N", "",                       \
      "Force of the mat on the block along X2 (OrthotropicContact.T2)")

#define RIG_OUTPUT_ROWS(X)                                                                     \
    X(u1, 9, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "m", "",            \
      "Displacement of the block relative to the mat along X1 (to OrthotropicContact.u1)")     \
    X(u2, 10, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "m", "",           \
      "Displacement of the block relative to the mat along X2 (to OrthotropicContact.u2)")     \
    X(N, 11, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "N", "",            \
      "Normal force of the block on the mat, mass g (to OrthotropicContact.N)")                \
    X(x1, 12, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "m", "",           \
      "Position of the block along X1")                                                        \
    X(x2, 13, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "m", "",           \
      "Position of the block along X2 (lateral drift)")                                        \
    X(driveForce, 14, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "N", "",   \
      "Driving force the sensor reads: fInt plus the push -T1")

/* Its rows (L would mark the law's: the rig has none). */
#define RIG_VARIABLES(X, L)                                                                    \
    X(time, 0, Float64, independent, continuous, , 0.0, NO_MIN, NO_MAX, "s", "",               \
      "Simulation time")                                                                       \
    RIG_PARAMETER_ROWS(X) RIG_INPUT_ROWS(X) RIG_OUTPUT_ROWS(X)

/* The table's tail, every table's (glue/fmu_table_tail.inc): FMU_VARIABLES
 * (no row of the law's group) and the value references RIG_VR_*. */
#define FMU_TABLE_ROWS RIG_VARIABLES
#define FMU_VR_PREFIX RIG_VR_
#include "glue/fmu_table_tail.inc"

/* clang-format on */
#endif
