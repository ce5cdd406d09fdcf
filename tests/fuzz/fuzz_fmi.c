/* libFuzzer target over FMI call sequences of one FMU (the model's variable
 * table FUZZ_TABLE_HEADER) in one FMI version (FUZZ_FMI = 2 or 3), linked
 * with the FMU's own sources as CMake builds them (OC_FUZZ, tools/fuzz.sh).
 *
 * The input is read as a program: each byte picks a call, the bytes after it
 * its arguments (value references from the table or any number, values from
 * a list of edge cases or any 8 bytes).  An integer is set and read mostly
 * through its type's call as the table gives it (FMI 3.0: an Int32 through
 * Int32, an enumeration through Int64, a structural parameter of
 * FMU_STRUCTURAL_PARAMETERS, an array's dimension, through UInt64, also in
 * configuration mode), else through another (refused).  Besides the sanitizers' findings,
 * the target aborts where a promise of docs/reference/fmus.md does not hold:
 *   - every call returns a defined status;
 *   - a successful read or derivative is finite (never NaN/inf with OK);
 *   - a rejected call changes nothing (the serialized instance is the same
 *     before and after it);
 *   - a state the FMU serialized is accepted back, into itself and into a
 *     fresh instance, and both then read the same outputs bit for bit;
 *   - (contact model) a committed step repeated with held inputs reads the
 *     same outputs, and the dissipated energy never decreases. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include FUZZ_TABLE_HEADER
#include "host_support.h"

#if FUZZ_FMI == 2
#include "fmi2Functions.h"
#else
#include "fmi3Functions.h"
#endif

#define FUZZ_FAIL(...)                                                                             \
    do {                                                                                           \
        fprintf(stderr, "fuzz_fmi: promise broken: " __VA_ARGS__);                                 \
        fprintf(stderr, "\n");                                                                     \
        abort();                                                                                   \
    } while (0)

/* ---- the variable table ------------------------------------------------- */

enum { K_F64 = 1, K_INT = 2, K_ENUM = 3 };
enum { C_IND = 1, C_PAR, C_IN, C_OUT };
#define C_independent C_IND
#define C_parameter C_PAR
#define C_input C_IN
#define C_output C_OUT
#define K_Float64 K_F64
#define K_Int32 K_INT
/* each enumeration type of the table is the enumeration kind here */
#ifdef FMU_ENUM_TYPES
#define FUZZ_ENUM_KIND(name, items) K_##name = K_ENUM,
enum { FMU_ENUM_TYPES(FUZZ_ENUM_KIND) FUZZ_ENUM_KINDS_END };
#undef FUZZ_ENUM_KIND
#endif
typedef struct {
    unsigned vr;
    int kind, causality;
    const char *name;
} var;
#define FUZZ_VAR(name, vr, type, caus, ...) {vr, K_##type, C_##caus, #name},
static const var VARS[] = {FMU_VARIABLES(FUZZ_VAR)};
#undef FUZZ_VAR
enum { NVARS = sizeof VARS / sizeof VARS[0] };

static const var *find(const char *name) {
    for (int i = 0; i < NVARS; ++i)
        if (strcmp(VARS[i].name, name) == 0) return &VARS[i];
    return NULL;
}

#if FUZZ_FMI == 3
static const var *by_vr(unsigned vr) {
    for (int i = 0; i < NVARS; ++i)
        if (VARS[i].vr == vr) return &VARS[i];
    return NULL;
}

/* Whether the table lists v among FMU_STRUCTURAL_PARAMETERS (names apart by
 * spaces): FMI 3.0's UInt64 array dimensions. */
