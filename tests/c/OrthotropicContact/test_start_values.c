/* Start values an FMU reads from <resources>/start_values.txt at
 * instantiation (format: fmu_instance.h): both FMI versions (2.0 through a
 * file URI with a percent-escaped space, 3.0 through a native path), exact
 * hexadecimal floats, every kind of bad line refused with the file and line
 * named, no file = the compiled defaults, reset back to the file's values.
 * OC_TEST_DIR (from CMake) holds "start values/resources/". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi2Functions.h"
#include "fmi3Functions.h"
#include "glue/fmu_instance.h"
#include "host_support.h"
#include "models/OrthotropicContact/table.h"

#define DIR OC_TEST_DIR "/start values/resources/"
#define URI "file://" OC_TEST_DIR "/start%20values/resources"

static void write_file(const char *text) {
    FILE *f = fopen(DIR "start_values.txt", "wb");
    CHECK(f != NULL, "cannot write the fixture");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static fmi2Component make2(void) {
    return fmi2Instantiate("sv", fmi2CoSimulation, FMU_GUID, URI, &host_keep2_cb, 0, 0);
}
static fmi3Instance make3(void) {
    return fmi3InstantiateCoSimulation("sv", FMU_GUID, DIR, 0, 0, 0, 0, NULL, 0, NULL, host_keep3,
                                       NULL);
}

static void test_uri_decoding(void) {
    const char *cases[][2] = {{"file:///home/a%20b/res/", "/home/a b/res/"},
                              {"file:/home/x", "/home/x"},
                              {"file://localhost/home/x", "/home/x"},
                              {"file:///C:/Users/x%2By", "C:/Users/x+y"},
                              {"FILE:///c|/dir", "c:/dir"},
                              {"file://server/share/r", "//server/share/r"}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        char *p = fmu_path_from_uri(cases[k][0]);
        CHECK(p && strcmp(p, cases[k][1]) == 0, "%s -> %s, expected %s", cases[k][0],
              p ? p : "NULL", cases[k][1]);
        free(p);
    }
    CHECK(fmu_path_from_uri("http://x/y") == NULL, "http URI taken as a file");
}

/* 0.5, -0.375, the largest subnormal's neighbour and 1e-300 written as %a:
 * read back bit for bit. */
static void test_values_read_exactly(void) {
    char text[1024];
    const double eps1 = 12345.678901234567, s1 = -0.375, s2 = 1e-300;
    snprintf(text, sizeof text,
             "# calibrated\r\n\n  mu1 = 0x1p-1\r\neps1=%a\n slidingRule = 1\ninitialSlip =2\t\n"
             "s1Start = %a\ns2Start = %a\nbeta = 0\n",
             eps1, s1, s2);
    write_file(text);
    const fmi2ValueReference vr[5] = {OC_VR_mu1, OC_VR_eps1, OC_VR_s1Start, OC_VR_s2Start,
                                      OC_VR_beta};
    const double want[5] = {0.5, eps1, s1, s2, 0.0};
    fmi2Component c = make2();
    CHECK(c != NULL, "FMI 2.0 refused a good file: %s", host_log.message);
    if (!c) return;
    fmi2SetupExperiment(c, 0, 0, 0, 0, 0);
    fmi2EnterInitializationMode(c);
    double got[5];
    int rule, init;
    const fmi2ValueReference vr_rule = OC_VR_slidingRule, vr_init = OC_VR_initialSlip;
    CHECK(fmi2GetReal(c, vr, 5, got) == fmi2OK && memcmp(got, want, sizeof got) == 0,
          "FMI 2.0 values: %a %a %a %a", got[0], got[1], got[2], got[3]);
    CHECK(fmi2GetInteger(c, &vr_rule, 1, &rule) == fmi2OK && rule == 1, "rule %d", rule);
    CHECK(fmi2GetInteger(c, &vr_init, 1, &init) == fmi2OK && init == 2, "initialSlip %d", init);
    /* Reset returns to the file's values, not the compiled ones. */
    const double other = 0.25;
    fmi2Reset(c);
    fmi2SetReal(c, vr, 1, &other);
    fmi2Reset(c);
    fmi2SetupExperiment(c, 0, 0, 0, 0, 0);
    fmi2EnterInitializationMode(c);
    CHECK(fmi2GetReal(c, vr, 5, got) == fmi2OK && memcmp(got, want, sizeof got) == 0,
          "after reset: mu1 = %g", got[0]);
    fmi2FreeInstance(c);

    fmi3Instance d = make3();
    CHECK(d != NULL, "FMI 3.0 refused a good file: %s", host_log.message);
    if (!d) return;
    fmi3EnterInitializationMode(d, 0, 0, 0, 0, 0);
    fmi3Int64 r64;
    CHECK(fmi3GetFloat64(d, vr, 5, got, 5) == fmi3OK && memcmp(got, want, sizeof got) == 0,
          "FMI 3.0 values");
    CHECK(fmi3GetInt64(d, &vr_rule, 1, &r64, 1) == fmi3OK && r64 == 1, "FMI 3.0 rule");
    fmi3FreeInstance(d);
}

