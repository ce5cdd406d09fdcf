/* The FMI 3.0 glue called directly: state machine, variable types, the
 * derivatives, and a state restored into a fresh instance. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi3Functions.h"
#include "host_support.h"
#include "initial_slip.h"
#include "models/OrthotropicContact/table.h"

static fmi3Instance make(const char *name) {
    fmi3Instance c =
        fmi3InstantiateCoSimulation(name, FMU_GUID, "", fmi3False, fmi3False, fmi3False, fmi3False,
                                    NULL, 0, NULL, host_keep3, NULL);
    CHECK(c != NULL, "instantiate %s failed", name);
    return c;
}

static void start(fmi3Instance c) {
    CHECK(fmi3EnterInitializationMode(c, fmi3False, 0, 0, fmi3False, 0) == fmi3OK, "enter init");
    CHECK(fmi3ExitInitializationMode(c) == fmi3OK, "exit init");
}

static double t_now;
static void drive(fmi3Instance c, double u1, double u2, double N, double *t) {
    const fmi3ValueReference vrs[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
    const double v[3] = {u1, u2, N};
    fmi3Boolean ev, term, early;
    CHECK(fmi3SetFloat64(c, vrs, 3, v, 3) == fmi3OK, "set inputs: %s", host_log.message);
    CHECK(fmi3DoStep(c, *t, 1e-3, fmi3True, &ev, &term, &early, &t_now) == fmi3OK, "doStep: %s",
          host_log.message);
    CHECK(!ev && !term && !early && fabs(t_now - (*t + 1e-3)) < 1e-15, "doStep flags");
    *t += 1e-3;
}

static void test_rejects(void) {
    host_log.count = 0;
    CHECK(fmi3InstantiateCoSimulation("x", "{bad}", "", 0, 0, 0, 0, NULL, 0, NULL, host_keep3,
                                      NULL) == NULL,
          "bad token accepted");
    CHECK(strstr(host_log.message, "instantiationToken"), "reason: %s", host_log.message);
    CHECK(fmi3InstantiateCoSimulation("x", FMU_GUID, "", 0, 0, 1, 0, NULL, 0, NULL, host_keep3,
                                      NULL) == NULL,
          "event mode accepted");
    CHECK(fmi3InstantiateModelExchange("x", FMU_GUID, "", 0, 0, NULL, host_keep3) == NULL, "ME");
}

static void test_types_and_states(void) {
    fmi3Instance c = make("types");
    const fmi3ValueReference vr_rule = OC_VR_slidingRule, vr_state = OC_VR_contactState,
                             vr_T1 = OC_VR_T1, vr_mu1 = OC_VR_mu1;
    fmi3Int64 rule = 1;
    fmi3Int32 i32 = 0;
    double v;
    CHECK(fmi3GetFloat64(c, &vr_T1, 1, &v, 1) == fmi3Error, "get while instantiated");
    CHECK(fmi3SetInt64(c, &vr_rule, 1, &rule, 1) == fmi3OK, "rule through Int64 (Enumeration)");
    CHECK(fmi3SetInt32(c, &vr_rule, 1, &i32, 1) == fmi3Error, "enumeration set as Int32");
    rule = 4;
    CHECK(fmi3SetInt64(c, &vr_rule, 1, &rule, 1) == fmi3Error, "rule 4 accepted");
    v = 0.3;
    CHECK(fmi3SetFloat64(c, &vr_mu1, 1, &v, 2) == fmi3Error, "nValues mismatch accepted");
    start(c);
    CHECK(fmi3GetInt64(c, &vr_rule, 1, &rule, 1) == fmi3OK && rule == 1, "rule read back");
    CHECK(fmi3GetInt32(c, &vr_state, 1, &i32, 1) == fmi3OK, "contactState as Int32");
    CHECK(fmi3GetInt64(c, &vr_state, 1, &rule, 1) == fmi3Error, "Int32 read as Int64");
    CHECK(fmi3SetFloat64(c, &vr_mu1, 1, &v, 1) == fmi3Error, "fixed parameter in step mode");
    fmi3Boolean b;
    CHECK(fmi3GetBoolean(c, &vr_T1, 1, &b, 1) == fmi3Error, "Boolean of a Float64");
    CHECK(fmi3EnterEventMode(c) == fmi3Error, "event mode");
    CHECK(fmi3EnterConfigurationMode(c) == fmi3Error, "configuration mode");
    double t = 0;
    drive(c, 1e-3, 2e-4, 18.0, &t);
    fmi3Boolean ev, term, early;
    double last;
    CHECK(fmi3DoStep(c, t, 1.7e308, 0, &ev, &term, &early, &last) == fmi3OK, "huge finite step");
    CHECK(fmi3DoStep(c, last, 1.7e308, 0, &ev, &term, &early, &last) == fmi3Error, "step to inf");
    CHECK(fmi3DoStep(c, t, INFINITY, 0, &ev, &term, &early, &last) == fmi3Error, "inf step");
    CHECK(fmi3Terminate(c) == fmi3OK, "terminate");
    CHECK(fmi3Reset(c) == fmi3OK, "reset");
    v = 0.3;
    CHECK(fmi3SetFloat64(c, &vr_mu1, 1, &v, 1) == fmi3OK, "parameter after reset");
    fmi3FreeInstance(c);
}

static void test_derivatives(void) {
    fmi3Instance c = make("der");
    start(c);
    double t = 0;
    for (int k = 1; k <= 30; ++k) drive(c, 2e-4 * k, 5e-5 * k, 18.0, &t);
    const fmi3ValueReference unk[5] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2,
                                       OC_VR_dissipatedEnergy};
    const fmi3ValueReference kn[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
    double J[5][3], JT[3][5];
    for (int j = 0; j < 3; ++j) {
        double seed[3] = {0, 0, 0}, col[5];
        seed[j] = 1;
        CHECK(fmi3GetDirectionalDerivative(c, unk, 5, kn, 3, seed, 3, col, 5) == fmi3OK, "dir");
        for (int i = 0; i < 5; ++i) J[i][j] = col[i];
    }
    for (int i = 0; i < 5; ++i) {
        double seed[5] = {0, 0, 0, 0, 0}, row[3];
        seed[i] = 1;
        CHECK(fmi3GetAdjointDerivative(c, unk, 5, kn, 3, seed, 5, row, 3) == fmi3OK, "adjoint");
        for (int j = 0; j < 3; ++j) JT[j][i] = row[j];
    }
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 3; ++j)
            CHECK(J[i][j] == JT[j][i], "adjoint is not the transpose at %d %d", i, j);
    double seed[3] = {1, 0, 0}, out[5];
    CHECK(fmi3GetDirectionalDerivative(c, unk, 5, kn, 3, seed, 2, out, 5) == fmi3Error,
          "nSeed mismatch accepted");
    fmi3FreeInstance(c);
}

static void test_state_into_fresh_instance(void) {
    fmi3Instance a = make("a");
    start(a);
    double ta = 0;
    for (int k = 1; k <= 80; ++k) drive(a, 1e-4 * k, 3e-5 * k, k % 23 ? 18.0 : 0.0, &ta);
    fmi3FMUState st = NULL;
    CHECK(fmi3GetFMUState(a, &st) == fmi3OK, "get state");
    size_t n = 0;
    CHECK(fmi3SerializedFMUStateSize(a, st, &n) == fmi3OK, "size");
    fmi3Byte *bytes = malloc(n);
    CHECK(fmi3SerializeFMUState(a, st, bytes, n) == fmi3OK, "serialize");
    const fmi3ValueReference out[5] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2,
                                       OC_VR_dissipatedEnergy};
    double ya[5], yb[5];
    double tb = ta;
    for (int k = 81; k <= 120; ++k) drive(a, 1e-4 * k, -2e-5 * k, 18.0, &ta);
    fmi3GetFloat64(a, out, 5, ya, 5);
    fmi3Instance b = make("b"); /* never initialized: the state carries the mode */
    fmi3FMUState sb = NULL;
    CHECK(fmi3DeserializeFMUState(b, bytes, n, &sb) == fmi3OK, "deserialize");
    CHECK(fmi3SetFMUState(b, sb) == fmi3OK, "set into a fresh instance");
    for (int k = 81; k <= 120; ++k) drive(b, 1e-4 * k, -2e-5 * k, 18.0, &tb);
    CHECK(fmi3GetFloat64(b, out, 5, yb, 5) == fmi3OK, "read");
    CHECK(memcmp(ya, yb, sizeof ya) == 0, "fresh instance did not continue bit-exactly");
    bytes[n / 2] ^= 0x40;
    bytes[3] ^= 1;
    fmi3FMUState bad = NULL;
    CHECK(fmi3DeserializeFMUState(b, bytes, n, &bad) == fmi3Error && bad == NULL,
          "corrupt accepted");
    free(bytes);
    fmi3FreeFMUState(a, &st);
    fmi3FreeFMUState(b, &sb);
    fmi3FreeInstance(a);
    fmi3FreeInstance(b);
}

