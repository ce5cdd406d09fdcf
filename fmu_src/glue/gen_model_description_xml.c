/*
 * The FMI 2.0 and FMI 3.0 model descriptions and the FMI 3.0
 * buildDescription.xml, from the table's facts (GEN,
 * gen_model_description.h).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "glue/gen_model_description.h"

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
          "  </LogCategories>\n\n",
          f);
    fprintf(f, "  <DefaultExperiment %s/>\n\n", GEN.default_experiment);
}

static void header(FILE *f, const char *version) {
    fprintf(f,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<!-- Generated from the variable table by gen_model_description: edit the table, "
            "not this file. -->\n"
            "<fmiModelDescription\n  fmiVersion=\"%s\"\n  modelName=\"%s\"\n",
            version, GEN.name);
}

static void common_attrs(FILE *f, const char *license_path) {
    fputs("  description=\"", f);
    esc(f, GEN.description);
    fprintf(f,
            "\"\n  author=\"the orthocontact developers\"\n  version=\"%s\"\n"
            "  copyright=\"Copyright (c) 2026 the orthocontact developers\"\n"
            "  license=\"BSD-2-Clause (see %s)\"\n"
            "  generationTool=\"orthocontact gen_model_description\"\n"
            "  variableNamingConvention=\"flat\"",
            GEN.version, license_path);
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

/* FMI 2.0's Unknown of every output, with its dependencies in step mode
 * (initial 0: <Outputs>) or in initialization (1: <InitialUnknowns>). */
static void fmi2_unknowns(FILE *f, int initial) {
    for (int i = 0; i < NROWS; ++i)
        if (is(ROWS[i].causality, "output")) {
            fprintf(f, "      <Unknown index=\"%d\"", i + 1);
            dependencies(f, ROWS[i].name, initial, 1);
            fputs("/>\n", f);
        }
}

void fmi2(FILE *f, const char *token) {
    header(f, "2.0");
    fprintf(f, "  guid=\"%s\"\n", token);
    common_attrs(f, "documentation/LICENSE.txt");
    fprintf(f,
            "\n  numberOfEventIndicators=\"0\">\n\n"
            "  <CoSimulation\n    modelIdentifier=\"%s\"\n"
            "    canHandleVariableCommunicationStepSize=\"true\"\n"
            "    canGetAndSetFMUstate=\"true\"\n    canSerializeFMUstate=\"true\"\n"
            "    providesDirectionalDerivative=\"%s\">\n    <SourceFiles>\n",
            GEN.identifier, TF(GEN.provides_derivatives));
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
    fmi2_unknowns(f, 0);
    fputs("    </Outputs>\n    <InitialUnknowns>\n", f);
    fmi2_unknowns(f, 1);
    fputs("    </InitialUnknowns>\n  </ModelStructure>\n\n</fmiModelDescription>\n", f);
}

void fmi3(FILE *f, const char *token) {
    header(f, "3.0");
    fprintf(f, "  instantiationToken=\"%s\"\n", token);
    common_attrs(f, "documentation/licenses/LICENSE.txt");
    fprintf(f,
            ">\n\n  <CoSimulation\n    modelIdentifier=\"%s\"\n"
            "    canHandleVariableCommunicationStepSize=\"true\"\n"
            "    canGetAndSetFMUState=\"true\"\n    canSerializeFMUState=\"true\"\n"
            "    providesDirectionalDerivatives=\"%s\"\n"
            "    providesAdjointDerivatives=\"%s\"\n    hasEventMode=\"false\"/>\n\n",
            GEN.identifier, TF(GEN.provides_derivatives), TF(GEN.provides_derivatives));
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
        for (int k = 0; list_item(GEN.structural, k, name, kind); ++k)
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

void build(FILE *f) {
    fprintf(f,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<!-- Generated by gen_model_description: how to compile sources/ into the "
            "binary. -->\n"
            "<fmiBuildDescription fmiVersion=\"3.0\">\n"
            "  <BuildConfiguration modelIdentifier=\"%s\">\n"
            "    <SourceFileSet language=\"C99\">\n",
            GEN.identifier);
    for (int i = 0; i < NSOURCES; ++i) fprintf(f, "      <SourceFile name=\"%s\"/>\n", SOURCES[i]);
    fputs("      <SourceFile name=\"glue/fmi3_glue.c\"/>\n    </SourceFileSet>\n"
          "    <Library name=\"m\" description=\"the C math library (Linux)\"/>\n"
          "  </BuildConfiguration>\n</fmiBuildDescription>\n",
          f);
}
