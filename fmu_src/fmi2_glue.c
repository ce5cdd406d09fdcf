/*
 * FMI 2.0 Co-Simulation glue over oc_model: the FMI state machine, callbacks,
 * logging categories and status codes.  No contact mechanics lives here.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "model_variables.h"
#include "oc_model.h"

typedef enum {
    M_INSTANTIATED = 1 << 0,
    M_INIT = 1 << 1,
    M_STEP = 1 << 2,
    M_TERMINATED = 1 << 3
} mode_t_;

#define M_ALIVE (M_INSTANTIATED | M_INIT | M_STEP | M_TERMINATED)
#define M_READABLE (M_INIT | M_STEP | M_TERMINATED)

enum { LOG_ERROR = 0, LOG_WARNING = 1, LOG_CALLS = 2, LOG_N = 3 };
static const char *const LOG_NAMES[LOG_N] = {"logStatusError", "logStatusWarning", "logCalls"};

typedef struct {
    oc_model model;
    fmi2CallbackFunctions cb;
    char *name;
    mode_t_ mode;
    int log_on[LOG_N];
} Instance;

/* The logger formats its message printf-style: a literal '%' must be doubled. */
static void emit(Instance *I, fmi2Status status, int cat, const char *fmt, ...) {
    if (!I || !I->cb.logger || !I->log_on[cat]) return;
    char raw[512], esc[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(raw, sizeof raw, fmt, ap);
    va_end(ap);
    size_t j = 0;
    for (size_t i = 0; raw[i] && j + 2 < sizeof esc; ++i) {
        if (raw[i] == '%') esc[j++] = '%';
        esc[j++] = raw[i];
    }
    esc[j] = '\0';
    I->cb.logger(I->cb.componentEnvironment, I->name, status, LOG_NAMES[cat], esc);
}

#define LOG_ERR(I, ...) emit((I), fmi2Error, LOG_ERROR, __VA_ARGS__)
/* A status that is not available is fmi2Discard, not an error (FMI 2.0, 4.2.3). */
#define DISCARD(I, ...) emit((I), fmi2Discard, LOG_WARNING, __VA_ARGS__)

/* Every entry point starts here: a NULL instance or a call in the wrong
 * state is an error that changes nothing. */
static int allowed(Instance *I, const char *fn, int mask) {
    if (!I) return 0;
    if (!(I->mode & mask)) {
        LOG_ERR(I, "%s must not be called in the current state (%s)", fn,
                I->mode == M_INSTANTIATED ? "instantiated"
                : I->mode == M_INIT       ? "initialization mode"
                : I->mode == M_STEP       ? "step mode"
                                          : "terminated");
        return 0;
    }
    emit(I, fmi2OK, LOG_CALLS, "%s", fn);
    return 1;
}

static fmi2Status from_model(Instance *I, oc_status st, const oc_msg *msg, const char *fn) {
    if (st == OC_OK) return fmi2OK;
    LOG_ERR(I, "%s: %s", fn, msg->text);
    return fmi2Error;
}

static int settable(const Instance *I) {
    int allow = 0;
    if (I->mode & (M_INSTANTIATED | M_INIT)) allow |= OC_ALLOW_PARAMETERS;
    if (I->mode & (M_INSTANTIATED | M_INIT | M_STEP)) allow |= OC_ALLOW_INPUTS;
    return allow;
}

static int arrays_ok(Instance *I, const char *fn, size_t n, const void *vr, const void *value) {
    if (n > 0 && (!vr || !value)) {
        LOG_ERR(I, "%s: NULL array with nvr = %zu", fn, n);
        return 0;
    }
    return 1;
}

/* ---- Inquiry, instantiation, logging ---------------------------------- */

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn) {
    (void)fmuResourceLocation;
    (void)visible;
    if (!functions) return NULL;
    const char *name = instanceName ? instanceName : "";
#define EARLY_ERR(msg)                                                                       \
    do {                                                                                     \
        if (functions->logger)                                                               \
            functions->logger(functions->componentEnvironment, name, fmi2Error,             \
                              "logStatusError", msg);                                        \
        return NULL;                                                                         \
    } while (0)
    if (!instanceName || !*instanceName) EARLY_ERR("fmi2Instantiate: instanceName is empty");
    if (fmuType != fmi2CoSimulation)
        EARLY_ERR("fmi2Instantiate: OrthotropicContact supports Co-Simulation only");
    if (!fmuGUID || strcmp(fmuGUID, OC_GUID) != 0)
        EARLY_ERR("fmi2Instantiate: GUID does not match this FMU's modelDescription.xml");
    Instance *I = functions->allocateMemory ? functions->allocateMemory(1, sizeof *I)
                                            : calloc(1, sizeof *I);
    if (!I) EARLY_ERR("fmi2Instantiate: out of memory");
    memset(I, 0, sizeof *I);
    size_t len = strlen(instanceName) + 1;
    I->name = functions->allocateMemory ? functions->allocateMemory(len, 1) : calloc(len, 1);
    if (!I->name) {
        if (functions->freeMemory) functions->freeMemory(I); else free(I);
        EARLY_ERR("fmi2Instantiate: out of memory");
    }
#undef EARLY_ERR
    memcpy(I->name, instanceName, len);
    I->cb = *functions;
    /* Errors and warnings are reported unless switched off explicitly with
     * fmi2SetDebugLogging; loggingOn adds the call trace. */
    I->log_on[LOG_ERROR] = I->log_on[LOG_WARNING] = 1;
    I->log_on[LOG_CALLS] = loggingOn ? 1 : 0;
    oc_model_init(&I->model);
    I->mode = M_INSTANTIATED;
    emit(I, fmi2OK, LOG_CALLS, "fmi2Instantiate");
    return I;
}

