/* Writes the FMI 2.0 modelDescription.xml from model_variables.h, so that
 * the XML and the C value references cannot drift apart.
 * Usage: gen_model_description [OUTPUT]   (stdout without OUTPUT) */
#include <stdio.h>
#include <string.h>

#include "model_variables.h"

typedef struct {
    const char *name, *type, *causality, *variability, *initial, *start, *unit, *display, *desc;
    unsigned int vr;
} row;

#define OC_ROW(name, vr, type, caus, var, init, start, unit, disp, desc) \
    {#name, #type, #caus, #var, #init, #start, unit, disp, desc, vr},
static const row ROWS[] = {OC_VARIABLES(OC_ROW)};
#undef OC_ROW
enum { NROWS = sizeof ROWS / sizeof ROWS[0] };

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

/* 1-based indices of the inputs, as the ModelStructure lists them. */
static void input_indices(FILE *f) {
    int first = 1;
    for (int i = 0; i < NROWS; ++i)
        if (strcmp(ROWS[i].causality, "input") == 0) {
            fprintf(f, first ? "%d" : " %d", i + 1);
            first = 0;
        }
}

int main(int argc, char **argv) {
    FILE *f = stdout;
    if (argc > 1 && !(f = fopen(argv[1], "w"))) {
        perror(argv[1]);
        return 1;
    }
    fprintf(f,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<!-- Generated from fmu_src/model_variables.h by gen_model_description: edit the table, "
            "not this file. -->\n"
            "<fmiModelDescription\n"
            "  fmiVersion=\"2.0\"\n"
            "  modelName=\"%s\"\n"
            "  guid=\"%s\"\n"
            "  description=\"Coupled orthotropic adhesion-friction contact interface "
            "(Konyukhov and Schweizerhof 2007), return mapping\"\n"
            "  version=\"%s\"\n"
            "  generationTool=\"orthocontact gen_model_description\"\n"
            "  variableNamingConvention=\"flat\"\n"
            "  numberOfEventIndicators=\"0\">\n\n",
            OC_MODEL_NAME, OC_GUID, OC_VERSION);
    fprintf(f,
            "  <CoSimulation\n"
            "    modelIdentifier=\"%s\"\n"
            "    canHandleVariableCommunicationStepSize=\"true\"\n"
            "    canGetAndSetFMUstate=\"true\"\n"
            "    canSerializeFMUstate=\"true\"\n"
            "    providesDirectionalDerivative=\"true\">\n"
            "    <SourceFiles>\n"
            "      <File name=\"contact_law.c\"/>\n"
            "      <File name=\"oc_model.c\"/>\n"
            "      <File name=\"fmi2_glue.c\"/>\n"
            "    </SourceFiles>\n"
            "  </CoSimulation>\n\n",
            OC_MODEL_IDENTIFIER);
    fputs("  <UnitDefinitions>\n"
          "    <Unit name=\"J\"><BaseUnit kg=\"1\" m=\"2\" s=\"-2\"/></Unit>\n"
          "    <Unit name=\"N\"><BaseUnit kg=\"1\" m=\"1\" s=\"-2\"/></Unit>\n"
          "    <Unit name=\"N/m\"><BaseUnit kg=\"1\" s=\"-2\"/></Unit>\n"
          "    <Unit name=\"m\"><BaseUnit m=\"1\"/></Unit>\n"
          "    <Unit name=\"rad\">\n"
          "      <BaseUnit rad=\"1\"/>\n"
          "      <DisplayUnit name=\"deg\" factor=\"57.29577951308232\"/>\n"
          "    </Unit>\n"
          "  </UnitDefinitions>\n\n"
          "  <LogCategories>\n"
          "    <Category name=\"logStatusError\" description=\"Errors: rejected calls and why\"/>\n"
          "    <Category name=\"logStatusWarning\" description=\"Warnings\"/>\n"
          "    <Category name=\"logCalls\" description=\"Trace of FMI function calls\"/>\n"
          "  </LogCategories>\n\n"
          "  <DefaultExperiment startTime=\"0\" stopTime=\"1\" stepSize=\"0.001\"/>\n\n"
          "  <ModelVariables>\n",
          f);
    for (int i = 0; i < NROWS; ++i) {
        const row *r = &ROWS[i];
        fprintf(f, "    <!-- index %d -->\n    <ScalarVariable name=\"%s\" valueReference=\"%u\"",
                i + 1, r->name, r->vr);
        fprintf(f, " causality=\"%s\" variability=\"%s\"", r->causality, r->variability);
        if (*r->initial) fprintf(f, " initial=\"%s\"", r->initial);
        fputs(" description=\"", f);
        esc(f, r->desc);
        fprintf(f, "\">\n      <%s", r->type);
        if (*r->unit && strcmp(r->unit, "1") != 0) fprintf(f, " unit=\"%s\"", r->unit);
        if (*r->display) fprintf(f, " displayUnit=\"%s\"", r->display);
        if (strcmp(r->initial, "calculated") != 0) fprintf(f, " start=\"%s\"", r->start);
        fputs("/>\n    </ScalarVariable>\n", f);
    }
    fputs("  </ModelVariables>\n\n  <ModelStructure>\n    <Outputs>\n", f);
    for (int i = 0; i < NROWS; ++i)
        if (strcmp(ROWS[i].causality, "output") == 0) {
            fprintf(f, "      <Unknown index=\"%d\" dependencies=\"", i + 1);
            input_indices(f);
            fputs("\"/>\n", f);
        }
    /* In initialization mode the outputs depend on the parameters too; no
     * dependencies attribute says "on every known", which is the truth. */
    fputs("    </Outputs>\n    <InitialUnknowns>\n", f);
    for (int i = 0; i < NROWS; ++i)
        if (strcmp(ROWS[i].causality, "output") == 0)
            fprintf(f, "      <Unknown index=\"%d\"/>\n", i + 1);
    fputs("    </InitialUnknowns>\n  </ModelStructure>\n\n</fmiModelDescription>\n", f);
    if (f != stdout) fclose(f);
    return 0;
}
