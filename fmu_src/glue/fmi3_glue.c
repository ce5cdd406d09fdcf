/*
 * FMI 3.0 Co-Simulation: the standard's signatures translated onto the shared,
 * version-independent instance (fmu_instance.h) and the model (fmu_model.h).
 * No mechanics and no model variables live here.  Float64 variables, Int32
 * variables, Enumerations (through the Int64 functions, as FMI 3.0 asks) and
 * structural parameters (UInt64, as the standard's Dimension element asks;
 * Int32 rows of the table: fmu_model.h) are served; every other type has no
 * variables.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "glue/fmu_instance.h"

#define INST(c) ((fmu_instance *)(c))

/* What FMI 2.0 defines alike (glue/fmi_both.inc) */
#define FMI_PREFIX fmi3
#define FMI_INSTANCE fmi3Instance
#define FMI_STATE State
#define FMI_DESERIALIZE Deserialize
#define FMI_CONFIG FMU_CONFIG
#include "glue/fmi_both.inc"

typedef struct {
    fmi3InstanceEnvironment env;
    fmi3LogMessageCallback log;
} glue3;

static void log_fmi3(fmu_instance *I, int status, const char *category, const char *text) {
    const glue3 *g = I->glue;
    if (g->log) g->log(g->env, (fmi3Status)status, category, text);
}

static void *calloc3(size_t n, size_t size) { return calloc(n, size); }

/* One value per value reference (a model's arrays are outputs: gets of a
 * model with arrays take get_values).  The test inline, the message out of
 * line (at -O2 the whole was a call on every get and set). */
static int arrays_refused(fmu_instance *I, const char *fn, size_t nvr, const void *vr,
                          const void *values, size_t nValues);
static inline int arrays_ok(fmu_instance *I, const char *fn, size_t nvr, const void *vr,
                            const void *values, size_t nValues) {
    if (nValues == nvr && (nvr == 0 || (vr && values))) return 1;
    return arrays_refused(I, fn, nvr, vr, values, nValues);
}

static int arrays_refused(fmu_instance *I, const char *fn, size_t nvr, const void *vr,
                          const void *values, size_t nValues) {
    if (nvr > 0 && (!vr || !values)) {
        FMU_ERROR(I, "%s: NULL array with nValueReferences = %zu", fn, nvr);
        return 0;
    }
    if (nValues != nvr) {
        FMU_ERROR(I, "%s: nValues = %zu but nValueReferences = %zu (%s)", fn, nValues, nvr,
                  FMU_MODEL_INFO.arrays ? "only outputs are arrays: every settable variable is a "
                                          "scalar"
                                        : "every variable is a scalar");
        return 0;
    }
    return 1;
}

/* ---- Inquiry, instantiation, logging ---------------------------------- */

const char *fmi3GetVersion(void) { return fmi3Version; }

/* An instantiation refused before an instance exists: "<function>: <why>"
 * to the importer's logger, if it gave one. */
static void refuse3(fmi3InstanceEnvironment env, fmi3LogMessageCallback log, const char *fn,
                    const char *why) {
    char text[256];
    snprintf(text, sizeof text, "%s: %s", fn, why);
    if (log) log(env, fmi3Error, "logStatusError", text);
}

fmi3Instance fmi3InstantiateCoSimulation(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate) {
    (void)visible;
    (void)earlyReturnAllowed;
    (void)requiredIntermediateVariables;
    (void)intermediateUpdate;
    const char *why = NULL;
    if (!instanceName || !*instanceName)
        why = "instanceName is empty";
    else if (!instantiationToken || strcmp(instantiationToken, FMU_MODEL_INFO.token) != 0)
        why = "instantiationToken does not match this FMU's modelDescription.xml";
    else if (eventModeUsed)
        why = "this FMU has no event mode (hasEventMode = false)";
    /* A request for intermediate variables is allowed and answered by
     * providing none (as the Reference-FMUs do): intermediateUpdate is never
     * called, since doStep never returns early or stops between points. */
    else if (nRequiredIntermediateVariables > 0 && !requiredIntermediateVariables)
        why = "requiredIntermediateVariables is NULL with nRequiredIntermediateVariables > 0";
    if (why) {
        refuse3(instanceEnvironment, logMessage, __func__, why);
        return NULL;
    }
    glue3 *g = calloc(1, sizeof *g);
    if (!g) return NULL;
    g->env = instanceEnvironment;
    g->log = logMessage;
    fmu_instance *I = fmu_instance_new(instanceName, calloc3, free, log_fmi3, g, loggingOn);
    if (!I) {
        refuse3(instanceEnvironment, logMessage, __func__, "out of memory");
        free(g);
        return NULL;
    }
    return with_start_values(I, __func__, resourcePath, 0);
}

