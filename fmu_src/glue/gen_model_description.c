/* Writes a model's FMI 2.0 and FMI 3.0 model descriptions, the FMI 3.0
 * buildDescription.xml and documentation/index.html from its variable table,
 * so that the XML, the documentation and the C value references cannot drift
 * apart.  Compiled once per model with -DFMU_TABLE_HEADER="<table header>".
 *
 * The guid / instantiationToken is computed here from the content of both
 * model descriptions written without it (FNV-1a, 128 bits as two 64-bit
 * lanes, formatted as a GUID), and `token` writes it as the header
 * fmu_token.h that the binary is compiled with: description and binary agree
 * by construction, and any change of the description changes the token.
 * The version comes from the build (-DFMU_VERSION="...").
 *
 * Usage: gen_model_description fmi2|fmi3|build|html2|html3|token|manifest [OUTPUT]   (stdout
 * without OUTPUT) */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FMU_GENERATOR 1 /* the table header must not include the token this computes */
#include FMU_TABLE_HEADER
#ifdef FMU_MODEL_HEADER
#include FMU_MODEL_HEADER      /* the serialized state's field list, FMU_STATE_FIELDS */
#include "glue/fmu_instance.h" /* its header's */
#endif

#ifndef FMU_VERSION
#error "compile with -DFMU_VERSION=\"x.y.z\" (CMake passes the version of the file VERSION)"
#endif

#define STR(x) #x
#define XSTR(x) STR(x)

typedef struct {
    const char *name, *type, *causality, *variability, *initial, *unit, *display, *desc;
    unsigned int vr;
    double start, min, max;
    int grouped; /* a row of the table's group (FMU_GROUP: the law's parameters) */
} row;

#ifndef FMU_PROVIDES_DERIVATIVES
#define FMU_PROVIDES_DERIVATIVES 1
#endif
#define TF(x) ((x) ? "true" : "false")

#define ROW(name, vr, type, caus, var, init, start, lo, hi, unit, disp, desc)                      \
    {#name, #type, #caus, #var, #init, unit, disp, desc, vr, start, lo, hi, 0},
#define GROUP_ROW(name, vr, type, caus, var, init, start, lo, hi, unit, disp, desc)                \
    {#name, #type, #caus, #var, #init, unit, disp, desc, vr, start, lo, hi, 1},
/* A table may mark a group of rows (FMU_GROUPED_VARIABLES(X, G), named
 * FMU_GROUP): the manifest lists it for the package. */
#ifdef FMU_GROUPED_VARIABLES
static const row ROWS[] = {FMU_GROUPED_VARIABLES(ROW, GROUP_ROW)};
#else
#define FMU_GROUP ""
static const row ROWS[] = {FMU_VARIABLES(ROW)};
#endif
#undef ROW
#undef GROUP_ROW
enum { NROWS = sizeof ROWS / sizeof ROWS[0] };

typedef struct {
    const char *name, *desc;
    int value;
} item;
typedef struct {
    const char *name;
    const item *items;
    int n;
} enum_type;
#ifdef FMU_ENUM_TYPES
#define ITEM(name, value, desc) {#name, desc, value},
#define ENUM_ITEMS(type, ITEMS) static const item ITEMS_##type[] = {ITEMS(ITEM)};
FMU_ENUM_TYPES(ENUM_ITEMS)
#define ENUM_ROW(type, ITEMS) {#type, ITEMS_##type, (int)(sizeof ITEMS_##type / sizeof(item))},
static const enum_type ENUMS[] = {FMU_ENUM_TYPES(ENUM_ROW)};
enum { NENUMS = sizeof ENUMS / sizeof ENUMS[0] };
#else
static const enum_type ENUMS[1];
enum { NENUMS = 0 };
#endif

#define SRC(f) #f,
static const char *const SOURCES[] = {FMU_SOURCES(SRC) FMU_GLUE_SOURCES(SRC)};
#undef SRC
enum { NSOURCES = sizeof SOURCES / sizeof SOURCES[0] };

/* SI units this project's models use: name, base-unit exponents. */
static const struct {
    const char *name, *base, *display;
} UNITS[] = {
    {"s", "s=\"1\"", NULL},
    {"m", "m=\"1\"", NULL},
    {"kg", "kg=\"1\"", NULL},
    {"N", "kg=\"1\" m=\"1\" s=\"-2\"", NULL},
    {"N/m", "kg=\"1\" s=\"-2\"", NULL},
    {"N.s/m", "kg=\"1\" s=\"-1\"", NULL},
    {"N/m3", "kg=\"1\" m=\"-2\" s=\"-2\"", NULL},
    {"N.s/m3", "kg=\"1\" m=\"-2\" s=\"-1\"", NULL},
    {"J", "kg=\"1\" m=\"2\" s=\"-2\"", NULL},
    {"N.m", "kg=\"1\" m=\"2\" s=\"-2\"", NULL},
    {"m/s", "m=\"1\" s=\"-1\"", NULL},
    {"m/s2", "m=\"1\" s=\"-2\"", NULL},
    {"rad", "rad=\"1\"", "<DisplayUnit name=\"deg\" factor=\"57.29577951308232\"/>"},
};

static void esc(FILE *f, const char *s) {
    for (; *s; ++s) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*s, f);
        }
    }
}

