/*
 * FMI 2.0 Co-Simulation: the standard's signatures translated onto the shared,
 * version-independent instance (fmu_instance.c) and the model (fmu_model.h).
 * No mechanics and no model variables live here.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "glue/fmu_instance.h"

#define INST(c) ((fmu_instance *)(c))

/* The logger formats its message printf-style: a literal '%' is doubled. */
static void log_fmi2(fmu_instance *I, int status, const char *category, const char *text) {
    const fmi2CallbackFunctions *cb = I->glue;
    if (!cb->logger) return;
    char esc[1024];
    size_t j = 0;
    for (size_t i = 0; text[i] && j + 2 < sizeof esc; ++i) {
        if (text[i] == '%') esc[j++] = '%';
        esc[j++] = text[i];
    }
    esc[j] = '\0';
    cb->logger(cb->componentEnvironment, I->name, (fmi2Status)status, category, esc);
}

static fmi2Status status2(int s) { return (fmi2Status)s; }

static int arrays_refused(fmu_instance *I, const char *fn, size_t n) {
    FMU_ERROR(I, "%s: NULL array with n = %zu", fn, n);
    return 0;
}

/* The test inline, the message out of line. */
static inline int arrays_ok(fmu_instance *I, const char *fn, size_t n, const void *a,
                            const void *b) {
    return n == 0 || (a && b) ? 1 : arrays_refused(I, fn, n);
}

static void *calloc2(size_t n, size_t size) { return calloc(n, size); }

/* ---- Inquiry, instantiation, logging ---------------------------------- */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn) {
    (void)visible;
    if (!functions) return NULL;
    const char *name = instanceName ? instanceName : "";
    const char *why = NULL;
    if (!instanceName || !*instanceName)
        why = "instanceName is empty";
    else if (fmuType != fmi2CoSimulation)
        why = "this FMU supports Co-Simulation only";
    else if (!fmuGUID || strcmp(fmuGUID, FMU_MODEL_INFO.token) != 0)
        why = "GUID does not match this FMU's modelDescription.xml";
    /* Memory from the importer must go back to the importer: one callback
     * without the other cannot be honoured. */
    else if ((functions->allocateMemory == NULL) != (functions->freeMemory == NULL))
        why = "allocateMemory and freeMemory must be given together";
    if (why) {
        if (functions->logger)
            functions->logger(functions->componentEnvironment, name, fmi2Error, "logStatusError",
                              "%s: %s", __func__, why);
        return NULL;
    }
    void *(*alloc)(size_t, size_t) =
        functions->allocateMemory ? functions->allocateMemory : calloc2;
    void (*release)(void *) = functions->freeMemory ? functions->freeMemory : free;
    fmi2CallbackFunctions *cb = alloc(1, sizeof *cb);
    if (!cb) return NULL;
    *cb = *functions;
    fmu_instance *I = fmu_instance_new(instanceName, alloc, release, log_fmi2, cb, loggingOn);
    if (!I) {
        if (functions->logger)
            functions->logger(functions->componentEnvironment, name, fmi2Error, "logStatusError",
                              "%s: out of memory", __func__);
        release(cb);
        return NULL;
    }
    fmu_log(I, FMU_S_OK, FMU_LOG_CALLS, __func__);
    if (fmu_load_start_values(I, __func__, fmuResourceLocation, 1) != 0) {
        fmu_instance_free(I);
        release(cb);
        return NULL;
    }
    return I;
}

void fmi2FreeInstance(fmi2Component c) {
    fmu_instance *I = INST(c);
    if (!I) return;
    fmu_log(I, FMU_S_OK, FMU_LOG_CALLS, __func__);
    void (*release)(void *) = I->release;
    void *cb = I->glue;
    fmu_instance_free(I);
    release(cb);
}

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return fmi2Error;
    return fmu_set_debug_logging(I, __func__, loggingOn, nCategories, categories) ? fmi2Error
                                                                                  : fmi2OK;
}

