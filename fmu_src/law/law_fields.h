/*
 * The law's part of a model's serialized state (glue/fmu_fields.h), once:
 * its parameters (an oc_params, from the law's rows: law/law_table.h) and
 * a committed state (an oc_state).  A model that carries the law puts them
 * in its field list as records (FMU_RECORD, FMU_RECORDS).
 */
#ifndef OC_LAW_FIELDS_H
#define OC_LAW_FIELDS_H

#include "glue/fmu_fields.h"
#include "law/contact_law.h"
#include "law/law_table.h"

/* The parameters in the rows' order, each in its table's range; the
 * sliding rule a u32. */
#define OC_PARAM_FIELD(name, vr, ...) FMU_F64(oc_params, name, #name, NULL, RANGE, vr),
#define OC_RULE_FIELD(name, vr, ...) FMU_U32(oc_params, rule, #name, NULL, RANGE, vr),
static const fmu_field OC_PARAM_FIELD_LIST[] = {OC_LAW_ROWS(OC_PARAM_FIELD, OC_RULE_FIELD)};
#undef OC_PARAM_FIELD
#undef OC_RULE_FIELD
static const fmu_fields OC_PARAMS_FIELDS = FMU_FIELDS(OC_PARAM_FIELD_LIST, oc_params);

/* A committed state: the step's inputs, the force's yield coordinates, the
 * slip and the dissipated energy.  Checked by oc_state_check against the
 * law, once the parameters are known. */
static const fmu_field OC_STATE_FIELD_LIST[] = {FMU_F64(oc_state, u[0], "u1", NULL, NONE, 0),
                                                FMU_F64(oc_state, u[1], "u2", NULL, NONE, 0),
                                                FMU_F64(oc_state, N, "N", NULL, NONE, 0),
                                                FMU_F64(oc_state, a[0], "a1", NULL, NONE, 0),
                                                FMU_F64(oc_state, a[1], "a2", NULL, NONE, 0),
                                                FMU_F64(oc_state, s[0], "s1", NULL, NONE, 0),
                                                FMU_F64(oc_state, s[1], "s2", NULL, NONE, 0),
                                                FMU_F64(oc_state, energy, "energy", NULL, NONE, 0)};
static const fmu_fields OC_STATE_FIELDS = FMU_FIELDS(OC_STATE_FIELD_LIST, oc_state);

#endif