/* The shortest decimal that reads back as the same double. */
static void num(char *buf, size_t n, double x) {
    for (int prec = 15; prec <= 17; ++prec) {
        snprintf(buf, n, "%.*g", prec, x);
        if (strtod(buf, NULL) == x) return;
    }
}

static int is(const char *a, const char *b) { return strcmp(a, b) == 0; }
static int is_int(const row *r) { return !is(r->type, "Float64"); }
static int is_enum(const row *r) { return is_int(r) && !is(r->type, "Int32"); }
static int has_start(const row *r) {
    return !is(r->initial, "calculated") && !is(r->causality, "independent");
}

static void value_attrs(FILE *f, const row *r) {
    char b[64];
    if (*r->unit && !is(r->unit, "1")) fprintf(f, " unit=\"%s\"", r->unit);
    if (*r->display) fprintf(f, " displayUnit=\"%s\"", r->display);
    if (isfinite(r->min)) {
        if (is_int(r))
            fprintf(f, " min=\"%d\"", (int)r->min);
        else {
            num(b, sizeof b, r->min);
            fprintf(f, " min=\"%s\"", b);
        }
    }
    if (isfinite(r->max)) {
        if (is_int(r))
            fprintf(f, " max=\"%d\"", (int)r->max);
        else {
            num(b, sizeof b, r->max);
            fprintf(f, " max=\"%s\"", b);
        }
    }
    if (has_start(r)) {
        if (is_int(r))
            fprintf(f, " start=\"%d\"", (int)r->start);
        else {
            num(b, sizeof b, r->start);
            fprintf(f, " start=\"%s\"", b);
        }
    }
}

static void unit_definitions(FILE *f) {
    fputs("  <UnitDefinitions>\n", f);
    for (size_t u = 0; u < sizeof UNITS / sizeof UNITS[0]; ++u) {
        int used = 0;
        for (int i = 0; i < NROWS; ++i) used |= is(ROWS[i].unit, UNITS[u].name);
        if (!used) continue;
        fprintf(f, "    <Unit name=\"%s\">\n      <BaseUnit %s/>\n", UNITS[u].name, UNITS[u].base);
        if (UNITS[u].display) fprintf(f, "      %s\n", UNITS[u].display);
        fputs("    </Unit>\n", f);
    }
    fputs("  </UnitDefinitions>\n\n", f);
}

static void log_categories(FILE *f) {
    fputs("  <LogCategories>\n"
          "    <Category name=\"logStatusError\" description=\"Errors: rejected calls and why\"/>\n"
          "    <Category name=\"logStatusWarning\" description=\"Warnings\"/>\n"
          "    <Category name=\"logCalls\" description=\"Trace of FMI function calls\"/>\n"
          "  </LogCategories>\n\n"
          "  <DefaultExperiment " FMU_DEFAULT_EXPERIMENT "/>\n\n",
          f);
}

static void header(FILE *f, const char *version) {
    fprintf(f,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<!-- Generated from the variable table by gen_model_description: edit the table, "
            "not this file. -->\n"
            "<fmiModelDescription\n  fmiVersion=\"%s\"\n  modelName=\"%s\"\n",
            version, FMU_MODEL_NAME);
}

static void common_attrs(FILE *f, const char *license_path) {
    fputs("  description=\"", f);
    esc(f, FMU_DESCRIPTION);
    fprintf(f,
            "\"\n  author=\"the orthocontact developers\"\n  version=\"%s\"\n"
            "  copyright=\"Copyright (c) 2026 the orthocontact developers\"\n"
            "  license=\"BSD-2-Clause (see %s)\"\n"
            "  generationTool=\"orthocontact gen_model_description\"\n"
            "  variableNamingConvention=\"flat\"",
            FMU_VERSION, license_path);
}

/* What each output depends on, from the table's FMU_DEPENDENCIES(D),
 * D(output, "step knowns", "initialization knowns"): lists of "name" (kind
 * dependent) or "name:kind".  check_dependencies refuses a table that leaves
 * an output out or names what is not a known of the mode. */
typedef struct {
    const char *output, *step, *init;
} dep;
#ifndef FMU_DEPENDENCIES
#error "the table must declare FMU_DEPENDENCIES(D): every output's dependencies in both modes"
#endif
#define DEP(out, step, init) {#out, step, init},
static const dep DEPS[] = {FMU_DEPENDENCIES(DEP)};
#undef DEP
enum { NDEPS = sizeof DEPS / sizeof DEPS[0] };

static const dep *deps_of(const char *output) {
    for (int k = 0; k < NDEPS; ++k)
        if (is(DEPS[k].output, output)) return &DEPS[k];
    return NULL;
}

/* The k-th item of a space-separated list into name and kind (dependent
 * when the item has no ":kind"); 0 when there is no k-th token. */
static int list_item(const char *list, int k, char name[64], char kind[16]) {
    const char *p = list;
    for (;;) {
        while (*p == ' ') ++p;
        if (!*p) return 0;
        const char *end = p;
        while (*end && *end != ' ') ++end;
        if (k-- == 0) {
            const char *colon = memchr(p, ':', (size_t)(end - p));
            const char *name_end = colon ? colon : end;
            snprintf(name, 64, "%.*s", (int)(name_end - p), p);
            if (colon)
                snprintf(kind, 16, "%.*s", (int)(end - colon - 1), colon + 1);
            else
                snprintf(kind, 16, "dependent");
            return 1;
        }
        p = end;
    }
}

