/* The FMI 2.0 glue called directly: state machine, logging categories,
 * instance independence and state handling. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi2Functions.h"
#include "host_support.h"
#include "initial_slip.h"
#include "models/OrthotropicContact/table.h"

static fmi2Component make(const char *name) {
    fmi2Component c =
        fmi2Instantiate(name, fmi2CoSimulation, FMU_GUID, "", &host_keep2_cb, fmi2False, fmi2False);
    CHECK(c != NULL, "instantiate %s failed", name);
    return c;
}

static void start(fmi2Component c) {
    CHECK(fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0) == fmi2OK, "setup");
    CHECK(fmi2EnterInitializationMode(c) == fmi2OK, "enter init");
    CHECK(fmi2ExitInitializationMode(c) == fmi2OK, "exit init");
}

static void test_instantiate_rejects(void) {
    host_log.count = 0;
    CHECK(fmi2Instantiate("x", fmi2ModelExchange, FMU_GUID, "", &host_keep2_cb, 0, 0) == NULL,
          "ME accepted");
    CHECK(host_log.count == 1 && strstr(host_log.message, "Co-Simulation"), "no reason logged");
    CHECK(fmi2Instantiate("x", fmi2CoSimulation, "{bad}", "", &host_keep2_cb, 0, 0) == NULL,
          "GUID accepted");
    CHECK(strstr(host_log.message, "GUID") != NULL, "GUID reason not logged: %s", host_log.message);
    CHECK(fmi2Instantiate("", fmi2CoSimulation, FMU_GUID, "", &host_keep2_cb, 0, 0) == NULL,
          "empty name");
    CHECK(fmi2Instantiate("x", fmi2CoSimulation, FMU_GUID, "", NULL, 0, 0) == NULL,
          "NULL callbacks");
}

static void test_state_machine(void) {
    fmi2Component c = make("sm");
    const fmi2ValueReference vr_T1 = OC_VR_T1, vr_mu1 = OC_VR_mu1;
    double v;
    host_log.count = 0;
    CHECK(fmi2DoStep(c, 0, 1e-3, fmi2True) == fmi2Error, "doStep before init");
    CHECK(host_log.count == 1 && host_log.status == fmi2Error, "wrong-state call not logged");
    CHECK(strcmp(host_log.category, "logStatusError") == 0, "category %s", host_log.category);
    CHECK(fmi2GetReal(c, &vr_T1, 1, &v) == fmi2Error, "getReal while instantiated");
    CHECK(fmi2ExitInitializationMode(c) == fmi2Error, "exit init before enter");
    start(c);
    CHECK(fmi2SetupExperiment(c, 0, 0, 0, 0, 0) == fmi2Error, "setup in step mode");
    v = 0.5;
    CHECK(fmi2SetReal(c, &vr_mu1, 1, &v) == fmi2Error, "fixed parameter set in step mode");
    CHECK(strstr(host_log.message, "fixed") != NULL, "reason: %s", host_log.message);
    CHECK(fmi2DoStep(c, 0, 1e-3, fmi2True) == fmi2OK, "doStep");
    CHECK(fmi2DoStep(c, 0.5, 1e-3, fmi2True) == fmi2Error, "doStep at the wrong time");
    CHECK(fmi2DoStep(c, 1e-3, -1, fmi2True) == fmi2Error, "negative step");
    CHECK(fmi2DoStep(c, 1e-3, INFINITY, fmi2True) == fmi2Error, "infinite step");
    CHECK(fmi2DoStep(c, 1e-3, 1.7e308, fmi2True) == fmi2OK, "a huge but finite step");
    CHECK(fmi2DoStep(c, 1e-3 + 1.7e308, 1.7e308, fmi2True) == fmi2Error, "step to t = inf");
    CHECK(fmi2GetReal(c, &vr_T1, 1, NULL) == fmi2Error, "NULL value array");
    CHECK(fmi2Terminate(c) == fmi2OK, "terminate");
    CHECK(fmi2DoStep(c, 1e-3, 1e-3, fmi2True) == fmi2Error, "doStep after terminate");
    CHECK(fmi2GetReal(c, &vr_T1, 1, &v) == fmi2OK, "getReal after terminate");
    CHECK(fmi2Reset(c) == fmi2OK, "reset");
    v = 0.5;
    CHECK(fmi2SetReal(c, &vr_mu1, 1, &v) == fmi2OK, "parameter after reset");
    CHECK(fmi2EnterEventMode(c) == fmi2Error, "ME function accepted");
    CHECK(fmi2DoStep(NULL, 0, 1, 0) == fmi2Error, "NULL instance");
    fmi2FreeInstance(c);
    fmi2FreeInstance(NULL);
}

static void test_logging_filter(void) {
    fmi2Component c = make("log");
    const fmi2ValueReference bad = 999;
    double v = 0;
    host_log.count = 0;
    CHECK(fmi2SetReal(c, &bad, 1, &v) == fmi2Error, "unknown vr");
    CHECK(host_log.count == 1 && strstr(host_log.message, "999"), "unknown vr not named: %s",
          host_log.message);
    const fmi2String cats[] = {"logStatusError"};
    CHECK(fmi2SetDebugLogging(c, fmi2False, 1, cats) == fmi2OK, "switch errors off");
    host_log.count = 0;
    CHECK(fmi2SetReal(c, &bad, 1, &v) == fmi2Error, "still an error");
    CHECK(host_log.count == 0, "filtered category still logged");
    CHECK(fmi2SetDebugLogging(c, fmi2True, 0, NULL) == fmi2OK, "all on");
    host_log.count = 0;
    start(c);
    CHECK(host_log.count >= 3 && strcmp(host_log.category, "logCalls") == 0, "call trace missing");
    const fmi2String unknown[] = {"logNonsense"};
    CHECK(fmi2SetDebugLogging(c, fmi2True, 1, unknown) == fmi2Error, "unknown category");
    /* A '%' in a message must reach the logger as a literal. */
    const fmi2String pct[] = {"50%s"};
    fmi2SetDebugLogging(c, fmi2True, 1, pct);
    CHECK(strstr(host_log.message, "50%s") != NULL, "percent mangled: %s", host_log.message);
    fmi2FreeInstance(c);
}

