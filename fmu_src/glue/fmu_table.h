/*
 * What every model's table (fmu_src/models/<Model>/table.h) is made of.
 * gen_model_description writes both model descriptions (FMI 2.0 and 3.0),
 * the FMI 3.0 buildDescription.xml, documentation/index.html and the
 * package's manifest variables/<Model>.json from a table, and the C code
 * takes value references, types, start values and min/max from it.
 *
 * A table defines:
 *   FMU_MODEL_NAME, FMU_MODEL_IDENTIFIER, FMU_DESCRIPTION, FMU_STATE_TAG
 *     (the first bytes of its serialized states), FMU_DEFAULT_EXPERIMENT;
 *   FMU_SOURCES(S): its sources under fmu_src/ besides the glue's (below:
 *     FMU_GLUE_SOURCES) and the version's (CMake's fmu_add reads the list;
 *     the headers of their folders ship with them);
 *   its rows, ROWS(X, L): its variables, one row each, in the order of
 *     the model descriptions, value reference 0 the independent variable
 *     time; a row is X(name, vr, type, causality, variability, initial,
 *     start, min, max, unit, displayUnit, description), the law's rows
 *     (law/law_table.h) L(...) alike:
 *       type: Float64, Int32 or the name of an enumeration type of
 *             FMU_ENUM_TYPES (an Integer with min/max in FMI 2.0, an
 *             Enumeration in FMI 3.0);
 *       initial: exact or calculated ("calculated" entries have no start);
 *       min, max: numbers (NO_MIN / NO_MAX for none); the model refuses
 *             values outside them;
 *     its tail, last: FMU_TABLE_ROWS the name of ROWS, FMU_VR_PREFIX its
 *     value references' prefix, then glue/fmu_table_tail.inc, which
 *     defines FMU_VARIABLES(X), FMU_GROUPED_VARIABLES(X, L) with FMU_GROUP
 *     (the law's rows, which the manifest names) and the value references'
 *     enumerators;
 *   FMU_DEPENDENCIES(D): what each output depends on, D(output, step
 *     mode, initialization), each a list of the knowns it is computed from,
 *     "name" (no particular structure) or "name:kind"; gen_model_description
 *     refuses an output without its row and a name that is not a known of
 *     the mode;
 *   FMU_MODEL_HEADER: the model's header (its struct and FMU_STATE_FIELDS,
 *     the field list of its serialized state: glue/fmu_fields.h), from
 *     which the manifest says the state's layout;
 *   optionally FMU_ENUM_TYPES(T), FMU_ARRAYS(A) and
 *     FMU_STRUCTURAL_PARAMETERS (FMI 3.0 arrays), FMU_PROVIDES_DERIVATIVES;
 *   for the generator only (#ifdef FMU_GENERATOR), FMU_DOC_HTML: the
 *     model's part of documentation/index.html.
 * Its rows are grouped in macros of a few rows each (the inputs, the
 * outputs, ...), ROWS listing the groups in order.
 */
#ifndef FMU_TABLE_H
#define FMU_TABLE_H

#include <math.h>

#define NO_MIN (-HUGE_VAL)
#define NO_MAX HUGE_VAL

/* A row macro that drops its row: FMU_NO_ROW for the rows a use leaves out. */
#define FMU_NO_ROW(...)

/* A row's name and a space: "mu1 mu2 ... " from rows, for a list of knowns. */
#define FMU_NAME_SPACE(name, ...) #name " "

/* The glue's sources, every model's after its own FMU_SOURCES (and before
 * the version's, glue/fmi2_glue.c or glue/fmi3_glue.c): the one list of
 * them, which CMake's fmu_add reads and gen_model_description names in
 * the model descriptions.  One S(...) a line, each an area of the glue. */
/* clang-format off */
#define FMU_GLUE_SOURCES(S)                                                                        \
    S(glue/fmu_values.c)        /* variables: lookup, set, get; messages */                        \
    S(glue/fmu_jacobian.c)      /* directional derivatives */                                      \
    S(glue/fmu_instance.c)      /* the instance, its log and its phases */                         \
    S(glue/fmu_start_values.c)  /* start values from the resources */                              \
    S(glue/fmu_fields.c)        /* a serialized state's field lists */                             \
    S(glue/fmu_state.c)         /* the serialized state, the FMU-state functions */
/* clang-format on */

#endif
