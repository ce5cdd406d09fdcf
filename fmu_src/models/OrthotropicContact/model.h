/*
 * The contact element as a model of the shared FMI glue (fmu_model.h),
 * independent of the FMI version: the variables of models/OrthotropicContact/table.h, the
 * pending/committed step logic and the serialized state.
 *
 * Step semantics: setting inputs computes the step from the committed state
 * without committing it; outputs read that pending result; a doStep commits
 * it.  After a commit the outputs read the step just committed until the
 * inputs are set again; a further commit with held inputs takes a new step
 * from the new committed state.
 *
 * Initial condition: until initialization ends, the committed state is an
 * unloaded contact with slip s = u (initialSlip = atInputs) or s = (s1Start,
 * s2Start) (explicit), rederived whenever an input or parameter is set; so
 * ExitInitializationMode starts the first step from it.
 */
#ifndef OC_MODEL_H
#define OC_MODEL_H

#include "glue/fmu_fields.h"
#include "glue/fmu_model.h"
#include "law/contact_law.h"
#include "law/law_fields.h"
#include "models/OrthotropicContact/table.h"

#ifdef __cplusplus
extern "C" {
#endif

struct fmu_model {
    oc_params params;
    oc_law law;
    double u[2], N;    /* the current inputs */
    int initial_slip;  /* OC_INITIAL_AT_INPUTS or OC_INITIAL_EXPLICIT */
    double s_start[2]; /* the explicit initial slip [m] */
    oc_state start;    /* the state the shown result was computed from */
    /* The shown result is steps[shown]; the law writes the next one into
     * the other and it is shown only if it is finite, so that a refused
     * step changes nothing without copying a whole step back and forth (a
     * step copied right after the law stored it field by field stalls the
     * CPU's store forwarding; docs/benchmarks.md). */
    oc_step steps[2];
    int shown;
    /* The shown result's outputs, where the table reads them: */
    double T[2];          /* T1, T2: its force on the body, -q */
    double s[2];          /* s1, s2 */
    double energy;        /* dissipatedEnergy */
    int contact;          /* contactState */
    int result_committed; /* 0: pending, committed state = start; 1: = steps[shown].next */
    double time;
};
typedef struct fmu_model oc_model;

/* The values of the parameter initialSlip (models/OrthotropicContact/table.h). */
enum { OC_INITIAL_AT_INPUTS = 1, OC_INITIAL_EXPLICIT = 2 };

/* The model's part of the serialized state (glue/fmu_fields.h).  The shown
 * result is not stored but recomputed: the law is a function of the
 * committed state and the inputs, so nothing derived can disagree with
 * what it derives from. */
static const fmu_field OC_MODEL_FIELD_LIST[] = {
    FMU_RECORD(oc_model, params, &OC_PARAMS_FIELDS, "the law's parameters"),
    FMU_F64(oc_model, u[0], "u1", "the inputs", FINITE, 0),
    FMU_F64(oc_model, u[1], "u2", "the inputs", FINITE, 0),
    FMU_F64(oc_model, N, "N", "the inputs", FINITE, 0),
    FMU_RECORD(oc_model, start, &OC_STATE_FIELDS, "the committed state"),
    FMU_U32(oc_model, initial_slip, "initialSlip", "the initial slip", RANGE, OC_VR_initialSlip),
    FMU_F64(oc_model, s_start[0], "s1Start", "the initial slip", RANGE, OC_VR_s1Start),
    FMU_F64(oc_model, s_start[1], "s2Start", "the initial slip", RANGE, OC_VR_s2Start),
    FMU_U32(oc_model, result_committed, "committed",
            "the commit flag (1: the shown step is committed)", FLAG, 0)};
static const fmu_fields FMU_STATE_FIELDS = FMU_FIELDS(OC_MODEL_FIELD_LIST, oc_model);
/* What model.c writes itself (glue/fmu_model_defaults.inc the rest): its
 * update, and its state's reader, which derives the law and the shown step. */
#define FMU_HAS_UPDATE 1
#define FMU_HAS_STATE_READ 1

#ifdef __cplusplus
}
#endif
#endif
