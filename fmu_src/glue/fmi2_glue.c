/*
 * FMI 2.0 Co-Simulation: the standard's signatures translated onto the shared,
 * version-independent instance (fmu_instance.h) and the model (fmu_model.h).
 * No mechanics and no model variables live here.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "glue/fmu_instance.h"

#define INST(c) ((fmu_instance *)(c))

/* What FMI 3.0 defines alike (glue/fmi_both.inc) */
#define FMI_PREFIX fmi2
#define FMI_INSTANCE fmi2Component
#define FMI_STATE state
#define FMI_DESERIALIZE DeSerialize
#define FMI_CONFIG 0
#include "glue/fmi_both.inc"

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

static int arrays_refused(fmu_instance *I, const char *fn, size_t n) {
    FMU_ERROR(I, "%s: NULL array with n = %zu", fn, n);
    return 0;
}

/* The test inline, the message out of line. */
static inline int arrays_ok(fmu_instance *I, const char *fn, size_t n, const void *a,
                            const void *b) {
    return n == 0 || (a && b) ? 1 : arrays_refused(I, fn, n);
}

#define SETTABLE (FMU_INSTANTIATED | FMU_INIT | FMU_STEP)

/* A get's or a set's checks: the phases it is allowed in, its arrays. */
static inline int may_access(fmu_instance *I, const char *fn, int phases, size_t n, const void *vr,
                             const void *value) {
    return fmu_allowed(I, fn, phases) && arrays_ok(I, fn, n, vr, value);
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
    return with_start_values(I, __func__, fmuResourceLocation, 1);
}

/* ---- Initialization, termination, reset -------------------------------- */

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    fmu_instance *I = INST(c);
    (void)toleranceDefined;
    (void)tolerance; /* the law is solved to machine precision */
    if (!fmu_allowed(I, __func__, FMU_INSTANTIATED)) return fmi2Error;
    return status_of(start_at(I, __func__, startTime, stopTimeDefined, stopTime));
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_INSTANTIATED)) return fmi2Error;
    I->phase = FMU_INIT;
    return fmi2OK;
}

/* ---- Getting and setting values ----------------------------------------- */

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[]) {
    fmu_instance *I = INST(c);
    if (!may_access(I, __func__, FMU_READABLE, nvr, vr, value)) return fmi2Error;
    fmu_msg msg;
    return status_of(
        fmu_result(I, fmu_model_get_float64(I->model, vr, nvr, value, &msg), &msg, __func__));
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[]) {
    fmu_instance *I = INST(c);
    if (!may_access(I, __func__, FMU_READABLE, nvr, vr, value)) return fmi2Error;
    fmu_msg msg;
    return status_of(fmu_result(I,
                                fmu_model_get_int(I->model, vr, nvr, value, sizeof(fmi2Integer),
                                                  FMU_INT32 | FMU_ENUM, &msg),
                                &msg, __func__));
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[]) {
    fmu_instance *I = INST(c);
    if (!may_access(I, __func__, SETTABLE, nvr, vr, value)) return fmi2Error;
    fmu_msg msg;
    return status_of(fmu_result(
        I, fmu_model_set_float64(I->model, vr, nvr, value, fmu_settable(I), &msg), &msg, __func__));
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[]) {
    fmu_instance *I = INST(c);
    if (!may_access(I, __func__, SETTABLE, nvr, vr, value)) return fmi2Error;
    fmu_msg msg;
    return status_of(fmu_result(I,
                                fmu_model_set_int(I->model, vr, nvr, value, sizeof(fmi2Integer),
                                                  FMU_INT32 | FMU_ENUM, fmu_settable(I), &msg),
                                &msg, __func__));
}

