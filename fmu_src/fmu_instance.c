#include "fmu_instance.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "fmu_bytes.h"

const char *const FMU_LOG_NAMES[FMU_LOG_N] = {"logStatusError", "logStatusWarning", "logCalls"};

fmu_status fmu_fail(fmu_msg *msg, const char *fmt, ...) {
    if (msg) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg->text, sizeof msg->text, fmt, ap);
        va_end(ap);
    }
    return FMU_ERR;
}

fmu_instance *fmu_instance_new(const char *name, void *(*alloc)(size_t, size_t),
                               void (*release)(void *), fmu_log_fn log, void *glue,
                               int logging_on) {
    fmu_instance *I = alloc(1, sizeof *I);
    if (!I) return NULL;
    memset(I, 0, sizeof *I);
    const size_t len = strlen(name) + 1;
    I->name = alloc(len, 1);
    I->model = alloc(1, fmu_model_size());
    if (!I->name || !I->model) {
        if (I->name) release(I->name);
        if (I->model) release(I->model);
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
    fmu_model_init(I->model);
    I->phase = FMU_INSTANTIATED;
    return I;
}

void fmu_instance_free(fmu_instance *I) {
    if (!I) return;
    void (*release)(void *) = I->release;
    release(I->model);
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
    default: return "terminated";
    }
}

int fmu_allowed(fmu_instance *I, const char *fn, int phases) {
    if (!I) return 0;
    if (!(I->phase & phases)) {
        FMU_ERROR(I, "%s must not be called in the current state (%s)", fn, phase_name(I->phase));
        return 0;
    }
    fmu_log(I, FMU_S_OK, FMU_LOG_CALLS, "%s", fn);
    return 1;
}

int fmu_settable(const fmu_instance *I) {
    int allow = 0;
    if (I->phase & (FMU_INSTANTIATED | FMU_INIT)) allow |= FMU_ALLOW_PARAMETERS;
    if (I->phase & (FMU_INSTANTIATED | FMU_INIT | FMU_STEP)) allow |= FMU_ALLOW_INPUTS;
    return allow;
}

int fmu_result(fmu_instance *I, fmu_status st, const fmu_msg *msg, const char *fn) {
    if (st == FMU_OK) return FMU_S_OK;
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
            FMU_ERROR(I, "%s: unknown log category \"%s\" (known: logStatusError, "
                         "logStatusWarning, logCalls)", fn, categories[i] ? categories[i] : "(null)");
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
    if (fmu_model_check(I->model, msg) != FMU_OK) {
        *time = before;
        return FMU_ERR;
    }
    return FMU_OK;
}

fmu_status fmu_do_step(fmu_instance *I, double t, double h, fmu_msg *msg) {
    double *time = fmu_model_time(I->model);
    if (!isfinite(t) || !isfinite(h) || !(h > 0) || !isfinite(t + h))
        return fmu_fail(msg, "currentCommunicationPoint=%g, communicationStepSize=%g: the step "
                             "size must be > 0 and the time must stay finite", t, h);
    /* Masters that count time as t0 + k h differ from a sum of steps by
     * rounding only; anything beyond that is a master error. */
    if (fabs(t - *time) > 1e-9 * fmax(fabs(*time), h))
        return fmu_fail(msg, "currentCommunicationPoint=%.17g but the FMU is at time %.17g", t,
                        *time);
    const double before = *time;
    *time = t + h;
    if (fmu_model_do_step(I->model, h, msg) != FMU_OK) {
        *time = before;
        return FMU_ERR;
    }
    return FMU_OK;
}

/* Layout: tag[4], format u32, total length u32, phase u32, time f64, model. */
enum { STATE_FORMAT = 2, STATE_HEADER = 4 + 4 + 4 + 4 + 8 };

size_t fmu_state_size(void) { return STATE_HEADER + fmu_model_state_size(); }

void fmu_state_write(const fmu_instance *I, unsigned char *buf) {
    unsigned char *p = buf;
    memcpy(p, FMU_MODEL_INFO.tag, 4);
    p = fmu_put_u32(p + 4, STATE_FORMAT);
    p = fmu_put_u32(p, (uint32_t)fmu_state_size());
    p = fmu_put_u32(p, (uint32_t)I->phase);
    p = fmu_put_f64(p, *fmu_model_time(I->model));
    fmu_model_state_write(I->model, p);
}