static fmi3Instance refuse_interface(fmi3InstanceEnvironment env, fmi3LogMessageCallback log,
                                     const char *fn) {
    refuse3(env, log, fn, NO_ME);
    return NULL;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible,
                                          fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage) {
    (void)instanceName;
    (void)instantiationToken;
    (void)resourcePath;
    (void)visible;
    (void)loggingOn;
    return refuse_interface(instanceEnvironment, logMessage, __func__);
}

fmi3Instance fmi3InstantiateScheduledExecution(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
    fmi3LockPreemptionCallback lockPreemption, fmi3UnlockPreemptionCallback unlockPreemption) {
    (void)instanceName;
    (void)instantiationToken;
    (void)resourcePath;
    (void)visible;
    (void)loggingOn;
    (void)clockUpdate;
    (void)lockPreemption;
    (void)unlockPreemption;
    return refuse_interface(instanceEnvironment, logMessage, __func__);
}

/* ---- Initialization, termination, reset -------------------------------- */

fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime) {
    fmu_instance *I = INST(c);
    (void)toleranceDefined;
    (void)tolerance; /* the law is solved to machine precision */
    if (!fmu_allowed(I, __func__, FMU_INSTANTIATED) ||
        start_at(I, __func__, startTime, stopTimeDefined, stopTime) != FMU_S_OK)
        return fmi3Error;
    I->phase = FMU_INIT;
    return fmi3OK;
}

/* ---- Getting and setting values ----------------------------------------- */

#define SETTABLE (FMU_INSTANTIATED | FMU_INIT | FMU_STEP | FMU_CONFIG)

/* A get of a model with arrays: nValues counts the arrays' elements. */
static int get_values(fmu_instance *I, const char *fn, const fmi3ValueReference vr[], size_t nvr,
                      void *values, size_t nValues, int type, size_t width) {
    if (nvr > 0 && (!vr || !values)) {
        FMU_ERROR(I, "%s: NULL array with nValueReferences = %zu", fn, nvr);
        return FMU_S_ERROR;
    }
    fmu_msg msg;
    return fmu_result(
        I, fmu_model_get_values(I->model, vr, nvr, values, nValues, type, width, &msg), &msg, fn);
}

/* In configuration mode only the structural parameters may be set. */
static int config_ok(fmu_instance *I, const char *fn, const fmi3ValueReference vr[], size_t nvr) {
    if (I->phase != FMU_CONFIG) return 1;
    for (size_t i = 0; i < nvr; ++i)
        if (!fmu_model_is_structural(vr[i])) {
            const char *name = fmu_model_variable_name(vr[i]);
            FMU_ERROR(I,
                      "%s: %s (vr %u) is not a structural parameter: in configuration mode "
                      "only structural parameters may be set",
                      fn, name ? name : "unknown", vr[i]);
            return 0;
        }
    return 1;
}

fmi3Status fmi3GetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                          fmi3Float64 values[], size_t nValues) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_READABLE)) return fmi3Error;
    if (FMU_MODEL_INFO.arrays)
        return status_of(get_values(I, __func__, vr, nvr, values, nValues, FMU_T_Float64, 8));
    if (!arrays_ok(I, __func__, nvr, vr, values, nValues)) return fmi3Error;
    fmu_msg msg;
    return status_of(
        fmu_result(I, fmu_model_get_float64(I->model, vr, nvr, values, &msg), &msg, __func__));
}

fmi3Status fmi3SetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                          const fmi3Float64 values[], size_t nValues) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, SETTABLE) || !arrays_ok(I, __func__, nvr, vr, values, nValues) ||
        !config_ok(I, __func__, vr, nvr))
        return fmi3Error;
    fmu_msg msg;
    return status_of(
        fmu_result(I, fmu_model_set_float64(I->model, vr, nvr, values, fmu_settable(I), &msg), &msg,
                   __func__));
}

/* Int32 variables through the Int32 functions, Enumerations through Int64,
 * structural parameters through UInt64 (each refused by the others): a
 * get and a set of integers of `width` bytes, the kinds its type may touch. */
