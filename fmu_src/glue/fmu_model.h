/*
 * What a model provides to the shared FMI glue (glue/fmu_table.h's
 * FMU_GLUE_SOURCES, fmi2_glue.c, fmi3_glue.c), as the Modelica Reference-FMUs share one set of FMI
 * functions across models: the glue belongs to no model, a model knows nothing of FMI.
 *
 * A model provides its physics and its state, nothing else:
 *   - `struct fmu_model`, in which every variable of its table (FMU_VARIABLES
 *     in its table header) has a slot: a double for Float64, an int for
 *     Int32 and Enumerations.  The model names the slots with one macro per
 *     variable, FMU_SLOT_<name> (an offsetof), and builds its row array
 *     with FMU_VAR_ROW, so a variable without a slot does not compile.
 *   - FMU_MODEL_INFO: identity, the rows, and its hooks (below).
 *   - fmu_model_do_step, and those of fmu_model_update and the serialized
 *     state's writer and reader it has: glue/fmu_model_defaults.inc, which
 *     its model.c includes last, writes the others and the state's size
 *     from its field list (FMU_STATE_FIELDS) and its header's flags
 *     FMU_HAS_UPDATE, FMU_HAS_STATE_WRITE, FMU_HAS_STATE_READ.
 * The glue does the rest once for every model: variable lookup by value
 * reference (an array index), type, causality, phase, range and
 * settability checks, atomic batches, start values, getters.
 * Value reference 0 is the independent variable time.
 */
#ifndef FMU_MODEL_H
#define FMU_MODEL_H

#include <stddef.h>
#include <stdint.h>

#include "compiler.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { FMU_OK = 0, FMU_ERR = 1 } fmu_status;

/* The functions a step passes through (set inputs, the model's update and
 * do_step, get outputs) are defined OC_HOT (compiler.h): inlined into the
 * FMI entry points of each FMU binary, an ordinary call elsewhere. */

/* Why a call failed; on FMU_ERR nothing in the model has changed.  Written
 * only when a call fails: a successful call never formats anything. */
typedef struct {
    char text[256];
} fmu_msg;

fmu_status fmu_fail(fmu_msg *msg, const char *fmt, ...);

/* What may be set now: fixed parameters before the end of initialization,
 * inputs whenever the model is alive. */
enum { FMU_ALLOW_PARAMETERS = 1, FMU_ALLOW_INPUTS = 2 };

/* Integer kinds as the variable table names them.  FMI 2.0 reads both as
 * Integer; FMI 3.0 reads Int32 through fmi3GetInt32 and Enumerations
 * through fmi3GetInt64.  The type codes are the kind bits, so that "may this
 * function touch this variable" is one AND.
 * FMI 3.0 also has FMU_UINT64: a structural parameter (an array dimension,
 * an Int32 row of its table) is a UInt64 there, as the standard's Dimension
 * element requires, served through fmi3GetUInt64 / fmi3SetUInt64 only; an
 * FMI 3.0 caller adds FMU_AS_FMI3 to its kinds to see it so (FMI 2.0 keeps
 * the table's Integer).  No variable's type has either bit. */
enum { FMU_INT32 = 1, FMU_ENUM = 2, FMU_UINT64 = 8, FMU_AS_FMI3 = 16 };
enum { FMU_T_Int32 = FMU_INT32, FMU_T_Enum = FMU_ENUM, FMU_T_Float64 = 4 };
enum { FMU_C_independent = 1, FMU_C_parameter, FMU_C_input, FMU_C_output };
/* Which FMU_ALLOW_* bit a causality needs to be set (0: never settable). */
enum {
    FMU_SET_independent = 0,
    FMU_SET_parameter = FMU_ALLOW_PARAMETERS,
    FMU_SET_input = FMU_ALLOW_INPUTS,
    FMU_SET_output = 0
};

/* One row of a model's table, indexed by value reference. */
typedef struct {
    const char *name;        /* NULL: no variable has this value reference */
    unsigned char type;      /* FMU_T_* */
    unsigned char causality; /* FMU_C_* */
    unsigned char settable;  /* FMU_ALLOW_* bit needed to set it, 0: never */
    double start, min, max;  /* min/max may be infinite: values must also be finite */
    size_t slot;             /* byte offset of the value in struct fmu_model */
    const char *unit;        /* the table's unit ("rad", "N/m"; "1" or "" for none), for messages */
} fmu_var;