#ifndef FMU_STRUCTURAL_PARAMETERS
#define FMU_STRUCTURAL_PARAMETERS ""
#endif
static int structural(const var *v) {
    const char *list = FMU_STRUCTURAL_PARAMETERS;
    const size_t n = strlen(v->name);
    for (const char *p = list; (p = strstr(p, v->name)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return 1;
    return 0;
}
#endif

/* ---- reading the program --------------------------------------------------- */

typedef struct {
    const uint8_t *p;
    size_t n;
} reader;

static unsigned byte(reader *r) {
    if (!r->n) return 0;
    --r->n;
    return *r->p++;
}

static double value(reader *r) {
    static const double edge[] = {0.0,
                                  -0.0,
                                  1.0,
                                  -1.0,
                                  0.5,
                                  2.0,
                                  1e-3,
                                  -1e-3,
                                  10.0,
                                  1e-300,
                                  1e300,
                                  DBL_MAX,
                                  -DBL_MAX,
                                  DBL_MIN,
                                  4.9406564584124654e-324,
                                  1e-310,
                                  0x1p1023,
                                  1.2e308,
                                  1e-150,
                                  1e150,
                                  1e10,
                                  1e-10,
                                  3.0,
                                  1e303,
                                  1e6,
                                  12.566370614359172,
                                  1.5707963267948966,
                                  0.408};
    const unsigned b = byte(r);
    const unsigned ne = sizeof edge / sizeof edge[0];
    if (b < ne) return edge[b];
    if (b < 200) return ((double)b - 128.0) * (b & 1 ? 1e-4 : 0.25); /* ordinary numbers */
    if (b < 205)
        return b == 200   ? NAN
               : b == 201 ? INFINITY
               : b == 202 ? -INFINITY
               : b == 203 ? -1e300
                          : 1e-5;
    uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits = bits << 8 | byte(r);
    double x;
    memcpy(&x, &bits, 8);
    return x;
}

static unsigned vref(reader *r) {
    const unsigned b = byte(r);
    if (b < 240) return VARS[b % NVARS].vr;
    return b == 240 ? 0xFFFFFFFFu : b == 241 ? (unsigned)NVARS + 3 : byte(r);
}

/* ---- one FMI version behind one set of names ------------------------------- */

#if FUZZ_FMI == 2
typedef fmi2Component inst;
typedef int status;
static inst make(int logging) {
    return fmi2Instantiate("fuzz", fmi2CoSimulation, FMU_GUID, "", &host_quiet2_cb, 0, logging);
}
static void destroy(inst c) { fmi2FreeInstance(c); }
static int st_ok(status s) { return s == fmi2OK; }
static int st_defined(status s) {
    return s == fmi2OK || s == fmi2Warning || s == fmi2Discard || s == fmi2Error || s == fmi2Fatal;
}
static void forget_setup(void) {}
static status set_f64(inst c, const unsigned *vr, size_t n, const double *v) {
    return fmi2SetReal(c, vr, n, v);
}
static status get_f64(inst c, const unsigned *vr, size_t n, double *v) {
    return fmi2GetReal(c, vr, n, v);
}
/* FMI 2.0 has one integer call, Integer, for Int32 and enumerations alike. */
static status set_int(inst c, unsigned vr, int64_t v, unsigned how) {
    (void)how;
    const fmi2Integer x = (fmi2Integer)v;
    return fmi2SetInteger(c, &vr, 1, &x);
}
static status get_int(inst c, unsigned vr, unsigned how) {
    (void)how;
    fmi2Integer x;
    return fmi2GetInteger(c, &vr, 1, &x);
}
static status other_type(inst c, unsigned vr, unsigned how) {
    fmi2Boolean b = fmi2True;
    fmi2String str = "x";
    switch (how % 4) {
    case 0: return fmi2SetBoolean(c, &vr, 1, &b);
    case 1: return fmi2GetBoolean(c, &vr, 1, &b);
    case 2: return fmi2SetString(c, &vr, 1, &str);
    default: return fmi2GetString(c, &vr, 1, &str);
    }
}
static status setup(inst c, double t0, double stop, int has_stop) {
    return fmi2SetupExperiment(c, fmi2False, 0.0, t0, has_stop, stop);
}
static status enter_init(inst c) { return fmi2EnterInitializationMode(c); }
static status exit_init(inst c) { return fmi2ExitInitializationMode(c); }
static status do_step(inst c, double t, double h) { return fmi2DoStep(c, t, h, fmi2True); }
static status terminate(inst c) { return fmi2Terminate(c); }
static status reset(inst c) { return fmi2Reset(c); }
static status logging(inst c, int on) { return fmi2SetDebugLogging(c, on, 0, NULL); }
static status derivative(inst c, const unsigned *u, size_t nu, const unsigned *k, size_t nk,
                         const double *seed, double *out, int adjoint) {
    if (adjoint) return fmi2Error; /* FMI 2.0 has no adjoint */
    return fmi2GetDirectionalDerivative(c, u, nu, k, nk, seed, out);
}
/* Serializes the instance into buf (size *n); 0 if it cannot. */
static int serialize(inst c, unsigned char *buf, size_t cap, size_t *n) {
    fmi2FMUstate st = NULL;
    if (fmi2GetFMUstate(c, &st) != fmi2OK) return 0;
    int ok = fmi2SerializedFMUstateSize(c, st, n) == fmi2OK;
    if (ok && *n > cap) FUZZ_FAIL("a serialized state of %zu bytes exceeds STATE_CAP", *n);
    ok = ok && fmi2SerializeFMUstate(c, st, (fmi2Byte *)buf, *n) == fmi2OK;
    fmi2FreeFMUstate(c, &st);
    return ok;
}
static status restore(inst c, const unsigned char *buf, size_t n) {
    fmi2FMUstate st = NULL;
    status s = fmi2DeSerializeFMUstate(c, (const fmi2Byte *)buf, n, &st);
    if (s != fmi2OK) return s;
    s = fmi2SetFMUstate(c, st);
    fmi2FreeFMUstate(c, &st);
    return s;
}
#else
typedef fmi3Instance inst;
typedef int status;
static inst make(int logging) {
    return fmi3InstantiateCoSimulation("fuzz", FMU_GUID, "", 0, logging, 0, 0, NULL, 0, NULL,
                                       host_quiet3, NULL);
}
static void destroy(inst c) { fmi3FreeInstance(c); }
static int st_ok(status s) { return s == fmi3OK; }
static int st_defined(status s) {
    return s == fmi3OK || s == fmi3Warning || s == fmi3Discard || s == fmi3Error || s == fmi3Fatal;
}
static status set_f64(inst c, const unsigned *vr, size_t n, const double *v) {
    return fmi3SetFloat64(c, vr, n, v, n);
}
static status get_f64(inst c, const unsigned *vr, size_t n, double *v) {
    return fmi3GetFloat64(c, vr, n, v, n);
}
/* The integer call for vr: 0 Int32, 1 Int64, 2 UInt64; its type's as the
 * table gives it (an unknown vr: Int32), or with how's low bits 3 another. */
static unsigned int_call(unsigned vr, unsigned how) {
    if ((how & 3) == 3) return (how >> 2) % 3;
    const var *x = by_vr(vr);
    return !x ? 0 : structural(x) ? 2 : x->kind == K_ENUM ? 1 : 0;
}
static status set_int(inst c, unsigned vr, int64_t v, unsigned how) {
    const fmi3Int32 x = (fmi3Int32)v;
    const fmi3UInt64 u = (fmi3UInt64)v; /* a negative v: a huge count, refused */
    switch (int_call(vr, how)) {
    case 0: return fmi3SetInt32(c, &vr, 1, &x, 1);
    case 1: return fmi3SetInt64(c, &vr, 1, &v, 1);
    default: return fmi3SetUInt64(c, &vr, 1, &u, 1);
    }
}
static status get_int(inst c, unsigned vr, unsigned how) {
    fmi3Int32 x;
    fmi3Int64 y;
    fmi3UInt64 u;
    switch (int_call(vr, how)) {
    case 0: return fmi3GetInt32(c, &vr, 1, &x, 1);
    case 1: return fmi3GetInt64(c, &vr, 1, &y, 1);
    default: return fmi3GetUInt64(c, &vr, 1, &u, 1);
    }
}
static status enter_config(inst c) { return fmi3EnterConfigurationMode(c); }
static status exit_config(inst c) { return fmi3ExitConfigurationMode(c); }
static status other_type(inst c, unsigned vr, unsigned how) {
    fmi3Boolean b = fmi3True;
    fmi3Float32 f = 1.0f;
    fmi3UInt64 u = 1;
    switch (how % 4) {
    case 0: return fmi3SetBoolean(c, &vr, 1, &b, 1);
    case 1: return fmi3GetFloat32(c, &vr, 1, &f, 1);
    case 2: return fmi3SetUInt64(c, &vr, 1, &u, 1);
    default: return fmi3GetBoolean(c, &vr, 1, &b, 1);
    }
}
/* FMI 3.0 takes the experiment's times with fmi3EnterInitializationMode;
 * "setup" keeps them here until then (reset for every input, so that each
 * input replays alone). */
static double start_time, stop_time;
static int has_stop_time;
static void forget_setup(void) {
    start_time = stop_time = 0.0;
    has_stop_time = 0;
}
static status setup(inst c, double t0, double stop, int has_stop) {
    (void)c;
    start_time = t0;
    stop_time = stop;
    has_stop_time = has_stop;
    return fmi3OK;
}
static status enter_init(inst c) {
    return fmi3EnterInitializationMode(c, fmi3False, 0.0, start_time, has_stop_time, stop_time);
}
static status exit_init(inst c) { return fmi3ExitInitializationMode(c); }
static status do_step(inst c, double t, double h) {
    fmi3Boolean ev, term, early;
    double last;
    return fmi3DoStep(c, t, h, fmi3True, &ev, &term, &early, &last);
}
static status terminate(inst c) { return fmi3Terminate(c); }
static status reset(inst c) { return fmi3Reset(c); }
static status logging(inst c, int on) { return fmi3SetDebugLogging(c, on, 0, NULL); }
static status derivative(inst c, const unsigned *u, size_t nu, const unsigned *k, size_t nk,
                         const double *seed, double *out, int adjoint) {
    const size_t ns = adjoint ? nu : nk, no = adjoint ? nk : nu;
    return adjoint ? fmi3GetAdjointDerivative(c, u, nu, k, nk, seed, ns, out, no)
                   : fmi3GetDirectionalDerivative(c, u, nu, k, nk, seed, ns, out, no);
}
static int serialize(inst c, unsigned char *buf, size_t cap, size_t *n) {
    fmi3FMUState st = NULL;
    if (fmi3GetFMUState(c, &st) != fmi3OK) return 0;
    int ok = fmi3SerializedFMUStateSize(c, st, n) == fmi3OK;
    if (ok && *n > cap) FUZZ_FAIL("a serialized state of %zu bytes exceeds STATE_CAP", *n);
    ok = ok && fmi3SerializeFMUState(c, st, buf, *n) == fmi3OK;
    fmi3FreeFMUState(c, &st);
    return ok;
}
static status restore(inst c, const unsigned char *buf, size_t n) {
    fmi3FMUState st = NULL;
    status s = fmi3DeserializeFMUState(c, buf, n, &st);
    if (s != fmi3OK) return s;
    s = fmi3SetFMUState(c, st);
    fmi3FreeFMUState(c, &st);
    return s;
}
#endif

/* ---- the promises ---------------------------------------------------------- */

/* Room for the largest serialized state of any model: the ContactPatch
 * serializes its 32 x 32 cells (about 66 kB).  A larger state aborts
 * (serialize) rather than skip the checks that need it. */
enum { STATE_CAP = 1 << 17 };

/* Reads every Float64 variable; 1 if the read succeeded (then all finite). */
static int read_all(inst c, double *v) {
    unsigned vr[NVARS];
    size_t n = 0;
    for (int i = 0; i < NVARS; ++i)
        if (VARS[i].kind == K_F64) vr[n++] = VARS[i].vr;
    const status s = get_f64(c, vr, n, v);
    if (!st_defined(s)) FUZZ_FAIL("get of all Float64 returned status %d", s);
    if (!st_ok(s)) return 0;
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(v[i])) FUZZ_FAIL("read %g with OK (vr %u)", v[i], vr[i]);
    return 1;
}

/* A state the FMU wrote must restore, into itself and into a fresh instance,
 * and both must then read the same outputs. */
static void check_own_state(inst c) {
    static unsigned char buf[STATE_CAP];
    size_t n = 0;
    if (!serialize(c, buf, sizeof buf, &n)) return;
    double before[NVARS], after[NVARS], fresh[NVARS];
    const int had = read_all(c, before);
    if (!st_ok(restore(c, buf, n))) FUZZ_FAIL("the FMU refused its own state (same instance)");
    inst d = make(0);
    if (!d) return;
    if (!st_ok(restore(d, buf, n))) FUZZ_FAIL("the FMU refused its own state (fresh instance)");
    const int ra = read_all(c, after), rf = read_all(d, fresh);
    if (had != ra || had != rf) FUZZ_FAIL("a restored state reads differently (status)");
    if (had)
        for (int i = 0, j = 0; i < NVARS; ++i) {
            if (VARS[i].kind != K_F64) continue;
            if (memcmp(&before[j], &after[j], sizeof(double)) != 0 ||
                memcmp(&before[j], &fresh[j], sizeof(double)) != 0)
                FUZZ_FAIL("a restored state reads %s = %.17g (itself) and %.17g (fresh), not %.17g",
                          VARS[i].name, after[j], fresh[j], before[j]);
            ++j;
        }
    destroy(d);
}

/* Runs one call that may be rejected: if it is, the instance must be as
 * before, byte for byte of its serialized state. */
static unsigned char snap_before[STATE_CAP], snap_after[STATE_CAP];
static size_t snap_n;
static int snapped;
static void snap(inst c) { snapped = serialize(c, snap_before, sizeof snap_before, &snap_n); }
static void rejected_changes_nothing(inst c, status s, const char *what) {
    if (!st_defined(s)) FUZZ_FAIL("%s returned status %d", what, s);
    if (st_ok(s) || !snapped) return;
    size_t n = 0;
    if (!serialize(c, snap_after, sizeof snap_after, &n))
        FUZZ_FAIL("%s: rejected, then no state", what);
    if (n != snap_n || memcmp(snap_before, snap_after, n) != 0)
        FUZZ_FAIL("%s was rejected but changed the instance", what);
}

/* The mode changes of op 8 by its byte % 7 (0 is the setup; none: logging). */
struct mode_change {
    status (*call)(inst);
    const char *what;
};
static const struct mode_change MODE_CHANGES[7] = {{NULL, NULL},
                                                   {enter_init, "enter init"},
                                                   {exit_init, "exit init"},
                                                   {terminate, "terminate"},
                                                   {NULL, NULL},
#if FUZZ_FMI == 3
                                                   {enter_config, "enter configuration mode"},
                                                   {exit_config, "exit configuration mode"}
#endif
};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    reader r = {data, size};
    forget_setup();
    inst c = make(byte(&r) & 1);
    if (!c) return 0;
    double t = 0.0, energy = 0.0;
    int stepping = 0;
    const var *E = find("dissipatedEnergy");
    for (int k = 0; k < 256 && r.n; ++k) {
        const unsigned op = byte(&r) % 16;
        status s = 0;
        snap(c);
        switch (op) {
        case 0:
        case 1:
        case 2: { /* Float64 values, 1-4 at once */
            unsigned vr[4];
            double v[4];
            const size_t n = 1 + byte(&r) % 4;
            for (size_t i = 0; i < n; ++i) {
                vr[i] = vref(&r);
                v[i] = value(&r);
            }
            s = set_f64(c, vr, n, v);
            rejected_changes_nothing(c, s, "set Float64");
            break;
        }
        case 3: {
            const unsigned vr = vref(&r), how = byte(&r);
            s = set_int(c, vr, (int64_t)(int8_t)byte(&r), how);
            rejected_changes_nothing(c, s, "set integer");
            break;
        }
        case 4: {
            const unsigned vr = vref(&r), how = byte(&r);
            s = byte(&r) & 1 ? get_int(c, vr, how) : other_type(c, vr, how);
            rejected_changes_nothing(c, s, "integer or other type");
            break;
        }
        case 5:
        case 6:
        case 7: { /* steps, mostly at the right communication point */
            const unsigned how = byte(&r);
            const double h = how & 3 ? 1e-3 * (1 + (how >> 2)) : value(&r);
            const double tc = how & 0x80 ? value(&r) : t;
            s = do_step(c, tc, h);
            rejected_changes_nothing(c, s, "do step");
            if (st_ok(s)) {
                t = tc + h;
                double y[NVARS], y2[NVARS];
                if (E && read_all(c, y)) {
                    /* held inputs: the same outputs, and no energy lost */
                    size_t ie = 0;
                    for (int i = 0; i < NVARS && &VARS[i] != E; ++i) ie += VARS[i].kind == K_F64;
                    if (stepping && y[ie] < energy) FUZZ_FAIL("dissipated energy decreased");
                    energy = y[ie];
                    stepping = 1;
                    if (st_ok(do_step(c, t, 1e-3))) {
                        t += 1e-3;
                        if (read_all(c, y2)) {
                            /* time (vr 0) moved; nothing else may */
                            size_t j = 0;
                            for (int i = 0; i < NVARS; ++i) {
                                if (VARS[i].kind != K_F64) continue;
                                if (VARS[i].causality != C_IND &&
                                    memcmp(&y[j], &y2[j], sizeof(double)) != 0)
                                    FUZZ_FAIL("a held step changed %s: %.17g -> %.17g",
                                              VARS[i].name, y[j], y2[j]);
                                ++j;
                            }
                        }
                    }
                }
            }
            break;
        }
        case 8: {
            const unsigned how = byte(&r);
            switch (how % 7) {
            case 0: {
                const double t0 = how & 8 ? value(&r) : 0.0;
                s = setup(c, t0, value(&r), how & 16);
                rejected_changes_nothing(c, s, "setup");
                if (st_ok(s)) t = t0;
                break;
            }
            default: {
                const struct mode_change *m = &MODE_CHANGES[how % 7];
                if (!m->call) {
                    s = logging(c, how & 32);
                    break;
                }
                s = m->call(c);
                rejected_changes_nothing(c, s, m->what);
                if (m->call == exit_init) stepping = 0;
                break;
            }
            }
            break;
        }
        case 9:
            s = reset(c);
            rejected_changes_nothing(c, s, "reset");
            if (st_ok(s)) t = 0.0, stepping = 0;
            break;
        case 10:
        case 11: {
            double v[NVARS];
            read_all(c, v);
            break;
        }
        case 12: check_own_state(c); break;
        case 13: { /* restore a mangled copy of the own state */
            static unsigned char buf[STATE_CAP];
            size_t n = 0;
            if (!serialize(c, buf, sizeof buf, &n) || n == 0) break;
            const unsigned at = byte(&r) | byte(&r) << 8;
            const unsigned how = byte(&r);
            if (how & 1)
                buf[at % n] ^= (unsigned char)(1u << (how >> 1 & 7));
            else if (how & 2) {
                const double x = value(&r);
                memcpy(buf + (at % (n > 8 ? n - 8 : 1)), &x, n >= 8 ? 8 : n);
            }
            s = restore(c, buf, how & 4 ? at % (n + 1) : n);
            rejected_changes_nothing(c, s, "restore");
            if (st_ok(s)) {
                double y[NVARS];
                read_all(c, y);
                check_own_state(c); /* whatever was accepted must round-trip */
                stepping = 0;
            }
            break;
        }
        case 14: {
            unsigned u[3], kn[3];
            double seed[3], out[3];
            const size_t nu = 1 + byte(&r) % 3, nk = 1 + byte(&r) % 3;
            const int adjoint = byte(&r) & 1;
            for (size_t i = 0; i < 3; ++i) {
                u[i] = vref(&r);
                kn[i] = vref(&r);
                seed[i] = byte(&r) & 1 ? 1.0 : value(&r);
            }
            s = derivative(c, u, nu, kn, nk, seed, out, adjoint);
            rejected_changes_nothing(c, s, "derivative");
            if (st_ok(s))
                for (size_t i = 0; i < (adjoint ? nk : nu); ++i)
                    if (!isfinite(out[i])) FUZZ_FAIL("derivative %g with OK", out[i]);
            break;
        }
        default: { /* a new instance */
            destroy(c);
            forget_setup();
            c = make(byte(&r) & 1);
            if (!c) return 0;
            t = 0.0;
            stepping = 0;
        }
        }
    }
    check_own_state(c);
    destroy(c);
    return 0;
}