static void test_bad_files_refused(void) {
    const struct {
        const char *text, *expect;
        int line;
    } bad[] = {
        {"mu1 = 0.5\n", "hexadecimal float", 1},
        {"# ok\nmu9 = 0x1p0\n", "no variable named \"mu9\"", 2},
        {"T1 = 0x1p0\n", "not a parameter", 1},
        {"u1 = 0x1p0\n", "not a parameter", 1},
        {"mu1 = -0x1p0\n", "outside", 1},
        {"alpha = 0x1.68p+6\n", "outside [-12.5664, 12.5664] rad", 1},
        {"mu1 = 0x1p0 x\n", "characters after the number", 1},
        {"mu1 0x1p0\n", "name = value", 1},
        {"mu1 = 0x1p0\nmu1 = 0x1p0\n", "given twice", 2},
        {"slidingRule = 4\n", "outside", 1},
        {"slidingRule = 0x1p1\n", "decimal integer", 1},
        {"eps1 = 0x1.00000000000001p0\n", "more digits than a double", 1},
        {"eps1 = 0x1p-1080\n", "not representable", 1},
        {"eps1 = 0x1\n", "no binary exponent", 1},
        {"alpha = 0x1p+9999\n", "not representable", 1},
        {"mu1 = 1234567890123456\n", "more than 15 digits", 1},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
        write_file(bad[k].text);
        host_log.message[0] = '\0';
        fmi2Component c = make2();
        char line[32];
        snprintf(line, sizeof line, "line %d:", bad[k].line);
        CHECK(c == NULL, "FMI 2.0 accepted: %s", bad[k].text);
        CHECK(strstr(host_log.message, bad[k].expect) && strstr(host_log.message, line) &&
                  strstr(host_log.message, "start values/resources/start_values.txt"),
              "case %zu: message \"%s\"", k, host_log.message);
        if (c) fmi2FreeInstance(c);
        fmi3Instance d = make3();
        CHECK(d == NULL && strstr(host_log.message, bad[k].expect), "FMI 3.0 case %zu: %s", k,
              host_log.message);
        if (d) fmi3FreeInstance(d);
    }
    /* Each value in its range, together inadmissible for the law (tensors
     * that overflow): refused as well, with the model's reason. */
    char text[256];
    snprintf(text, sizeof text, "mu1 = %a\nmu2 = %a\neps1 = %a\neps2 = %a\n", 1e-150, 1e150, 1e300,
             1e-300);
    write_file(text);
    fmi2Component c = make2();
    CHECK(c == NULL && strstr(host_log.message, "not admissible"), "inadmissible set: %s",
          host_log.message);
    if (c) fmi2FreeInstance(c);
}

static void test_no_file_is_the_defaults(void) {
    remove(DIR "start_values.txt");
    host_log.message[0] = '\0';
    fmi2Component c = make2();
    CHECK(c != NULL && host_log.message[0] == '\0', "no file: %s", host_log.message);
    fmi2SetupExperiment(c, 0, 0, 0, 0, 0);
    fmi2EnterInitializationMode(c);
    const fmi2ValueReference vr = OC_VR_mu1;
    double v;
    CHECK(fmi2GetReal(c, &vr, 1, &v) == fmi2OK && v == 0.408, "default mu1 %g", v);
    fmi2FreeInstance(c);
    fmi3Instance d = fmi3InstantiateCoSimulation("sv", FMU_GUID, NULL, 0, 0, 0, 0, NULL, 0, NULL,
                                                 host_keep3, NULL);
    CHECK(d != NULL, "NULL resourcePath refused");
    if (d) fmi3FreeInstance(d);
}

int main(void) {
    test_uri_decoding();
    test_values_read_exactly();
    test_bad_files_refused();
    test_no_file_is_the_defaults();
    return oc_report();
}