void fmi2FreeInstance(fmi2Component c) {
    Instance *I = c;
    if (!I) return;
    emit(I, fmi2OK, LOG_CALLS, "fmi2FreeInstance");
    fmi2CallbackFreeMemory fm = I->cb.freeMemory;
    if (fm) {
        fm(I->name);
        fm(I);
    } else {
        free(I->name);
        free(I);
    }
}

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
    Instance *I = c;
    if (!allowed(I, "fmi2SetDebugLogging", M_ALIVE)) return fmi2Error;
    if (nCategories > 0 && !categories) {
        LOG_ERR(I, "fmi2SetDebugLogging: categories is NULL with nCategories = %zu", nCategories);
        return fmi2Error;
    }
    int next[LOG_N];
    for (int k = 0; k < LOG_N; ++k) next[k] = nCategories == 0 ? (loggingOn ? 1 : 0) : I->log_on[k];
    for (size_t i = 0; i < nCategories; ++i) {
        int found = -1;
        for (int k = 0; k < LOG_N; ++k)
            if (categories[i] && strcmp(categories[i], LOG_NAMES[k]) == 0) found = k;
        if (found < 0) {
            LOG_ERR(I, "fmi2SetDebugLogging: unknown log category \"%s\" (known: logStatusError, "
                       "logStatusWarning, logCalls)", categories[i] ? categories[i] : "(null)");
            return fmi2Error;
        }
        next[found] = loggingOn ? 1 : 0;
    }
    memcpy(I->log_on, next, sizeof next);
    return fmi2OK;
}

/* ---- Initialization, termination, reset -------------------------------- */

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined,
                               fmi2Real stopTime) {
    Instance *I = c;
    (void)toleranceDefined;
    (void)tolerance; /* the law is solved to machine precision */
    if (!allowed(I, "fmi2SetupExperiment", M_INSTANTIATED)) return fmi2Error;
    if (!isfinite(startTime) || (stopTimeDefined && !(stopTime >= startTime))) {
        LOG_ERR(I, "fmi2SetupExperiment: startTime = %g, stopTime = %g are not a valid interval",
                startTime, stopTime);
        return fmi2Error;
    }
    I->model.time = startTime;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    Instance *I = c;
    if (!allowed(I, "fmi2EnterInitializationMode", M_INSTANTIATED)) return fmi2Error;
    I->mode = M_INIT;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    Instance *I = c;
    if (!allowed(I, "fmi2ExitInitializationMode", M_INIT)) return fmi2Error;
    I->mode = M_STEP;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c) {
    Instance *I = c;
    if (!allowed(I, "fmi2Terminate", M_INIT | M_STEP)) return fmi2Error;
    I->mode = M_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c) {
    Instance *I = c;
    if (!allowed(I, "fmi2Reset", M_ALIVE)) return fmi2Error;
    oc_model_init(&I->model);
    I->mode = M_INSTANTIATED;
    return fmi2OK;
}

