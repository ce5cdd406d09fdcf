/*
 * The package's manifest, variables/<Model>.json, from the table's facts
 * (GEN, gen_model_description.h): every variable with its columns, the
 * FMI 3.0 arrays, the serialized state's layout, the enumerations.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "glue/fmu_instance.h" /* the serialized state's header */
#include "glue/gen_model_description.h"

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
    fprintf(f, "  \"state\": {\"bytes\": %zu, \"format\": %d, \"tag\": \"%.4s\", \"header\": ",
            FMU_STATE_HEADER_BYTES + fmu_fields_size(GEN.state), FMU_STATE_FORMAT, GEN.tag);
    json_str(f, FMU_STATE_HEADER_LAYOUT);
    fprintf(f, ", \"headerBytes\": %d, \"parts\": [", FMU_STATE_HEADER_BYTES);
    const fmu_fields *L = GEN.state;
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

/* The manifest the Python package reads instead of typing the table's
 * facts: every variable with its columns, the enumerations' items and the
 * table's group (the law's parameters, in the table's order). */
void manifest(FILE *f) {
    fputs("{\n  \"generated\": \"by gen_model_description from the variable table: edit the "
          "table, not this file\",\n  \"modelIdentifier\": ",
          f);
    json_str(f, GEN.identifier);
    fprintf(f, ",\n  \"version\": \"%s\",\n  \"providesDerivatives\": %s,\n  \"variables\": [\n",
            GEN.version, TF(GEN.provides_derivatives));
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
        json_str(f, r->grouped ? GEN.group : "");
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
        for (int k = 0; list_item(GEN.structural, k, name, kind); ++k) {
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
            for (int k = 0; list_item(GEN.structural, k, name, kind); ++k) {
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
    if (GEN.state) state_layout(f);
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