static fmi3Status get_ints(fmi3Instance c, const char *fn, const fmi3ValueReference vr[],
                           size_t nvr, void *values, size_t nValues, int kinds, size_t width) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, fn, FMU_READABLE)) return fmi3Error;
    if (FMU_MODEL_INFO.arrays)
        return status_of(get_values(I, fn, vr, nvr, values, nValues, kinds, width));
    if (!arrays_ok(I, fn, nvr, vr, values, nValues)) return fmi3Error;
    fmu_msg msg;
    return status_of(
        fmu_result(I, fmu_model_get_int(I->model, vr, nvr, values, width, kinds, &msg), &msg, fn));
}

static fmi3Status set_ints(fmi3Instance c, const char *fn, const fmi3ValueReference vr[],
                           size_t nvr, const void *values, size_t nValues, int kinds,
                           size_t width) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, fn, SETTABLE) || !arrays_ok(I, fn, nvr, vr, values, nValues) ||
        !config_ok(I, fn, vr, nvr))
        return fmi3Error;
    fmu_msg msg;
    return status_of(fmu_result(
        I, fmu_model_set_int(I->model, vr, nvr, values, width, kinds, fmu_settable(I), &msg), &msg,
        fn));
}

#define INT_ACCESS(TYPE, CTYPE, KIND)                                                              \
    fmi3Status fmi3Get##TYPE(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,            \
                             CTYPE values[], size_t nValues) {                                     \
        return get_ints(c, __func__, vr, nvr, values, nValues, KIND, sizeof(CTYPE));               \
    }                                                                                              \
    fmi3Status fmi3Set##TYPE(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,            \
                             const CTYPE values[], size_t nValues) {                               \
        return set_ints(c, __func__, vr, nvr, values, nValues, KIND, sizeof(CTYPE));               \
    }
INT_ACCESS(Int32, fmi3Int32, FMU_INT32 | FMU_AS_FMI3)
INT_ACCESS(Int64, fmi3Int64, FMU_ENUM | FMU_AS_FMI3)
INT_ACCESS(UInt64, fmi3UInt64, FMU_UINT64 | FMU_AS_FMI3)

#define NO_VARIABLES(TYPE, CTYPE)                                                                  \
    fmi3Status fmi3Get##TYPE(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,            \
                             CTYPE values[], size_t nValues) {                                     \
        (void)values;                                                                              \
        (void)nValues;                                                                             \
        return no_such_variables(INST(c), __func__, FMU_READABLE, nvr, vr);                        \
    }                                                                                              \
    fmi3Status fmi3Set##TYPE(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,            \
                             const CTYPE values[], size_t nValues) {                               \
        (void)values;                                                                              \
        (void)nValues;                                                                             \
        return no_such_variables(INST(c), __func__, SETTABLE, nvr, vr);                            \
    }
NO_VARIABLES(Float32, fmi3Float32)
NO_VARIABLES(Int8, fmi3Int8)
NO_VARIABLES(UInt8, fmi3UInt8)
NO_VARIABLES(Int16, fmi3Int16)
NO_VARIABLES(UInt16, fmi3UInt16)
NO_VARIABLES(UInt32, fmi3UInt32)
NO_VARIABLES(Boolean, fmi3Boolean)
NO_VARIABLES(String, fmi3String)

fmi3Status fmi3GetBinary(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                         size_t valueSizes[], fmi3Binary values[], size_t nValues) {
    (void)valueSizes;
    (void)values;
    (void)nValues;
    return no_such_variables(INST(c), __func__, FMU_READABLE, nvr, vr);
}

fmi3Status fmi3SetBinary(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                         const size_t valueSizes[], const fmi3Binary values[], size_t nValues) {
    (void)valueSizes;
    (void)values;
    (void)nValues;
    return no_such_variables(INST(c), __func__, SETTABLE, nvr, vr);
}

fmi3Status fmi3GetClock(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                        fmi3Clock values[]) {
    (void)values;
    return no_such_variables(INST(c), __func__, FMU_ALIVE, nvr, vr);
}

fmi3Status fmi3SetClock(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                        const fmi3Clock values[]) {
    (void)values;
    return no_such_variables(INST(c), __func__, FMU_ALIVE, nvr, vr);
}