/* initial_slip.h's first step, through the FMI 3.0 calls. */
static void first_step(int rule_int, int initial_int, double s0, int inputs_in_init, double y[5],
                       int *state) {
    const int64_t rule = rule_int, initial = initial_int;
    fmi3Instance c = make("initial");
    const fmi3ValueReference vr_rule = OC_VR_slidingRule, vr_init = OC_VR_initialSlip;
    const fmi3ValueReference vr_s[2] = {OC_VR_s1Start, OC_VR_s2Start};
    const double s_start[2] = {s0, 0.5 * s0};
    CHECK(fmi3SetInt64(c, &vr_rule, 1, &rule, 1) == fmi3OK, "rule");
    CHECK(fmi3SetInt64(c, &vr_init, 1, &initial, 1) == fmi3OK, "initialSlip");
    CHECK(fmi3SetFloat64(c, vr_s, 2, s_start, 2) == fmi3OK, "s1Start, s2Start");
    const fmi3ValueReference in[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
    const double u[3] = {1.0, 0.5, 18.39};
    CHECK(fmi3EnterInitializationMode(c, 0, 0, 0, 0, 0) == fmi3OK, "enter");
    if (inputs_in_init) CHECK(fmi3SetFloat64(c, in, 3, u, 3) == fmi3OK, "inputs in init");
    CHECK(fmi3ExitInitializationMode(c) == fmi3OK, "exit");
    CHECK(fmi3SetFloat64(c, in, 3, u, 3) == fmi3OK, "inputs");
    fmi3Boolean ev, term, early;
    double last;
    CHECK(fmi3DoStep(c, 0, 1e-3, 1, &ev, &term, &early, &last) == fmi3OK, "step");
    const fmi3ValueReference out[5] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2,
                                       OC_VR_dissipatedEnergy};
    const fmi3ValueReference vr_state = OC_VR_contactState;
    fmi3Int32 st = -1; /* a failed read leaves it (CHECK has counted the failure) */
    CHECK(fmi3GetFloat64(c, out, 5, y, 5) == fmi3OK &&
              fmi3GetInt32(c, &vr_state, 1, &st, 1) == fmi3OK,
          "read");
    *state = st;
    fmi3FreeInstance(c);
}