/* The kind with which `list` names `known`, or NULL if it does not. */
static const char *kind_in(const char *list, const char *known) {
    static char kind[16];
    char name[64];
    for (int k = 0; list_item(list, k, name, kind); ++k)
        if (is(name, known)) return kind;
    return NULL;
}

static const row *row_named(const char *name) {
    for (int i = 0; i < NROWS; ++i)
        if (is(ROWS[i].name, name)) return &ROWS[i];
    return NULL;
}

/* FMI 3.0 only (the table's FMU_ARRAYS(A), FMU_STRUCTURAL_PARAMETERS):
 * array outputs whose dimensions are the structural parameters, in order,
 * each element depending on what the scalar output `like` depends on. */
typedef struct {
    const char *name, *type, *unit, *like, *desc;
    unsigned int vr;
} array_row;
#ifdef FMU_ARRAYS
#define ARRAY_ROW(name, vr, type, unit, like, desc) {#name, #type, unit, #like, desc, vr},
static const array_row ARRAYS[] = {FMU_ARRAYS(ARRAY_ROW)};
#undef ARRAY_ROW
enum { NARRAYS = sizeof ARRAYS / sizeof ARRAYS[0] };
#else
static const array_row ARRAYS[1];
enum { NARRAYS = 0 };
#endif
#ifndef FMU_STRUCTURAL_PARAMETERS
#define FMU_STRUCTURAL_PARAMETERS ""
#endif
/* Whether the table names any: a variable, not the literal, in a condition
 * (clang warns of a constant operand of && and ||). */
static const int HAS_STRUCTURAL = sizeof(FMU_STRUCTURAL_PARAMETERS) > 1;

static int is_structural(const row *r) {
    return kind_in(FMU_STRUCTURAL_PARAMETERS, r->name) != NULL;
}

/* A structural parameter is an array dimension here, and FMI 3.0 (its
 * Dimension element, section 2.4.7) wants a dimension's variable to be a
 * UInt64 constant or structural parameter with start > 0: written so in
 * FMI 3.0 whatever its table type, which FMI 2.0 keeps (an Integer).  The
 * glue serves it through the UInt64 functions (fmu_model.h, FMU_UINT64). */
#define STRUCTURAL_TYPE_FMI3 "UInt64"

/* A known of the mode: at a communication point the inputs (the time moves
 * with doStep as the hidden state does: the importer sets neither); in
 * initialization mode also the start time and every variable with
 * initial = exact, the knowns FMI 2.0 and 3.0 name. */
static int is_known(const row *r, int init) {
    if (is(r->causality, "input")) return 1;
    return init && (is(r->causality, "independent") || is(r->initial, "exact"));
}

/* FMI 2.0 and 3.0: constant (c v) and, at communication points only, fixed,
 * tunable, discrete (p v) are for floating-point unknowns; dependent for any. */
static int kind_allowed(const char *kind, const row *unknown, int init) {
    if (is(kind, "dependent")) return 1;
    if (is_int(unknown)) return 0;
    if (is(kind, "constant")) return 1;
    return !init && (is(kind, "fixed") || is(kind, "tunable") || is(kind, "discrete"));
}

static int check_dependencies(void) {
    int bad = 0;
    for (int a = 0; a < NARRAYS; ++a)
        if (!deps_of(ARRAYS[a].like)) {
            fprintf(stderr,
                    "gen_model_description: array %s is like %s, not an output with "
                    "dependencies\n",
                    ARRAYS[a].name, ARRAYS[a].like);
            bad = 1;
        }
    {
        char name[64], kind[16];
        for (int k = 0; list_item(FMU_STRUCTURAL_PARAMETERS, k, name, kind); ++k) {
            const row *r = row_named(name);
            /* an Int32 of the table (FMI 2.0's Integer) becomes FMI 3.0's UInt64:
             * min >= 1 makes every value it can take, the start too, > 0 */
            if (!r || !is(r->type, "Int32") || !is(r->causality, "parameter") || r->min < 1 ||
                !(r->start >= r->min && r->start <= r->max) || !is(r->initial, "exact") ||
                !(is(r->variability, "fixed") || is(r->variability, "tunable"))) {
                fprintf(stderr,
                        "gen_model_description: structural parameter %s is not an Int32 "
                        "parameter, fixed or tunable, initial exact, with min >= 1 and its "
                        "start in [min, max]\n",
                        name);
                bad = 1;
            }
        }
    }
    for (int i = 0; i < NROWS; ++i)
        if (is(ROWS[i].causality, "output") && !deps_of(ROWS[i].name)) {
            fprintf(stderr, "gen_model_description: output %s has no FMU_DEPENDENCIES row\n",
                    ROWS[i].name);
            bad = 1;
        }
    for (int k = 0; k < NDEPS; ++k) {
        const row *out = row_named(DEPS[k].output);
        if (!out || !is(out->causality, "output")) {
            fprintf(stderr, "gen_model_description: FMU_DEPENDENCIES names %s, not an output\n",
                    DEPS[k].output);
            bad = 1;
            continue;
        }
        for (int init = 0; init < 2; ++init) {
            const char *list = init ? DEPS[k].init : DEPS[k].step;
            char name[64], kind[16];
            for (int t = 0; list_item(list, t, name, kind); ++t) {
                const row *r = row_named(name);
                int seen = 0;
                char other[64], other_kind[16];
                for (int u = 0; list_item(list, u, other, other_kind); ++u) seen += is(other, name);
                const char *why = !r                               ? "no such variable"
                                  : !is_known(r, init)             ? "not a known of this mode"
                                  : !kind_allowed(kind, out, init) ? "a kind not allowed here"
                                  : seen > 1                       ? "named twice"
                                                                   : NULL;
                if (why) {
                    fprintf(stderr, "gen_model_description: %s depends on %s:%s in %s: %s\n",
                            DEPS[k].output, name, kind, init ? "initialization" : "step mode", why);
                    bad = 1;
                }
            }
        }
    }
    return bad;
}