/* ---- Initialization, termination, reset -------------------------------- */

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    fmu_instance *I = INST(c);
    (void)toleranceDefined;
    (void)tolerance; /* the law is solved to machine precision */
    if (!fmu_allowed(I, __func__, FMU_INSTANTIATED)) return fmi2Error;
    if (!isfinite(startTime) || (stopTimeDefined && !(stopTime >= startTime))) {
        FMU_ERROR(I, "%s: startTime = %g, stopTime = %g are not a valid interval", __func__,
                  startTime, stopTime);
        return fmi2Error;
    }
    fmu_msg msg;
    return status2(fmu_result(I, fmu_set_start_time(I, startTime, &msg), &msg, __func__));
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_INSTANTIATED)) return fmi2Error;
    I->phase = FMU_INIT;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_INIT)) return fmi2Error;
    fmu_msg msg;
    return status2(fmu_result(I, fmu_exit_init(I, &msg), &msg, __func__));
}

fmi2Status fmi2Terminate(fmi2Component c) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_INIT | FMU_STEP)) return fmi2Error;
    I->phase = FMU_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return fmi2Error;
    fmu_reset(I);
    return fmi2OK;
}

/* ---- Getting and setting values ----------------------------------------- */

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[]) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_READABLE) || !arrays_ok(I, __func__, nvr, vr, value))
        return fmi2Error;
    fmu_msg msg;
    return status2(
        fmu_result(I, fmu_model_get_float64(I->model, vr, nvr, value, &msg), &msg, __func__));
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[]) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_READABLE) || !arrays_ok(I, __func__, nvr, vr, value))
        return fmi2Error;
    fmu_msg msg;
    return status2(fmu_result(I,
                              fmu_model_get_int(I->model, vr, nvr, value, sizeof(fmi2Integer),
                                                FMU_INT32 | FMU_ENUM, &msg),
                              &msg, __func__));
}

static fmi2Status no_such_variables(fmu_instance *I, const char *fn, int phases, size_t nvr,
                                    const fmi2ValueReference vr[]) {
    if (!fmu_allowed(I, fn, phases)) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    FMU_ERROR(I, "%s: unknown value reference %u (this FMU has no variables of that type)", fn,
              vr ? vr[0] : 0u);
    return fmi2Error;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[]) {
    (void)value;
    return no_such_variables(INST(c), __func__, FMU_READABLE, nvr, vr);
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[]) {
    (void)value;
    return no_such_variables(INST(c), __func__, FMU_READABLE, nvr, vr);
}

#define SETTABLE (FMU_INSTANTIATED | FMU_INIT | FMU_STEP)

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[]) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, SETTABLE) || !arrays_ok(I, __func__, nvr, vr, value))
        return fmi2Error;
    fmu_msg msg;
    return status2(fmu_result(
        I, fmu_model_set_float64(I->model, vr, nvr, value, fmu_settable(I), &msg), &msg, __func__));
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[]) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, SETTABLE) || !arrays_ok(I, __func__, nvr, vr, value))
        return fmi2Error;
    fmu_msg msg;
    return status2(fmu_result(I,
                              fmu_model_set_int(I->model, vr, nvr, value, sizeof(fmi2Integer),
                                                FMU_INT32 | FMU_ENUM, fmu_settable(I), &msg),
                              &msg, __func__));
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[]) {
    (void)value;
    return no_such_variables(INST(c), __func__, SETTABLE, nvr, vr);
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[]) {
    (void)value;
    return no_such_variables(INST(c), __func__, SETTABLE, nvr, vr);
}

/* ---- FMU state ------------------------------------------------------------ */

/* The state objects and their checks are the shared instance layer's. */

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return fmi2Error;
    return status2(fmu_state_get(I, __func__, FMUstate));
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return fmi2Error;
    return status2(fmu_state_set(I, __func__, FMUstate));
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return fmi2Error;
    return status2(fmu_state_free(I, __func__, FMUstate));
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size) {
    fmu_instance *I = INST(c);
    (void)FMUstate;
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return fmi2Error;
    return status2(fmu_state_size_of(I, __func__, size));
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[],
                                 size_t size) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return fmi2Error;
    return status2(
        fmu_state_serialize(I, __func__, FMUstate, (unsigned char *)serializedState, size));
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_ALIVE)) return fmi2Error;
    return status2(
        fmu_state_deserialize(I, __func__, (const unsigned char *)serializedState, size, FMUstate));
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[]) {
    fmu_instance *I = INST(c);
    const char *fn = __func__;
    if (!fmu_allowed(I, fn, FMU_READABLE) || !arrays_ok(I, fn, nUnknown, vUnknown_ref, dvUnknown) ||
        !arrays_ok(I, fn, nKnown, vKnown_ref, dvKnown))
        return fmi2Error;
    fmu_msg msg;
    return status2(fmu_result(I,
                              fmu_model_derivative(I->model, vUnknown_ref, nUnknown, vKnown_ref,
                                                   nKnown, dvKnown, dvUnknown, 0, &msg),
                              &msg, fn));
}

