/* The ContactPad model through its FMI 2.0 functions, linked with its own
 * sources (models/ContactPad/model.c and pressure.c, the patch's cells, the
 * law, the glue):
 *   - the directional derivatives of T1, T2, Mz, Fn, M1, M2 and
 *     dissipatedEnergy against central differences of the pending step,
 *     over random grids, rules, poses (lift-off among them) and damping,
 *     column by column wherever no cell changes between stick and slip
 *     within the difference;
 *   - full contact: Fn = kn A d and the moments of the continuum's linear
 *     pressure to 1e-12 on random grids and turns, the cells' normal forces
 *     (read from the committed states the FMU serialized) summing to Fn;
 *   - random call sequences with hostile values: every call returns a
 *     defined status, a successful read is finite, a refused call changes
 *     nothing (the serialized state is the same byte for byte), and a state
 *     the FMU wrote restores into a fresh instance reading the same outputs.
 * The lift-off's exact integrals against the continuum's closed form:
 * tests/fmus/test_pad.py (closed_forms.pad). */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "fmi2Functions.h"
#include "host_support.h"
#include "models/ContactPad/model.h"
#include "models/ContactPad/table.h"
#include "random_values.h"

enum { NK = 6, NU = 7 };
static const fmi2ValueReference KNOWN[NK] = {PAD_VR_u1, PAD_VR_u2,   PAD_VR_theta,
                                             PAD_VR_d,  PAD_VR_phi1, PAD_VR_phi2};
static const fmi2ValueReference UNKNOWN[NU] = {
    PAD_VR_T1, PAD_VR_T2, PAD_VR_Mz, PAD_VR_Fn, PAD_VR_M1, PAD_VR_M2, PAD_VR_dissipatedEnergy};

static fmi2Component make(void) {
    return fmi2Instantiate("pad", fmi2CoSimulation, FMU_GUID, "", &host_quiet2_cb, 0, 0);
}

/* The pending outputs for inputs x, then slipFraction and contactState. */
static void pending(fmi2Component c, const double x[NK], double y[NU + 2]) {
    fmi2SetReal(c, KNOWN, NK, x);
    fmi2GetReal(c, UNKNOWN, NU, y);
    const fmi2ValueReference sf = PAD_VR_slipFraction, cs = PAD_VR_contactState;
    fmi2Integer state = -1;
    fmi2GetReal(c, &sf, 1, &y[NU]);
    fmi2GetInteger(c, &cs, 1, &state);
    y[NU + 1] = state;
}

/* A pad of random grid, rule, size and foundation in initialization mode. */
static fmi2Component random_pad(double *L, double *W, double *kn, int *n1, int *n2) {
    fmi2Component c = make();
    *n1 = 1 + (int)pick(7);
    *n2 = 1 + (int)pick(6);
    const fmi2ValueReference ivr[3] = {PAD_VR_n1, PAD_VR_n2, PAD_VR_slidingRule};
    const fmi2Integer iv[3] = {*n1, *n2, 1 + (int)pick(2)};
    fmi2SetInteger(c, ivr, 3, iv);
    *L = 0.02 + 0.1 * uniform();
    *W = 0.02 + 0.1 * uniform();
    *kn = 1e7 * (1 + 20 * uniform());
    const fmi2ValueReference pvr[6] = {PAD_VR_alpha, PAD_VR_beta, PAD_VR_length,
                                       PAD_VR_width, PAD_VR_kn,   PAD_VR_dn};
    const double pv[6] = {3 * uniform(), 3 * uniform(), *L, *W, *kn, pick(2) ? 0.0 : 3e4};
    fmi2SetReal(c, pvr, 6, pv);
    fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0);
    fmi2EnterInitializationMode(c);
    return c;
}

