/*
 * The one table of the OrthotropicContact FMU (glue/fmu_table.h says what a
 * table holds): the point contact, the law's rows (law/law_table.h) with
 * its inputs, outputs and initial slip.
 */
#ifndef OC_MODEL_VARIABLES_H
#define OC_MODEL_VARIABLES_H

#include "glue/fmu_table.h"
#include "law/law_table.h"

/* A table's rows and lists keep their own layout. */
/* clang-format off */

#define FMU_MODEL_NAME "OrthotropicContact"
#define FMU_MODEL_IDENTIFIER "OrthotropicContact"
/* The guid / instantiationToken is a hash of the generated model
 * descriptions (gen_model_description writes it into fmu_token.h as
 * FMU_TOKEN, alias FMU_GUID): it changes whenever the description does, and
 * the binary and the description agree by construction.  The version is the
 * build's (CMake, from the file VERSION). */
#ifndef FMU_GENERATOR
#include "fmu_token.h"
#endif
#define FMU_STATE_TAG {'O', 'C', 'S', 'T'}
#define FMU_DESCRIPTION                                                                      \
    "Coupled orthotropic adhesion-friction contact interface (Konyukhov and Schweizerhof "   \
    "2007): tangential force from the displacement of a body on a surface by an implicit " \
    "return mapping"
/* Sources of the binary besides the glue's (glue/fmu_table.h's
 * FMU_GLUE_SOURCES, and the version's glue/fmi2_glue.c or glue/fmi3_glue.c),
 * under fmu_src/; CMake's fmu_add reads the list from here and ships the
 * headers of their folders with them. */
#define FMU_SOURCES(S) S(law/contact_law.c) S(models/OrthotropicContact/model.c)
/* The model: its struct and its serialized state's field list (FMU_STATE_FIELDS). */
#define FMU_MODEL_HEADER "models/OrthotropicContact/model.h"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"1\" stepSize=\"0.001\""

