/*
 * What the glue's own files share and no model sees (fmu_values.c,
 * fmu_jacobian.c, fmu_instance.c, fmu_start_values.c, fmu_state.c): the
 * model's info, a variable's slot, the variable of a value reference, the
 * refresh hook with its default, the range check and a range's unit in a
 * message.
 */
#ifndef FMU_ACCESS_H
#define FMU_ACCESS_H

#include <string.h>

#include "glue/fmu_instance.h"

#define INFO FMU_MODEL_INFO
#define SLOT_D(m, x) ((double *)((char *)(m) + (x)->slot))
#define SLOT_I(m, x) ((int *)((char *)(m) + (x)->slot))
#define CSLOT_D(m, x) ((const double *)((const char *)(m) + (x)->slot))
#define CSLOT_I(m, x) ((const int *)((const char *)(m) + (x)->slot))

/* Direct indexing: no search, no string work on the way of a value. */
static inline const fmu_var *var_of(unsigned int vr) {
    return vr < INFO.n_vars && INFO.vars[vr].name ? &INFO.vars[vr] : NULL;
}

/* The outputs that follow from the time, parameters and inputs, or why one
 * is not finite (then nothing has changed): fmu_model.h. */
static inline fmu_status model_refresh(fmu_model *m, fmu_msg *msg) {
    return INFO.refresh ? INFO.refresh(m, msg) : FMU_OK;
}

/* In range and finite (v - v is NaN for an infinity and for NaN). */
static inline int in_range(const fmu_var *x, double v) {
    return (v >= x->min) & (v <= x->max) & (v - v == 0.0); /* one branch, not three */
}

/* A range in a message names its unit, so that "alpha = 90" outside
 * [-12.5664, 12.5664] rad says what was wrong (degrees); none for "1" and "". */
static inline const char *unit_of(const fmu_var *x) {
    return x && x->unit && *x->unit && strcmp(x->unit, "1") != 0 ? x->unit : "";
}
static inline const char *unit_sep(const fmu_var *x) { return *unit_of(x) ? " " : ""; }

/* Frees every state the instance holds (fmu_state.c): with the instance. */
void fmu_states_free(fmu_instance *I);

#endif
