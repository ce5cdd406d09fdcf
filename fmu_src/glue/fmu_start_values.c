/*
 * Start values from the FMU's resources, start_values.txt (its format:
 * fmu_instance.h): the resources' path from a file URI, the numbers read
 * exactly and independently of the locale, every line checked.
 */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glue/fmu_access.h"

static int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

static int lower(int c) { return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c; }

char *fmu_path_from_uri(const char *uri) {
    if (!uri) return NULL;
    static const char scheme[] = "file:";
    for (int i = 0; i < 5; ++i)
        if (lower((unsigned char)uri[i]) != scheme[i]) return NULL;
    const char *p = uri + 5;
    if (p[0] == '/' && p[1] == '/') { /* an authority: empty or localhost, else a UNC host */
        p += 2;
        if (strncmp(p, "localhost/", 10) == 0)
            p += 9;
        else if (*p != '/')
            p -= 2; /* keep //host/share */
    }
    char *out = malloc(strlen(p) + 1);
    if (!out) return NULL;
    size_t n = 0;
    for (; *p; ++p) {
        int hi, lo;
        if (*p == '%' && (hi = hex_digit(p[1])) >= 0 && (lo = hex_digit(p[2])) >= 0) {
            out[n++] = (char)(hi * 16 + lo);
            p += 2;
        } else {
            out[n++] = *p;
        }
    }
    out[n] = '\0';
    /* /C:/dir or /C|/dir: a Windows drive letter */
    if (out[0] == '/' && ((out[1] >= 'A' && out[1] <= 'Z') || (out[1] >= 'a' && out[1] <= 'z')) &&
        (out[2] == ':' || out[2] == '|') && (out[3] == '/' || out[3] == '\0')) {
        memmove(out, out + 1, n);
        out[1] = ':';
    }
    return out;
}

/* A C99 hexadecimal floating constant, exactly: NULL, or what is wrong. */
static const char *parse_hex_float(const char *s, double *value) {
    int neg = 0;
    if (*s == '+' || *s == '-') neg = *s++ == '-';
    if (!(s[0] == '0' && (s[1] == 'x' || s[1] == 'X'))) return "no 0x";
    s += 2;
    uint64_t mant = 0;
    long e2 = 0;
    int digits = 0, point = 0, d;
    for (;; ++s) {
        if (*s == '.' && !point) {
            point = 1;
            continue;
        }
        if ((d = hex_digit(*s)) < 0) break;
        ++digits;
        if (mant >> 56) { /* more would not fit: only zeros may follow */
            if (d != 0) return "more digits than a double holds";
            if (!point) e2 += 4;
        } else {
            mant = mant * 16 + (uint64_t)d;
            if (point) e2 -= 4;
        }
    }
    if (digits == 0) return "no hexadecimal digits";
    if (*s != 'p' && *s != 'P') return "no binary exponent (p)";
    ++s;
    int eneg = 0;
    if (*s == '+' || *s == '-') eneg = *s++ == '-';
    long e = 0;
    int edigits = 0;
    for (; *s >= '0' && *s <= '9'; ++s, ++edigits)
        if (e < 100000) e = e * 10 + (*s - '0');
    if (edigits == 0) return "no exponent digits";
    if (*s) return "characters after the number";
    e2 += eneg ? -e : e;
    while (mant && !(mant & 1)) {
        mant >>= 1;
        ++e2;
    }
    if (mant >> 53) return "more digits than a double holds";
    const double m = (double)mant; /* exact: < 2^53 */
    const double v = mant ? ldexp(m, (int)(e2 < -100000  ? -100000
                                           : e2 > 100000 ? 100000
                                                         : e2))
                          : 0.0;
    if (mant && (!isfinite(v) || v == 0.0 || ldexp(v, (int)-e2) != m))
        return "not representable exactly as a double";
    *value = neg ? -v : v;
    return NULL;
}

/* A decimal integer of at most 15 digits (exact as a double): NULL, or why not. */
static const char *parse_decimal_integer(const char *s, double *value) {
    int neg = 0;
    if (*s == '+' || *s == '-') neg = *s++ == '-';
    double v = 0;
    int digits = 0;
    for (; *s >= '0' && *s <= '9'; ++s)
        if (++digits <= 15) v = v * 10 + (*s - '0');
    if (digits == 0 || *s) return "not a decimal integer";
    if (digits > 15) return "more than 15 digits";
    *value = neg ? -v : v;
    return NULL;
}

static int is_blank(char c) { return c == ' ' || c == '\t'; }

/* Logs why the file is refused (with its line if > 0), closes it and frees
 * start and freeme: -1. */
