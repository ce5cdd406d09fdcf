/*
 * What the generator's parts read the table's facts with (GEN,
 * gen_model_description.h): escaped text and the shortest numbers, rows by
 * name and kind, the lists of names, the dependencies and their checks.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glue/gen_model_description.h"

void esc(FILE *f, const char *s) {
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
void num(char *buf, size_t n, double x) {
    for (int prec = 15; prec <= 17; ++prec) {
        snprintf(buf, n, "%.*g", prec, x);
        if (strtod(buf, NULL) == x) return;
    }
}

int is(const char *a, const char *b) { return strcmp(a, b) == 0; }
int is_int(const row *r) { return !is(r->type, "Float64"); }
int is_enum(const row *r) { return is_int(r) && !is(r->type, "Int32"); }
int has_start(const row *r) {
    return !is(r->initial, "calculated") && !is(r->causality, "independent");
}

const dep *deps_of(const char *output) {
    for (int k = 0; k < NDEPS; ++k)
        if (is(DEPS[k].output, output)) return &DEPS[k];
    return NULL;
}

/* The k-th item of a space-separated list into name and kind (dependent
 * when the item has no ":kind"); 0 when there is no k-th token. */
int list_item(const char *list, int k, char name[64], char kind[16]) {
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
const char *kind_in(const char *list, const char *known) {
    static char kind[16];
    char name[64];
    for (int k = 0; list_item(list, k, name, kind); ++k)
        if (is(name, known)) return kind;
    return NULL;
}

const row *row_named(const char *name) {
    for (int i = 0; i < NROWS; ++i)
        if (is(ROWS[i].name, name)) return &ROWS[i];
    return NULL;
}

int is_structural(const row *r) { return kind_in(GEN.structural, r->name) != NULL; }

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

int check_dependencies(void) {
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
        for (int k = 0; list_item(GEN.structural, k, name, kind); ++k) {
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

/* A JSON string: the table's texts are ASCII with no control characters
 * but quotes and backslashes are escaped all the same. */
void json_str(FILE *f, const char *s) {
    fputc('"', f);
    for (; *s; ++s) {
        if (*s == '"' || *s == '\\') fputc('\\', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

/* A number, or null for none (an infinite bound). */
void json_num(FILE *f, const row *r, double x) {
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