/* ---- What this FMU does not provide ----------------------------------------- */

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance c, fmi3ValueReference valueReference,
                                               size_t *nDependencies) {
    (void)valueReference;
    (void)nDependencies;
    return unsupported(c, __func__,
                       "dependencies are given in the "
                       "model description's ModelStructure only");
}

fmi3Status fmi3GetVariableDependencies(fmi3Instance c, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[],
                                       fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[],
                                       fmi3DependencyKind dependencyKinds[], size_t nDependencies) {
    (void)dependent;
    (void)elementIndicesOfDependent;
    (void)independents;
    (void)elementIndicesOfIndependents;
    (void)dependencyKinds;
    (void)nDependencies;
    return unsupported(c, __func__,
                       "dependencies are given in the model "
                       "description's ModelStructure only");
}

/* Configuration mode, entered from the instantiated phase only and left back
 * to it: the structural parameters are fixed, so there is no
 * reconfiguration mode. */
static fmi3Status configuration(fmi3Instance c, const char *fn, int from, int to) {
    fmu_instance *I = INST(c);
    if (!FMU_MODEL_INFO.arrays || !FMU_MODEL_INFO.arrays->n_structural)
        return unsupported(c, fn, "this FMU has no structural parameters");
    if (!fmu_allowed(I, fn, from)) return fmi3Error;
    I->phase = to;
    return fmi3OK;
}
fmi3Status fmi3EnterConfigurationMode(fmi3Instance c) {
    return configuration(c, __func__, FMU_INSTANTIATED, FMU_CONFIG);
}
fmi3Status fmi3ExitConfigurationMode(fmi3Instance c) {
    return configuration(c, __func__, FMU_CONFIG, FMU_INSTANTIATED);
}

#define NO_CLOCKS "this FMU has no clocks"
fmi3Status fmi3GetIntervalDecimal(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                                  fmi3Float64 intervals[], fmi3IntervalQualifier q[]) {
    (void)vr;
    (void)n;
    (void)intervals;
    (void)q;
    return unsupported(c, __func__, NO_CLOCKS);
}
fmi3Status fmi3GetIntervalFraction(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                                   fmi3UInt64 counters[], fmi3UInt64 resolutions[],
                                   fmi3IntervalQualifier q[]) {
    (void)vr;
    (void)n;
    (void)counters;
    (void)resolutions;
    (void)q;
    return unsupported(c, __func__, NO_CLOCKS);
}
/* The calls on clocks' shifts and intervals given as one number (decimal)
 * or as counters and resolutions (fraction), one a row; const for a set. */
#define NO_CLOCK_DECIMAL(name, CONST)                                                              \
    fmi3Status fmi3##name(fmi3Instance c, const fmi3ValueReference vr[], size_t n,                 \
                          CONST fmi3Float64 values[]) {                                            \
        (void)vr;                                                                                  \
        (void)n;                                                                                   \
        (void)values;                                                                              \
        return unsupported(c, __func__, NO_CLOCKS);                                                \
    }
#define NO_CLOCK_FRACTION(name, CONST)                                                             \
    fmi3Status fmi3##name(fmi3Instance c, const fmi3ValueReference vr[], size_t n,                 \
                          CONST fmi3UInt64 counters[], CONST fmi3UInt64 resolutions[]) {           \
        (void)vr;                                                                                  \
        (void)n;                                                                                   \
        (void)counters;                                                                            \
        (void)resolutions;                                                                         \
        return unsupported(c, __func__, NO_CLOCKS);                                                \
    }
NO_CLOCK_DECIMAL(GetShiftDecimal, )
NO_CLOCK_DECIMAL(SetIntervalDecimal, const)
NO_CLOCK_DECIMAL(SetShiftDecimal, const)
NO_CLOCK_FRACTION(GetShiftFraction, )
NO_CLOCK_FRACTION(SetIntervalFraction, const)
NO_CLOCK_FRACTION(SetShiftFraction, const)
fmi3Status fmi3ActivateModelPartition(fmi3Instance c, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime) {
    (void)clockReference;
    (void)activationTime;
    return unsupported(c, __func__, NO_ME);
}