/* ---- Getting and setting values ----------------------------------------- */

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[]) {
    Instance *I = c;
    if (!allowed(I, "fmi2GetReal", M_READABLE) || !arrays_ok(I, "fmi2GetReal", nvr, vr, value))
        return fmi2Error;
    oc_msg msg;
    return from_model(I, oc_model_get_real(&I->model, vr, nvr, value, &msg), &msg, "fmi2GetReal");
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[]) {
    Instance *I = c;
    if (!allowed(I, "fmi2GetInteger", M_READABLE) ||
        !arrays_ok(I, "fmi2GetInteger", nvr, vr, value))
        return fmi2Error;
    oc_msg msg;
    return from_model(I, oc_model_get_integer(&I->model, vr, nvr, value, &msg), &msg,
                      "fmi2GetInteger");
}

static fmi2Status no_such_variables(Instance *I, const char *fn, int mask, size_t nvr,
                                    const fmi2ValueReference vr[]) {
    if (!allowed(I, fn, mask)) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    LOG_ERR(I, "%s: unknown value reference %u (this FMU has no variables of that type)", fn,
            vr ? vr[0] : 0u);
    return fmi2Error;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[]) {
    (void)value;
    return no_such_variables(c, "fmi2GetBoolean", M_READABLE, nvr, vr);
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[]) {
    (void)value;
    return no_such_variables(c, "fmi2GetString", M_READABLE, nvr, vr);
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[]) {
    Instance *I = c;
    if (!allowed(I, "fmi2SetReal", M_INSTANTIATED | M_INIT | M_STEP) ||
        !arrays_ok(I, "fmi2SetReal", nvr, vr, value))
        return fmi2Error;
    oc_msg msg;
    return from_model(I, oc_model_set_real(&I->model, vr, nvr, value, settable(I), &msg), &msg,
                      "fmi2SetReal");
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[]) {
    Instance *I = c;
    if (!allowed(I, "fmi2SetInteger", M_INSTANTIATED | M_INIT | M_STEP) ||
        !arrays_ok(I, "fmi2SetInteger", nvr, vr, value))
        return fmi2Error;
    oc_msg msg;
    return from_model(I, oc_model_set_integer(&I->model, vr, nvr, value, settable(I), &msg), &msg,
                      "fmi2SetInteger");
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[]) {
    (void)value;
    return no_such_variables(c, "fmi2SetBoolean", M_INSTANTIATED | M_INIT | M_STEP, nvr, vr);
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[]) {
    (void)value;
    return no_such_variables(c, "fmi2SetString", M_INSTANTIATED | M_INIT | M_STEP, nvr, vr);
}

/* ---- FMU state ------------------------------------------------------------ */

