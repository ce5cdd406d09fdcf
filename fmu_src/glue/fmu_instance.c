#include "glue/fmu_instance.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glue/fmu_bytes.h"
#include "glue/fmu_fields.h"

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

/* ---- the table-driven variable access, once for every model ------------- */

#define INFO FMU_MODEL_INFO
#define SLOT_D(m, x) ((double *)((char *)(m) + (x)->slot))
#define SLOT_I(m, x) ((int *)((char *)(m) + (x)->slot))
#define CSLOT_D(m, x) ((const double *)((const char *)(m) + (x)->slot))
#define CSLOT_I(m, x) ((const int *)((const char *)(m) + (x)->slot))

/* Direct indexing: no search, no string work on the way of a value. */
static inline const fmu_var *var_of(unsigned int vr) {
    return vr < INFO.n_vars && INFO.vars[vr].name ? &INFO.vars[vr] : NULL;
}

const fmu_var *fmu_model_var(unsigned int vr) { return var_of(vr); }

const char *fmu_model_variable_name(unsigned int vr) {
    const fmu_var *x = var_of(vr);
    return x ? x->name : NULL;
}

size_t fmu_model_size(void) { return INFO.size; }
double *fmu_model_time(fmu_model *m) { return SLOT_D(m, &INFO.vars[0]); }

/* The outputs that follow from the time, parameters and inputs, or why one
 * is not finite (then nothing has changed): fmu_model.h. */
static inline fmu_status model_refresh(fmu_model *m, fmu_msg *msg) {
    return INFO.refresh ? INFO.refresh(m, msg) : FMU_OK;
}

/* The type of vr as a message names it; `kind` as kind_of gives it, so that
 * a structural parameter is named for both versions where the caller's is
 * not known (a Float64 set). */
static const char *type_name(int kind, unsigned int vr) {
    return kind == FMU_T_Float64                                ? "Float64 (Real)"
           : kind == FMU_UINT64                                 ? "UInt64 (a structural parameter)"
           : kind == FMU_T_Int32 && fmu_model_is_structural(vr) ? "Integer (UInt64 in FMI 3.0)"
           : kind == FMU_T_Int32                                ? "Int32 (Integer)"
                                                                : "Enumeration (Integer)";
}

/* x's kind as the caller sees it: its table type, but FMU_UINT64 for a
 * structural parameter when the caller is FMI 3.0 (fmu_model.h). */
static inline int kind_of(const fmu_var *x, unsigned int vr, int kinds) {
    return (kinds & FMU_AS_FMI3) && fmu_model_is_structural(vr) ? FMU_UINT64 : x->type;
}

/* The name of what a get or set asked for, from its kinds. */
static const char *asked_name(int kinds) {
    return kinds & FMU_UINT64                             ? "UInt64"
           : (kinds & (FMU_INT32 | FMU_ENUM)) == FMU_ENUM ? "Enumeration (Int64)"
           : (kinds & (FMU_INT32 | FMU_ENUM)) == FMU_INT32
               ? ((kinds & FMU_AS_FMI3) ? "Int32" : "Integer")
               : "Integer";
}

/* A range in a message names its unit, so that "alpha = 90" outside
 * [-12.5664, 12.5664] rad says what was wrong (degrees); none for "1" and "". */
static const char *unit_of(const fmu_var *x) {
    return x && x->unit && *x->unit && strcmp(x->unit, "1") != 0 ? x->unit : "";
}
static const char *unit_sep(const fmu_var *x) { return *unit_of(x) ? " " : ""; }

/* The message for a value the fast check refused: only here is anything
 * formatted. */