static void drive(fmi2Component c, double u1, double u2, double N, double *t) {
    const fmi2ValueReference vrs[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
    const double v[3] = {u1, u2, N};
    CHECK(fmi2SetReal(c, vrs, 3, v) == fmi2OK, "set inputs");
    CHECK(fmi2DoStep(c, *t, 1e-3, fmi2True) == fmi2OK, "doStep");
    *t += 1e-3;
}

static void test_instances_and_state(void) {
    fmi2Component a = make("a"), b = make("b");
    start(a);
    start(b);
    double ta = 0, tb = 0;
    for (int k = 1; k <= 100; ++k) drive(a, 1e-4 * k, 2e-5 * k, 18.0, &ta);
    drive(b, 1e-5, 0, 18.0, &tb);
    const fmi2ValueReference out[4] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2};
    double ya[4], yb[4];
    fmi2GetReal(a, out, 4, ya);
    fmi2GetReal(b, out, 4, yb);
    CHECK(ya[2] != 0 && yb[2] == 0, "instances share state");

    fmi2FMUstate st = NULL;
    CHECK(fmi2GetFMUstate(a, &st) == fmi2OK, "get state");
    size_t n = 0;
    CHECK(fmi2SerializedFMUstateSize(a, st, &n) == fmi2OK && n > 0, "size");
    fmi2Byte *bytes = malloc(n);
    CHECK(fmi2SerializeFMUstate(a, st, bytes, n) == fmi2OK, "serialize");
    for (int k = 101; k <= 150; ++k) drive(a, 1e-4 * k, -1e-5 * k, 18.0, &ta);
    double later[4];
    fmi2GetReal(a, out, 4, later);
    CHECK(fmi2SetFMUstate(a, st) == fmi2OK, "set state");
    double back[4];
    fmi2GetReal(a, out, 4, back);
    CHECK(memcmp(back, ya, sizeof ya) == 0, "restored outputs differ");
    fmi2FMUstate st2 = NULL;
    CHECK(fmi2DeSerializeFMUstate(b, bytes, n, &st2) == fmi2OK, "deserialize");
    CHECK(fmi2SetFMUstate(b, st2) == fmi2OK, "set deserialized state on b");
    double tb2 = ta - 50e-3;
    for (int k = 101; k <= 150; ++k) drive(b, 1e-4 * k, -1e-5 * k, 18.0, &tb2);
    double again[4];
    fmi2GetReal(b, out, 4, again);
    CHECK(memcmp(again, later, sizeof later) == 0, "continuation after deserialize not bit-exact");
    bytes[0] ^= 0xff;
    fmi2FMUstate st3 = NULL;
    CHECK(fmi2DeSerializeFMUstate(b, bytes, n, &st3) == fmi2Error && st3 == NULL,
          "corrupt image accepted");
    CHECK(fmi2DeSerializeFMUstate(b, bytes, n - 1, &st3) == fmi2Error, "short image accepted");
    bytes[0] ^= 0xff;

    /* Restored into a freshly instantiated instance, the next step continues
     * exactly as the original (the state carries the FMI mode and time). */
    fmi2Component fresh = make("fresh");
    fmi2FMUstate st4 = NULL;
    CHECK(fmi2DeSerializeFMUstate(fresh, bytes, n, &st4) == fmi2OK, "deserialize into fresh");
    CHECK(fmi2SetFMUstate(fresh, st4) == fmi2OK, "set state into fresh: %s", host_log.message);
    double tf = ta - 50e-3;
    for (int k = 101; k <= 150; ++k) drive(fresh, 1e-4 * k, -1e-5 * k, 18.0, &tf);
    double cont[4];
    CHECK(fmi2GetReal(fresh, out, 4, cont) == fmi2OK, "read after restore");
    CHECK(memcmp(cont, later, sizeof later) == 0, "fresh instance did not continue bit-exactly");
    /* Equal states give equal bytes. */
    fmi2FMUstate s5 = NULL, s6 = NULL;
    fmi2GetFMUstate(fresh, &s5);
    fmi2GetFMUstate(b, &s6);
    fmi2Byte *b5 = malloc(n), *b6 = malloc(n);
    fmi2SerializeFMUstate(fresh, s5, b5, n);
    fmi2SerializeFMUstate(b, s6, b6, n);
    CHECK(memcmp(b5, b6, n) == 0, "equal states serialize differently");
    /* Every single-bit flip is refused or gives a state that restores to
     * finite outputs; truncated and random bytes are refused. */
    int refused = 0;
    for (size_t i = 0; i < n; ++i)
        for (int bit = 0; bit < 8; ++bit) {
            memcpy(b6, b5, n);
            b6[i] ^= (fmi2Byte)(1 << bit);
            fmi2FMUstate s7 = NULL;
            if (fmi2DeSerializeFMUstate(fresh, b6, n, &s7) != fmi2OK) {
                ++refused;
                continue;
            }
            CHECK(fmi2SetFMUstate(fresh, s7) == fmi2OK, "accepted state not settable");
            double y[4] = {0};
            fmi2GetReal(fresh, out, 4, y);
            CHECK(isfinite(y[0]) && isfinite(y[1]) && isfinite(y[2]) && isfinite(y[3]),
                  "flipped state gives non-finite outputs");
            fmi2FreeFMUstate(fresh, &s7);
        }
    CHECK(refused > 0, "no flipped state refused");
    for (size_t len = 0; len < n; ++len) {
        fmi2FMUstate s8 = NULL;
        CHECK(fmi2DeSerializeFMUstate(fresh, b5, len, &s8) == fmi2Error, "truncated to %zu", len);
    }
    unsigned seed = 12345;
    for (int k = 0; k < 2000; ++k) {
        for (size_t i = 0; i < n; ++i)
            b6[i] = (fmi2Byte)((seed = seed * 1103515245u + 12345u) >> 16);
        if (k % 2) memcpy(b6, b5, 24); /* a valid header: the fields must be checked too */
        fmi2FMUstate s9 = NULL;
        CHECK(fmi2DeSerializeFMUstate(fresh, b6, n, &s9) == fmi2Error, "random bytes accepted");
    }
    free(b5);
    free(b6);
    fmi2FreeFMUstate(fresh, &s5);
    fmi2FreeFMUstate(b, &s6);
    fmi2FreeFMUstate(fresh, &st4);
    fmi2FreeInstance(fresh);
    free(bytes);
    fmi2FreeFMUstate(a, &st);
    fmi2FreeFMUstate(b, &st2);
    CHECK(st == NULL && st2 == NULL, "free did not clear the handle");
    fmi2FreeInstance(a);
    fmi2FreeInstance(b);
}

