/* The CarriageBlock rig through the shared FMI 2.0 glue: its table served
 * by the glue (types, causalities, ranges, atomic batches), its outputs
 * against their closed forms, its lateral dynamics against the closed form
 * of the scheme it documents, and its state restored into a fresh instance. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi2Functions.h"
#include "glue/fmu_bytes.h"
#include "host_support.h"
#include "models/CarriageBlock/table.h"

static fmi2Component make(const char *name) {
    fmi2Component c = fmi2Instantiate(name, fmi2CoSimulation, FMU_GUID, "", &host_keep2_cb, 0, 0);
    CHECK(c != NULL, "instantiate %s: %s", name, host_log.message);
    return c;
}

static void start(fmi2Component c) {
    CHECK(fmi2SetupExperiment(c, 0, 0, 0, 0, 0) == fmi2OK, "setup");
    CHECK(fmi2EnterInitializationMode(c) == fmi2OK, "enter");
    CHECK(fmi2ExitInitializationMode(c) == fmi2OK, "exit: %s", host_log.message);
}

static double get(fmi2Component c, fmi2ValueReference vr) {
    double v = NAN;
    CHECK(fmi2GetReal(c, &vr, 1, &v) == fmi2OK, "get vr %u: %s", vr, host_log.message);
    return v;
}

static void set(fmi2Component c, fmi2ValueReference vr, double v) {
    CHECK(fmi2SetReal(c, &vr, 1, &v) == fmi2OK, "set vr %u = %g: %s", vr, v, host_log.message);
}

static void test_table_and_errors(void) {
    fmi2Component c = make("table");
    /* Defaults are the table's start values. */
    const struct {
        fmi2ValueReference vr;
        double start;
    } par[] = {{RIG_VR_mass, 1.875},     {RIG_VR_g, 9.806},     {RIG_VR_fInt, 5.0},
               {RIG_VR_velocity, 0.244}, {RIG_VR_muStrip, 0.0}, {RIG_VR_cStrip, 0.0}};
    double v;
    CHECK(fmi2GetReal(c, &par[0].vr, 1, &v) == fmi2Error, "read while instantiated");
    start(c);
    for (size_t k = 0; k < sizeof par / sizeof par[0]; ++k)
        CHECK(get(c, par[k].vr) == par[k].start, "start of vr %u", par[k].vr);
    /* Every vr of the table reads as a Real, none as an Integer, nothing else reads. */
    for (fmi2ValueReference vr = 0; vr < 30; ++vr) {
        int i;
        const int ok = fmi2GetReal(c, &vr, 1, &v) == fmi2OK;
        CHECK(ok == (vr < RIG_VR_COUNT_PLUS_ONE), "vr %u readable: %d", vr, ok);
        CHECK(fmi2GetInteger(c, &vr, 1, &i) == fmi2Error, "vr %u read as Integer", vr);
        if (!ok) CHECK(strstr(host_log.message, "unknown value reference"), "%s", host_log.message);
    }
    fmi2Terminate(c);
    fmi2Reset(c);
    /* Causality, range and phase, each refused with its reason; nothing changes. */
    const fmi2ValueReference vr_mass = RIG_VR_mass, vr_x1 = RIG_VR_x1, vr_T1 = RIG_VR_T1,
                             vr_time = RIG_VR_time;
    v = 0.0;
    CHECK(fmi2SetReal(c, &vr_mass, 1, &v) == fmi2Error && strstr(host_log.message, "mass"),
          "mass 0");
    v = 1.0;
    CHECK(fmi2SetReal(c, &vr_x1, 1, &v) == fmi2Error && strstr(host_log.message, "output"),
          "output");
    CHECK(fmi2SetReal(c, &vr_time, 1, &v) == fmi2Error && strstr(host_log.message, "independent"),
          "time set");
    v = NAN;
    CHECK(fmi2SetReal(c, &vr_T1, 1, &v) == fmi2Error && strstr(host_log.message, "finite"), "NaN");
    v = INFINITY;
    CHECK(fmi2SetReal(c, &vr_T1, 1, &v) == fmi2Error, "inf input accepted");
    const fmi2ValueReference batch[2] = {RIG_VR_velocity, RIG_VR_g};
    const double bv[2] = {0.5, -1.0};
    CHECK(fmi2SetReal(c, batch, 2, bv) == fmi2Error, "g < 0 accepted");
    int iv = 1;
    CHECK(fmi2SetInteger(c, &vr_mass, 1, &iv) == fmi2Error && strstr(host_log.message, "Float64"),
          "Integer set of a Real: %s", host_log.message);
    start(c);
    CHECK(get(c, RIG_VR_velocity) == 0.244, "partial batch applied");
    CHECK(get(c, RIG_VR_mass) == 1.875, "rejected mass kept");
    v = 2.0;
    CHECK(fmi2SetReal(c, &vr_mass, 1, &v) == fmi2Error && strstr(host_log.message, "fixed"),
          "parameter in step mode");
    const fmi2ValueReference u = RIG_VR_u1, kn = RIG_VR_T1;
    double seed = 1, out;
    CHECK(fmi2GetDirectionalDerivative(c, &u, 1, &kn, 1, &seed, &out) == fmi2Error &&
              strstr(host_log.message, "no derivatives"),
          "derivative: %s", host_log.message);
    fmi2FreeInstance(c);
}