static fmu_status why_not_settable(const fmu_var *x, unsigned int vr, int kind, int type_ok,
                                   double value, int allow, fmu_msg *msg) {
    if (!x) return fmu_fail(msg, "unknown value reference %u", vr);
    if (!type_ok)
        return fmu_fail(msg, "variable %s (vr %u) is of type %s", x->name, vr, type_name(kind, vr));
    if (x->causality == FMU_C_output)
        return fmu_fail(msg, "variable %s is an output and cannot be set", x->name);
    if (x->causality == FMU_C_independent)
        return fmu_fail(msg, "variable %s is the independent variable: doStep advances it",
                        x->name);
    if (x->causality == FMU_C_parameter && !(allow & FMU_ALLOW_PARAMETERS))
        return fmu_fail(msg,
                        "parameter %s is fixed: it can be set only before the end of "
                        "initialization (reset the FMU to change it)",
                        x->name);
    if (x->causality == FMU_C_input && !(allow & FMU_ALLOW_INPUTS))
        return fmu_fail(msg, "input %s cannot be set in this state", x->name);
    if (!isfinite(value))
        return fmu_fail(msg, "%s = %g rejected: values must be finite", x->name, value);
    return fmu_fail(msg, "%s = %g rejected: outside [%g, %g]%s%s", x->name, value, x->min, x->max,
                    unit_sep(x), unit_of(x));
}

/* In range and finite (v - v is NaN for an infinity and for NaN). */
static inline int in_range(const fmu_var *x, double v) {
    return (v >= x->min) & (v <= x->max) & (v - v == 0.0); /* one branch, not three */
}

fmu_status fmu_model_check_range(unsigned int vr, double value, const char *context, fmu_msg *msg) {
    const fmu_var *x = var_of(vr);
    if (x && in_range(x, value)) return FMU_OK;
    return fmu_fail(msg, "%s: %s = %g is outside [%g, %g]%s%s", context, x ? x->name : "?", value,
                    x ? x->min : NAN, x ? x->max : NAN, unit_sep(x), unit_of(x));
}

/* The values set by one call, saved on the stack up to this many (the
 * setters: glue/set_batch.inc). */
enum { SAVED_ON_STACK = 16 };

#define SET_ATTR OC_HOT
#define SET_NAME fmu_model_set_float64
#define SET_VALUES const double v[]
#define SET_CTYPE double
#define SET_SLOT SLOT_D
#define SET_VALUE v[i]
#define SET_TYPE_OK x->type == FMU_T_Float64
#define SET_KIND x->type
#include "glue/set_batch.inc"

/* In [min, max] (checked before the write): the int slot holds it.  A
 * UInt64 is read unsigned, so that 2^64 - 1 is refused as itself. */
#define SET_ATTR
#define SET_NAME fmu_model_set_int
#define SET_VALUES const void *v, size_t width, int kinds
#define SET_CTYPE int
#define SET_SLOT SLOT_I
#define SET_VALUE                                                                                  \
    (kinds & FMU_UINT64) ? (double)((const uint64_t *)v)[i] : (double)fmu_int_at(v, width, i)
#define SET_TYPE_OK kind_of(x, vr[i], kinds) & kinds
#define SET_KIND kind_of(x, vr[i], kinds)
#include "glue/set_batch.inc"

static fmu_status not_of_type(unsigned int vr, int kinds, fmu_msg *msg) {
    const fmu_var *x = var_of(vr);
    const char *asked =
        (kinds & ~FMU_AS_FMI3) == FMU_T_Float64 ? "Float64 (Real)" : asked_name(kinds);
    if (x)
        return fmu_fail(msg, "variable %s (vr %u) is of type %s, not %s", x->name, vr,
                        type_name(kind_of(x, vr, kinds), vr), asked);
    return fmu_fail(msg, "unknown value reference %u", vr);
}

OC_HOT fmu_status fmu_model_get_float64(const fmu_model *m, const unsigned int vr[], size_t n,
                                        double v[], fmu_msg *msg) {
    const fmu_var *const vars = INFO.vars;
    const unsigned int nv = INFO.n_vars;
    for (size_t i = 0; i < n; ++i) {
        /* a row without a variable has type 0: no name test on the way */
        const fmu_var *x = &vars[vr[i] < nv ? vr[i] : 0];
        if (vr[i] >= nv || x->type != FMU_T_Float64) return not_of_type(vr[i], FMU_T_Float64, msg);
        v[i] = *CSLOT_D(m, x);
    }
    return FMU_OK;
}

