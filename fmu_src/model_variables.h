/*
 * The one table of the FMU's variables.  modelDescription.xml is generated
 * from it (tools: gen_model_description; the committed copy at the repo root
 * is checked against the generated one by the CTest `model_description_in_sync`),
 * and the value references of the C code are these enums.
 *
 * X(name, vr, type, causality, variability, initial, start, unit, displayUnit, description)
 *   initial: exact or calculated ("calculated" entries have no start in the XML);
 *   inputs leave initial empty, as FMI 2.0 requires.
 */
#ifndef OC_MODEL_VARIABLES_H
#define OC_MODEL_VARIABLES_H

#define OC_MODEL_NAME "OrthotropicContact"
#define OC_MODEL_IDENTIFIER "OrthotropicContact"
#define OC_GUID "{8c6e3f52-4d1a-4b7e-9a35-0f1473db3576}"
#define OC_VERSION "0.1.0"

#define OC_VARIABLES(X)                                                                        \
    X(mu1, 1, Real, parameter, fixed, exact, 0.408, "1", "",                                   \
      "Friction coefficient along friction axis 1 (at angle beta)")                            \
    X(mu2, 2, Real, parameter, fixed, exact, 0.625, "1", "",                                   \
      "Friction coefficient along friction axis 2 (at angle beta + 90 deg)")                   \
    X(eps1, 3, Real, parameter, fixed, exact, 12510.0, "N/m", "",                              \
      "Tangential (adhesion) stiffness along adhesion axis 1 (at angle alpha)")                \
    X(eps2, 4, Real, parameter, fixed, exact, 10000.0, "N/m", "",                              \
      "Tangential (adhesion) stiffness along adhesion axis 2 (at angle alpha + 90 deg)")       \
    X(alpha, 5, Real, parameter, fixed, exact, 1.5707963267948966, "rad", "deg",               \
      "Angle of adhesion axis 1, counterclockwise from X1")                                    \
    X(beta, 6, Real, parameter, fixed, exact, 0.0, "rad", "deg",                               \
      "Angle of friction axis 1, counterclockwise from X1")                                    \
    X(slidingRule, 7, Integer, parameter, fixed, exact, 2, "", "",                             \
      "Sliding rule: 1 associated (G = F), 2 coupled (G = (B F B)^-1), "                       \
      "3 literal eq. (20) of the paper (step-size dependent, for reproduction only)")         \
    X(u1, 8, Real, input, continuous, , 0.0, "m", "",                                          \
      "Displacement of the body relative to the surface along X1")                             \
    X(u2, 9, Real, input, continuous, , 0.0, "m", "",                                          \
      "Displacement of the body relative to the surface along X2")                             \
    X(N, 10, Real, input, continuous, , 0.0, "N", "",                                          \
      "Normal force pressing the body on the surface (N <= 0: open contact)")                  \
    X(T1, 11, Real, output, continuous, calculated, 0.0, "N", "",                              \
      "Tangential force of the surface on the body along X1")                                  \
    X(T2, 12, Real, output, continuous, calculated, 0.0, "N", "",                              \
      "Tangential force of the surface on the body along X2")                                  \
    X(s1, 13, Real, output, continuous, calculated, 0.0, "m", "", "Slip displacement along X1") \
    X(s2, 14, Real, output, continuous, calculated, 0.0, "m", "", "Slip displacement along X2") \
    X(contactState, 15, Integer, output, discrete, calculated, 0, "", "",                      \
      "State of the step: 0 open, 1 stick, 2 slip")                                            \
    X(dissipatedEnergy, 16, Real, output, continuous, calculated, 0.0, "J", "",                \
      "Frictional energy dissipated over the committed steps")

#define OC_VR_ENUM_ENTRY(name, vr, ...) OC_VR_##name = vr,
enum { OC_VARIABLES(OC_VR_ENUM_ENTRY) OC_VR_COUNT_PLUS_ONE };
#undef OC_VR_ENUM_ENTRY

#endif