/* ---- Co-Simulation ---------------------------------------------------------- */

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
    fmu_instance *I = INST(c);
    (void)vr;
    (void)order;
    (void)value;
    if (!fmu_allowed(I, __func__, FMU_INIT | FMU_STEP)) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    FMU_ERROR(I, "%s: canInterpolateInputs is false", __func__);
    return fmi2Error;
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
    fmu_instance *I = INST(c);
    (void)vr;
    (void)order;
    (void)value;
    if (!fmu_allowed(I, __func__, FMU_READABLE)) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    FMU_ERROR(I, "%s: maxOutputDerivativeOrder is 0", __func__);
    return fmi2Error;
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    fmu_instance *I = INST(c);
    (void)noSetFMUStatePriorToCurrentPoint;
    if (!fmu_allowed(I, __func__, FMU_STEP)) return fmi2Error;
    fmu_msg msg;
    return status2(fmu_result(
        I, fmu_do_step(I, currentCommunicationPoint, communicationStepSize, &msg), &msg, __func__));
}

fmi2Status fmi2CancelStep(fmi2Component c) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_STEP)) return fmi2Error;
    FMU_ERROR(I, "%s: doStep never runs asynchronously here", __func__);
    return fmi2Error;
}

/* A status kind that is not provided is fmi2Discard, not an error (FMI 2.0, 4.2.3). */
static fmi2Status discard(fmu_instance *I, const char *fn, const char *what) {
    fmu_log(I, FMU_S_DISCARD, FMU_LOG_WARNING, "%s: %s", fn, what);
    return fmi2Discard;
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value) {
    fmu_instance *I = INST(c);
    (void)s;
    (void)value;
    if (!fmu_allowed(I, __func__, FMU_STEP | FMU_TERMINATED)) return fmi2Error;
    return discard(I, __func__,
                   "no status kind of type fmi2Status is provided (doStep is synchronous)");
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_STEP | FMU_TERMINATED)) return fmi2Error;
    if (s == fmi2LastSuccessfulTime && value) {
        *value = *fmu_model_time(I->model);
        return fmi2OK;
    }
    return discard(I, __func__, "only fmi2LastSuccessfulTime is provided");
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value) {
    fmu_instance *I = INST(c);
    (void)s;
    (void)value;
    if (!fmu_allowed(I, __func__, FMU_STEP | FMU_TERMINATED)) return fmi2Error;
    return discard(I, __func__, "no Integer status is provided");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_STEP | FMU_TERMINATED)) return fmi2Error;
    if (s == fmi2Terminated && value) {
        *value = fmi2False; /* the FMU never asks to end the simulation */
        return fmi2OK;
    }
    return discard(I, __func__, "only fmi2Terminated is provided");
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value) {
    fmu_instance *I = INST(c);
    (void)s;
    (void)value;
    if (!fmu_allowed(I, __func__, FMU_STEP | FMU_TERMINATED)) return fmi2Error;
    return discard(I, __func__, "no String status is provided");
}

/* ---- Model Exchange: not supported, exported so every symbol resolves ---- */

static fmi2Status not_me(fmi2Component c, const char *fn) {
    if (c) FMU_ERROR(INST(c), "%s: this is a Co-Simulation FMU only", fn);
    return fmi2Error;
}

fmi2Status fmi2EnterEventMode(fmi2Component c) { return not_me(c, __func__); }
fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *e) {
    (void)e;
    return not_me(c, __func__);
}
fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) { return not_me(c, __func__); }
fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean noSet, fmi2Boolean *enter,
                                       fmi2Boolean *term) {
    (void)noSet;
    (void)enter;
    (void)term;
    return not_me(c, __func__);
}
fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time) {
    (void)time;
    return not_me(c, __func__);
}
fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx) {
    (void)x;
    (void)nx;
    return not_me(c, __func__);
}
fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real dx[], size_t nx) {
    (void)dx;
    (void)nx;
    return not_me(c, __func__);
}
fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real ei[], size_t ni) {
    (void)ei;
    (void)ni;
    return not_me(c, __func__);
}
fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
    (void)x;
    (void)nx;
    return not_me(c, __func__);
}
fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real n[], size_t nx) {
    (void)n;
    (void)nx;
    return not_me(c, __func__);
}
