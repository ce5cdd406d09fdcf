/*
 * documentation/index.html of FMI 2.0 and of FMI 3.0, from the table's
 * facts (GEN, gen_model_description.h) and its text, FMU_DOC_HTML.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "glue/gen_model_description.h"

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

void html(FILE *f, int v) {
    fprintf(
        f,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\">"
        "<title>%s (FMI "
        "%d.0)</title>\n<style>body{font-family:sans-serif;max-width:80em;margin:2em auto}"
        "table{border-collapse:collapse;font-size:90%%}td,th{border:1px solid #999;padding:2px 6px;"
        "text-align:left;vertical-align:top}code{background:#eee}</style></head>\n<body>\n"
        "<!-- Generated from the variable table by gen_model_description. -->\n"
        "<h1>%s %s: FMI %d.0 Co-Simulation</h1>\n<p>",
        GEN.name, v, GEN.name, GEN.version, v);
    esc(f, GEN.description);
    fprintf(f,
            ".</p>\n<p>This page describes the FMI %d.0 FMU; the FMI %d.0 one of the same "
            "version is built from the same sources and gives the same outputs bit for bit.</p>\n",
            v, v == 2 ? 3 : 2);
    doc(f, GEN.doc_html, v); /* the table's text (glue/fmu_table.h) */
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
                GEN.structural, is(ARRAYS[a].unit, "1") ? "" : ARRAYS[a].unit);
        esc(f, ARRAYS[a].desc);
        fputs("</td></tr>\n", f);
    }
    fputs("</table>\n", f);
    if (v == 3 && HAS_STRUCTURAL)
        fprintf(f,
                "<p>Structural parameters (causality structuralParameter), settable in "
                "configuration mode as well as before initialization: <code>%s</code>, of type "
                "%s (fmi3GetUInt64, fmi3SetUInt64) as the standard wants an array's dimension "
                "to be (Integer parameters in FMI 2.0). The arrays above are their shape, "
                "row-major (the last index fastest); fmi3GetFloat64 and fmi3GetInt32 take "
                "nValues, the number of values of all the variables asked for.</p>\n",
                GEN.structural, STRUCTURAL_TYPE_FMI3);
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
    fputs(GEN.version, f);
    fputs(" (the repository's <code>CITATION.cff</code> holds both).</p>\n", f);
    fprintf(f,
            "<h2>License</h2>\n<p>BSD-2-Clause: see <code>%s</code> beside this page.</p>\n"
            "</body>\n</html>\n",
            v == 2 ? "LICENSE.txt" : "licenses/LICENSE.txt");
}
