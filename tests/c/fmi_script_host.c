/* A minimal FMI importer that runs a script of FMI calls on one FMU binary
 * and prints every value it reads exactly.  The same source is built for
 * Linux and for Windows (zig cc -target x86_64-windows-gnu), so that the
 * tests run the FMUs' linux64 and win64 binaries (the latter under wine) on
 * the same calls and compare the outputs bit for bit (tests/fmus/test_windows.py).
 * The host computes nothing for the calls: it copies values from the script
 * into the calls and from the calls into its output, with no decimal
 * conversion (a value is written and read as a hexadecimal float, by hand, so
 * that no platform's printf or strtod is involved).  Its one computation is
 * on request: the platform's sin or cos of a value, so that the test can
 * tell where the two platforms' libms round differently.
 *
 * Usage: fmi_script_host 2|3 BINARY RESOURCES SCRIPT OUTPUT
 *   RESOURCES: FMI 2.0's fmuResourceLocation (a URI) or FMI 3.0's resourcePath.
 * Script, one call a line (tokens separated by blanks; a float is written as
 * Python's float.hex() writes it, e.g. -0x1.999999999999ap-4):
 *   instantiate TOKEN
 *   configure | end_configure                  (FMI 3.0: configuration mode)
 *   init START STOP                            (setup, enter initialization)
 *   end_init
 *   set TYPE VR VALUE                          (TYPE: the call's, see below)
 *   step T H                                   (doStep, noSetFMUStatePriorToCurrentPoint)
 *   get TYPE VR N                              (N values: an FMI 3.0 array has n > 1)
 *   free
 *   sin X | cos X                              (the libm's, printed: "sin VALUE")
 * TYPE: FMI 2.0 Real, Integer; FMI 3.0 Float64, Int32, Int64, UInt64.
 * Output: for each get, "VR v1 v2 ..." (floats in hex as above, integers in
 * decimal).  A call returning other than OK: its status and the line on
 * stderr, and exit 3; a bad script line: exit 2. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
typedef HMODULE library;
static library lib_open(const char *path) { return LoadLibraryA(path); }
static void *lib_sym(library l, const char *name) { return (void *)GetProcAddress(l, name); }
static void lib_close(library l) { FreeLibrary(l); }
#else
#include <dlfcn.h>
typedef void *library;
static library lib_open(const char *path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void *lib_sym(library l, const char *name) { return dlsym(l, name); }
static void lib_close(library l) { dlclose(l); }
#endif

#include <math.h>
#include <stdarg.h>
#include <stdint.h>

#include "fmi2FunctionTypes.h"
#include "fmi3FunctionTypes.h"

#define MAXN 4096

static int line_no;

static void die(int code, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "fmi_script_host: line %d: ", line_no);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(code);
}

/* ---- exact hexadecimal floats, without printf's or strtod's ------------- */

static int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

/* float.hex()'s form: [-]0x1.<13 digits>p<e> (normal), [-]0x0.<13 digits>p-1022
 * (subnormal), [-]0x0.0p+0, inf, -inf. */
static double parse_hex(const char *s) {
    uint64_t sign = 0, mant = 0;
    if (*s == '-') {
        sign = (uint64_t)1 << 63;
        ++s;
    }
    uint64_t bits = 0;
    if (strcmp(s, "inf") == 0) {
        bits = (uint64_t)0x7ff << 52;
    } else {
        if (!(s[0] == '0' && s[1] == 'x' && (s[2] == '0' || s[2] == '1') && s[3] == '.'))
            die(2, "not a hexadecimal float: %s", s);
        const int lead = s[2] - '0';
        s += 4;
        int digits = 0, d;
        for (; (d = hex_digit(*s)) >= 0; ++s, ++digits) mant = mant << 4 | (uint64_t)d;
        if (digits < 1 || digits > 13 || *s != 'p') die(2, "not a hexadecimal float: %s", s);
        mant <<= 4 * (13 - digits);
        long e = strtol(s + 1, NULL, 10);
        if (lead == 1 && e >= -1022 && e <= 1023)
            bits = (uint64_t)(e + 1023) << 52 | mant;
        else if (lead == 0 && (mant == 0 || e == -1022))
            bits = mant;
        else
            die(2, "not a double's hexadecimal form: exponent %ld", e);
    }
    bits |= sign;
    double x;
    memcpy(&x, &bits, sizeof x);
    return x;
}