/* Outputs that are functions of the parameters, the inputs and the time. */
static void test_outputs_closed_forms(void) {
    fmi2Component c = make("outputs");
    set(c, RIG_VR_mass, 2.5);
    set(c, RIG_VR_g, 9.81);
    set(c, RIG_VR_velocity, 0.3);
    set(c, RIG_VR_fInt, 4.0);
    start(c);
    CHECK(get(c, RIG_VR_N) == 2.5 * 9.81, "N = mass g");
    set(c, RIG_VR_T1, -7.0);
    CHECK(get(c, RIG_VR_driveForce) == 4.0 + 7.0, "driveForce = fInt - T1 after setting T1");
    double t = 0;
    const double h = 0.01;
    for (int k = 0; k < 10; ++k, t += h) CHECK(fmi2DoStep(c, t, h, 1) == fmi2OK, "step");
    CHECK(get(c, RIG_VR_x1) == 0.3 * get(c, RIG_VR_time), "x1 = velocity t");
    CHECK(get(c, RIG_VR_u1) == get(c, RIG_VR_x1) && get(c, RIG_VR_u2) == get(c, RIG_VR_x2),
          "u = x");
    fmi2FreeInstance(c);
}

/* Free lateral motion under a constant T2 (no strip): symplectic Euler gives
 * v_k = k h a and x_k = a h^2 k (k + 1) / 2 exactly (to rounding). */
static void test_free_motion_closed_form(void) {
    fmi2Component c = make("free");
    start(c);
    const double T2 = 0.75, m = 1.875, a = T2 / m, h = 1e-3;
    set(c, RIG_VR_T2, T2);
    double t = 0;
    for (int k = 1; k <= 400; ++k, t += h) {
        CHECK(fmi2DoStep(c, t, h, 1) == fmi2OK, "step");
        if (k % 100 == 0) {
            const double x = a * h * h * k * (k + 1) / 2;
            CHECK_CLOSE(get(c, RIG_VR_x2), x, 1e-12 * x, "x2 of the scheme");
        }
    }
    fmi2FreeInstance(c);
}

/* The strip: a Coulomb force that holds the block while |T2| <= muStrip P,
 * and a viscous term whose steady lateral velocity is T2 / cStrip. */
static void test_strip(void) {
    fmi2Component c = make("coulomb");
    set(c, RIG_VR_muStrip, 0.5);
    start(c);
    set(c, RIG_VR_T1, -4.0); /* push P = 4 N, strip holds up to 2 N */
    set(c, RIG_VR_T2, 1.9);
    double t = 0;
    for (int k = 0; k < 200; ++k, t += 1e-3) fmi2DoStep(c, t, 1e-3, 1);
    CHECK(get(c, RIG_VR_x2) == 0.0, "the strip let the block drift: x2 = %g", get(c, RIG_VR_x2));
    fmi2FreeInstance(c);

    c = make("viscous");
    set(c, RIG_VR_cStrip, 50.0);
    start(c);
    set(c, RIG_VR_T2, 2.0);
    t = 0;
    const double h = 1e-3;
    for (int k = 0; k < 2000; ++k, t += h) fmi2DoStep(c, t, h, 1); /* 53 time constants */
    const double x_before = get(c, RIG_VR_x2);
    fmi2DoStep(c, t, h, 1);
    CHECK_CLOSE((get(c, RIG_VR_x2) - x_before) / h, 2.0 / 50.0, 1e-9, "steady velocity T2/c");
    fmi2FreeInstance(c);
}