/* The dependencies and their kinds of `output` in a mode, as the two
 * attributes, in the order of the variables (by index or value reference). */
static void dependencies(FILE *f, const char *output, int init, int by_index) {
    const dep *d = deps_of(output);
    const char *list = init ? d->init : d->step;
    int first = 1;
    fputs(" dependencies=\"", f);
    for (int i = 0; i < NROWS; ++i)
        if (kind_in(list, ROWS[i].name)) {
            fprintf(f, first ? "%u" : " %u", by_index ? (unsigned)(i + 1) : ROWS[i].vr);
            first = 0;
        }
    fputs("\" dependenciesKind=\"", f);
    first = 1;
    for (int i = 0; i < NROWS; ++i) {
        const char *kind = kind_in(list, ROWS[i].name);
        if (kind) {
            fprintf(f, first ? "%s" : " %s", kind);
            first = 0;
        }
    }
    fputc('"', f);
}

static void fmi2(FILE *f, const char *token) {
    header(f, "2.0");
    fprintf(f, "  guid=\"%s\"\n", token);
    common_attrs(f, "documentation/LICENSE.txt");
    fprintf(f,
            "\n  numberOfEventIndicators=\"0\">\n\n"
            "  <CoSimulation\n    modelIdentifier=\"%s\"\n"
            "    canHandleVariableCommunicationStepSize=\"true\"\n"
            "    canGetAndSetFMUstate=\"true\"\n    canSerializeFMUstate=\"true\"\n"
            "    providesDirectionalDerivative=\"%s\">\n    <SourceFiles>\n",
            FMU_MODEL_IDENTIFIER, TF(FMU_PROVIDES_DERIVATIVES));
    for (int i = 0; i < NSOURCES; ++i) fprintf(f, "      <File name=\"%s\"/>\n", SOURCES[i]);
    fputs("      <File name=\"glue/fmi2_glue.c\"/>\n    </SourceFiles>\n  </CoSimulation>\n\n", f);
    unit_definitions(f);
    log_categories(f);
    fputs("  <ModelVariables>\n", f);
    for (int i = 0; i < NROWS; ++i) {
        const row *r = &ROWS[i];
        fprintf(f, "    <!-- index %d -->\n    <ScalarVariable name=\"%s\" valueReference=\"%u\"",
                i + 1, r->name, r->vr);
        fprintf(f, " causality=\"%s\" variability=\"%s\"", r->causality, r->variability);
        if (*r->initial) fprintf(f, " initial=\"%s\"", r->initial);
        fputs(" description=\"", f);
        esc(f, r->desc);
        fprintf(f, "\">\n      <%s", is_int(r) ? "Integer" : "Real");
        value_attrs(f, r);
        fputs("/>\n    </ScalarVariable>\n", f);
    }
    fputs("  </ModelVariables>\n\n  <ModelStructure>\n    <Outputs>\n", f);
    for (int i = 0; i < NROWS; ++i)
        if (is(ROWS[i].causality, "output")) {
            fprintf(f, "      <Unknown index=\"%d\"", i + 1);
            dependencies(f, ROWS[i].name, 0, 1);
            fputs("/>\n", f);
        }
    fputs("    </Outputs>\n    <InitialUnknowns>\n", f);
    for (int i = 0; i < NROWS; ++i)
        if (is(ROWS[i].causality, "output")) {
            fprintf(f, "      <Unknown index=\"%d\"", i + 1);
            dependencies(f, ROWS[i].name, 1, 1);
            fputs("/>\n", f);
        }
    fputs("    </InitialUnknowns>\n  </ModelStructure>\n\n</fmiModelDescription>\n", f);
}