static void print_hex(FILE *out, double x) {
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    const char *sign = b >> 63 ? "-" : "";
    const unsigned e = (unsigned)(b >> 52 & 0x7ff);
    const unsigned long long m = (unsigned long long)(b & (((uint64_t)1 << 52) - 1));
    if (e == 0x7ff)
        fprintf(out, m ? " nan" : " %sinf", sign);
    else if (e == 0)
        fprintf(out, " %s0x0.%013llxp%s", sign, m, m ? "-1022" : "+0");
    else
        fprintf(out, " %s0x1.%013llxp%+d", sign, m, (int)e - 1023);
}

/* ---- the calls -------------------------------------------------------- */

static void logger2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                    fmi2String category, fmi2String message, ...) {
    va_list ap;
    (void)env;
    (void)name;
    va_start(ap, message);
    fprintf(stderr, "[%s %d] ", category ? category : "", (int)status);
    vfprintf(stderr, message, ap);
    fputc('\n', stderr);
    va_end(ap);
}

static void logger3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category,
                    fmi3String message) {
    (void)env;
    fprintf(stderr, "[%s %d] %s\n", category ? category : "", (int)status, message);
}

static library lib;

static void *sym(const char *name) {
    void *f = lib_sym(lib, name);
    if (!f) die(2, "the binary exports no %s", name);
    return f;
}

#define CALL(fn, ...) ((fn##TYPE *)sym(#fn))(__VA_ARGS__)

static void check(int status, const char *what) {
    if (status != 0) die(3, "%s returned status %d", what, status);
}

