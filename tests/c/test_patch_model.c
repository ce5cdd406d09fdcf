/* The ContactPatch model through its FMI 2.0 functions, linked with its own
 * sources (patch_model.c, the law, the glue):
 *   - the directional derivatives against central differences of the
 *     pending step, over random grids, rules, pressures and paths, column
 *     by column wherever no cell changes between stick and slip within the
 *     difference;
 *   - random call sequences with hostile values: every call returns a
 *     defined status, a successful read is finite, a refused call changes
 *     nothing (the serialized state is the same byte for byte), and a state
 *     the FMU wrote restores into a fresh instance reading the same outputs. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi2Functions.h"
#include "patch_variables.h"
#include "random_values.h"

static void quiet(fmi2ComponentEnvironment e, fmi2String n, fmi2Status s, fmi2String c,
                  fmi2String m, ...) {
    (void)e; (void)n; (void)s; (void)c; (void)m;
}
static const fmi2CallbackFunctions CB = {quiet, calloc, free, NULL, NULL};

static const fmi2ValueReference KNOWN[6] = {PATCH_VR_u1, PATCH_VR_u2, PATCH_VR_theta,
                                            PATCH_VR_N, PATCH_VR_p1, PATCH_VR_p2};
static const fmi2ValueReference UNKNOWN[4] = {PATCH_VR_T1, PATCH_VR_T2, PATCH_VR_Mz,
                                              PATCH_VR_dissipatedEnergy};

static fmi2Component make(void) {
    return fmi2Instantiate("patch", fmi2CoSimulation, FMU_GUID, "", &CB, 0, 0);
}

/* The pending outputs (and the slip fraction) for inputs x. */
static void pending(fmi2Component c, const double x[6], double y[5]) {
    fmi2SetReal(c, KNOWN, 6, x);
    fmi2GetReal(c, UNKNOWN, 4, y);
    const fmi2ValueReference sf = PATCH_VR_slipFraction;
    fmi2GetReal(c, &sf, 1, &y[4]);
}

static void derivatives_match_differences(void) {
    int checked = 0, episodes_slipping = 0;
    for (int episode = 0; episode < 60; ++episode) {
        fmi2Component c = make();
        const fmi2ValueReference ivr[3] = {PATCH_VR_n1, PATCH_VR_n2, PATCH_VR_slidingRule};
        const fmi2Integer iv[3] = {1 + (int)pick(6), 1 + (int)pick(5), 1 + (int)pick(2)};
        fmi2SetInteger(c, ivr, 3, iv);
        const fmi2ValueReference pvr[4] = {PATCH_VR_alpha, PATCH_VR_beta, PATCH_VR_length, PATCH_VR_width};
        const double pv[4] = {3 * uniform(), 3 * uniform(), 0.02 + 0.1 * uniform(), 0.02 + 0.1 * uniform()};
        fmi2SetReal(c, pvr, 4, pv);
        fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0);
        fmi2EnterInitializationMode(c);
        double x[6] = {0, 0, 0, 20, 0, 0};
        x[4] = (uniform() - 0.5) * pv[2] / 7;
        x[5] = (uniform() - 0.5) * pv[3] / 7;
        fmi2SetReal(c, KNOWN, 6, x);
        fmi2ExitInitializationMode(c);
        double t = 0;
        for (int k = 0; k < 30; ++k, t += 1e-3) {
            x[0] += 1e-4 * (uniform() - 0.2);
            x[1] += 4e-5 * (uniform() - 0.5);
            x[2] += 1e-2 * (uniform() - 0.2);
            x[3] = 10 + 20 * uniform();
            fmi2SetReal(c, KNOWN, 6, x);
            fmi2DoStep(c, t, 1e-3, fmi2True);
        }
        x[0] += 1e-5;
        x[2] += 1e-3;
        double y[5];
        pending(c, x, y);
        episodes_slipping += y[4] > 0;
        double col[6][4]; /* column j: d(T1, T2, Mz, energy)/d(known j) */
        for (int j = 0; j < 6; ++j) {
            const double seed = 1.0;
            CHECK(fmi2GetDirectionalDerivative(c, UNKNOWN, 4, &KNOWN[j], 1, &seed, col[j]) == fmi2OK,
                  "derivative column %d", j);
        }
        static const double H[6] = {1e-9, 1e-9, 1e-8, 1e-6, 1e-8, 1e-8};
        for (int j = 0; j < 6; ++j) {
            double xp[6], xm[6], yp[5], ym[5];
            memcpy(xp, x, sizeof x);
            memcpy(xm, x, sizeof x);
            xp[j] += H[j];
            xm[j] -= H[j];
            pending(c, xp, yp);
            pending(c, xm, ym);
            if (yp[4] != y[4] || ym[4] != y[4]) continue; /* a cell switched: no derivative */
            for (int i = 0; i < 4; ++i) {
                double scale = 0;
                for (int k = 0; k < 6; ++k) scale = fmax(scale, fabs(col[k][i]));
                const double fd = (yp[i] - ym[i]) / (2 * H[j]);
                CHECK_CLOSE(col[j][i], fd, 3e-5 * scale + 1e-12, "dY/dX");
            }
            ++checked;
        }
        pending(c, x, y);
        fmi2Terminate(c);
        fmi2FreeInstance(c);
    }
    CHECK(checked > 250, "only %d columns checked", checked);
    CHECK(episodes_slipping > 20, "only %d episodes slipping", episodes_slipping);
    printf("derivatives: %d columns checked, %d of 60 states slipping\n", checked, episodes_slipping);
}