static void fmi3(FILE *f, const char *token) {
    header(f, "3.0");
    fprintf(f, "  instantiationToken=\"%s\"\n", token);
    common_attrs(f, "documentation/licenses/LICENSE.txt");
    fprintf(f,
            ">\n\n  <CoSimulation\n    modelIdentifier=\"%s\"\n"
            "    canHandleVariableCommunicationStepSize=\"true\"\n"
            "    canGetAndSetFMUState=\"true\"\n    canSerializeFMUState=\"true\"\n"
            "    providesDirectionalDerivatives=\"%s\"\n"
            "    providesAdjointDerivatives=\"%s\"\n    hasEventMode=\"false\"/>\n\n",
            FMU_MODEL_IDENTIFIER, TF(FMU_PROVIDES_DERIVATIVES), TF(FMU_PROVIDES_DERIVATIVES));
    unit_definitions(f);
    if (NENUMS > 0) {
        fputs("  <TypeDefinitions>\n", f);
        for (int e = 0; e < NENUMS; ++e) {
            fprintf(f, "    <EnumerationType name=\"%s\">\n", ENUMS[e].name);
            for (int k = 0; k < ENUMS[e].n; ++k) {
                fprintf(f, "      <Item name=\"%s\" value=\"%d\" description=\"",
                        ENUMS[e].items[k].name, ENUMS[e].items[k].value);
                esc(f, ENUMS[e].items[k].desc);
                fputs("\"/>\n", f);
            }
            fputs("    </EnumerationType>\n", f);
        }
        fputs("  </TypeDefinitions>\n\n", f);
    }
    log_categories(f);
    fputs("  <ModelVariables>\n", f);
    for (int i = 0; i < NROWS; ++i) {
        const row *r = &ROWS[i];
        const char *el = is_structural(r) ? STRUCTURAL_TYPE_FMI3
                         : is_enum(r)     ? "Enumeration"
                                          : r->type;
        fprintf(f, "    <%s name=\"%s\" valueReference=\"%u\"", el, r->name, r->vr);
        if (is_enum(r)) fprintf(f, " declaredType=\"%s\"", r->type);
        fprintf(f, " causality=\"%s\" variability=\"%s\"",
                is_structural(r) ? "structuralParameter" : r->causality, r->variability);
        if (*r->initial) fprintf(f, " initial=\"%s\"", r->initial);
        fputs(" description=\"", f);
        esc(f, r->desc);
        fputc('"', f);
        value_attrs(f, r);
        fputs("/>\n", f);
    }
    for (int a = 0; a < NARRAYS; ++a) {
        const array_row *x = &ARRAYS[a];
        fprintf(f,
                "    <%s name=\"%s\" valueReference=\"%u\" causality=\"output\" "
                "variability=\"%s\" initial=\"calculated\" description=\"",
                x->type, x->name, x->vr, is(x->type, "Float64") ? "continuous" : "discrete");
        esc(f, x->desc);
        fputc('"', f);
        if (*x->unit && !is(x->unit, "1")) fprintf(f, " unit=\"%s\"", x->unit);
        fputs(">\n", f);
        char name[64], kind[16];
        for (int k = 0; list_item(FMU_STRUCTURAL_PARAMETERS, k, name, kind); ++k)
            fprintf(f, "      <Dimension valueReference=\"%u\"/>\n", row_named(name)->vr);
        fprintf(f, "    </%s>\n", x->type);
    }
    fputs("  </ModelVariables>\n\n  <ModelStructure>\n", f);
    for (int init = 0; init < 2; ++init) {
        const char *el = init ? "InitialUnknown" : "Output";
        for (int i = 0; i < NROWS; ++i)
            if (is(ROWS[i].causality, "output")) {
                fprintf(f, "    <%s valueReference=\"%u\"", el, ROWS[i].vr);
                dependencies(f, ROWS[i].name, init, 0);
                fputs("/>\n", f);
            }
        for (int a = 0; a < NARRAYS; ++a) {
            fprintf(f, "    <%s valueReference=\"%u\"", el, ARRAYS[a].vr);
            dependencies(f, ARRAYS[a].like, init, 0);
            fputs("/>\n", f);
        }
    }
    fputs("  </ModelStructure>\n\n</fmiModelDescription>\n", f);
}

static void build(FILE *f) {
    fprintf(f,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<!-- Generated by gen_model_description: how to compile sources/ into the "
            "binary. -->\n"
            "<fmiBuildDescription fmiVersion=\"3.0\">\n"
            "  <BuildConfiguration modelIdentifier=\"%s\">\n"
            "    <SourceFileSet language=\"C99\">\n",
            FMU_MODEL_IDENTIFIER);
    for (int i = 0; i < NSOURCES; ++i) fprintf(f, "      <SourceFile name=\"%s\"/>\n", SOURCES[i]);
    fputs("      <SourceFile name=\"glue/fmi3_glue.c\"/>\n    </SourceFileSet>\n"
          "    <Library name=\"m\" description=\"the C math library (Linux)\"/>\n"
          "  </BuildConfiguration>\n</fmiBuildDescription>\n",
          f);
}

/* Model documentation text with the FMI version's names put in: @SET@,
 * @GET@, @DOSTEP@, @DIRDER@, @REAL@ (the Float64 functions, the directional
 * derivative and the type of FMI 2.0 or 3.0). */
static void doc(FILE *f, const char *text, int v) {
    static const char *const KEYS[][3] = {
        {"@SET@", "fmi2SetReal", "fmi3SetFloat64"},
        {"@GET@", "fmi2GetReal", "fmi3GetFloat64"},
        {"@DOSTEP@", "fmi2DoStep", "fmi3DoStep"},
        {"@DIRDER@", "fmi2GetDirectionalDerivative", "fmi3GetDirectionalDerivative"},
        {"@REAL@", "Real", "Float64"}};
    while (*text) {
        int done = 0;
        for (size_t k = 0; k < sizeof KEYS / sizeof KEYS[0] && !done; ++k) {
            const size_t n = strlen(KEYS[k][0]);
            if (strncmp(text, KEYS[k][0], n) == 0) {
                fputs(KEYS[k][v == 2 ? 1 : 2], f);
                text += n;
                done = 1;
            }
        }
        if (!done) fputc(*text++, f);
    }
}