/* An fmi2FMUstate is a buffer holding the model's pointer-free image. */

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate) {
    Instance *I = c;
    if (!allowed(I, "fmi2GetFMUstate", M_ALIVE)) return fmi2Error;
    if (!FMUstate) {
        LOG_ERR(I, "fmi2GetFMUstate: FMUstate is NULL");
        return fmi2Error;
    }
    unsigned char *buf = *FMUstate;
    if (!buf) {
        buf = I->cb.allocateMemory ? I->cb.allocateMemory(1, oc_model_image_size())
                                   : calloc(1, oc_model_image_size());
        if (!buf) {
            LOG_ERR(I, "fmi2GetFMUstate: out of memory");
            return fmi2Error;
        }
    }
    oc_model_write_image(&I->model, buf);
    *FMUstate = buf;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
    Instance *I = c;
    if (!allowed(I, "fmi2SetFMUstate", M_ALIVE)) return fmi2Error;
    oc_msg msg;
    return from_model(I, oc_model_read_image(&I->model, FMUstate, oc_model_image_size(), &msg),
                      &msg, "fmi2SetFMUstate");
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate) {
    Instance *I = c;
    if (!allowed(I, "fmi2FreeFMUstate", M_ALIVE)) return fmi2Error;
    if (FMUstate && *FMUstate) {
        if (I->cb.freeMemory) I->cb.freeMemory(*FMUstate); else free(*FMUstate);
        *FMUstate = NULL;
    }
    return fmi2OK;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size) {
    Instance *I = c;
    (void)FMUstate;
    if (!allowed(I, "fmi2SerializedFMUstateSize", M_ALIVE)) return fmi2Error;
    if (!size) {
        LOG_ERR(I, "fmi2SerializedFMUstateSize: size is NULL");
        return fmi2Error;
    }
    *size = oc_model_image_size();
    return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[],
                                 size_t size) {
    Instance *I = c;
    if (!allowed(I, "fmi2SerializeFMUstate", M_ALIVE)) return fmi2Error;
    if (!FMUstate || !serializedState || size < oc_model_image_size()) {
        LOG_ERR(I, "fmi2SerializeFMUstate: needs a state and a buffer of %zu bytes (got %zu)",
                oc_model_image_size(), size);
        return fmi2Error;
    }
    memcpy(serializedState, FMUstate, oc_model_image_size());
    return fmi2OK;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate) {
    Instance *I = c;
    if (!allowed(I, "fmi2DeSerializeFMUstate", M_ALIVE)) return fmi2Error;
    if (!FMUstate) {
        LOG_ERR(I, "fmi2DeSerializeFMUstate: FMUstate is NULL");
        return fmi2Error;
    }
    /* Validate by reading into a scratch model: a bad image is refused
     * before any state buffer is touched. */
    oc_model scratch;
    oc_msg msg;
    if (oc_model_read_image(&scratch, (const unsigned char *)serializedState, size, &msg) != OC_OK)
        return from_model(I, OC_ERR, &msg, "fmi2DeSerializeFMUstate");
    unsigned char *buf = *FMUstate;
    if (!buf) {
        buf = I->cb.allocateMemory ? I->cb.allocateMemory(1, size) : calloc(1, size);
        if (!buf) {
            LOG_ERR(I, "fmi2DeSerializeFMUstate: out of memory");
            return fmi2Error;
        }
    }
    memcpy(buf, serializedState, size);
    *FMUstate = buf;
    return fmi2OK;
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[]) {
    Instance *I = c;
    if (!allowed(I, "fmi2GetDirectionalDerivative", M_READABLE) ||
        !arrays_ok(I, "fmi2GetDirectionalDerivative", nUnknown, vUnknown_ref, dvUnknown) ||
        !arrays_ok(I, "fmi2GetDirectionalDerivative", nKnown, vKnown_ref, dvKnown))
        return fmi2Error;
    oc_msg msg;
    return from_model(I,
                      oc_model_directional_derivative(&I->model, vUnknown_ref, nUnknown,
                                                      vKnown_ref, nKnown, dvKnown, dvUnknown, &msg),
                      &msg, "fmi2GetDirectionalDerivative");
}

/* ---- Co-Simulation ---------------------------------------------------------- */

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
    Instance *I = c;
    (void)vr; (void)order; (void)value;
    if (!allowed(I, "fmi2SetRealInputDerivatives", M_INIT | M_STEP)) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    LOG_ERR(I, "fmi2SetRealInputDerivatives: canInterpolateInputs is false");
    return fmi2Error;
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
    Instance *I = c;
    (void)vr; (void)order; (void)value;
    if (!allowed(I, "fmi2GetRealOutputDerivatives", M_READABLE)) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    LOG_ERR(I, "fmi2GetRealOutputDerivatives: maxOutputDerivativeOrder is 0");
    return fmi2Error;
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    Instance *I = c;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (!allowed(I, "fmi2DoStep", M_STEP)) return fmi2Error;
    oc_msg msg;
    return from_model(I,
                      oc_model_do_step(&I->model, currentCommunicationPoint, communicationStepSize,
                                       &msg),
                      &msg, "fmi2DoStep");
}