/* initial_slip.h's first step, through the FMI 2.0 calls. */
static void first_step(int rule, int initial, double s0, int inputs_in_init, double y[5],
                       int *state) {
    fmi2Component c = make("initial");
    const fmi2ValueReference vr_rule = OC_VR_slidingRule, vr_init = OC_VR_initialSlip;
    const fmi2ValueReference vr_s[2] = {OC_VR_s1Start, OC_VR_s2Start};
    const double s_start[2] = {s0, 0.5 * s0};
    CHECK(fmi2SetInteger(c, &vr_rule, 1, &rule) == fmi2OK, "rule");
    CHECK(fmi2SetInteger(c, &vr_init, 1, &initial) == fmi2OK, "initialSlip");
    CHECK(fmi2SetReal(c, vr_s, 2, s_start) == fmi2OK, "s1Start, s2Start");
    const fmi2ValueReference in[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N};
    const double u[3] = {1.0, 0.5, 18.39};
    CHECK(fmi2SetupExperiment(c, 0, 0, 0, 0, 0) == fmi2OK, "setup");
    CHECK(fmi2EnterInitializationMode(c) == fmi2OK, "enter");
    if (inputs_in_init) CHECK(fmi2SetReal(c, in, 3, u) == fmi2OK, "inputs in init");
    CHECK(fmi2ExitInitializationMode(c) == fmi2OK, "exit");
    CHECK(fmi2SetReal(c, in, 3, u) == fmi2OK, "inputs");
    CHECK(fmi2DoStep(c, 0, 1e-3, 1) == fmi2OK, "step");
    const fmi2ValueReference out[5] = {OC_VR_T1, OC_VR_T2, OC_VR_s1, OC_VR_s2,
                                       OC_VR_dissipatedEnergy};
    const fmi2ValueReference vr_state = OC_VR_contactState;
    CHECK(fmi2GetReal(c, out, 5, y) == fmi2OK && fmi2GetInteger(c, &vr_state, 1, state) == fmi2OK,
          "read");
    fmi2FreeInstance(c);
}