/* A value with its display unit beside it: rad also in degrees. */
static void value_cell(char *buf, size_t n, const row *r, double x) {
    char v[64];
    num(v, sizeof v, x);
    if (is(r->unit, "rad"))
        snprintf(buf, n, "%s (%.10g&deg;)", v, x * 57.29577951308232);
    else
        snprintf(buf, n, "%s", v);
}

/* The type of a variable as FMI version v names it. */
static const char *type_name(const row *r, int v, char *buf, size_t n) {
    if (v == 2) {
        snprintf(buf, n, "%s",
                 is(r->type, "Float64") ? "Real"
                 : is_enum(r)           ? "Integer (see below)"
                                        : "Integer");
    } else {
        snprintf(buf, n, "%s%s", is_enum(r) ? "Enumeration " : "",
                 is_structural(r) ? STRUCTURAL_TYPE_FMI3 : r->type);
    }
    return buf;
}

static void html(FILE *f, int v) {
    fprintf(
        f,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\">"
        "<title>%s (FMI "
        "%d.0)</title>\n<style>body{font-family:sans-serif;max-width:80em;margin:2em auto}"
        "table{border-collapse:collapse;font-size:90%%}td,th{border:1px solid #999;padding:2px 6px;"
        "text-align:left;vertical-align:top}code{background:#eee}</style></head>\n<body>\n"
        "<!-- Generated from the variable table by gen_model_description. -->\n"
        "<h1>%s %s: FMI %d.0 Co-Simulation</h1>\n<p>",
        FMU_MODEL_NAME, v, FMU_MODEL_NAME, FMU_VERSION, v);
    esc(f, FMU_DESCRIPTION);
    fprintf(f,
            ".</p>\n<p>This page describes the FMI %d.0 FMU; the FMI %d.0 one of the same "
            "version is built from the same sources and gives the same outputs bit for bit.</p>\n",
            v, v == 2 ? 3 : 2);
    doc(f, FMU_DOC_HTML, v); /* the table's text (glue/fmu_table.h) */
    fputs("<h2>Variables</h2>\n<table>\n<tr><th>name</th><th>vr</th><th>causality</th>"
          "<th>variability</th><th>type</th><th>unit</th><th>start</th><th>min</th><th>max</th>"
          "<th>description</th></tr>\n",
          f);
    for (int i = 0; i < NROWS; ++i) {
        const row *r = &ROWS[i];
        char s[96] = "", lo[96] = "", hi[96] = "", type[96];
        if (has_start(r)) value_cell(s, sizeof s, r, r->start);
        if (isfinite(r->min)) value_cell(lo, sizeof lo, r, r->min);
        if (isfinite(r->max)) value_cell(hi, sizeof hi, r, r->max);
        fprintf(f,
                "<tr><td><code>%s</code></td><td>%u</td><td>%s</td><td>%s</td><td>%s</td>"
                "<td>%s%s%s%s</td><td>%s</td><td>%s</td><td>%s</td><td>",
                r->name, r->vr, v == 3 && is_structural(r) ? "structuralParameter" : r->causality,
                r->variability, type_name(r, v, type, sizeof type), is(r->unit, "1") ? "" : r->unit,
                *r->display ? " (display " : "", r->display, *r->display ? ")" : "", s, lo, hi);
        esc(f, r->desc);
        fputs("</td></tr>\n", f);
    }
    for (int a = 0; v == 3 && a < NARRAYS; ++a) {
        fprintf(f,
                "<tr><td><code>%s</code></td><td>%u</td><td>output</td><td>%s</td>"
                "<td>%s[%s]</td><td>%s</td><td></td><td></td><td></td><td>",
                ARRAYS[a].name, ARRAYS[a].vr,
                is(ARRAYS[a].type, "Float64") ? "continuous" : "discrete", ARRAYS[a].type,
                FMU_STRUCTURAL_PARAMETERS, is(ARRAYS[a].unit, "1") ? "" : ARRAYS[a].unit);
        esc(f, ARRAYS[a].desc);
        fputs("</td></tr>\n", f);
    }
    fputs("</table>\n", f);
    if (v == 3 && HAS_STRUCTURAL)
        fputs("<p>Structural parameters (causality structuralParameter), settable in configuration "
              "mode as well as before initialization: <code>" FMU_STRUCTURAL_PARAMETERS "</code>, "
              "of type " STRUCTURAL_TYPE_FMI3 " (fmi3GetUInt64, fmi3SetUInt64) as the standard "
              "wants an array's dimension to be (Integer parameters in FMI 2.0). "
              "The arrays above are their shape, row-major (the last index fastest); "
              "fmi3GetFloat64 and fmi3GetInt32 take nValues, the number of values of all the "
              "variables asked for.</p>\n",
              f);
    for (int e = 0; e < NENUMS; ++e) {
        const char *var = "";
        for (int i = 0; i < NROWS; ++i)
            if (is(ROWS[i].type, ENUMS[e].name)) var = ROWS[i].name;
        if (v == 2)
            fprintf(f, "<h2>The Integer values of <code>%s</code></h2>\n<ul>\n", var);
        else
            fprintf(f, "<h2>Enumeration %s (<code>%s</code>)</h2>\n<ul>\n", ENUMS[e].name, var);
        for (int k = 0; k < ENUMS[e].n; ++k) {
            fprintf(f, "<li><code>%d</code> %s: ", ENUMS[e].items[k].value, ENUMS[e].items[k].name);
            esc(f, ENUMS[e].items[k].desc);
            fputs("</li>\n", f);
        }
        fputs("</ul>\n", f);
    }
    fputs(
        "<h2>How to cite</h2>\n<p>The law and the rig are those of A. Konyukhov, K. Schweizerhof, "
        "<i>On coupled models of anisotropic contact surfaces and their experimental "
        "validation</i>, "
        "report, Institut f&uuml;r Mechanik, Universit&auml;t Karlsruhe, 2007.  This FMU: the "
        "orthocontact developers, <i>orthocontact</i>, version ",
        f);
    fputs(FMU_VERSION, f);
    fputs(" (the repository's <code>CITATION.cff</code> holds both).</p>\n", f);
    fprintf(f,
            "<h2>License</h2>\n<p>BSD-2-Clause: see <code>%s</code> beside this page.</p>\n"
            "</body>\n</html>\n",
            v == 2 ? "LICENSE.txt" : "licenses/LICENSE.txt");
}