/* The row of a table entry X(name, vr, type, causality, ...); the model
 * defines FMU_SLOT_<name> for every variable and, for a table with
 * enumeration types, FMU_T_<EnumType> = FMU_T_Enum (FMU_ENUM_KIND). */
#define FMU_VAR_ROW(name, vr, type, caus, var, init, start, lo, hi, unit, ...)                     \
    [vr] = {#name, FMU_T_##type,    FMU_C_##caus, FMU_SET_##caus, start, lo,                       \
            hi,    FMU_SLOT_##name, unit},
#define FMU_ENUM_KIND(type, items) FMU_T_##type = FMU_T_Enum,

typedef struct fmu_model fmu_model;

/* What the changed-mask of fmu_model_update says: which causalities were set. */
enum { FMU_CHANGED_PARAMETERS = FMU_ALLOW_PARAMETERS, FMU_CHANGED_INPUTS = FMU_ALLOW_INPUTS };

typedef struct {
    const char *model_identifier;
    const char *token;    /* FMI 2.0 guid, FMI 3.0 instantiationToken */
    unsigned char tag[4]; /* first bytes of a serialized state of this model */
    const fmu_var *vars;  /* indexed by value reference; vars[0] is time */
    unsigned int n_vars;
    size_t size; /* sizeof(struct fmu_model) */
    /* Optional hooks; NULL takes the glue's default. */
    /* Writes into their slots the outputs that follow from the time, the
     * parameters and the inputs alone (not from what update and do_step
     * keep), e.g. those that depend on the time; or, if one of them would
     * not be a finite number, fails with the reason and changes nothing.
     * Whenever the glue changes the time, a parameter or an input (a set,
     * before update; the start time; a step, at the step's end, before
     * do_step; a restored state; initialization) it calls this, and if it
     * fails it puts back what it changed: no call returns OK with such an
     * output not finite.  Default: no such outputs. */
    fmu_status (*refresh)(fmu_model *m, fmu_msg *msg);
    /* At the end of initialization; changes no parameter, input or time.
     * Default: nothing to do. */
    fmu_status (*exit_init)(fmu_model *m, fmu_msg *msg);
    /* adjoint = 0: out = J seed (seed over `known`, out over `unknown`);
     * adjoint = 1: out = J^T seed (seed over `unknown`, out over `known`).
     * Default: an error, "this FMU provides no derivatives". */
    fmu_status (*derivative)(const fmu_model *m, const unsigned int unknown[], size_t n_unknown,
                             const unsigned int known[], size_t n_known, const double seed[],
                             double out[], int adjoint, fmu_msg *msg);
    /* FMI 3.0 arrays and structural parameters; NULL: scalars only. */
    const struct fmu_arrays *arrays;
} fmu_model_info;

/* A model's FMI 3.0 array variables (outputs only; FMI 2.0 has none): their
 * value references follow the table's (>= n_vars), their sizes are products
 * of structural parameters, which the importer may set in configuration mode
 * as well as where the table lets it set them. */
typedef struct fmu_arrays {
    /* The number of values array vr holds now (>= 1) and its type
     * (FMU_T_Float64 or FMU_T_Int32); 0 if vr is not an array. */
    size_t (*size)(const fmu_model *m, unsigned int vr, int *type);
    /* Writes them in row-major order, as doubles or int32_t by its type. */
    void (*get)(const fmu_model *m, unsigned int vr, void *out);
    const unsigned int *structural; /* the structural parameters' value references */
    unsigned int n_structural;
} fmu_arrays;
extern const fmu_model_info FMU_MODEL_INFO;

/* ---- what each model implements (or glue/fmu_model_defaults.inc for it) -- */

/* Every output is a finite number whenever a call returns OK: the outputs
 * of refresh (above) the glue checks through it; those that update,
 * do_step and state_read keep in their slots, these check themselves and
 * fail, changing nothing, when one would not be finite. */

/* Called after the glue has written checked values into the slots and
 * refresh has accepted them (at initialization `changed` has both bits):
 * derive what follows from them, or fail with the reason, in which case the
 * glue restores the slots and the model must have changed nothing else.
 * `allow` is the phase's FMU_ALLOW_*: FMU_ALLOW_PARAMETERS set means
 * initialization has not ended.  The glue's (no FMU_HAS_UPDATE): nothing
 * to derive. */
fmu_status fmu_model_update(fmu_model *m, int changed, int allow, fmu_msg *msg);

/* Advances the model by h [s] (> 0, finite).  The glue keeps the time: it
 * is already the step's end when this runs, and the glue puts it back if
 * the step is refused. */
fmu_status fmu_model_do_step(fmu_model *m, double h, fmu_msg *msg);

/* The model's part of a serialized state: a fixed number of bytes, field by
 * field, little-endian (fmu_bytes.h).  Reading validates every field and
 * changes `m` only on success; the glue then sets the state's time and asks
 * refresh (on a copy when the model has refresh, so that a refused state
 * changes nothing).  The glue's size is its field list's, and so are its
 * writer and reader unless the model has its own (FMU_HAS_STATE_WRITE,
 * FMU_HAS_STATE_READ). */
size_t fmu_model_state_size(void);
void fmu_model_state_write(const fmu_model *m, unsigned char *buf);
fmu_status fmu_model_state_read(fmu_model *m, const unsigned char *buf, fmu_msg *msg);

/* ---- what the glue implements once for every model (fmu_values.c) ---- */

size_t fmu_model_size(void);
/* The model at its table's start values; fmu_model_init_from takes them
 * from `start` (one per value reference) instead. */
void fmu_model_init(fmu_model *m);
fmu_status fmu_model_init_from(fmu_model *m, const double start[], fmu_msg *msg);
double *fmu_model_time(fmu_model *m);
const char *fmu_model_variable_name(unsigned int vr);
/* The row of vr, or NULL. */
const fmu_var *fmu_model_var(unsigned int vr);

fmu_status fmu_model_set_float64(fmu_model *m, const unsigned int vr[], size_t n, const double v[],
                                 int allow, fmu_msg *msg);
fmu_status fmu_model_get_float64(const fmu_model *m, const unsigned int vr[], size_t n, double v[],
                                 fmu_msg *msg);
/* Integers travel as int32_t or int64_t arrays (width 4 or 8; uint64_t
 * when kinds has FMU_UINT64); `kinds` is the mask of FMU_INT32 / FMU_ENUM /
 * FMU_UINT64 the calling function may touch, with FMU_AS_FMI3 from FMI 3.0. */
fmu_status fmu_model_set_int(fmu_model *m, const unsigned int vr[], size_t n, const void *v,
                             size_t width, int kinds, int allow, fmu_msg *msg);
fmu_status fmu_model_get_int(const fmu_model *m, const unsigned int vr[], size_t n, void *v,
                             size_t width, int kinds, fmu_msg *msg);
/* FMI 3.0 gets, arrays included: the values of vr[] in order, each array's
 * in row-major order, nValues their total; `type` FMU_T_Float64 (v double[])
 * or the integer kinds with width as fmu_model_get_int (structural
 * parameters are FMU_UINT64 here, whether or not FMU_AS_FMI3 is given). */
fmu_status fmu_model_get_values(const fmu_model *m, const unsigned int vr[], size_t n, void *v,
                                size_t n_values, int type, size_t width, fmu_msg *msg);
/* Whether vr is one of the model's structural parameters. */
int fmu_model_is_structural(unsigned int vr);
/* The model's derivative hook, or why there is none (fmu_jacobian.c). */
fmu_status fmu_model_derivative(const fmu_model *m, const unsigned int unknown[], size_t n_unknown,
                                const unsigned int known[], size_t n_known, const double seed[],
                                double out[], int adjoint, fmu_msg *msg);
/* Whether `value` lies in vr's [min, max] (for models validating a
 * serialized state against their table). */
fmu_status fmu_model_check_range(unsigned int vr, double value, const char *context, fmu_msg *msg);

/* Width-generic integer access. */
static inline int64_t fmu_int_at(const void *v, size_t width, size_t i) {
    return width == 4 ? (int64_t)((const int32_t *)v)[i] : ((const int64_t *)v)[i];
}
static inline void fmu_int_put(void *v, size_t width, size_t i, int64_t x) {
    if (width == 4)
        ((int32_t *)v)[i] = (int32_t)x;
    else
        ((int64_t *)v)[i] = x;
}

#ifdef __cplusplus
}
#endif
#endif
