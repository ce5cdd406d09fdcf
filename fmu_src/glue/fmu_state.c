/*
 * The serialized state (fmu_instance.h): the glue's header (tag, format,
 * length, phase, time), then the model's fields; and the FMU-state entry
 * points of both standards over the states an instance holds.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "glue/fmu_access.h"
#include "glue/fmu_bytes.h"

/* A state object: a link by which its instance lists it, then the
 * serialized state, to which the importer's handle points.  The list lets
 * free and get refuse a handle this instance did not give (a double free, a
 * stray pointer) instead of passing it to the allocator, and free the
 * states left over with the instance. */
typedef struct fmu_held_state {
    struct fmu_held_state *next;
} fmu_held_state;

static unsigned char *held_bytes(fmu_held_state *s) { return (unsigned char *)(s + 1); }

static unsigned char *held_new(fmu_instance *I, size_t size) {
    fmu_held_state *s = I->alloc(1, sizeof *s + size);
    if (!s) return NULL;
    s->next = I->states;
    I->states = s;
    return held_bytes(s);
}

/* The link that holds the state whose bytes are `p`, or NULL: compares
 * addresses only, never reads through p. */
static fmu_held_state **held_find(fmu_instance *I, const void *p) {
    for (fmu_held_state **at = &I->states; *at; at = &(*at)->next)
        if (held_bytes(*at) == p) return at;
    return NULL;
}

static void held_release(fmu_instance *I, fmu_held_state **at) {
    fmu_held_state *s = *at;
    *at = s->next;
    I->release(s);
}

void fmu_states_free(fmu_instance *I) {
    while (I->states) held_release(I, &I->states);
}

/* Layout: FMU_STATE_HEADER_LAYOUT (fmu_instance.h), the model's fields. */
enum { STATE_FORMAT = FMU_STATE_FORMAT, STATE_HEADER = FMU_STATE_HEADER_BYTES };

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
    uint32_t format, length, phase;
    double time;
    const unsigned char *p = buf;
    /* Tag and format first, so that a state of an older FMU is told as such
     * rather than as a wrong size. */
    if (size < 8 || memcmp(p, FMU_MODEL_INFO.tag, 4) != 0)
        return fmu_fail(msg, "not a serialized %s state (%s)", FMU_MODEL_INFO.model_identifier,
                        size < 8 ? "too short" : "wrong tag");
    p = fmu_get_u32(p + 4, &format);
    if (format != STATE_FORMAT)
        return fmu_fail(msg,
                        "serialized state of format %u, this FMU reads format %d only "
                        "(states are not carried across FMU versions: save them again "
                        "with this one)",
                        (unsigned)format, STATE_FORMAT);
    if (size != fmu_state_size())
        return fmu_fail(msg, "a serialized %s state has %zu bytes, got %zu",
                        FMU_MODEL_INFO.model_identifier, fmu_state_size(), size);
    p = fmu_get_u32(p, &length);
    p = fmu_get_u32(p, &phase);
    p = fmu_get_f64(p, &time);
    if (length != fmu_state_size())
        return fmu_fail(msg, "serialized state says it has %u bytes, expected %zu",
                        (unsigned)length, fmu_state_size());
    if (phase != FMU_INSTANTIATED && phase != FMU_INIT && phase != FMU_STEP &&
        phase != FMU_TERMINATED)
        return fmu_fail(msg, "serialized state holds an unknown phase %u", (unsigned)phase);
    if (!isfinite(time)) return fmu_fail(msg, "serialized state holds a non-finite time");
    if (!INFO.refresh) { /* the model's read checks all it keeps, and changes m only on success */
        if (fmu_model_state_read(I->model, p, msg) != FMU_OK) return FMU_ERR;
        *fmu_model_time(I->model) = time;
        I->phase = (int)phase;
        return FMU_OK;
    }
    /* refresh can refuse only after the model's read has succeeded: read
     * into a copy, so that a refused state changes nothing. */
    fmu_model *next = I->alloc(1, fmu_model_size());
    if (!next) return fmu_fail(msg, "out of memory");
    memcpy(next, I->model, fmu_model_size());
    fmu_status st = fmu_model_state_read(next, p, msg);
    if (st == FMU_OK) {
        *fmu_model_time(next) = time;
        fmu_msg why;
        if ((st = model_refresh(next, &why)) != FMU_OK)
            fmu_fail(msg, "serialized state at t = %g s: %s", time, why.text);
    }
    if (st == FMU_OK) {
        memcpy(I->model, next, fmu_model_size());
        I->phase = (int)phase;
    }
    I->release(next);
    return st;
}

int fmu_state_get(fmu_instance *I, const char *fn, void **state) {
    if (!state) {
        FMU_ERROR(I, "%s: the state pointer is NULL", fn);
        return FMU_S_ERROR;
    }
    unsigned char *buf = *state;
    if (buf && !held_find(I, buf)) {
        FMU_ERROR(I, "%s: *state is neither NULL nor a state of this instance", fn);
        return FMU_S_ERROR;
    }
    if (!buf && !(buf = held_new(I, fmu_state_size()))) {
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

int fmu_state_free(fmu_instance *I, const char *fn, void **state) {
    if (!state || !*state) return FMU_S_OK; /* as the standards ask: nothing to free */
    fmu_held_state **at = held_find(I, *state);
    if (at) {
        held_release(I, at);
        *state = NULL;
        return FMU_S_OK;
    }
    /* The handle itself instead of its address, as fmusim 0.0.39 of the
     * Reference-FMUs passes it when it saves or restores a state (one of
     * ours: nothing else is freed); said in the log, the call succeeds. */
    if ((at = held_find(I, state))) {
        held_release(I, at);
        fmu_log(I, FMU_S_WARNING, FMU_LOG_WARNING,
                "%s: given the state instead of a pointer to "
                "it; freed it (the importer's handle now dangles)",
                fn);
        return FMU_S_OK;
    }
    FMU_ERROR(I,
              "%s: not a state of this instance (freed already, or another instance's): "
              "nothing freed",
              fn);
    return FMU_S_ERROR;
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
    fmu_msg msg;
    fmu_model_init(scratch.model);
    const fmu_status st = fmu_state_read(&scratch, bytes, size, &msg);
    I->release(scratch.model);
    if (st != FMU_OK) return fmu_result(I, st, &msg, fn);
    unsigned char *buf = *state;
    if (buf && !held_find(I, buf)) {
        FMU_ERROR(I, "%s: *state is neither NULL nor a state of this instance", fn);
        return FMU_S_ERROR;
    }
    if (!buf && !(buf = held_new(I, size))) {
        FMU_ERROR(I, "%s: out of memory", fn);
        return FMU_S_ERROR;
    }
    memcpy(buf, bytes, size);
    *state = buf;
    return FMU_S_OK;
}