/* A JSON string: the table's texts are ASCII with no control characters
 * but quotes and backslashes are escaped all the same. */
static void json_str(FILE *f, const char *s) {
    fputc('"', f);
    for (; *s; ++s) {
        if (*s == '"' || *s == '\\') fputc('\\', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

/* A number, or null for none (an infinite bound). */
static void json_num(FILE *f, const row *r, double x) {
    char b[64];
    if (!isfinite(x))
        fputs("null", f);
    else if (is_int(r))
        fprintf(f, "%d", (int)x);
    else {
        num(b, sizeof b, x);
        fputs(b, f);
    }
}

#ifdef FMU_MODEL_HEADER
static void state_layout(FILE *f);
#endif

/* The manifest the Python package reads instead of typing the table's
 * facts: every variable with its columns, the enumerations' items and the
 * table's group (the law's parameters, in the table's order). */
static void manifest(FILE *f) {
    fputs("{\n  \"generated\": \"by gen_model_description from the variable table: edit the "
          "table, not this file\",\n  \"modelIdentifier\": ",
          f);
    json_str(f, FMU_MODEL_IDENTIFIER);
    fprintf(f, ",\n  \"version\": \"%s\",\n  \"providesDerivatives\": %s,\n  \"variables\": [\n",
            FMU_VERSION, TF(FMU_PROVIDES_DERIVATIVES));
    for (int i = 0; i < NROWS; ++i) {
        const row *r = &ROWS[i];
        fputs("    {\"name\": ", f);
        json_str(f, r->name);
        fprintf(f, ", \"valueReference\": %u, \"type\": ", r->vr);
        json_str(f, is_enum(r) ? "Enumeration" : r->type);
        fputs(", \"declaredType\": ", f);
        if (is_enum(r))
            json_str(f, r->type);
        else
            fputs("null", f);
        fputs(", \"causality\": ", f);
        json_str(f, r->causality);
        fputs(", \"variability\": ", f);
        json_str(f, r->variability);
        fputs(", \"initial\": ", f);
        json_str(f, r->initial);
        fputs(", \"unit\": ", f);
        json_str(f, is(r->unit, "1") ? "" : r->unit);
        fputs(", \"displayUnit\": ", f);
        json_str(f, r->display);
        fputs(", \"start\": ", f);
        if (has_start(r))
            json_num(f, r, r->start);
        else
            fputs("null", f);
        fputs(", \"min\": ", f);
        json_num(f, r, r->min);
        fputs(", \"max\": ", f);
        json_num(f, r, r->max);
        fputs(", \"group\": ", f);
        json_str(f, r->grouped ? FMU_GROUP : "");
        fputs(", \"description\": ", f);
        json_str(f, r->desc);
        fputs(i + 1 < NROWS ? "},\n" : "}\n", f);
    }
    fputs("  ],\n", f);
    if (NARRAYS > 0 || HAS_STRUCTURAL) {
        /* FMI 3.0 only: n1, n2 are structural parameters there, and the arrays */
        fputs("  \"fmi3\": {\"structuralType\": \"" STRUCTURAL_TYPE_FMI3 "\", "
              "\"structuralParameters\": [",
              f);
        char name[64], kind[16];
        for (int k = 0; list_item(FMU_STRUCTURAL_PARAMETERS, k, name, kind); ++k) {
            if (k) fputs(", ", f);
            json_str(f, name);
        }
        fputs("], \"arrays\": [\n", f);
        for (int a = 0; a < NARRAYS; ++a) {
            const array_row *x = &ARRAYS[a];
            fputs("    {\"name\": ", f);
            json_str(f, x->name);
            fprintf(f, ", \"valueReference\": %u, \"type\": ", x->vr);
            json_str(f, x->type);
            fputs(", \"unit\": ", f);
            json_str(f, is(x->unit, "1") ? "" : x->unit);
            fputs(", \"dimensions\": [", f);
            for (int k = 0; list_item(FMU_STRUCTURAL_PARAMETERS, k, name, kind); ++k) {
                if (k) fputs(", ", f);
                json_str(f, name);
            }
            fputs("], \"dependenciesOf\": ", f);
            json_str(f, x->like);
            fputs(", \"description\": ", f);
            json_str(f, x->desc);
            fputs(a + 1 < NARRAYS ? "},\n" : "}\n", f);
        }
        fputs("  ]},\n", f);
    }
#ifdef FMU_MODEL_HEADER
    state_layout(f);
#endif
    fputs("  \"enumerations\": {", f);
    for (int e = 0; e < NENUMS; ++e) {
        fputs(e ? ",\n    " : "\n    ", f);
        json_str(f, ENUMS[e].name);
        fputs(": {", f);
        for (int k = 0; k < ENUMS[e].n; ++k) {
            if (k) fputs(", ", f);
            json_str(f, ENUMS[e].items[k].name);
            fprintf(f, ": %d", ENUMS[e].items[k].value);
        }
        fputc('}', f);
    }
    fputs(NENUMS ? "\n  }\n}\n" : "}\n}\n", f);
}

#ifdef FMU_MODEL_HEADER
/* A record's fields as {"name": ..., "type": ...} items, a nested record's
 * flattened into them. */
static void field_items(FILE *f, const fmu_fields *list, int *first) {
    for (unsigned int i = 0; i < list->n; ++i) {
        const fmu_field *x = &list->field[i];
        if (x->type == FMU_FIELD_RECORD) {
            field_items(f, x->record, first);
            continue;
        }
        fputs(*first ? "{\"name\": " : ", {\"name\": ", f);
        json_str(f, x->name);
        fprintf(f, ", \"type\": \"%s\"}", x->type == FMU_FIELD_F64 ? "f64" : "u32");
        *first = 0;
    }
}

/* The serialized state's layout, from the model's field list: the glue's
 * header, then the parts, each a run of fields of one group (a record its
 * own part, repeated `count` times). */
static void state_layout(FILE *f) {
    static const char TAG[4] = FMU_STATE_TAG;
    fprintf(f, "  \"state\": {\"bytes\": %zu, \"format\": %d, \"tag\": \"%.4s\", \"header\": ",
            FMU_STATE_HEADER_BYTES + fmu_fields_size(&FMU_STATE_FIELDS), FMU_STATE_FORMAT, TAG);
    json_str(f, FMU_STATE_HEADER_LAYOUT);
    fprintf(f, ", \"headerBytes\": %d, \"parts\": [", FMU_STATE_HEADER_BYTES);
    const fmu_fields *L = &FMU_STATE_FIELDS;
    for (unsigned int i = 0; i < L->n;) {
        const fmu_field *x = &L->field[i];
        fputs(i ? ",\n    {\"part\": " : "\n    {\"part\": ", f);
        json_str(f, x->group);
        int first = 1;
        if (x->type == FMU_FIELD_RECORD) {
            fprintf(f, ", \"count\": %u, \"fields\": [", x->count);
            field_items(f, x->record, &first);
            ++i;
        } else {
            fputs(", \"count\": 1, \"fields\": [", f);
            unsigned int j = i;
            while (j < L->n && L->field[j].type != FMU_FIELD_RECORD &&
                   is(L->field[j].group, x->group))
                ++j;
            const fmu_fields run = {x, j - i, 0};
            field_items(f, &run, &first);
            i = j;
        }
        fputs("]}", f);
    }
    fputs("]},\n", f);
}
#endif

/* FNV-1a over everything written to f, in two lanes with different bases. */
static void hash_file(FILE *f, uint64_t h[2]) {
    rewind(f);
    int c;
    while ((c = fgetc(f)) != EOF)
        for (int k = 0; k < 2; ++k) h[k] = (h[k] ^ (uint64_t)(unsigned char)c) * 0x100000001b3ull;
}

static void compute_token(char token[39]) {
    uint64_t h[2] = {0xcbf29ce484222325ull, 0x84222325cbf29ce4ull};
    FILE *t = tmpfile();
    if (!t) {
        perror("tmpfile");
        exit(1);
    }
    fmi2(t, "");
    fmi3(t, "");
    hash_file(t, h);
    fclose(t);
    snprintf(token, 39, "{%08x-%04x-%04x-%04x-%012llx}", (unsigned)(h[0] >> 32),
             (unsigned)(h[0] >> 16) & 0xffffu, (unsigned)h[0] & 0xffffu,
             (unsigned)(h[1] >> 48) & 0xffffu, (unsigned long long)(h[1] & 0xffffffffffffull));
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: %s fmi2|fmi3|build|html2|html3|token|manifest [OUTPUT]\n", argv[0]);
        return 2;
    }
    if (check_dependencies()) return 1;
    char token[39];
    compute_token(token);
    FILE *f = stdout;
    if (argc > 2 && !(f = fopen(argv[2], "w"))) {
        perror(argv[2]);
        return 1;
    }
    if (is(argv[1], "fmi2"))
        fmi2(f, token);
    else if (is(argv[1], "fmi3"))
        fmi3(f, token);
    else if (is(argv[1], "token"))
        fprintf(f,
                "/* Generated by gen_model_description from the model descriptions' content. */\n"
                "#ifndef FMU_TOKEN_H\n#define FMU_TOKEN_H\n"
                "#define FMU_TOKEN \"%s\"\n#define FMU_GUID FMU_TOKEN\n#endif\n",
                token);
    else if (is(argv[1], "build"))
        build(f);
    else if (is(argv[1], "html2"))
        html(f, 2);
    else if (is(argv[1], "html3"))
        html(f, 3);
    else if (is(argv[1], "manifest"))
        manifest(f);
    else {
        fprintf(stderr, "unknown output %s\n", argv[1]);
        return 2;
    }
    if (f != stdout) fclose(f);
    return 0;
}