#define NO_EVENTS "this FMU has no event mode (hasEventMode = false)"
fmi3Status fmi3EnterEventMode(fmi3Instance c) { return unsupported(c, __func__, NO_EVENTS); }
fmi3Status fmi3EnterStepMode(fmi3Instance c) { return unsupported(c, __func__, NO_EVENTS); }
fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance c) {
    return unsupported(c, __func__, NO_EVENTS);
}
fmi3Status fmi3UpdateDiscreteStates(fmi3Instance c, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation,
                                    fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged,
                                    fmi3Boolean *nextEventTimeDefined, fmi3Float64 *nextEventTime) {
    (void)discreteStatesNeedUpdate;
    (void)terminateSimulation;
    (void)nominalsOfContinuousStatesChanged;
    (void)valuesOfContinuousStatesChanged;
    (void)nextEventTimeDefined;
    (void)nextEventTime;
    return unsupported(c, __func__, NO_EVENTS);
}

/* Model Exchange: the functions glue/fmi_both.inc does not define */
FMI_NO_ME_ARRAY(GetContinuousStateDerivatives, fmi3Float64)
fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance c, size_t *n) {
    (void)n;
    return unsupported(c, __func__, NO_ME);
}
fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance c, size_t *n) {
    (void)n;
    return unsupported(c, __func__, NO_ME);
}

/* ---- Derivatives ------------------------------------------------------------ */

fmi3Status fmi3GetOutputDerivatives(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr,
                                    const fmi3Int32 orders[], fmi3Float64 values[],
                                    size_t nValues) {
    (void)vr;
    (void)orders;
    (void)values;
    (void)nValues;
    return refuse_unless_empty(c, __func__, FMU_READABLE, nvr, "maxOutputDerivativeOrder is 0");
}

static fmi3Status derivative3(fmi3Instance c, const char *fn, const fmi3ValueReference unknowns[],
                              size_t nUnknowns, const fmi3ValueReference knowns[], size_t nKnowns,
                              const fmi3Float64 seed[], size_t nSeed, fmi3Float64 sensitivity[],
                              size_t nSensitivity, int adjoint) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, fn, FMU_READABLE)) return fmi3Error;
    const size_t want_seed = adjoint ? nUnknowns : nKnowns,
                 want_out = adjoint ? nKnowns : nUnknowns;
    if (nSeed != want_seed || nSensitivity != want_out || (nUnknowns > 0 && !unknowns) ||
        (nKnowns > 0 && !knowns) || (nSeed > 0 && !seed) || (nSensitivity > 0 && !sensitivity)) {
        FMU_ERROR(I,
                  "%s: needs %zu seeds and %zu sensitivities for %zu unknowns and %zu knowns "
                  "(got %zu, %zu, or a NULL array)",
                  fn, want_seed, want_out, nUnknowns, nKnowns, nSeed, nSensitivity);
        return fmi3Error;
    }
    fmu_msg msg;
    return status_of(fmu_result(I,
                                fmu_model_derivative(I->model, unknowns, nUnknowns, knowns, nKnowns,
                                                     seed, sensitivity, adjoint, &msg),
                                &msg, fn));
}

/* The two derivatives' calls, one a row. */
#define DERIVATIVE(KIND, adjoint)                                                                  \
    fmi3Status fmi3Get##KIND##Derivative(fmi3Instance c, const fmi3ValueReference unknowns[],      \
                                         size_t nUnknowns, const fmi3ValueReference knowns[],      \
                                         size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,   \
                                         fmi3Float64 sensitivity[], size_t nSensitivity) {         \
        return derivative3(c, __func__, unknowns, nUnknowns, knowns, nKnowns, seed, nSeed,         \
                           sensitivity, nSensitivity, adjoint);                                    \
    }
DERIVATIVE(Directional, 0)
DERIVATIVE(Adjoint, 1)

/* ---- Co-Simulation ---------------------------------------------------------- */

fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime) {
    fmu_instance *I = INST(c);
    (void)noSetFMUStatePriorToCurrentPoint;
    if (!fmu_allowed(I, __func__, FMU_STEP)) return fmi3Error;
    fmu_msg msg;
    const int st = fmu_result(
        I, fmu_do_step(I, currentCommunicationPoint, communicationStepSize, &msg), &msg, __func__);
    if (eventHandlingNeeded) *eventHandlingNeeded = fmi3False;
    if (terminateSimulation) *terminateSimulation = fmi3False;
    if (earlyReturn) *earlyReturn = fmi3False;
    if (lastSuccessfulTime) *lastSuccessfulTime = *fmu_model_time(I->model);
    return status_of(st);
}