static void test_state_into_fresh_instance(void) {
    fmi2Component a = make("a");
    set(a, RIG_VR_muStrip, 0.2);
    set(a, RIG_VR_cStrip, 3.0);
    start(a);
    double t = 0;
    const double h = 2e-4;
    for (int k = 0; k < 300; ++k, t += h) {
        set(a, RIG_VR_T1, -5.0 - 0.01 * k);
        set(a, RIG_VR_T2, 2.0 * sin(0.05 * k));
        fmi2DoStep(a, t, h, 1);
    }
    fmi2FMUstate st = NULL;
    size_t n = 0;
    CHECK(fmi2GetFMUstate(a, &st) == fmi2OK && fmi2SerializedFMUstateSize(a, st, &n) == fmi2OK,
          "get state");
    fmi2Byte *bytes = malloc(n);
    CHECK(fmi2SerializeFMUstate(a, st, bytes, n) == fmi2OK, "serialize");
    CHECK(memcmp(bytes, "CBST", 4) == 0, "tag");
    fmi2Component b = make("b"); /* never initialized */
    fmi2FMUstate sb = NULL;
    CHECK(fmi2DeSerializeFMUstate(b, bytes, n, &sb) == fmi2OK && fmi2SetFMUstate(b, sb) == fmi2OK,
          "restore: %s", host_log.message);
    double tb = t;
    for (int k = 0; k < 100; ++k, t += h, tb += h) {
        set(a, RIG_VR_T2, -1.0);
        set(b, RIG_VR_T2, -1.0);
        fmi2DoStep(a, t, h, 1);
        CHECK(fmi2DoStep(b, tb, h, 1) == fmi2OK, "restored instance steps: %s", host_log.message);
    }
    for (fmi2ValueReference vr = 0; vr < RIG_VR_COUNT_PLUS_ONE; ++vr) {
        const double ya = get(a, vr), yb = get(b, vr);
        CHECK(memcmp(&ya, &yb, sizeof ya) == 0, "vr %u: %.17g vs %.17g", vr, ya, yb);
    }
    fmu_put_f64((unsigned char *)bytes + 4 + 4 + 4 + 4 + 8, NAN); /* mass, after the header */
    fmi2FMUstate bad = NULL;
    CHECK(fmi2DeSerializeFMUstate(b, bytes, n, &bad) == fmi2Error && bad == NULL,
          "forged mass accepted");
    free(bytes);
    fmi2FreeFMUstate(a, &st);
    fmi2FreeFMUstate(b, &sb);
    fmi2FreeInstance(a);
    fmi2FreeInstance(b);
}

/* Every output finite before OK: x1 = u1 = velocity time
 * can overflow from a velocity and a time each inside its range.  Each way
 * in is refused with an error and a logged reason, and changes nothing. */
static void all_outputs(fmi2Component c, double out[RIG_VR_COUNT_PLUS_ONE]) {
    for (fmi2ValueReference vr = 0; vr < RIG_VR_COUNT_PLUS_ONE; ++vr) out[vr] = get(c, vr);
}

static void same_outputs(const double a[RIG_VR_COUNT_PLUS_ONE],
                         const double b[RIG_VR_COUNT_PLUS_ONE], const char *what) {
    for (fmi2ValueReference vr = 0; vr < RIG_VR_COUNT_PLUS_ONE; ++vr)
        CHECK(memcmp(&a[vr], &b[vr], sizeof a[vr]) == 0, "%s changed vr %u: %.17g -> %.17g", what,
              vr, a[vr], b[vr]);
}