fmu_status fmu_model_get_int(const fmu_model *m, const unsigned int vr[], size_t n, void *v,
                             size_t width, int kinds, fmu_msg *msg) {
    for (size_t i = 0; i < n; ++i) {
        const fmu_var *x = var_of(vr[i]);
        if (!x || !(kind_of(x, vr[i], kinds) & kinds)) return not_of_type(vr[i], kinds, msg);
        fmu_int_put(v, width, i, *CSLOT_I(m, x));
    }
    return FMU_OK;
}

int fmu_model_is_structural(unsigned int vr) {
    const fmu_arrays *a = INFO.arrays;
    for (unsigned int k = 0; a && k < a->n_structural; ++k)
        if (a->structural[k] == vr) return 1;
    return 0;
}

/* The number of values vr holds (1 for a scalar) and its type as FMI 3.0
 * sees it (0: unknown). */
static size_t values_of(const fmu_model *m, unsigned int vr, int *type) {
    const fmu_arrays *a = INFO.arrays;
    size_t n;
    if (a && vr >= INFO.n_vars && (n = a->size(m, vr, type)) > 0) return n;
    const fmu_var *x = var_of(vr);
    *type = x ? kind_of(x, vr, FMU_AS_FMI3) : 0;
    return 1;
}

fmu_status fmu_model_get_values(const fmu_model *m, const unsigned int vr[], size_t n, void *v,
                                size_t n_values, int type, size_t width, fmu_msg *msg) {
    size_t total = 0;
    for (size_t i = 0; i < n; ++i) {
        int t;
        total += values_of(m, vr[i], &t);
        if (!(t & type)) /* the type codes are the kind bits */
            return not_of_type(vr[i], type | FMU_AS_FMI3, msg);
    }
    if (total != n_values)
        return fmu_fail(msg, "nValues = %zu but the %zu variables hold %zu values", n_values, n,
                        total);
    size_t at = 0;
    for (size_t i = 0; i < n; ++i) {
        int t;
        const size_t k = values_of(m, vr[i], &t);
        if (vr[i] >= INFO.n_vars) {
            /* an Int32 array is asked for through the Int32 functions only (width 4) */
            INFO.arrays->get(m, vr[i],
                             type == FMU_T_Float64 ? (void *)((double *)v + at)
                                                   : (void *)((int32_t *)v + at));
        } else if (type == FMU_T_Float64) {
            ((double *)v)[at] = *CSLOT_D(m, var_of(vr[i]));
        } else {
            fmu_int_put(v, width, at, *CSLOT_I(m, var_of(vr[i])));
        }
        at += k;
    }
    return FMU_OK;
}

fmu_status fmu_model_derivative(const fmu_model *m, const unsigned int unknown[], size_t n_unknown,
                                const unsigned int known[], size_t n_known, const double seed[],
                                double out[], int adjoint, fmu_msg *msg) {
    if (!INFO.derivative)
        return fmu_fail(msg, "this FMU provides no derivatives (providesDirectionalDerivative = "
                             "false)");
    return INFO.derivative(m, unknown, n_unknown, known, n_known, seed, out, adjoint, msg);
}

static const char *name_or_unknown(unsigned int vr) {
    const fmu_var *x = var_of(vr);
    return x ? x->name : "unknown";
}

/* vr's position in list[0..n), -1 if it is not there */
static int index_of(const unsigned int *list, int n, unsigned int vr) {
    for (int i = 0; i < n; ++i)
        if (list[i] == vr) return i;
    return -1;
}

/* "T1, T2, ...": the names of list[0..n), for a message */
static const char *names_of(const unsigned int *list, int n, char *buf, size_t size) {
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && used < size; ++i) {
        const int w =
            snprintf(buf + used, size - used, "%s%s", i ? ", " : "", name_or_unknown(list[i]));
        if (w < 0) break;
        used += (size_t)w;
    }
    return buf;
}

