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
 *   - random call sequences with hostile values, rolling among them: every
 *     call returns a defined status, a successful read is finite, a refused
 *     call changes nothing (the serialized state is the same byte for
 *     byte), and a state the FMU wrote restores into a fresh instance
 *     reading the same outputs.
 * The lift-off's exact integrals against the continuum's closed form:
 * tests/fmus/test_pad.py (closed_forms.pad). */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cells_tests.h"
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
        random_path(c, KNOWN, NK, x, 20, d0, 0.8, 0.4);
        double y[NU + 2];
        pending(c, x, y);
        const fmi2ValueReference cf = PAD_VR_contactFraction;
        double fraction = 1;
        fmi2GetReal(c, &cf, 1, &fraction);
        lifted += fraction < 1;
        slipping += y[NU] > 0;
        double col[NK][NU];
        derivative_columns(c, KNOWN, NK, UNKNOWN, NU, &col[0][0]);
        const double H[NK] = {1e-9, 1e-9, 1e-8, 1e-6 * d0, 1e-6 * tilt, 1e-6 * tilt};
        for (int j = 0; j < NK; ++j) {
            double xp[NK], xm[NK], yp[NU + 2], ym[NU + 2];
            central_points(x, NK, j, H[j], xp, xm);
            pending(c, xp, yp);
            pending(c, xm, ym);
            if (yp[NU] != y[NU] || ym[NU] != y[NU] || yp[NU + 1] != y[NU + 1] ||
                ym[NU + 1] != y[NU + 1])
                continue; /* a cell switched: no derivative */
            for (int i = 0; i < NU; ++i) {
                double scale = 0;
                for (int k = 0; k < NK; ++k) scale = fmax(scale, fabs(col[k][i] * H[k] / H[j]));
                const double fd = (yp[i] - ym[i]) / (2 * H[j]);
                /* and the difference's rounding: dissipatedEnergy, a sum over the run
                 * (the damper's work among it), is large beside its change in H */
                const double rounding = 16 * DBL_EPSILON * (fabs(yp[i]) + fabs(ym[i])) / (2 * H[j]);
                CHECK_CLOSE(col[j][i], fd, 3e-5 * scale + rounding + 1e-12, "dY/dX");
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

/* The random sequences' inputs: the pose and the rolling speed vr. */
static const fmi2ValueReference ROLLING_KNOWN[NK + 1] = {
    PAD_VR_u1, PAD_VR_u2, PAD_VR_theta, PAD_VR_d, PAD_VR_phi1, PAD_VR_phi2, PAD_VR_vr};

/* Half the inputs pressing, the tilts small; two input sets in three
 * rolling, by up to a few cells a step either way. */
static void plausible(double v[NK + 1]) {
    v[3] = 1e-6 * (uniform() + 0.5), v[4] *= 0.01, v[5] *= 0.01;
    v[6] = pick(3) ? v[6] * 1e3 : 0.0;
}

/* Steps of 1 to 3 ms: the damping's rate over varied steps. */
static double step_size(void) { return 1e-3 * (1 + pick(3)); }

int main(void) {
    rng_state = 0x9e3779b97f4a7c15ull;
    derivatives_match_differences();
    full_contact_is_the_linear_pressure_on_every_grid();
    const cells_random M = {make, ROLLING_KNOWN, NK + 1,    UNKNOWN,
                            NU,   plausible,     PAD_VR_dn, step_size};
    random_sequences(&M);
    return oc_report();
}