fmi2Status fmi2CancelStep(fmi2Component c) {
    Instance *I = c;
    if (!allowed(I, "fmi2CancelStep", M_STEP)) return fmi2Error;
    LOG_ERR(I, "fmi2CancelStep: doStep never runs asynchronously here");
    return fmi2Error;
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value) {
    Instance *I = c;
    (void)s; (void)value;
    if (!allowed(I, "fmi2GetStatus", M_STEP | M_TERMINATED)) return fmi2Error;
    DISCARD(I, "fmi2GetStatus: no status kind of type fmi2Status is provided (doStep is synchronous)");
    return fmi2Discard;
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value) {
    Instance *I = c;
    if (!allowed(I, "fmi2GetRealStatus", M_STEP | M_TERMINATED)) return fmi2Error;
    if (s == fmi2LastSuccessfulTime && value) {
        *value = I->model.time;
        return fmi2OK;
    }
    DISCARD(I, "fmi2GetRealStatus: only fmi2LastSuccessfulTime is provided");
    return fmi2Discard;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value) {
    Instance *I = c;
    (void)s; (void)value;
    if (!allowed(I, "fmi2GetIntegerStatus", M_STEP | M_TERMINATED)) return fmi2Error;
    DISCARD(I, "fmi2GetIntegerStatus: no Integer status is provided");
    return fmi2Discard;
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value) {
    Instance *I = c;
    if (!allowed(I, "fmi2GetBooleanStatus", M_STEP | M_TERMINATED)) return fmi2Error;
    if (s == fmi2Terminated && value) {
        *value = fmi2False; /* the contact never asks to end the simulation */
        return fmi2OK;
    }
    DISCARD(I, "fmi2GetBooleanStatus: only fmi2Terminated is provided");
    return fmi2Discard;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value) {
    Instance *I = c;
    (void)s; (void)value;
    if (!allowed(I, "fmi2GetStringStatus", M_STEP | M_TERMINATED)) return fmi2Error;
    DISCARD(I, "fmi2GetStringStatus: no String status is provided");
    return fmi2Discard;
}

/* ---- Model Exchange: not supported, exported so every symbol resolves ---- */

static fmi2Status not_me(fmi2Component c, const char *fn) {
    Instance *I = c;
    if (I) LOG_ERR(I, "%s: OrthotropicContact is a Co-Simulation FMU only", fn);
    return fmi2Error;
}

fmi2Status fmi2EnterEventMode(fmi2Component c) { return not_me(c, "fmi2EnterEventMode"); }
fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *e) {
    (void)e;
    return not_me(c, "fmi2NewDiscreteStates");
}
fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) {
    return not_me(c, "fmi2EnterContinuousTimeMode");
}
fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean noSet, fmi2Boolean *enter,
                                       fmi2Boolean *term) {
    (void)noSet; (void)enter; (void)term;
    return not_me(c, "fmi2CompletedIntegratorStep");
}
fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time) {
    (void)time;
    return not_me(c, "fmi2SetTime");
}
fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx) {
    (void)x; (void)nx;
    return not_me(c, "fmi2SetContinuousStates");
}
fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real dx[], size_t nx) {
    (void)dx; (void)nx;
    return not_me(c, "fmi2GetDerivatives");
}
fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real ei[], size_t ni) {
    (void)ei; (void)ni;
    return not_me(c, "fmi2GetEventIndicators");
}
fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
    (void)x; (void)nx;
    return not_me(c, "fmi2GetContinuousStates");
}
fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real n[], size_t nx) {
    (void)n; (void)nx;
    return not_me(c, "fmi2GetNominalsOfContinuousStates");
}
