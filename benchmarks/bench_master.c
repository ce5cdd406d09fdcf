/* Benchmark (not a test): what the compiled master adds to the contact FMU's
 * own step.  The master (master_src/rig_master.c, as `orthocontact uq` runs
 * it: the aged mat's dynamic rig at the UQ step of 4 ms, 512 steps a run,
 * ten mat angles) is timed per rig step; then the same inputs, recorded from
 * those runs, are replayed through the same FMU binary with nothing but
 * fmi2SetReal(u1, u2, N) + fmi2DoStep + fmi2GetReal(T1, T2): the contact's
 * own cost on exactly those steps.  Both in one run, interleaved, the least
 * disturbed of `rounds`, thread CPU time.  Target: rig step <= 1.5x
 * contact step.
 *
 *   bench_master [rounds]
 * Environment: BENCH_OURS_FMI2 (the contact binary to run instead of the
 * host build's, e.g. the shipped one that `orthocontact uq` loads).
 */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "fmi2Functions.h"
#include "fmu_token.h"
#include "host_support.h"
#include "rig_master.h"

enum { ANGLES = 10, STEPS = 513, REPS = 20 }; /* ceil(0.5 m / (0.244 m/s 4 ms)) */

int main(int argc, char **argv) {
    const int rounds = argc > 1 ? atoi(argv[1]) : 7;
    char err[512];
    const char *ours = getenv("BENCH_OURS_FMI2") ? getenv("BENCH_OURS_FMI2") : OURS_FMI2;
    void *m = rm_open(ours, FMU_TOKEN, "", err, sizeof err);
    if (!m) return fprintf(stderr, "%s\n", err), 2;
    rm_contact p[ANGLES];
    rig_setup r[ANGLES];
    rig_figures out[ANGLES];
    const double deg = 3.141592653589793 / 180.0;
    for (int i = 0; i < ANGLES; ++i) {
        const double th = 10.0 * i * deg;
        p[i] = (rm_contact){0.408, 0.625, 12510.0, 10000.0, th + 90.0 * deg, th, 2};
        r[i] = (rig_setup){1.875, 9.806, 5.0, 0.244, 0.5, 0.0, 4e-3, 0.5, 0.0, 0};
    }
    /* the inputs the rig gives the contact, run by run */
    static double rows[ANGLES][STEPS + 1][RM_RECORD_COLUMNS];
    long n_rows[ANGLES];
    for (int i = 0; i < ANGLES; ++i)
        if (rm_record(m, &p[i], &r[i], 1, &rows[i][0][0], STEPS + 1, &n_rows[i], &out[i], err,
                      sizeof err) != 0 ||
            n_rows[i] != STEPS)
            return fprintf(stderr, "record: %s (%ld rows)\n", err, n_rows[i]), 2;

    void *lib = dlopen(ours, RTLD_NOW | RTLD_LOCAL);
    if (!lib) return fprintf(stderr, "%s\n", dlerror()), 2;
    fmi2InstantiateTYPE *inst = (fmi2InstantiateTYPE *)dlsym(lib, "fmi2Instantiate");
    fmi2FreeInstanceTYPE *free_inst = (fmi2FreeInstanceTYPE *)dlsym(lib, "fmi2FreeInstance");
    fmi2SetRealTYPE *set_real = (fmi2SetRealTYPE *)dlsym(lib, "fmi2SetReal");
    fmi2GetRealTYPE *get_real = (fmi2GetRealTYPE *)dlsym(lib, "fmi2GetReal");
    fmi2SetIntegerTYPE *set_int = (fmi2SetIntegerTYPE *)dlsym(lib, "fmi2SetInteger");
    fmi2DoStepTYPE *do_step = (fmi2DoStepTYPE *)dlsym(lib, "fmi2DoStep");
    fmi2ResetTYPE *reset = (fmi2ResetTYPE *)dlsym(lib, "fmi2Reset");
    fmi2SetupExperimentTYPE *setup = (fmi2SetupExperimentTYPE *)dlsym(lib, "fmi2SetupExperiment");
    fmi2EnterInitializationModeTYPE *enter =
        (fmi2EnterInitializationModeTYPE *)dlsym(lib, "fmi2EnterInitializationMode");
    fmi2ExitInitializationModeTYPE *exit_ =
        (fmi2ExitInitializationModeTYPE *)dlsym(lib, "fmi2ExitInitializationMode");

    double best_rig = 1e30, best_contact = 1e30, lo = 1e30, hi = 0, sink = 0;
    for (int round = 0; round < rounds; ++round) {
        double t0 = now();
        for (int k = 0; k < REPS; ++k)
            if (rm_run(m, ANGLES, p, r, out, err, sizeof err) != 0)
                return fprintf(stderr, "%s\n", err), 2;
        const double rig_ns = 1e9 * (now() - t0) / (REPS * ANGLES * STEPS);

        /* the same steps through the FMI calls alone, set up as the master
         * sets up every run (one instance, reset between runs) */
        fmi2Component c = inst("replay", fmi2CoSimulation, FMU_TOKEN, "", &host_print2_cb, 0, 0);
        t0 = now();
        for (int k = 0; k < REPS; ++k)
            for (int i = 0; i < ANGLES; ++i) {
#define LAW_VR(name, vr, ...) vr,
#define LAW_VALUE(name, ...) p[i].name,
                const fmi2ValueReference vr[] = {OC_LAW_PARAMETERS(LAW_VR)},
                                         vr_rule = OC_VR_slidingRule;
                const fmi2ValueReference in[3] = {OC_VR_u1, OC_VR_u2, OC_VR_N},
                                         vr_T[2] = {OC_VR_T1, OC_VR_T2};
                const double v[] = {OC_LAW_PARAMETERS(LAW_VALUE)};
#undef LAW_VR
#undef LAW_VALUE
                const fmi2Integer rule = p[i].rule;
                reset(c);
                set_real(c, vr, sizeof vr / sizeof vr[0], v);
                set_int(c, &vr_rule, 1, &rule);
                setup(c, fmi2False, 0, 0, fmi2False, 0);
                enter(c);
                exit_(c);
                const double N = r[i].mass * r[i].g, h = r[i].step;
                double t = 0;
                for (int s = 0; s < STEPS; ++s) {
                    const double u[3] = {rows[i][s][1], rows[i][s][2], N};
                    double T[2];
                    set_real(c, in, 3, u);
                    do_step(c, t, h, fmi2True);
                    t += h;
                    get_real(c, vr_T, 2, T);
                    sink += T[0];
                }
            }
        const double contact_ns = 1e9 * (now() - t0) / (REPS * ANGLES * STEPS);
        free_inst(c);
        best_rig = fmin(best_rig, rig_ns);
        best_contact = fmin(best_contact, contact_ns);
        lo = fmin(lo, rig_ns / contact_ns);
        hi = fmax(hi, rig_ns / contact_ns);
    }
    printf("# the compiled master on the aged mat's dynamic rig at 4 ms (uq), %d runs x %d steps "
           "a round, least disturbed of %d rounds\n",
           REPS * ANGLES, STEPS, rounds);
    printf("rig step (master + contact): %6.1f ns  (%.2f M rig steps/s)\n", best_rig,
           1e3 / best_rig);
    printf("contact step alone:          %6.1f ns  (%.2f M contact steps/s)\n", best_contact,
           1e3 / best_contact);
    printf("rig / contact: %.2f [rounds %.2f-%.2f]  target <= 1.50 %s\n", best_rig / best_contact,
           lo, hi, best_rig / best_contact <= 1.5 ? "met" : "NOT MET");
    if (sink == 12345.6789) printf(" ");
    rm_close(m);
    dlclose(lib);
    return 0;
}
