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
 * This part includes the table and gives its facts as data (GEN: the parts
 * of gen_model_description.h write from them), computes the token and
 * dispatches; its other parts are compiled with it, gen_model_description*.c.
 *
 * Usage: gen_model_description fmi2|fmi3|build|html2|html3|token|manifest [OUTPUT]   (stdout
 * without OUTPUT) */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FMU_GENERATOR 1 /* the table header must not include the token this computes */
#include FMU_TABLE_HEADER
#ifdef FMU_MODEL_HEADER
#include FMU_MODEL_HEADER /* the serialized state's field list, FMU_STATE_FIELDS */
#endif

#include "glue/gen_model_description.h"

#ifndef FMU_VERSION
#error "compile with -DFMU_VERSION=\"x.y.z\" (CMake passes the version of the file VERSION)"
#endif

/* The table's facts as data (GEN), which the generator's other parts read. */

#ifndef FMU_PROVIDES_DERIVATIVES
#define FMU_PROVIDES_DERIVATIVES 1
#endif

#define ROW(name, vr, type, caus, var, init, start, lo, hi, unit, disp, desc)                      \
    {#name, #type, #caus, #var, #init, unit, disp, desc, vr, start, lo, hi, 0},
#define GROUP_ROW(name, vr, type, caus, var, init, start, lo, hi, unit, disp, desc)                \
    {#name, #type, #caus, #var, #init, unit, disp, desc, vr, start, lo, hi, 1},
/* A table may mark a group of rows (FMU_GROUPED_VARIABLES(X, G), named
 * FMU_GROUP): the manifest lists it for the package. */
#ifdef FMU_GROUPED_VARIABLES
static const row T_ROWS[] = {FMU_GROUPED_VARIABLES(ROW, GROUP_ROW)};
#else
#define FMU_GROUP ""
static const row T_ROWS[] = {FMU_VARIABLES(ROW)};
#endif
#undef ROW
#undef GROUP_ROW

#ifdef FMU_ENUM_TYPES
#define ITEM(name, value, desc) {#name, desc, value},
#define ENUM_ITEMS(type, ITEMS) static const item ITEMS_##type[] = {ITEMS(ITEM)};
FMU_ENUM_TYPES(ENUM_ITEMS)
#define ENUM_ROW(type, ITEMS) {#type, ITEMS_##type, (int)(sizeof ITEMS_##type / sizeof(item))},
static const enum_type T_ENUMS[] = {FMU_ENUM_TYPES(ENUM_ROW)};
enum { T_NENUMS = sizeof T_ENUMS / sizeof T_ENUMS[0] };
#else
static const enum_type T_ENUMS[1];
enum { T_NENUMS = 0 };
#endif

#define SRC(f) #f,
static const char *const T_SOURCES[] = {FMU_SOURCES(SRC) FMU_GLUE_SOURCES(SRC)};
#undef SRC

#ifndef FMU_DEPENDENCIES
#error "the table must declare FMU_DEPENDENCIES(D): every output's dependencies in both modes"
#endif
#define DEP(out, step, init) {#out, step, init},
static const dep T_DEPS[] = {FMU_DEPENDENCIES(DEP)};
#undef DEP

#ifdef FMU_ARRAYS
#define ARRAY_ROW(name, vr, type, unit, like, desc) {#name, #type, unit, #like, desc, vr},
static const array_row T_ARRAYS[] = {FMU_ARRAYS(ARRAY_ROW)};
#undef ARRAY_ROW
enum { T_NARRAYS = sizeof T_ARRAYS / sizeof T_ARRAYS[0] };
#else
static const array_row T_ARRAYS[1];
enum { T_NARRAYS = 0 };
#endif
#ifndef FMU_STRUCTURAL_PARAMETERS
#define FMU_STRUCTURAL_PARAMETERS ""
#endif
#ifdef FMU_MODEL_HEADER
#define T_STATE (&FMU_STATE_FIELDS)
#else
#define T_STATE NULL
#endif

#define COUNT(a) ((int)(sizeof a / sizeof a[0]))
const gen_model GEN = {FMU_MODEL_NAME,
                       FMU_MODEL_IDENTIFIER,
                       FMU_DESCRIPTION,
                       FMU_DEFAULT_EXPERIMENT,
                       FMU_DOC_HTML,
                       FMU_VERSION,
                       FMU_GROUP,
                       FMU_STRUCTURAL_PARAMETERS,
                       FMU_PROVIDES_DERIVATIVES,
                       T_ROWS,
                       COUNT(T_ROWS),
                       T_ENUMS,
                       T_NENUMS,
                       T_DEPS,
                       COUNT(T_DEPS),
                       T_ARRAYS,
                       T_NARRAYS,
                       T_SOURCES,
                       COUNT(T_SOURCES),
                       T_STATE,
                       FMU_STATE_TAG};

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