/* A range in the refusal names the variable's unit: alpha = 90 is degrees
 * given to a variable in rad. */
static void test_range_message_names_the_unit(void) {
    fmi2Component c = make("unit");
    const fmi2ValueReference alpha = OC_VR_alpha, eps1 = OC_VR_eps1, mu1 = OC_VR_mu1;
    double v = 90.0;
    CHECK(fmi2SetReal(c, &alpha, 1, &v) == fmi2Error, "alpha = 90 accepted");
    CHECK(strstr(host_log.message, "alpha = 90 rejected: outside [-12.5664, 12.5664] rad") != NULL,
          "unit not named: %s", host_log.message);
    v = -1.0;
    CHECK(fmi2SetReal(c, &eps1, 1, &v) == fmi2Error, "eps1 = -1 accepted");
    CHECK(strstr(host_log.message, "1e+300] N/m") != NULL, "unit not named: %s", host_log.message);
    v = -1.0; /* dimensionless ("1"): no unit after the range */
    CHECK(fmi2SetReal(c, &mu1, 1, &v) == fmi2Error, "mu1 = -1 accepted");
    CHECK(strstr(host_log.message, "1e+150]") != NULL && strstr(host_log.message, "] 1") == NULL,
          "dimensionless unit printed: %s", host_log.message);
    fmi2FreeInstance(c);
}

/* Only a handle this instance gave is freed: a second free and another
 * instance's state are refused with a logged reason, nothing crashes; the
 * state itself passed for its address (as fmusim 0.0.39 of the
 * Reference-FMUs does when it saves or restores a state) is freed with a
 * warning.  The sanitizer build sees any wrong free. */
static void test_state_handles(void) {
    fmi2Component a = make("handles-a"), b = make("handles-b");
    start(a);
    fmi2FMUstate st = NULL, kept = NULL, other = NULL;
    CHECK(fmi2GetFMUstate(a, &st) == fmi2OK && st != NULL, "get state");
    kept = st;
    CHECK(fmi2FreeFMUstate(a, &st) == fmi2OK && st == NULL, "free");
    host_log.count = 0;
    CHECK(fmi2FreeFMUstate(a, &kept) == fmi2Error && kept != NULL, "double free accepted");
    CHECK(host_log.count == 1 && strstr(host_log.message, "not a state of this instance"),
          "reason: %s", host_log.message);
    CHECK(fmi2GetFMUstate(a, &kept) == fmi2Error, "a freed state reused by get");
    CHECK(fmi2GetFMUstate(b, &other) == fmi2OK, "get state of b");
    CHECK(fmi2FreeFMUstate(a, &other) == fmi2Error && other != NULL, "b's state freed by a");
    CHECK(fmi2FreeFMUstate(b, &other) == fmi2OK && other == NULL, "b frees its own");
    CHECK(fmi2GetFMUstate(a, &st) == fmi2OK, "get again");
    host_log.count = 0;
    CHECK(fmi2FreeFMUstate(a, (fmi2FMUstate *)st) == fmi2OK, "the state for its address");
    CHECK(host_log.count == 1 && host_log.status == fmi2Warning &&
              strstr(host_log.message, "given the state instead of a pointer to it"),
          "warning: %s", host_log.message);
    fmi2FMUstate left = NULL; /* one left for FreeInstance to free */
    CHECK(fmi2GetFMUstate(a, &left) == fmi2OK, "get one to leave");
    fmi2FreeInstance(a);
    fmi2FreeInstance(b);
}

int main(void) {
    CHECK(strcmp(fmi2GetVersion(), "2.0") == 0, "version");
    CHECK(strcmp(fmi2GetTypesPlatform(), "default") == 0, "types platform");
    test_instantiate_rejects();
    test_state_machine();
    test_logging_filter();
    test_range_message_names_the_unit();
    test_instances_and_state();
    test_state_handles();
    check_initial_slip(first_step);
    return oc_report();
}