/* An importer may list required intermediate variables (fmusim
 * --record-intermediate-values does): the FMU accepts and provides none,
 * and runs as without the request. */
static int n_intermediate_calls;
static void intermediate(fmi3InstanceEnvironment env, fmi3Float64 t, fmi3Boolean setRequested,
                         fmi3Boolean getAllowed, fmi3Boolean stepFinished,
                         fmi3Boolean canReturnEarly, fmi3Boolean *returnEarly,
                         fmi3Float64 *earlyReturnTime) {
    (void)env;
    (void)t;
    (void)setRequested;
    (void)getAllowed;
    (void)stepFinished;
    (void)canReturnEarly;
    (void)returnEarly;
    (void)earlyReturnTime;
    ++n_intermediate_calls;
}

static void test_intermediate_variables_requested(void) {
    const fmi3ValueReference wanted[3] = {OC_VR_T1, OC_VR_T2, OC_VR_s1};
    fmi3Instance c = fmi3InstantiateCoSimulation("inter", FMU_GUID, "", 0, 0, 0, 0, wanted, 3, NULL,
                                                 host_keep3, intermediate);
    CHECK(c != NULL, "a request for intermediate variables refused: %s", host_log.message);
    fmi3Instance plain = make("plain");
    start(c);
    start(plain);
    double t = 0, tp = 0;
    for (int k = 1; k <= 20; ++k) {
        drive(c, 3e-4 * k, 1e-4 * k, 18.0, &t);
        drive(plain, 3e-4 * k, 1e-4 * k, 18.0, &tp);
    }
    const fmi3ValueReference out[3] = {OC_VR_T1, OC_VR_T2, OC_VR_s1};
    double a[3], b[3];
    CHECK(fmi3GetFloat64(c, out, 3, a, 3) == fmi3OK &&
              fmi3GetFloat64(plain, out, 3, b, 3) == fmi3OK,
          "read");
    CHECK(memcmp(a, b, sizeof a) == 0, "the request changed the results");
    CHECK(n_intermediate_calls == 0, "intermediateUpdate called %d times", n_intermediate_calls);
    fmi3FreeInstance(c);
    fmi3FreeInstance(plain);
    CHECK(fmi3InstantiateCoSimulation("x", FMU_GUID, "", 0, 0, 0, 0, NULL, 2, NULL, host_keep3,
                                      NULL) == NULL,
          "NULL list with a count accepted");
}