#ifdef FMU_GENERATOR
/* The law in short, for documentation/index.html. */
static const char FMU_DOC_HTML[] =
    "<h2>The law</h2>\n<ul>\n"
    "<li>B = Q(alpha) diag(eps1, eps2) Q(alpha)<sup>T</sup> (adhesion), "
    "F = Q(beta) diag(1/mu1<sup>2</sup>, 1/mu2<sup>2</sup>) Q(beta)<sup>T</sup> (friction); "
    "angles counterclockwise from X1.</li>\n"
    "<li>Elastic force q = B (u - s), force on the body T = -q, yield function "
    "&Phi; = sqrt(q &middot; F q) - N.</li>\n"
    "<li>Stick if &Phi;(trial) &le; 0; otherwise slip s = s<sub>n</sub> + &Delta;&gamma; G q "
    "with &Phi;(q) = 0, solved implicitly (a monotone scalar iteration); G = F (associated) or "
    "(B F B)<sup>-1</sup> (coupled).  N &le; 0 opens the contact (T = 0, s follows u).</li>\n"
    "<li>Dissipated energy: the sum of q &middot; &Delta;s over committed steps, never "
    "negative.  Rate-independent: the step size does not enter.</li>\n"
    "</ul>\n<h2>Step semantics</h2>\n<p>After setting u1, u2, N the outputs read the step "
    "from the committed state without committing it (a master may iterate, with the "
    "directional derivative); doStep commits it.  The FMU state (get/set/serialize) holds "
    "everything, the FMI mode included: it restores into a freshly instantiated instance."
    "</p>\n"
    "<h2>Initial condition</h2>\n<p>The committed state before the first step is an "
    "unloaded contact with slip s.  With <code>initialSlip = atInputs</code> (default) s is "
    "the displacement u the FMU has when initialization ends (<code>ExitInitializationMode"
    "</code>): inputs wired to absolute positions give no force and no dissipation until the "
    "body moves.  With <code>initialSlip = explicit</code>, s = (s1Start, s2Start); explicit "
    "with s = 0 is the behaviour of versions before 0.4.  A path that starts at u = 0 gives "
    "the same results either way.</p>\n"
    "<h2>Wiring it into a system</h2>\n<ul>\n"
    "<li><code>u1, u2</code> [m]: the displacement of the body relative to the surface in the "
    "global frame (the body's position minus the surface's, where the surface moves).</li>\n"
    "<li><code>N</code> [N]: the normal force pressing the body on the surface (m g for a "
    "block on a level floor); N &le; 0 is an open contact.</li>\n"
    "<li><code>T1, T2</code> [N]: the force of the surface on the body: add it to the body's "
    "equation of motion (and -T to the surface's, if it is a body too).</li>\n"
    "<li>Direct feedthrough: T depends on u and N of the same step, T(u, N).  A loop body "
    "&rarr; contact &rarr; body is algebraic: a master either iterates on it (the outputs "
    "before @DOSTEP@ are the pending step's) or closes it through a body whose positions "
    "have no direct feedthrough, as the CarriageBlock FMU of this package:</li>\n</ul>\n"
    "<pre>for each communication step t &rarr; t + h:\n"
    "    body.@DOSTEP@(t, h)                        positions at t + h\n"
    "    contact.@SET@([u1, u2, N], [x1 - xs1, x2 - xs2, m g])\n"
    "    T1, T2 = contact.@GET@([T1, T2])          the force for these inputs (pending)\n"
    "    contact.@DOSTEP@(t, h)                     commit it\n"
    "    body.@SET@([T1, T2], [T1, T2])             acts on the body over its next step</pre>\n"
    "<h2>The explicit coupling's step limit</h2>\n<p>The loop above is explicit: the body "
    "steps with the force held.  On a stuck contact the force is a spring, T = -B (u - s), "
    "and the body's update with it held is the central-difference (symplectic Euler) update "
    "of a mass on a spring, u<sub>n+1</sub> - 2 u<sub>n</sub> + u<sub>n-1</sub> = h<sup>2</sup> "
    "(F - &epsilon; u<sub>n</sub>) / m, stable only for h &omega; &lt; 2, &omega; = "
    "sqrt(&epsilon; / m).  The stiffest direction of B is &epsilon;<sub>max</sub> = max(eps1, "
    "eps2), so the communication step must satisfy</p>\n"
    "<p><b>h &lt; 2 sqrt(m / &epsilon;<sub>max</sub>)</b> (m: the mass of the body the "
    "contact holds; add the stiffness of anything else holding it to &epsilon;<sub>max</sub>; "
    "for two bodies, use m<sub>1</sub> m<sub>2</sub> / (m<sub>1</sub> + m<sub>2</sub>)).</p>\n"
    "<p>Above it the solution grows: a body that truly sticks slides, and the dissipated energy "
    "is spurious.  Example: m = 0.05 kg on &epsilon;<sub>max</sub> = 25,000 N/m gives "
    "h &lt; 2 sqrt(0.05 / 25000) = 2.83 ms.  At h = 4 ms (h &omega; = 2.83) the first step "
    "moves the body by h<sup>2</sup> F / m = 8 F / &epsilon;: pushed by 30 % of the friction "
    "limit, the contact carries 2.4 times the limit and slides, where the stuck mass-spring "
    "never carries more than 2 F = 60 % of it.  (The default eps1 = 12510 N/m and the rig's "
    "1.875 kg give h &lt; 24.5 ms.)  What to do instead:</p>\n<ul>\n"
    "<li>a smaller step, h &lt; 2 sqrt(m / &epsilon;<sub>max</sub>); h &le; sqrt(m / "
    "&epsilon;<sub>max</sub>) (h &omega; &le; 1) also keeps the period within 5 %;</li>\n"
    "<li>or an implicit step of the body solved by iteration: set u, read the pending T and its "
    "derivative dT/du (@DIRDER@ of T1, T2 with respect to u1, u2: the consistent tangent, -B "
    "when stuck) and update u by Newton, e.g. on the trapezoidal step R(u) = u - u<sub>n</sub> "
    "- h v<sub>n</sub> - h<sup>2</sup>/4 (a<sub>n</sub> + a(u)) with dR/du = I - "
    "h<sup>2</sup>/(4 m) dT/du; then @DOSTEP@ commits.  Stable for any step: at 4 ms the "
    "body above sticks (one update a step).</li>\n</ul>\n"
    "<h2>What an importer prints</h2>\n<p>An importer that sets the inputs at t, calls "
    "@DOSTEP@(t, h) and then reads the outputs records at t + h the outputs of the step taken "
    "with the inputs of t (inputs are held over a step): a ramp u = v t reads one step behind, "
    "T(t + h) = T(u(t)).  <code>fmpy simulate</code> does exactly this.  Its default "
    "experiment, with no input file, prints zeros: N starts at 0, an open contact (T = 0, s "
    "follows u); give N and a path of u1, u2 as inputs.</p>\n";
#endif

/* Enumeration types: T(type name, items), items E(name, value, description);
 * the sliding rules' are law/law_table.h's, shared with the patch. */
#define FMU_ENUM_TYPES(T) T(SlidingRule, OC_SLIDING_RULE_ITEMS) T(InitialSlip, OC_INITIAL_SLIP_ITEMS)
#define OC_INITIAL_SLIP_ITEMS(E)                                                               \
    E(atInputs, 1, "s = u at the end of initialization: no force until the body moves")        \
    E(explicit, 2, "s = (s1Start, s2Start): the body is loaded by B (u - s) at once")