static int load_fail(fmu_instance *I, const char *fn, const char *path, int line, FILE *f,
                     char *freeme, double *start, const char *fmt, ...) {
    char text[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    if (line > 0)
        FMU_ERROR(I, "%s: %s, line %d: %s", fn, path, line, text);
    else
        FMU_ERROR(I, "%s: %s: %s", fn, path, text);
    if (f) fclose(f);
    free(start);
    free(freeme);
    return -1;
}

/* The file's path under `resources` (malloc'd); NULL if there is none to
 * read (*failed 0) or out of memory (logged, *failed 1). */
static char *start_values_path(fmu_instance *I, const char *fn, const char *resources, int is_uri,
                               int *failed) {
    *failed = 0;
    if (!resources || !*resources) return NULL;
    char *dir = is_uri ? fmu_path_from_uri(resources) : NULL;
    const char *base = is_uri ? dir : resources;
    if (!base) return NULL; /* not a file URI: no file this FMU can read */
    const size_t len = strlen(base);
    const int sep = len > 0 && (base[len - 1] == '/' || base[len - 1] == '\\');
    char *path = malloc(len + 1 + sizeof FMU_START_VALUES_FILE);
    if (!path) {
        free(dir);
        FMU_ERROR(I, "%s: out of memory", fn);
        *failed = 1;
        return NULL;
    }
    memcpy(path, base, len);
    if (!sep) path[len] = '/';
    memcpy(path + len + !sep, FMU_START_VALUES_FILE, sizeof FMU_START_VALUES_FILE);
    free(dir);
    return path;
}

/* A line's `name = value` (its end of line and trailing blanks cut): 1,
 * with *name and *value pointing into it; 0 for a blank line or a comment;
 * -1 if it is neither. */
static int split_line(char *p, char **name, char **value) {
    while (is_blank(*p)) ++p;
    if (*p == '\0' || *p == '#') return 0;
    *name = p;
    while (*p && !is_blank(*p) && *p != '=') ++p;
    char *name_end = p;
    while (is_blank(*p)) ++p;
    if (*p != '=') return -1;
    *name_end = '\0';
    ++p;
    while (is_blank(*p)) ++p;
    *value = p;
    return 1;
}

/* The value the text p gives x: NULL and *v, or what is wrong with it;
 * *expected what it should have been. */
static const char *value_of(const fmu_var *x, const char *p, double *v, const char **expected) {
    if (x->type != FMU_T_Float64) {
        *expected = "a decimal integer";
        return parse_decimal_integer(p, v);
    }
    *expected = "a hexadecimal float such as 0x1.8p+3 (printf %a, Python float.hex()) or a "
                "decimal integer";
    return (p[0] == '0' || ((p[0] == '-' || p[0] == '+') && p[1] == '0')) &&
                   (strchr(p, 'x') || strchr(p, 'X'))
               ? parse_hex_float(p, v)
               : parse_decimal_integer(p, v);
}

enum { LOAD_MESSAGE = 400 }; /* load_fail's, which a message fits */

/* Writes why a line is refused into why[LOAD_MESSAGE]: -1. */
static int refuse(char *why, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, LOAD_MESSAGE, fmt, ap);
    va_end(ap);
    return -1;
}

/* Takes `name = value` into start[] (seen[] marks the names given): 0, or
 * -1 and why. */
static int assign(const char *name, const char *p, double start[], unsigned char seen[],
                  char *why) {
    const unsigned int nv = INFO.n_vars;
    unsigned int vr = nv;
    for (unsigned int k = 0; k < nv; ++k)
        if (INFO.vars[k].name && strcmp(INFO.vars[k].name, name) == 0) vr = k;
    if (vr == nv) return refuse(why, "no variable named \"%s\"", name);
    const fmu_var *x = &INFO.vars[vr];
    if (x->causality != FMU_C_parameter) return refuse(why, "%s is not a parameter", name);
    if (seen[vr]) return refuse(why, "%s is given twice", name);
    seen[vr] = 1;
    double v;
    const char *expected, *bad = value_of(x, p, &v, &expected);
    if (bad) return refuse(why, "%s = \"%s\": %s; expected %s", name, p, bad, expected);
    if (!in_range(x, v))
        return refuse(why, "%s = %.17g is outside [%g, %g]%s%s", name, v, x->min, x->max,
                      unit_sep(x), unit_of(x));
    start[vr] = v;
    return 0;
}

/* Reads every line of f into start[]: 0, or -1 with why and *line the line
 * that was wrong (the last read for a read error). */
static int read_lines(FILE *f, double start[], unsigned char seen[], int *line, char *why) {
    char buf[1002];
    while (fgets(buf, sizeof buf, f)) {
        ++*line;
        size_t n = strlen(buf);
        if (n > 0 && buf[n - 1] == '\n')
            buf[--n] = '\0';
        else if (!feof(f))
            return refuse(why, "longer than 1000 characters");
        if (n > 0 && buf[n - 1] == '\r') buf[--n] = '\0';
        while (n > 0 && is_blank(buf[n - 1])) buf[--n] = '\0';
        char *name, *value;
        const int kind = split_line(buf, &name, &value);
        if (kind < 0) return refuse(why, "expected `name = value`");
        if (kind > 0 && assign(name, value, start, seen, why) != 0) return -1;
    }
    if (ferror(f)) return refuse(why, "read error");
    return 0;
}

int fmu_load_start_values(fmu_instance *I, const char *fn, const char *resources, int is_uri) {
    int failed;
    char *path = start_values_path(I, fn, resources, is_uri, &failed);
    if (!path) return failed ? -1 : 0;
    FILE *f = fopen(path, "rb");
    if (!f) { /* no file: the compiled start values */
        free(path);
        return 0;
    }
    const unsigned int nv = INFO.n_vars;
    double *start = malloc(nv * sizeof *start);
    unsigned char *seen = calloc(nv ? nv : 1, 1);
    if (!start || !seen) {
        free(seen);
        return load_fail(I, fn, path, 0, f, path, start, "out of memory");
    }
    memcpy(start, I->start, nv * sizeof *start);
    char why[LOAD_MESSAGE];
    int line = 0;
    const int read = read_lines(f, start, seen, &line, why);
    free(seen);
    if (read != 0) return load_fail(I, fn, path, line, f, path, start, "%s", why);
    fmu_msg msg;
    if (fmu_model_init_from(I->model, start, &msg) != FMU_OK)
        return load_fail(I, fn, path, 0, f, path, start, "the values are not admissible: %s",
                         msg.text);
    memcpy(I->start, start, nv * sizeof *start);
    fmu_log(I, FMU_S_OK, FMU_LOG_CALLS, "%s: start values from %s", fn, path);
    fclose(f);
    free(start);
    free(path);
    return 0;
}
