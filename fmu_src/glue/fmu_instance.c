/*
 * One FMU instance (fmu_instance.h): its life, its log, the phase's checks
 * of the entry points, the start time, reset, the end of initialization and
 * a communication step.
 */
#include "glue/fmu_instance.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "glue/fmu_access.h"

const char *const FMU_LOG_NAMES[FMU_LOG_N] = {"logStatusError", "logStatusWarning", "logCalls"};

fmu_instance *fmu_instance_new(const char *name, void *(*alloc)(size_t, size_t),
                               void (*release)(void *), fmu_log_fn log, void *glue,
                               int logging_on) {
    fmu_instance *I = alloc(1, sizeof *I);
    if (!I) return NULL;
    memset(I, 0, sizeof *I);
    const size_t len = strlen(name) + 1;
    I->name = alloc(len, 1);
    I->model = alloc(1, fmu_model_size());
    I->start = alloc(FMU_MODEL_INFO.n_vars, sizeof *I->start);
    if (!I->name || !I->model || !I->start) {
        if (I->name) release(I->name);
        if (I->model) release(I->model);
        if (I->start) release(I->start);
        release(I);
        return NULL;
    }
    memcpy(I->name, name, len);
    I->alloc = alloc;
    I->release = release;
    I->log = log;
    I->glue = glue;
    I->log_on[FMU_LOG_ERROR] = I->log_on[FMU_LOG_WARNING] = 1;
    I->log_on[FMU_LOG_CALLS] = logging_on ? 1 : 0;
    for (unsigned int vr = 0; vr < FMU_MODEL_INFO.n_vars; ++vr)
        I->start[vr] = FMU_MODEL_INFO.vars[vr].start;
    fmu_model_init(I->model);
    I->phase = FMU_INSTANTIATED;
    return I;
}

void fmu_instance_free(fmu_instance *I) {
    if (!I) return;
    /* the standards: freeing an instance frees what its functions allocated */
    fmu_states_free(I);
    void (*release)(void *) = I->release;
    release(I->model);
    release(I->start);
    release(I->name);
    release(I);
}

void fmu_log(fmu_instance *I, int status, int category, const char *fmt, ...) {
    if (!I || !I->log || !I->log_on[category]) return;
    char text[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    I->log(I, status, FMU_LOG_NAMES[category], text);
}

static const char *phase_name(int phase) {
    switch (phase) {
    case FMU_INSTANTIATED: return "instantiated";
    case FMU_INIT: return "initialization mode";
    case FMU_STEP: return "step mode";
    case FMU_CONFIG: return "configuration mode";
    default: return "terminated";
    }
}

int fmu_allowed_slow(fmu_instance *I, const char *fn, int phases) {
    if (!I) return 0;
    if (!(I->phase & phases)) {
        FMU_ERROR(I, "%s must not be called in the current state (%s)", fn, phase_name(I->phase));
        return 0;
    }
    fmu_log(I, FMU_S_OK, FMU_LOG_CALLS, "%s", fn);
    return 1;
}

int fmu_result_error(fmu_instance *I, const fmu_msg *msg, const char *fn) {
    FMU_ERROR(I, "%s: %s", fn, msg->text);
    return FMU_S_ERROR;
}

int fmu_set_debug_logging(fmu_instance *I, const char *fn, int on, size_t n,
                          const char *const categories[]) {
    if (n > 0 && !categories) {
        FMU_ERROR(I, "%s: categories is NULL with nCategories = %zu", fn, n);
        return -1;
    }
    int next[FMU_LOG_N];
    for (int k = 0; k < FMU_LOG_N; ++k) next[k] = n == 0 ? (on ? 1 : 0) : I->log_on[k];
    for (size_t i = 0; i < n; ++i) {
        int found = -1;
        for (int k = 0; k < FMU_LOG_N; ++k)
            if (categories[i] && strcmp(categories[i], FMU_LOG_NAMES[k]) == 0) found = k;
        if (found < 0) {
            FMU_ERROR(I,
                      "%s: unknown log category \"%s\" (known: logStatusError, "
                      "logStatusWarning, logCalls)",
                      fn, categories[i] ? categories[i] : "(null)");
            return -1;
        }
        next[found] = on ? 1 : 0;
    }
    memcpy(I->log_on, next, sizeof next);
    return 0;
}

fmu_status fmu_set_start_time(fmu_instance *I, double t, fmu_msg *msg) {
    double *time = fmu_model_time(I->model);
    const double before = *time;
    *time = t;
    if (model_refresh(I->model, msg) != FMU_OK) {
        *time = before;
        return FMU_ERR;
    }
    return FMU_OK;
}

void fmu_reset(fmu_instance *I) {
    fmu_msg msg;
    /* The start values were accepted at instantiation: they are again. */
    (void)fmu_model_init_from(I->model, I->start, &msg);
    I->phase = FMU_INSTANTIATED;
}

fmu_status fmu_exit_init(fmu_instance *I, fmu_msg *msg) {
    /* exit_init changes no time, parameter or input: refresh's outputs stand. */
    if (INFO.exit_init && INFO.exit_init(I->model, msg) != FMU_OK) return FMU_ERR;
    I->phase = FMU_STEP;
    return FMU_OK;
}

OC_HOT fmu_status fmu_do_step(fmu_instance *I, double t, double h, fmu_msg *msg) {
    double *time = fmu_model_time(I->model);
    if (!isfinite(t) || !isfinite(h) || !(h > 0) || !isfinite(t + h))
        return fmu_fail(msg,
                        "currentCommunicationPoint=%g, communicationStepSize=%g: the step "
                        "size must be > 0 and the time must stay finite",
                        t, h);
    /* Masters that count time as t0 + k h differ from a sum of steps by
     * rounding only; anything beyond that is a master error. */
    const double at = fabs(*time); /* finite: no NaN for fmax, which would be a libm call */
    if (fabs(t - *time) > 1e-9 * (at > h ? at : h))
        return fmu_fail(msg, "currentCommunicationPoint=%.17g but the FMU is at time %.17g", t,
                        *time);
    /* The time moves first: the outputs at the step's end are checked (and
     * the model steps) there, and the time goes back if either refuses. */
    const double before = *time;
    *time = t + h;
    if (model_refresh(I->model, msg) != FMU_OK) {
        *time = before;
        return FMU_ERR;
    }
    if (fmu_model_do_step(I->model, h, msg) != FMU_OK) {
        *time = before;
        (void)model_refresh(I->model, NULL); /* the outputs it had, accepted before */
        return FMU_ERR;
    }
    return FMU_OK;
}