int main(int argc, char **argv) {
    if (argc != 6 || (strcmp(argv[1], "2") != 0 && strcmp(argv[1], "3") != 0)) {
        fprintf(stderr, "usage: fmi_script_host 2|3 BINARY RESOURCES SCRIPT OUTPUT\n");
        return 2;
    }
    const int v3 = argv[1][0] == '3';
    lib = lib_open(argv[2]);
    if (!lib) {
        fprintf(stderr, "fmi_script_host: cannot load %s\n", argv[2]);
        return 2;
    }
    FILE *in = fopen(argv[4], "r"), *out = fopen(argv[5], "w");
    if (!in || !out) {
        fprintf(stderr, "fmi_script_host: cannot open %s or %s\n", argv[4], argv[5]);
        return 2;
    }
    static const fmi2CallbackFunctions callbacks = {logger2, calloc, free, NULL, NULL};
    void *c = NULL;
    char buf[512], cmd[32], a[128], b[128], d[128];
    while (fgets(buf, sizeof buf, in)) {
        ++line_no;
        int n = sscanf(buf, "%31s %127s %127s %127s", cmd, a, b, d);
        if (n <= 0) continue;
        if ((strcmp(cmd, "sin") == 0 || strcmp(cmd, "cos") == 0) && n == 2) {
            const double x = parse_hex(a);
            fputs(cmd, out);
            print_hex(out, cmd[0] == 's' ? sin(x) : cos(x));
            fputc('\n', out);
        } else if (strcmp(cmd, "instantiate") == 0 && n == 2) {
            c = v3 ? (void *)CALL(fmi3InstantiateCoSimulation, "host", a, argv[3], fmi3False,
                                  fmi3False, fmi3False, fmi3False, NULL, 0, NULL, logger3, NULL)
                   : (void *)CALL(fmi2Instantiate, "host", fmi2CoSimulation, a, argv[3], &callbacks,
                                  fmi2False, fmi2False);
            if (!c) die(3, "instantiate returned NULL");
        } else if (!c) {
            die(2, "%s before instantiate", cmd);
        } else if (strcmp(cmd, "configure") == 0 && v3) {
            check(CALL(fmi3EnterConfigurationMode, c), cmd);
        } else if (strcmp(cmd, "end_configure") == 0 && v3) {
            check(CALL(fmi3ExitConfigurationMode, c), cmd);
        } else if (strcmp(cmd, "init") == 0 && n == 3) {
            const double start = parse_hex(a), stop = parse_hex(b);
            if (v3) {
                check(CALL(fmi3EnterInitializationMode, c, fmi3False, 0.0, start, fmi3True, stop),
                      cmd);
            } else {
                check(CALL(fmi2SetupExperiment, c, fmi2False, 0.0, start, fmi2True, stop), cmd);
                check(CALL(fmi2EnterInitializationMode, c), cmd);
            }
        } else if (strcmp(cmd, "end_init") == 0) {
            check(v3 ? CALL(fmi3ExitInitializationMode, c) : CALL(fmi2ExitInitializationMode, c),
                  cmd);
        } else if (strcmp(cmd, "step") == 0 && n == 3) {
            const double t = parse_hex(a), h = parse_hex(b);
            if (v3) {
                fmi3Boolean event, terminate, early;
                fmi3Float64 last;
                check(CALL(fmi3DoStep, c, t, h, fmi3True, &event, &terminate, &early, &last), cmd);
            } else {
                check(CALL(fmi2DoStep, c, t, h, fmi2True), cmd);
            }
        } else if (strcmp(cmd, "set") == 0 && n == 4) {
            const char *t = a, *value = d; /* set TYPE VR VALUE */
            const unsigned vr = (unsigned)strtoul(b, NULL, 10);
            const int real = strcmp(t, "Real") == 0 || strcmp(t, "Float64") == 0;
            const double x = real ? parse_hex(value) : 0.0;
            const long long k = real ? 0 : strtoll(value, NULL, 10);
            if (strcmp(t, "Real") == 0 && !v3) {
                check(CALL(fmi2SetReal, c, &vr, 1, &x), cmd);
            } else if (strcmp(t, "Integer") == 0 && !v3) {
                const fmi2Integer i = (fmi2Integer)k;
                check(CALL(fmi2SetInteger, c, &vr, 1, &i), cmd);
            } else if (strcmp(t, "Float64") == 0 && v3) {
                check(CALL(fmi3SetFloat64, c, &vr, 1, &x, 1), cmd);
            } else if (strcmp(t, "Int32") == 0 && v3) {
                const fmi3Int32 i = (fmi3Int32)k;
                check(CALL(fmi3SetInt32, c, &vr, 1, &i, 1), cmd);
            } else if (strcmp(t, "Int64") == 0 && v3) {
                const fmi3Int64 i = (fmi3Int64)k;
                check(CALL(fmi3SetInt64, c, &vr, 1, &i, 1), cmd);
            } else if (strcmp(t, "UInt64") == 0 && v3) {
                const fmi3UInt64 i = (fmi3UInt64)k;
                check(CALL(fmi3SetUInt64, c, &vr, 1, &i, 1), cmd);
            } else {
                die(2, "no type %s in FMI %c.0", t, argv[1][0]);
            }
        } else if (strcmp(cmd, "get") == 0 && n == 4) {
            const char *t = a; /* get TYPE VR N */
            const unsigned vr = (unsigned)strtoul(b, NULL, 10);
            const long nv = strtol(d, NULL, 10);
            if (nv < 1 || nv > MAXN || (nv > 1 && !v3)) die(2, "bad count %s", d);
            static double x[MAXN];
            static long long k[MAXN];
            int real = 1;
            if (strcmp(t, "Real") == 0 && !v3) {
                check(CALL(fmi2GetReal, c, &vr, 1, x), cmd);
            } else if (strcmp(t, "Integer") == 0 && !v3) {
                fmi2Integer i;
                check(CALL(fmi2GetInteger, c, &vr, 1, &i), cmd);
                k[0] = i;
                real = 0;
            } else if (strcmp(t, "Float64") == 0 && v3) {
                check(CALL(fmi3GetFloat64, c, &vr, 1, x, (size_t)nv), cmd);
            } else if (strcmp(t, "Int32") == 0 && v3) {
                static fmi3Int32 i[MAXN];
                check(CALL(fmi3GetInt32, c, &vr, 1, i, (size_t)nv), cmd);
                for (long j = 0; j < nv; ++j) k[j] = i[j];
                real = 0;
            } else if (strcmp(t, "Int64") == 0 && v3) {
                static fmi3Int64 i[MAXN];
                check(CALL(fmi3GetInt64, c, &vr, 1, i, (size_t)nv), cmd);
                for (long j = 0; j < nv; ++j) k[j] = i[j];
                real = 0;
            } else if (strcmp(t, "UInt64") == 0 && v3) {
                static fmi3UInt64 i[MAXN];
                check(CALL(fmi3GetUInt64, c, &vr, 1, i, (size_t)nv), cmd);
                for (long j = 0; j < nv; ++j) k[j] = (long long)i[j];
                real = 0;
            } else {
                die(2, "no type %s in FMI %c.0", t, argv[1][0]);
            }
            fprintf(out, "%u", vr);
            for (long j = 0; j < nv; ++j) {
                if (real)
                    print_hex(out, x[j]);
                else
                    fprintf(out, " %lld", k[j]);
            }
            fputc('\n', out);
        } else if (strcmp(cmd, "free") == 0 && n == 1) {
            if (v3)
                CALL(fmi3FreeInstance, c);
            else
                CALL(fmi2FreeInstance, c);
            c = NULL;
        } else {
            die(2, "not a call: %s", buf);
        }
    }
    if (c) die(2, "no free at the end");
    if (fclose(out) != 0) die(2, "cannot write %s", argv[5]);
    fclose(in);
    lib_close(lib);
    return 0;
}
