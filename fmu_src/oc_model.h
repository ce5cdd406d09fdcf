/*
 * An instance of the contact element, independent of the FMI version: the
 * variables of model_variables.h, the pending/committed step logic and the
 * state image.  The FMI glue (fmi2_glue.c) adds only the FMI state machine,
 * memory and logging callbacks, and the mapping of status codes.
 *
 * Step semantics: setting inputs computes the step from the committed state
 * without committing it; outputs read that pending result; oc_model_do_step
 * commits it.  After a commit the outputs read the step just committed until
 * the inputs are set again; a further commit with held inputs takes a new
 * step from the new committed state.
 */
#ifndef OC_MODEL_H
#define OC_MODEL_H

#include <stddef.h>

#include "contact_law.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    oc_params params;
    oc_law law;
    double u[2], N;
    oc_state committed;
    oc_state start;   /* the state the shown result was computed from */
    oc_step result;   /* the shown result */
    int result_committed;
    double time;
} oc_model;

/* Status of a call: on OC_ERR nothing in the model has changed and msg
 * (if given) says why. */
typedef enum { OC_OK = 0, OC_ERR = 1 } oc_status;

typedef struct {
    char text[256];
} oc_msg;

/* What may be set now: parameters are fixed (settable only before the end
 * of initialization), inputs whenever the model is alive. */
enum { OC_ALLOW_PARAMETERS = 1, OC_ALLOW_INPUTS = 2 };

void oc_model_init(oc_model *m);

oc_status oc_model_set_real(oc_model *m, const unsigned int vr[], size_t n, const double v[],
                            int allow, oc_msg *msg);
oc_status oc_model_get_real(const oc_model *m, const unsigned int vr[], size_t n, double v[],
                            oc_msg *msg);
oc_status oc_model_set_integer(oc_model *m, const unsigned int vr[], size_t n, const int v[],
                               int allow, oc_msg *msg);
oc_status oc_model_get_integer(const oc_model *m, const unsigned int vr[], size_t n, int v[],
                               oc_msg *msg);

/* Commits the step; h is the communication step size [s] (> 0). */
oc_status oc_model_do_step(oc_model *m, double t, double h, oc_msg *msg);

/* Tangent of the outputs as they read now. */
oc_status oc_model_directional_derivative(const oc_model *m, const unsigned int unknown[],
                                          size_t n_unknown, const unsigned int known[],
                                          size_t n_known, const double dv_known[],
                                          double dv_unknown[], oc_msg *msg);

/* The state image: a fixed-size, pointer-free byte image with a header. */
size_t oc_model_image_size(void);
void oc_model_write_image(const oc_model *m, unsigned char *buf);
oc_status oc_model_read_image(oc_model *m, const unsigned char *buf, size_t size, oc_msg *msg);

/* Name of a variable by value reference, or NULL. */
const char *oc_variable_name(unsigned int vr);

#ifdef __cplusplus
}
#endif
#endif