enum { CAP = 1 << 17 };
static unsigned char before[CAP], after[CAP];

static size_t serialize(fmi2Component c, unsigned char *buf) {
    fmi2FMUstate st = NULL;
    size_t n = 0;
    if (fmi2GetFMUstate(c, &st) != fmi2OK) return 0;
    if (fmi2SerializedFMUstateSize(c, st, &n) != fmi2OK || n > CAP ||
        fmi2SerializeFMUstate(c, st, (fmi2Byte *)buf, n) != fmi2OK)
        n = 0;
    fmi2FreeFMUstate(c, &st);
    return n;
}

static int defined(fmi2Status s) {
    return s == fmi2OK || s == fmi2Warning || s == fmi2Discard || s == fmi2Error || s == fmi2Fatal;
}

static void random_sequences(void) {
    rng_state = 0x2545f4914f6cdd1dull;
    long refused = 0, restored = 0;
    for (int episode = 0; episode < 40; ++episode) {
        fmi2Component c = make();
        double t = 0;
        for (int k = 0; k < 150; ++k) {
            const size_t nb = serialize(c, before);
            fmi2Status s = fmi2OK;
            switch (pick(9)) {
            case 0: case 1: case 2: { /* inputs, sometimes hostile */
                double v[6];
                for (int i = 0; i < 6; ++i) v[i] = pick(6) ? (uniform() - 0.5) * 0.02 : hostile();
                if (pick(2)) v[3] = 5 + 20 * uniform();
                s = fmi2SetReal(c, KNOWN, 6, v);
                break;
            }
            case 3: { /* a parameter, any value */
                const fmi2ValueReference vr = 1 + (fmi2ValueReference)pick(PATCH_VR_p2);
                const double v = pick(3) ? uniform() * 40 : hostile();
                const fmi2Integer iv = (fmi2Integer)(pick(3) ? pick(40) : (unsigned)next());
                s = (vr == PATCH_VR_n1 || vr == PATCH_VR_n2 || vr == PATCH_VR_slidingRule ||
                     vr == PATCH_VR_initialSlip)
                        ? fmi2SetInteger(c, &vr, 1, &iv)
                        : fmi2SetReal(c, &vr, 1, &v);
                break;
            }
            case 4:
                s = fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0);
                if (s == fmi2OK) s = fmi2EnterInitializationMode(c);
                break;
            case 5: s = fmi2ExitInitializationMode(c); break;
            case 6: case 7:
                s = fmi2DoStep(c, t, 1e-3, fmi2True);
                if (s == fmi2OK) t += 1e-3;
                break;
            default: { /* a state round trip into a fresh instance */
                const size_t n = serialize(c, before);
                if (!n) break;
                fmi2Component d = make();
                fmi2FMUstate st = NULL;
                CHECK(fmi2DeSerializeFMUstate(d, (const fmi2Byte *)before, n, &st) == fmi2OK, "deserialize own state");
                CHECK(fmi2SetFMUstate(d, st) == fmi2OK, "set own state in a fresh instance");
                fmi2FreeFMUstate(d, &st);
                double a[4], b[4];
                const fmi2Status ra = fmi2GetReal(c, UNKNOWN, 4, a), rb = fmi2GetReal(d, UNKNOWN, 4, b);
                CHECK(ra == rb, "restored reads with status %d, original %d", rb, ra);
                if (ra == fmi2OK) CHECK(memcmp(a, b, sizeof a) == 0, "restored outputs differ");
                fmi2FreeInstance(d);
                ++restored;
                continue;
            }
            }
            CHECK(defined(s), "status %d", s);
            if (s != fmi2OK && nb) {
                ++refused;
                const size_t na = serialize(c, after);
                CHECK(na == nb && memcmp(before, after, nb) == 0, "a refused call changed the instance");
            }
            double y[4];
            if (fmi2GetReal(c, UNKNOWN, 4, y) == fmi2OK)
                for (int i = 0; i < 4; ++i) CHECK(isfinite(y[i]), "output %d = %g read with OK", i, y[i]);
        }
        fmi2FreeInstance(c);
    }
    CHECK(refused > 100 && restored > 100, "refused %ld, restored %ld", refused, restored);
    printf("random sequences: %ld calls refused unchanged, %ld states restored\n", refused, restored);
}

int main(void) {
    rng_state = 0x9e3779b97f4a7c15ull;
    derivatives_match_differences();
    random_sequences();
    return oc_report();
}