/* What each output depends on (ModelStructure, both FMI versions):
 * D(output, step mode, initialization), each a list of the knowns it is
 * computed from, "name" (no particular structure) or "name:kind".
 *   step mode: the inputs read at a communication point (FMI Outputs).  Every
 *     output is the pending step's for u1, u2, N (direct feedthrough).
 *   initialization: the knowns of initialization mode it is computed from
 *     (FMI InitialUnknowns): the start is s = u (atInputs) or s = (s1Start,
 *     s2Start) (explicit), and the first step's result follows from it with
 *     every parameter.  The stick/slip test does not read the rule: the state
 *     does not depend on slidingRule.  Nothing reads the start time.
 * gen_model_description refuses an output without its row and a name that
 * is not a known of the mode; tests/fmus/test_model_structure.py checks each
 * list against what the binary does. */
#define OC_INIT_KNOWNS_NO_RULE OC_LAW_NAMES "u1 u2 N initialSlip s1Start s2Start"
#define OC_INIT_KNOWNS OC_INIT_KNOWNS_NO_RULE " slidingRule"
#define FMU_DEPENDENCIES(D)                                                                    \
    D(T1, "u1 u2 N", OC_INIT_KNOWNS) D(T2, "u1 u2 N", OC_INIT_KNOWNS)                          \
    D(s1, "u1 u2 N", OC_INIT_KNOWNS) D(s2, "u1 u2 N", OC_INIT_KNOWNS)                          \
    D(contactState, "u1 u2 N", OC_INIT_KNOWNS_NO_RULE)                                         \
    D(dissipatedEnergy, "u1 u2 N", OC_INIT_KNOWNS)

/* The variables: time, the law's rows (its block, value references 1 to 15:
 * law/law_table.h), then from OC_LAW_VR_END = 16: */
#define OC_INPUT_ROWS(X)                                                                       \
    X(u1, 16, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "m", "",                      \
      "Displacement of the body relative to the surface along X1")                             \
    X(u2, 17, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "m", "",                      \
      "Displacement of the body relative to the surface along X2")                             \
    X(N, 18, Float64, input, continuous, , 0.0, NO_MIN, NO_MAX, "N", "",                       \
      "Normal force pressing the body on the surface (N <= 0: open contact)")

#define OC_OUTPUT_ROWS(X)                                                                      \
    X(T1, 19, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "N", "",           \
      "Tangential force of the surface on the body along X1")                                  \
    X(T2, 20, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "N", "",           \
      "Tangential force of the surface on the body along X2")                                  \
    X(s1, 21, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "m", "",           \
      "Slip displacement along X1")                                                            \
    X(s2, 22, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "m", "",           \
      "Slip displacement along X2")                                                            \
    X(contactState, 23, Int32, output, discrete, calculated, 0, 0, 2, "", "",                  \
      "State of the step: 0 open, 1 stick, 2 slip")                                            \
    X(dissipatedEnergy, 24, Float64, output, continuous, calculated, 0.0, NO_MIN, NO_MAX, "J", \
      "", "Frictional energy dissipated over the committed steps (never decreases)")

#define OC_INITIAL_SLIP_ROWS(X)                                                                \
    X(initialSlip, 25, InitialSlip, parameter, fixed, exact, 1, 1, 2, "", "",                  \
      "Initial slip: 1 atInputs (s = u when initialization ends: the contact starts unloaded " \
      "wherever the body is), 2 explicit (s = (s1Start, s2Start))")                            \
    X(s1Start, 26, Float64, parameter, fixed, exact, 0.0, -1e300, 1e300, "m", "",              \
      "Initial slip along X1 when initialSlip = explicit")                                     \
    X(s2Start, 27, Float64, parameter, fixed, exact, 0.0, -1e300, 1e300, "m", "",              \
      "Initial slip along X2 when initialSlip = explicit")

#define OC_VARIABLES(X, L)                                                                     \
    X(time, 0, Float64, independent, continuous, , 0.0, NO_MIN, NO_MAX, "s", "",               \
      "Simulation time")                                                                       \
    OC_LAW_ROWS(L, X) OC_INPUT_ROWS(X) OC_OUTPUT_ROWS(X) OC_INITIAL_SLIP_ROWS(X)

/* The law's rows are marked L in OC_VARIABLES: the model stores them in an
 * oc_params under their names and serializes them, the compiled master
 * fills them and the package's manifest (gen_model_description manifest)
 * lists them as the group "law", all from here. */
/* The table's tail, every table's (glue/fmu_table_tail.inc): FMU_VARIABLES,
 * the law's group and the value references OC_VR_*. */
#define FMU_TABLE_ROWS OC_VARIABLES
#define FMU_VR_PREFIX OC_VR_
#include "glue/fmu_table_tail.inc"

/* clang-format on */
#endif