fmu_status fmu_state_read(fmu_instance *I, const unsigned char *buf, size_t size, fmu_msg *msg) {
    if (!buf) return fmu_fail(msg, "the state is NULL");
    if (size != fmu_state_size())
        return fmu_fail(msg, "a serialized %s state has %zu bytes, got %zu",
                        FMU_MODEL_INFO.model_identifier, fmu_state_size(), size);
    uint32_t format, length, phase;
    double time;
    const unsigned char *p = buf;
    if (memcmp(p, FMU_MODEL_INFO.tag, 4) != 0)
        return fmu_fail(msg, "not a serialized %s state (wrong tag)", FMU_MODEL_INFO.model_identifier);
    p = fmu_get_u32(p + 4, &format);
    p = fmu_get_u32(p, &length);
    p = fmu_get_u32(p, &phase);
    p = fmu_get_f64(p, &time);
    if (format != STATE_FORMAT)
        return fmu_fail(msg, "serialized state of format %u, this FMU reads format %d",
                        (unsigned)format, STATE_FORMAT);
    if (length != fmu_state_size())
        return fmu_fail(msg, "serialized state says it has %u bytes, expected %zu",
                        (unsigned)length, fmu_state_size());
    if (phase != FMU_INSTANTIATED && phase != FMU_INIT && phase != FMU_STEP &&
        phase != FMU_TERMINATED)
        return fmu_fail(msg, "serialized state holds an unknown phase %u", (unsigned)phase);
    if (!isfinite(time)) return fmu_fail(msg, "serialized state holds a non-finite time");
    double *model_time = fmu_model_time(I->model);
    const double before = *model_time;
    *model_time = time;
    if (fmu_model_state_read(I->model, p, msg) != FMU_OK) {
        *model_time = before;
        return FMU_ERR;
    }
    I->phase = (int)phase;
    return FMU_OK;
}

int fmu_state_get(fmu_instance *I, const char *fn, void **state) {
    if (!state) {
        FMU_ERROR(I, "%s: the state pointer is NULL", fn);
        return FMU_S_ERROR;
    }
    unsigned char *buf = *state;
    if (!buf && !(buf = I->alloc(1, fmu_state_size()))) {
        FMU_ERROR(I, "%s: out of memory", fn);
        return FMU_S_ERROR;
    }
    fmu_state_write(I, buf);
    *state = buf;
    return FMU_S_OK;
}

int fmu_state_set(fmu_instance *I, const char *fn, const void *state) {
    fmu_msg msg;
    return fmu_result(I, fmu_state_read(I, state, fmu_state_size(), &msg), &msg, fn);
}

int fmu_state_free(fmu_instance *I, void **state) {
    if (state && *state) {
        I->release(*state);
        *state = NULL;
    }
    return FMU_S_OK;
}

int fmu_state_size_of(fmu_instance *I, const char *fn, size_t *size) {
    if (!size) {
        FMU_ERROR(I, "%s: size is NULL", fn);
        return FMU_S_ERROR;
    }
    *size = fmu_state_size();
    return FMU_S_OK;
}

int fmu_state_serialize(fmu_instance *I, const char *fn, const void *state, unsigned char *bytes,
                        size_t size) {
    if (!state || !bytes || size < fmu_state_size()) {
        FMU_ERROR(I, "%s: needs a state and a buffer of %zu bytes (got %zu)", fn, fmu_state_size(),
                  size);
        return FMU_S_ERROR;
    }
    memcpy(bytes, state, fmu_state_size());
    return FMU_S_OK;
}

int fmu_state_deserialize(fmu_instance *I, const char *fn, const unsigned char *bytes, size_t size,
                          void **state) {
    if (!state) {
        FMU_ERROR(I, "%s: the state pointer is NULL", fn);
        return FMU_S_ERROR;
    }
    /* Validate on a scratch instance: bad bytes are refused before any state
     * buffer is touched. */
    fmu_instance scratch = *I;
    scratch.model = I->alloc(1, fmu_model_size());
    if (!scratch.model) {
        FMU_ERROR(I, "%s: out of memory", fn);
        return FMU_S_ERROR;
    }
    fmu_model_init(scratch.model);
    fmu_msg msg;
    const fmu_status st = fmu_state_read(&scratch, bytes, size, &msg);
    I->release(scratch.model);
    if (st != FMU_OK) return fmu_result(I, st, &msg, fn);
    unsigned char *buf = *state;
    if (!buf && !(buf = I->alloc(1, size))) {
        FMU_ERROR(I, "%s: out of memory", fn);
        return FMU_S_ERROR;
    }
    memcpy(buf, bytes, size);
    *state = buf;
    return FMU_S_OK;
}