/* The point has no structural parameter: the UInt64 functions refuse each
 * of its variables by name and type.  A state is freed once, by its own
 * instance; the state itself passed for its address (fmusim 0.0.39) is
 * freed with a warning. */
static void test_uint64_and_state_handles(void) {
    fmi3Instance c = make("handles");
    const fmi3ValueReference vr_mu1 = OC_VR_mu1;
    fmi3UInt64 u = 1;
    host_log.count = 0;
    CHECK(fmi3SetUInt64(c, &vr_mu1, 1, &u, 1) == fmi3Error, "mu1 set as UInt64");
    CHECK(host_log.count == 1 &&
              strstr(host_log.message,
                     "fmi3SetUInt64: variable mu1 (vr 1) is of type Float64 (Real)"),
          "reason: %s", host_log.message);
    start(c);
    CHECK(fmi3GetUInt64(c, &vr_mu1, 1, &u, 1) == fmi3Error, "mu1 read as UInt64");
    fmi3FMUState st = NULL, kept = NULL;
    CHECK(fmi3GetFMUState(c, &st) == fmi3OK, "get state");
    kept = st;
    CHECK(fmi3FreeFMUState(c, &st) == fmi3OK && st == NULL, "free");
    CHECK(fmi3FreeFMUState(c, &kept) == fmi3Error, "double free accepted");
    CHECK(strstr(host_log.message, "not a state of this instance"), "reason: %s", host_log.message);
    CHECK(fmi3GetFMUState(c, &st) == fmi3OK, "get again");
    host_log.count = 0;
    CHECK(fmi3FreeFMUState(c, (fmi3FMUState *)st) == fmi3OK && host_log.count == 1 &&
              strstr(host_log.message, "given the state instead of a pointer to it"),
          "warning: %s", host_log.message);
    fmi3FreeInstance(c);
}

int main(void) {
    CHECK(strcmp(fmi3GetVersion(), "3.0") == 0, "version");
    test_rejects();
    test_types_and_states();
    test_derivatives();
    test_state_into_fresh_instance();
    test_uint64_and_state_handles();
    test_intermediate_variables_requested();
    check_initial_slip(first_step);
    return oc_report();
}
