/*
 * The table-driven variable access, once for every model (fmu_model.h): a
 * variable by its value reference, the setters' checks and their atomic
 * batches, the getters (FMI 3.0's arrays among them), a model at its start
 * values, and the messages of a refusal.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glue/fmu_access.h"

fmu_status fmu_fail(fmu_msg *msg, const char *fmt, ...) {
    if (msg) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg->text, sizeof msg->text, fmt, ap);
        va_end(ap);
    }
    return FMU_ERR;
}

const fmu_var *fmu_model_var(unsigned int vr) { return var_of(vr); }

const char *fmu_model_variable_name(unsigned int vr) {
    const fmu_var *x = var_of(vr);
    return x ? x->name : NULL;
}

size_t fmu_model_size(void) { return INFO.size; }
double *fmu_model_time(fmu_model *m) { return SLOT_D(m, &INFO.vars[0]); }

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