fmu_status fmu_jacobian_derivative(const fmu_jacobian *jac, const fmu_model *m,
                                   const unsigned int unknown[], size_t n_unknown,
                                   const unsigned int known[], size_t n_known, const double seed[],
                                   double out[], int adjoint, fmu_msg *msg) {
    char names[256];
    for (size_t j = 0; j < n_known; ++j)
        if (index_of(jac->inputs, jac->cols, known[j]) < 0)
            return fmu_fail(msg, "known vr %u (%s) is not an input %s", known[j],
                            name_or_unknown(known[j]),
                            names_of(jac->inputs, jac->cols, names, sizeof names));
    for (size_t i = 0; i < n_unknown; ++i)
        if (index_of(jac->outputs, jac->rows, unknown[i]) < 0)
            return fmu_fail(msg, "unknown vr %u (%s) is not an output %s", unknown[i],
                            name_or_unknown(unknown[i]),
                            names_of(jac->outputs, jac->rows, names, sizeof names));
    const size_t n_seed = adjoint ? n_unknown : n_known;
    for (size_t k = 0; k < n_seed; ++k)
        if (!isfinite(seed[k])) return fmu_fail(msg, "seed %zu is not finite", k);
    double J[FMU_JACOBIAN_MAX];
    jac->partials(m, J);
    const size_t n_out = adjoint ? n_known : n_unknown, cols = (size_t)jac->cols;
    /* every index was checked above */
#define JAC(row_vr, col_vr)                                                                        \
    J[(size_t)index_of(jac->outputs, jac->rows, row_vr) * cols +                                   \
      (size_t)index_of(jac->inputs, jac->cols, col_vr)]
    for (size_t k = 0; k < n_out; ++k) {
        double acc = 0.0;
        if (adjoint)
            for (size_t i = 0; i < n_unknown; ++i) acc += JAC(unknown[i], known[k]) * seed[i];
        else
            for (size_t j = 0; j < n_known; ++j) acc += JAC(unknown[k], known[j]) * seed[j];
        if (!isfinite(acc)) return fmu_fail(msg, "the derivative overflows");
        out[k] = acc;
    }
#undef JAC
    return FMU_OK;
}

fmu_status fmu_model_init_from(fmu_model *m, const double start[], fmu_msg *msg) {
    memset(m, 0, INFO.size);
    for (unsigned int vr = 0; vr < INFO.n_vars; ++vr) {
        const fmu_var *x = var_of(vr);
        if (!x || !(x->settable || x->causality == FMU_C_independent)) continue;
        const double s = start ? start[vr] : x->start;
        if (x->type == FMU_T_Float64)
            *SLOT_D(m, x) = s;
        else
            *SLOT_I(m, x) = (int)s;
    }
    if (model_refresh(m, msg) != FMU_OK) return FMU_ERR;
    return fmu_model_update(m, FMU_CHANGED_PARAMETERS | FMU_CHANGED_INPUTS,
                            FMU_ALLOW_PARAMETERS | FMU_ALLOW_INPUTS, msg);
}

void fmu_model_init(fmu_model *m) {
    fmu_msg msg;
    /* The table's start values are admissible (the C tests check it). */
    (void)fmu_model_init_from(m, NULL, &msg);
}

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

/* ---- the instance ------------------------------------------------------- */

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
    while (I->states) held_release(I, &I->states);
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

/* ---- start values from the resources (format: fmu_instance.h) ---------- */

static int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

static int lower(int c) { return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c; }

char *fmu_path_from_uri(const char *uri) {
    if (!uri) return NULL;
    static const char scheme[] = "file:";
    for (int i = 0; i < 5; ++i)
        if (lower((unsigned char)uri[i]) != scheme[i]) return NULL;
    const char *p = uri + 5;
    if (p[0] == '/' && p[1] == '/') { /* an authority: empty or localhost, else a UNC host */
        p += 2;
        if (strncmp(p, "localhost/", 10) == 0)
            p += 9;
        else if (*p != '/')
            p -= 2; /* keep //host/share */
    }
    char *out = malloc(strlen(p) + 1);
    if (!out) return NULL;
    size_t n = 0;
    for (; *p; ++p) {
        int hi, lo;
        if (*p == '%' && (hi = hex_digit(p[1])) >= 0 && (lo = hex_digit(p[2])) >= 0) {
            out[n++] = (char)(hi * 16 + lo);
            p += 2;
        } else {
            out[n++] = *p;
        }
    }
    out[n] = '\0';
    /* /C:/dir or /C|/dir: a Windows drive letter */
    if (out[0] == '/' && ((out[1] >= 'A' && out[1] <= 'Z') || (out[1] >= 'a' && out[1] <= 'z')) &&
        (out[2] == ':' || out[2] == '|') && (out[3] == '/' || out[3] == '\0')) {
        memmove(out, out + 1, n);
        out[1] = ':';
    }
    return out;
}