static void test_outputs_stay_finite(void) {
    const fmi2ValueReference vr_v = RIG_VR_velocity;
    const double fast = 1e6; /* the range's maximum */

    /* A start time whose x1 overflows. */
    fmi2Component c = make("start time");
    set(c, RIG_VR_velocity, fast);
    host_log.message[0] = '\0';
    CHECK(fmi2SetupExperiment(c, 0, 0, 1e303, 0, 0) == fmi2Error &&
              strstr(host_log.message, "overflows"),
          "start time 1e303 at 1e6 m/s: %s", host_log.message);
    CHECK(fmi2EnterInitializationMode(c) == fmi2OK, "enter after the refusal");
    CHECK(get(c, RIG_VR_time) == 0.0 && get(c, RIG_VR_x1) == 0.0, "the refused time was kept");
    fmi2FreeInstance(c);

    /* A velocity whose x1 overflows at the start time; x1 was finite. */
    c = make("velocity");
    CHECK(fmi2SetupExperiment(c, 0, 0, 1e303, 0, 0) == fmi2OK, "start time 1e303 at 0.244 m/s");
    CHECK(fmi2EnterInitializationMode(c) == fmi2OK, "enter");
    double before[RIG_VR_COUNT_PLUS_ONE], after[RIG_VR_COUNT_PLUS_ONE];
    all_outputs(c, before);
    CHECK(before[RIG_VR_x1] == 0.244 * 1e303, "x1 at the start time");
    CHECK(fmi2SetReal(c, &vr_v, 1, &fast) == fmi2Error && strstr(host_log.message, "overflows"),
          "velocity 1e6 at 1e303 s: %s", host_log.message);
    all_outputs(c, after);
    same_outputs(before, after, "a refused velocity");
    /* In a batch with a value that was accepted before it: all or nothing. */
    const fmi2ValueReference batch[2] = {RIG_VR_mass, RIG_VR_velocity};
    const double values[2] = {3.0, fast};
    CHECK(fmi2SetReal(c, batch, 2, values) == fmi2Error, "batch with an overflowing velocity");
    all_outputs(c, after);
    same_outputs(before, after, "a refused batch");
    fmi2FreeInstance(c);

    /* A step whose end time overflows x1; an ordinary step still goes. */
    c = make("step");
    set(c, RIG_VR_velocity, fast);
    const double t0 = 1.7e302; /* x1 = 1.7e308, just below the largest double */
    CHECK(fmi2SetupExperiment(c, 0, 0, t0, 0, 0) == fmi2OK, "start at %g", t0);
    CHECK(fmi2EnterInitializationMode(c) == fmi2OK && fmi2ExitInitializationMode(c) == fmi2OK,
          "init");
    set(c, RIG_VR_T1, -5.0);
    set(c, RIG_VR_T2, 1.0);
    all_outputs(c, before);
    CHECK(isfinite(before[RIG_VR_x1]), "x1 finite at the start");
    CHECK(fmi2DoStep(c, t0, 1e301, 1) == fmi2Error && strstr(host_log.message, "overflows"),
          "step to x1 = inf: %s", host_log.message);
    all_outputs(c, after);
    same_outputs(before, after, "a refused step");
    /* The lateral motion overflowing is refused alike, and the time moved
     * for it goes back (t0 + 5e300: x1 = 1.75e308 still finite). */
    set(c, RIG_VR_T2, 1.7e308);
    all_outputs(c, before);
    CHECK(fmi2DoStep(c, t0, 5e300, 1) == fmi2Error && strstr(host_log.message, "lateral motion"),
          "lateral overflow: %s", host_log.message);
    all_outputs(c, after);
    same_outputs(before, after, "a refused lateral step");
    set(c, RIG_VR_T2, 1.0);
    CHECK(fmi2DoStep(c, t0, 1.0, 1) == fmi2OK, "an ordinary step: %s", host_log.message);
    CHECK(get(c, RIG_VR_time) == t0 + 1.0 && get(c, RIG_VR_x1) == fast * (t0 + 1.0),
          "time and x1 after it");
    fmi2FreeInstance(c);

    /* A restored state whose time overflows x1: refused by deserialization,
     * and by fmi2SetFMUstate given the same bytes as a state. */
    c = make("state");
    set(c, RIG_VR_velocity, fast);
    start(c);
    set(c, RIG_VR_T1, -5.0);
    set(c, RIG_VR_T2, 1.0);
    CHECK(fmi2DoStep(c, 0.0, 1e-3, 1) == fmi2OK, "step");
    fmi2FMUstate st = NULL;
    size_t n = 0;
    CHECK(fmi2GetFMUstate(c, &st) == fmi2OK && fmi2SerializedFMUstateSize(c, st, &n) == fmi2OK,
          "get state");
    unsigned char *bytes = malloc(n);
    CHECK(fmi2SerializeFMUstate(c, st, (fmi2Byte *)bytes, n) == fmi2OK, "serialize");
    double t_state;
    fmu_get_f64(bytes + 16, &t_state); /* after tag, format, length and phase */
    CHECK(t_state == 1e-3, "the header's time is at byte 16: %g", t_state);
    fmu_put_f64(bytes + 16, 1e303);
    set(c, RIG_VR_T2, -2.0);
    CHECK(fmi2DoStep(c, 1e-3, 1e-3, 1) == fmi2OK, "a second step, so the state differs");
    all_outputs(c, before);
    fmi2FMUstate forged = NULL;
    CHECK(fmi2DeSerializeFMUstate(c, (const fmi2Byte *)bytes, n, &forged) == fmi2Error &&
              forged == NULL && strstr(host_log.message, "overflows") &&
              strstr(host_log.message, "1e+303"),
          "deserialize: %s", host_log.message);
    memcpy(st, bytes, n); /* the glue's state is its serialized bytes */
    CHECK(fmi2SetFMUstate(c, st) == fmi2Error && strstr(host_log.message, "overflows"),
          "set a state at t = 1e303: %s", host_log.message);
    all_outputs(c, after);
    same_outputs(before, after, "a refused state");
    fmu_put_f64(bytes + 16, 1e-3);
    memcpy(st, bytes, n);
    CHECK(fmi2SetFMUstate(c, st) == fmi2OK, "the untouched state restores: %s", host_log.message);
    CHECK(get(c, RIG_VR_time) == 1e-3 && get(c, RIG_VR_x1) == fast * 1e-3, "restored time, x1");
    free(bytes);
    fmi2FreeFMUstate(c, &st);
    fmi2FreeInstance(c);
}

int main(void) {
    test_table_and_errors();
    test_outputs_closed_forms();
    test_free_motion_closed_form();
    test_strip();
    test_state_into_fresh_instance();
    test_outputs_stay_finite();
    return oc_report();
}
