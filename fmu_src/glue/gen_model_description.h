/*
 * The model-description generator's parts (gen_model_description*.c):
 * gen_model_description.c includes the model's table and gives its facts
 * as data, GEN; gen_model_description_common.c reads them (names, lists,
 * numbers and the dependencies' checks), gen_model_description_xml.c writes
 * the model descriptions and buildDescription.xml,
 * gen_model_description_html.c documentation/index.html and
 * gen_model_description_manifest.c the package's manifest.
 */
#ifndef GEN_MODEL_DESCRIPTION_H
#define GEN_MODEL_DESCRIPTION_H

#include <stdio.h>

#include "glue/fmu_fields.h"

typedef struct {
    const char *name, *type, *causality, *variability, *initial, *unit, *display, *desc;
    unsigned int vr;
    double start, min, max;
    int grouped; /* a row of the table's group (FMU_GROUP: the law's parameters) */
} row;

typedef struct {
    const char *name, *desc;
    int value;
} item;
typedef struct {
    const char *name;
    const item *items;
    int n;
} enum_type;

/* What each output depends on, from the table's FMU_DEPENDENCIES(D),
 * D(output, "step knowns", "initialization knowns"): lists of "name" (kind
 * dependent) or "name:kind".  check_dependencies refuses a table that leaves
 * an output out or names what is not a known of the mode. */
typedef struct {
    const char *output, *step, *init;
} dep;

/* FMI 3.0 only (the table's FMU_ARRAYS(A), FMU_STRUCTURAL_PARAMETERS):
 * array outputs whose dimensions are the structural parameters, in order,
 * each element depending on what the scalar output `like` depends on. */
typedef struct {
    const char *name, *type, *unit, *like, *desc;
    unsigned int vr;
} array_row;

/* A model's facts as its table states them (gen_model_description.c). */
typedef struct {
    const char *name, *identifier, *description, *default_experiment, *doc_html, *version;
    const char *group;      /* FMU_GROUP, the name of the table's grouped rows */
    const char *structural; /* FMU_STRUCTURAL_PARAMETERS, "" for none */
    int provides_derivatives;
    const row *rows;
    int n_rows;
    const enum_type *enums;
    int n_enums;
    const dep *deps;
    int n_deps;
    const array_row *arrays;
    int n_arrays;
    const char *const *sources; /* the model's and the glue's, under fmu_src/ */
    int n_sources;
    const fmu_fields *state; /* FMU_STATE_FIELDS; NULL without FMU_MODEL_HEADER */
    char tag[4];             /* FMU_STATE_TAG */
} gen_model;
extern const gen_model GEN;

#define ROWS (GEN.rows)
#define NROWS (GEN.n_rows)
#define ENUMS (GEN.enums)
#define NENUMS (GEN.n_enums)
#define DEPS (GEN.deps)
#define NDEPS (GEN.n_deps)
#define ARRAYS (GEN.arrays)
#define NARRAYS (GEN.n_arrays)
#define SOURCES (GEN.sources)
#define NSOURCES (GEN.n_sources)
/* Whether the table names any structural parameter. */
#define HAS_STRUCTURAL (GEN.structural[0] != '\0')
#define TF(x) ((x) ? "true" : "false")

/* A structural parameter is an array dimension here, and FMI 3.0 (its
 * Dimension element, section 2.4.7) wants a dimension's variable to be a
 * UInt64 constant or structural parameter with start > 0: written so in
 * FMI 3.0 whatever its table type, which FMI 2.0 keeps (an Integer).  The
 * glue serves it through the UInt64 functions (fmu_model.h, FMU_UINT64). */
#define STRUCTURAL_TYPE_FMI3 "UInt64"

/* gen_model_description_common.c */
void esc(FILE *f, const char *s);
void num(char *buf, size_t n, double x);
int is(const char *a, const char *b);
int is_int(const row *r);
int is_enum(const row *r);
int has_start(const row *r);
const dep *deps_of(const char *output);
int list_item(const char *list, int k, char name[64], char kind[16]);
const char *kind_in(const char *list, const char *known);
const row *row_named(const char *name);
int is_structural(const row *r);
int check_dependencies(void);
void json_str(FILE *f, const char *s);
void json_num(FILE *f, const row *r, double x);
/* gen_model_description_xml.c */
void fmi2(FILE *f, const char *token);
void fmi3(FILE *f, const char *token);
void build(FILE *f);
/* gen_model_description_html.c */
void html(FILE *f, int v);
/* gen_model_description_manifest.c */
void manifest(FILE *f);

#endif