/* A C99 hexadecimal floating constant, exactly: NULL, or what is wrong. */
static const char *parse_hex_float(const char *s, double *value) {
    int neg = 0;
    if (*s == '+' || *s == '-') neg = *s++ == '-';
    if (!(s[0] == '0' && (s[1] == 'x' || s[1] == 'X'))) return "no 0x";
    s += 2;
    uint64_t mant = 0;
    long e2 = 0;
    int digits = 0, point = 0, d;
    for (;; ++s) {
        if (*s == '.' && !point) {
            point = 1;
            continue;
        }
        if ((d = hex_digit(*s)) < 0) break;
        ++digits;
        if (mant >> 56) { /* more would not fit: only zeros may follow */
            if (d != 0) return "more digits than a double holds";
            if (!point) e2 += 4;
        } else {
            mant = mant * 16 + (uint64_t)d;
            if (point) e2 -= 4;
        }
    }
    if (digits == 0) return "no hexadecimal digits";
    if (*s != 'p' && *s != 'P') return "no binary exponent (p)";
    ++s;
    int eneg = 0;
    if (*s == '+' || *s == '-') eneg = *s++ == '-';
    long e = 0;
    int edigits = 0;
    for (; *s >= '0' && *s <= '9'; ++s, ++edigits)
        if (e < 100000) e = e * 10 + (*s - '0');
    if (edigits == 0) return "no exponent digits";
    if (*s) return "characters after the number";
    e2 += eneg ? -e : e;
    while (mant && !(mant & 1)) {
        mant >>= 1;
        ++e2;
    }
    if (mant >> 53) return "more digits than a double holds";
    const double m = (double)mant; /* exact: < 2^53 */
    const double v = mant ? ldexp(m, (int)(e2 < -100000  ? -100000
                                           : e2 > 100000 ? 100000
                                                         : e2))
                          : 0.0;
    if (mant && (!isfinite(v) || v == 0.0 || ldexp(v, (int)-e2) != m))
        return "not representable exactly as a double";
    *value = neg ? -v : v;
    return NULL;
}

/* A decimal integer of at most 15 digits (exact as a double): NULL, or why not. */
static const char *parse_decimal_integer(const char *s, double *value) {
    int neg = 0;
    if (*s == '+' || *s == '-') neg = *s++ == '-';
    double v = 0;
    int digits = 0;
    for (; *s >= '0' && *s <= '9'; ++s)
        if (++digits <= 15) v = v * 10 + (*s - '0');
    if (digits == 0 || *s) return "not a decimal integer";
    if (digits > 15) return "more than 15 digits";
    *value = neg ? -v : v;
    return NULL;
}

static int is_blank(char c) { return c == ' ' || c == '\t'; }

