/*
 * What a model provides to the shared FMI glue (fmu_instance.c, fmi2_glue.c,
 * fmi3_glue.c), as the Modelica Reference-FMUs share one set of FMI functions
 * across models: the glue belongs to no model, a model knows nothing of FMI.
 *
 * Each model defines `struct fmu_model` and these functions; its variable
 * table (FMU_VARIABLES in its table header) generates both model
 * descriptions.  Value reference 0 is the independent variable time, held
 * by the model (fmu_model_time) so that the model's getters can serve it.
 */
#ifndef FMU_MODEL_H
#define FMU_MODEL_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { FMU_OK = 0, FMU_ERR = 1 } fmu_status;

/* Why a call failed; on FMU_ERR nothing in the model has changed. */
typedef struct {
    char text[256];
} fmu_msg;

fmu_status fmu_fail(fmu_msg *msg, const char *fmt, ...);

/* What may be set now: fixed parameters before the end of initialization,
 * inputs whenever the model is alive. */
enum { FMU_ALLOW_PARAMETERS = 1, FMU_ALLOW_INPUTS = 2 };

/* Integer kinds as the variable table names them.  FMI 2.0 reads both as
 * Integer; FMI 3.0 reads Int32 through fmi3GetInt32 and Enumerations
 * through fmi3GetInt64. */
enum { FMU_INT32 = 1, FMU_ENUM = 2 };

typedef struct fmu_model fmu_model;

typedef struct {
    const char *model_identifier;
    const char *token;      /* FMI 2.0 guid, FMI 3.0 instantiationToken */
    unsigned char tag[4];   /* first bytes of a serialized state of this model */
} fmu_model_info;
extern const fmu_model_info FMU_MODEL_INFO;

size_t fmu_model_size(void);
void fmu_model_init(fmu_model *m);
double *fmu_model_time(fmu_model *m);
const char *fmu_model_variable_name(unsigned int vr);

fmu_status fmu_model_set_float64(fmu_model *m, const unsigned int vr[], size_t n,
                                 const double v[], int allow, fmu_msg *msg);
fmu_status fmu_model_get_float64(const fmu_model *m, const unsigned int vr[], size_t n,
                                 double v[], fmu_msg *msg);
/* Integers travel as int32_t or int64_t arrays (width 4 or 8); `kinds` is
 * the mask of FMU_INT32 / FMU_ENUM the calling function may touch. */
fmu_status fmu_model_set_int(fmu_model *m, const unsigned int vr[], size_t n, const void *v,
                             size_t width, int kinds, int allow, fmu_msg *msg);
fmu_status fmu_model_get_int(const fmu_model *m, const unsigned int vr[], size_t n, void *v,
                             size_t width, int kinds, fmu_msg *msg);

/* Advances the model by h [s] (> 0, finite).  The glue keeps the time: it
 * is already the step's end when this runs (outputs that depend on it are
 * checked here), and the glue puts it back if the step is refused. */
fmu_status fmu_model_do_step(fmu_model *m, double h, fmu_msg *msg);

/* FMU_OK if every output the model gives now is a finite number.  The glue
 * asks after it moves the time at the start of an experiment, and puts the
 * time back on FMU_ERR (with msg saying why). */
fmu_status fmu_model_check(const fmu_model *m, fmu_msg *msg);

/* adjoint = 0: out = J seed (seed over `known`, out over `unknown`);
 * adjoint = 1: out = J^T seed (seed over `unknown`, out over `known`). */
fmu_status fmu_model_derivative(const fmu_model *m, const unsigned int unknown[],
                                size_t n_unknown, const unsigned int known[], size_t n_known,
                                const double seed[], double out[], int adjoint, fmu_msg *msg);

/* The model's part of a serialized state: a fixed number of bytes, field by
 * field, little-endian (fmu_bytes.h).  Reading validates every field and
 * changes `m` only on success; the model's time is already the state's
 * (the glue puts it back on failure). */
size_t fmu_model_state_size(void);
void fmu_model_state_write(const fmu_model *m, unsigned char *buf);
fmu_status fmu_model_state_read(fmu_model *m, const unsigned char *buf, fmu_msg *msg);

/* Width-generic integer access for the int setters and getters. */
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