static void derivatives_match_differences(void) {
    int checked = 0, lifted = 0, slipping = 0;
    for (int episode = 0; episode < 60; ++episode) {
        double L, W, kn;
        int n1, n2;
        fmi2Component c = random_pad(&L, &W, &kn, &n1, &n2);
        /* an approach of 20 N, tilted to lift the trailing part half the time */
        const double d0 = 20.0 / (kn * L * W);
        const double tilt = (pick(2) ? 4.0 : 0.5) * d0 / L;
        double x[NK] = {0, 0, 0, d0, tilt * (uniform() - 0.5), tilt * (uniform() - 0.5)};
        fmi2SetReal(c, KNOWN, NK, x);
        fmi2ExitInitializationMode(c);
        double t = 0;
        for (int k = 0; k < 20; ++k, t += 1e-3) {
            x[0] += 1e-4 * (uniform() - 0.2);
            x[1] += 4e-5 * (uniform() - 0.5);
            x[2] += 1e-2 * (uniform() - 0.2);
            x[3] = d0 * (0.8 + 0.4 * uniform());
            fmi2SetReal(c, KNOWN, NK, x);
            fmi2DoStep(c, t, 1e-3, fmi2True);
        }
        x[0] += 1e-5;
        x[2] += 1e-3;
        double y[NU + 2];
        pending(c, x, y);
        const fmi2ValueReference cf = PAD_VR_contactFraction;
        double fraction = 1;
        fmi2GetReal(c, &cf, 1, &fraction);
        lifted += fraction < 1;
        slipping += y[NU] > 0;
        double col[NK][NU];
        for (int j = 0; j < NK; ++j) {
            const double seed = 1.0;
            CHECK(fmi2GetDirectionalDerivative(c, UNKNOWN, NU, &KNOWN[j], 1, &seed, col[j]) ==
                      fmi2OK,
                  "derivative column %d", j);
        }
        const double H[NK] = {1e-9, 1e-9, 1e-8, 1e-6 * d0, 1e-6 * tilt, 1e-6 * tilt};
        for (int j = 0; j < NK; ++j) {
            double xp[NK], xm[NK], yp[NU + 2], ym[NU + 2];
            memcpy(xp, x, sizeof x);
            memcpy(xm, x, sizeof x);
            xp[j] += H[j];
            xm[j] -= H[j];
            pending(c, xp, yp);
            pending(c, xm, ym);
            if (yp[NU] != y[NU] || ym[NU] != y[NU] || yp[NU + 1] != y[NU + 1] ||
                ym[NU + 1] != y[NU + 1])
                continue; /* a cell switched: no derivative */
            for (int i = 0; i < NU; ++i) {
                double scale = 0;
                for (int k = 0; k < NK; ++k) scale = fmax(scale, fabs(col[k][i] * H[k] / H[j]));
                const double fd = (yp[i] - ym[i]) / (2 * H[j]);
                CHECK_CLOSE(col[j][i], fd, 3e-5 * scale + 1e-12, "dY/dX");
            }
            ++checked;
        }
        fmi2Terminate(c);
        fmi2FreeInstance(c);
    }
    CHECK(checked > 250, "only %d columns checked", checked);
    CHECK(lifted > 15 && slipping > 15, "only %d lifted, %d slipping", lifted, slipping);
    printf("derivatives: %d columns checked, %d of 60 poses lifting, %d slipping\n", checked,
           lifted, slipping);
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

/* In full contact the pressure is linear: Fn = kn A d, and the first
 * moment about the centre is kn (gx Ix, gy Iy) along the body's axes (g =
 * R^T (phi2, -phi1), Ix = W L^3/12, Iy = L W^3/12), turned into M1 = Y,
 * M2 = -X; the cells' normal forces (each committed state's N, the third of
 * its 8 doubles) sum to Fn. */
static void full_contact_is_the_linear_pressure_on_every_grid(void) {
    int checked = 0;
    for (int trial = 0; trial < 40; ++trial) {
        double L, W, kn;
        int n1, n2;
        fmi2Component c = random_pad(&L, &W, &kn, &n1, &n2);
        const double d = 1e-5 * (1 + uniform()), theta = 6 * (uniform() - 0.5);
        /* tilts that keep every corner pressed: |gx| L/2 + |gy| W/2 < d */
        const double phi1 = 0.9 * d / (L + W) * (uniform() - 0.5) * 2;
        const double phi2 = 0.9 * d / (L + W) * (uniform() - 0.5) * 2;
        const double x[NK] = {1e-5 * uniform(), 1e-5 * uniform(), theta, d, phi1, phi2};
        CHECK(fmi2SetReal(c, KNOWN, NK, x) == fmi2OK && fmi2ExitInitializationMode(c) == fmi2OK,
              "full contact: initialization");
        CHECK(fmi2DoStep(c, 0.0, 1e-3, fmi2True) == fmi2OK &&
                  fmi2DoStep(c, 1e-3, 1e-3, fmi2True) == fmi2OK,
              "full contact: doStep");
        double y[NU];
        fmi2GetReal(c, UNKNOWN, NU, y);
        const double cs = cos(theta), sn = sin(theta);
        const double gx = cs * phi2 - sn * phi1, gy = -sn * phi2 - cs * phi1;
        const double mx = kn * gx * W * L * L * L / 12, my = kn * gy * L * W * W * W / 12;
        const double M1 = sn * mx + cs * my, M2 = -(cs * mx - sn * my);
        const double Fn = kn * L * W * d;
        CHECK_CLOSE(y[3], Fn, 1e-12 * Fn, "Fn = kn A d");
        CHECK_CLOSE(y[4], M1, 1e-12 * Fn * (L + W), "M1");
        CHECK_CLOSE(y[5], M2, 1e-12 * Fn * (L + W), "M2");
        const size_t size = serialize(c, before);
        CHECK(size >= (size_t)PATCH_MAX_CELLS * 64, "state");
        const unsigned char *cells = before + size - (size_t)PATCH_MAX_CELLS * 64;
        double sum = 0;
        for (int k = 0; k < n1 * n2; ++k) {
            double Nc;
            memcpy(&Nc, cells + (size_t)k * 64 + 16, 8); /* little-endian hosts */
            CHECK(Nc > 0, "cell %d pressed by %g", k, Nc);
            sum += Nc;
        }
        CHECK_CLOSE(sum, Fn, 1e-12 * Fn, "the cells' normal forces");
        ++checked;
        fmi2Terminate(c);
        fmi2FreeInstance(c);
    }
    printf("full contact: Fn = kn A d and the linear pressure's moments to 1e-12 on %d grids\n",
           checked);
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
            case 0:
            case 1:
            case 2: { /* inputs, sometimes hostile */
                double v[NK];
                for (int i = 0; i < NK; ++i) v[i] = pick(6) ? (uniform() - 0.5) * 0.02 : hostile();
                if (pick(2)) v[3] = 1e-6 * (uniform() + 0.5), v[4] *= 0.01, v[5] *= 0.01;
                s = fmi2SetReal(c, KNOWN, NK, v);
                break;
            }
            case 3: { /* a parameter, any value */
                const fmi2ValueReference vr = 1 + (fmi2ValueReference)pick(PAD_VR_dn);
                const double v = pick(3) ? uniform() * 40 : hostile();
                const fmi2Integer iv = (fmi2Integer)(pick(3) ? pick(40) : (unsigned)next());
                s = (vr == PAD_VR_n1 || vr == PAD_VR_n2 || vr == PAD_VR_slidingRule ||
                     vr == PAD_VR_initialSlip)
                        ? fmi2SetInteger(c, &vr, 1, &iv)
                        : fmi2SetReal(c, &vr, 1, &v);
                break;
            }
            case 4:
                s = fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0);
                if (s == fmi2OK) s = fmi2EnterInitializationMode(c);
                break;
            case 5: s = fmi2ExitInitializationMode(c); break;
            case 6:
            case 7:
                s = fmi2DoStep(c, t, 1e-3 * (1 + pick(3)), fmi2True);
                if (s == fmi2OK) t += 1e-3;
                break;
            default: { /* a state round trip into a fresh instance */
                const size_t n = serialize(c, before);
                if (!n) break;
                fmi2Component d = make();
                fmi2FMUstate st = NULL;
                CHECK(fmi2DeSerializeFMUstate(d, (const fmi2Byte *)before, n, &st) == fmi2OK,
                      "deserialize own state");
                CHECK(fmi2SetFMUstate(d, st) == fmi2OK, "set own state in a fresh instance");
                fmi2FreeFMUstate(d, &st);
                double a[NU], b[NU];
                const fmi2Status ra = fmi2GetReal(c, UNKNOWN, NU, a),
                                 rb = fmi2GetReal(d, UNKNOWN, NU, b);
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
                CHECK(na == nb && memcmp(before, after, nb) == 0,
                      "a refused call changed the instance");
            }
            double y[NU];
            if (fmi2GetReal(c, UNKNOWN, NU, y) == fmi2OK)
                for (int i = 0; i < NU; ++i)
                    CHECK(isfinite(y[i]), "output %d = %g read with OK", i, y[i]);
        }
        fmi2FreeInstance(c);
    }
    CHECK(refused > 100 && restored > 100, "refused %ld, restored %ld", refused, restored);
    printf("random sequences: %ld calls refused unchanged, %ld states restored\n", refused,
           restored);
}

int main(void) {
    rng_state = 0x9e3779b97f4a7c15ull;
    derivatives_match_differences();
    full_contact_is_the_linear_pressure_on_every_grid();
    random_sequences();
    return oc_report();
}