static int load_fail(fmu_instance *I, const char *fn, const char *path, int line, FILE *f,
                     char *freeme, double *start, const char *fmt, ...) {
    char text[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    if (line > 0)
        FMU_ERROR(I, "%s: %s, line %d: %s", fn, path, line, text);
    else
        FMU_ERROR(I, "%s: %s: %s", fn, path, text);
    if (f) fclose(f);
    free(start);
    free(freeme);
    return -1;
}

int fmu_load_start_values(fmu_instance *I, const char *fn, const char *resources, int is_uri) {
    if (!resources || !*resources) return 0;
    char *dir = is_uri ? fmu_path_from_uri(resources) : NULL;
    const char *base = is_uri ? dir : resources;
    if (!base) return 0; /* not a file URI: no file this FMU can read */
    const size_t len = strlen(base);
    const int sep = len > 0 && (base[len - 1] == '/' || base[len - 1] == '\\');
    char *path = malloc(len + 1 + sizeof FMU_START_VALUES_FILE);
    if (!path) {
        free(dir);
        FMU_ERROR(I, "%s: out of memory", fn);
        return -1;
    }
    memcpy(path, base, len);
    if (!sep) path[len] = '/';
    memcpy(path + len + !sep, FMU_START_VALUES_FILE, sizeof FMU_START_VALUES_FILE);
    free(dir);
    FILE *f = fopen(path, "rb");
    if (!f) { /* no file: the compiled start values */
        free(path);
        return 0;
    }
    const unsigned int nv = INFO.n_vars;
    double *start = malloc(nv * sizeof *start);
    unsigned char *seen = calloc(nv ? nv : 1, 1);
    if (!start || !seen) {
        free(seen);
        return load_fail(I, fn, path, 0, f, path, start, "out of memory");
    }
    memcpy(start, I->start, nv * sizeof *start);
    char buf[1002];
    int line = 0;
#define FAIL(...)                                                                                  \
    do {                                                                                           \
        free(seen);                                                                                \
        return load_fail(I, fn, path, line, f, path, start, __VA_ARGS__);                          \
    } while (0)
    while (fgets(buf, sizeof buf, f)) {
        ++line;
        size_t n = strlen(buf);
        if (n > 0 && buf[n - 1] == '\n')
            buf[--n] = '\0';
        else if (!feof(f))
            FAIL("longer than 1000 characters");
        if (n > 0 && buf[n - 1] == '\r') buf[--n] = '\0';
        while (n > 0 && is_blank(buf[n - 1])) buf[--n] = '\0';
        char *p = buf;
        while (is_blank(*p)) ++p;
        if (*p == '\0' || *p == '#') continue;
        char *name = p;
        while (*p && !is_blank(*p) && *p != '=') ++p;
        char *name_end = p;
        while (is_blank(*p)) ++p;
        if (*p != '=') FAIL("expected `name = value`");
        *name_end = '\0';
        ++p;
        while (is_blank(*p)) ++p;
        unsigned int vr = nv;
        for (unsigned int k = 0; k < nv; ++k)
            if (INFO.vars[k].name && strcmp(INFO.vars[k].name, name) == 0) vr = k;
        if (vr == nv) FAIL("no variable named \"%s\"", name);
        const fmu_var *x = &INFO.vars[vr];
        if (x->causality != FMU_C_parameter) FAIL("%s is not a parameter", name);
        if (seen[vr]) FAIL("%s is given twice", name);
        seen[vr] = 1;
        double v;
        const char *why;
        if (x->type == FMU_T_Float64) {
            why = (p[0] == '0' || ((p[0] == '-' || p[0] == '+') && p[1] == '0')) &&
                          (strchr(p, 'x') || strchr(p, 'X'))
                      ? parse_hex_float(p, &v)
                      : parse_decimal_integer(p, &v);
            if (why)
                FAIL("%s = \"%s\": %s; expected a hexadecimal float such as 0x1.8p+3 "
                     "(printf %%a, Python float.hex()) or a decimal integer",
                     name, p, why);
        } else if ((why = parse_decimal_integer(p, &v)) != NULL) {
            FAIL("%s = \"%s\": %s; expected a decimal integer", name, p, why);
        }
        if (!in_range(x, v))
            FAIL("%s = %.17g is outside [%g, %g]%s%s", name, v, x->min, x->max, unit_sep(x),
                 unit_of(x));
        start[vr] = v;
    }
    if (ferror(f)) FAIL("read error");
#undef FAIL
    fmu_msg msg;
    if (fmu_model_init_from(I->model, start, &msg) != FMU_OK) {
        free(seen);
        line = 0;
        return load_fail(I, fn, path, 0, f, path, start, "the values are not admissible: %s",
                         msg.text);
    }
    memcpy(I->start, start, nv * sizeof *start);
    fmu_log(I, FMU_S_OK, FMU_LOG_CALLS, "%s: start values from %s", fn, path);
    fclose(f);
    free(seen);
    free(start);
    free(path);
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

/* ---- a model's serialized fields (fmu_fields.h) -------------------------- */

unsigned char *fmu_fields_write(const fmu_fields *list, const void *s, unsigned char *p) {
    for (unsigned int i = 0; i < list->n; ++i) {
        const fmu_field *f = &list->field[i];
        const char *at = (const char *)s + f->offset;
        if (f->type == FMU_FIELD_F64) {
            p = fmu_put_f64(p, *(const double *)(const void *)at);
        } else if (f->type == FMU_FIELD_U32) {
            p = fmu_put_u32(p, (uint32_t) * (const int *)(const void *)at);
        } else {
            for (unsigned int k = 0; k < f->count; ++k)
                p = fmu_fields_write(f->record, at + k * f->record->stride, p);
        }
    }
    return p;
}

/* The checks of a number read (a u32's as a double, exactly). */
static fmu_status check_read(const fmu_field *f, double v, fmu_msg *msg) {
    switch (f->check) {
    case FMU_CHECK_FINITE:
        if (isfinite(v)) return FMU_OK;
        return fmu_fail(msg, "serialized state: %s = %g is not finite", f->name, v);
    case FMU_CHECK_RANGE:
        if (f->type == FMU_FIELD_U32 && v > INT32_MAX)
            return fmu_fail(msg, "serialized state: %s = %.0f is not an int32", f->name, v);
        return fmu_model_check_range(f->vr, v, "serialized state", msg);
    case FMU_CHECK_FLAG:
        if (v == 0 || v == 1) return FMU_OK;
        return fmu_fail(msg, "serialized state: %s = %.0f is not 0 or 1", f->name, v);
    default: return FMU_OK;
    }
}

fmu_status fmu_fields_read(const fmu_fields *list, void *s, const unsigned char **p, fmu_msg *msg) {
    for (unsigned int i = 0; i < list->n; ++i) {
        const fmu_field *f = &list->field[i];
        char *at = (char *)s + f->offset;
        if (f->type == FMU_FIELD_RECORD) {
            for (unsigned int k = 0; k < f->count; ++k)
                if (fmu_fields_read(f->record, at + k * f->record->stride, p, msg) != FMU_OK)
                    return FMU_ERR;
            continue;
        }
        double v;
        if (f->type == FMU_FIELD_F64) {
            *p = fmu_get_f64(*p, &v);
            *(double *)(void *)at = v;
        } else {
            uint32_t u;
            *p = fmu_get_u32(*p, &u);
            v = (double)u;
            *(int *)(void *)at = (int)(u > INT32_MAX ? INT32_MAX : u); /* refused below */
        }
        if (check_read(f, v, msg) != FMU_OK) return FMU_ERR;
    }
    return FMU_OK;
}

int fmu_fields_same(const fmu_fields *list, const void *a, const void *b) {
    for (unsigned int i = 0; i < list->n; ++i) {
        const fmu_field *f = &list->field[i];
        const char *x = (const char *)a + f->offset, *y = (const char *)b + f->offset;
        if (f->type == FMU_FIELD_RECORD) {
            for (unsigned int k = 0; k < f->count; ++k)
                if (!fmu_fields_same(f->record, x + k * f->record->stride,
                                     y + k * f->record->stride))
                    return 0;
        } else if (memcmp(x, y, f->type == FMU_FIELD_F64 ? sizeof(double) : sizeof(int)) != 0) {
            return 0;
        }
    }
    return 1;
}

int fmu_fields_zero(const fmu_fields *list, const void *s) {
    for (unsigned int i = 0; i < list->n; ++i) {
        const fmu_field *f = &list->field[i];
        const char *at = (const char *)s + f->offset;
        if (f->type == FMU_FIELD_RECORD) {
            for (unsigned int k = 0; k < f->count; ++k)
                if (!fmu_fields_zero(f->record, at + k * f->record->stride)) return 0;
        } else if (f->type == FMU_FIELD_F64 ? *(const double *)(const void *)at != 0.0
                                            : *(const int *)(const void *)at != 0) {
            return 0;
        }
    }
    return 1;
}

/* ---- the serialized state: the glue's header, then the model's fields ---- */

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