/* Types of which this FMU has no variables (glue/fmi_both.inc), one a row. */
#define NO_VARIABLES(TYPE)                                                                         \
    fmi2Status fmi2Get##TYPE(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,           \
                             fmi2##TYPE value[]) {                                                 \
        (void)value;                                                                               \
        return no_such_variables(INST(c), __func__, FMU_READABLE, nvr, vr);                        \
    }                                                                                              \
    fmi2Status fmi2Set##TYPE(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,           \
                             const fmi2##TYPE value[]) {                                           \
        (void)value;                                                                               \
        return no_such_variables(INST(c), __func__, SETTABLE, nvr, vr);                            \
    }
NO_VARIABLES(Boolean)
NO_VARIABLES(String)

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
    return status_of(fmu_result(I,
                                fmu_model_derivative(I->model, vUnknown_ref, nUnknown, vKnown_ref,
                                                     nKnown, dvKnown, dvUnknown, 0, &msg),
                                &msg, fn));
}

/* ---- Co-Simulation ---------------------------------------------------------- */

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
    (void)vr;
    (void)order;
    (void)value;
    return refuse_unless_empty(c, __func__, FMU_INIT | FMU_STEP, nvr,
                               "canInterpolateInputs is false");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
    (void)vr;
    (void)order;
    (void)value;
    return refuse_unless_empty(c, __func__, FMU_READABLE, nvr, "maxOutputDerivativeOrder is 0");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    fmu_instance *I = INST(c);
    (void)noSetFMUStatePriorToCurrentPoint;
    if (!fmu_allowed(I, __func__, FMU_STEP)) return fmi2Error;
    fmu_msg msg;
    return status_of(fmu_result(
        I, fmu_do_step(I, currentCommunicationPoint, communicationStepSize, &msg), &msg, __func__));
}

fmi2Status fmi2CancelStep(fmi2Component c) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, __func__, FMU_STEP)) return fmi2Error;
    FMU_ERROR(I, "%s: doStep never runs asynchronously here", __func__);
    return fmi2Error;
}

/* A status kind of fmi2Get*Status: OK if `provided` (the caller writes its
 * value), else fmi2Discard, not an error (FMI 2.0, 4.2.3). */
static fmi2Status status_kind(fmi2Component c, const char *fn, int provided, const char *what) {
    fmu_instance *I = INST(c);
    if (!fmu_allowed(I, fn, FMU_STEP | FMU_TERMINATED)) return fmi2Error;
    if (provided) return fmi2OK;
    fmu_log(I, FMU_S_DISCARD, FMU_LOG_WARNING, "%s: %s", fn, what);
    return fmi2Discard;
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value) {
    (void)s;
    (void)value;
    return status_kind(c, __func__, 0,
                       "no status kind of type fmi2Status is provided (doStep is synchronous)");
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value) {
    const fmi2Status st = status_kind(c, __func__, s == fmi2LastSuccessfulTime && value,
                                      "only fmi2LastSuccessfulTime is provided");
    if (st == fmi2OK) *value = *fmu_model_time(INST(c)->model);
    return st;
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value) {
    const fmi2Status st =
        status_kind(c, __func__, s == fmi2Terminated && value, "only fmi2Terminated is provided");
    if (st == fmi2OK) *value = fmi2False; /* the FMU never asks to end the simulation */
    return st;
}

/* The kinds of which none is provided, one a row. */
#define NO_STATUS(TYPE)                                                                            \
    fmi2Status fmi2Get##TYPE##Status(fmi2Component c, const fmi2StatusKind s, fmi2##TYPE *value) { \
        (void)s;                                                                                   \
        (void)value;                                                                               \
        return status_kind(c, __func__, 0, "no " #TYPE " status is provided");                     \
    }
NO_STATUS(Integer)
NO_STATUS(String)

/* ---- Model Exchange: the functions glue/fmi_both.inc does not define ---- */

fmi2Status fmi2EnterEventMode(fmi2Component c) { return unsupported(c, __func__, NO_ME); }
fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *e) {
    (void)e;
    return unsupported(c, __func__, NO_ME);
}
FMI_NO_ME_ARRAY(GetDerivatives, double)
