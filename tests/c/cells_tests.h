/* What the C tests of the models on the patch's cells (tests/c/ContactPatch,
 * tests/c/ContactPad) share through FMI 2.0, written once: an instance's
 * serialized state, a defined status, the derivatives' random path,
 * columns and central points, and random call sequences with
 * hostile values, in which every call returns a defined status, a
 * successful read is finite, a refused call changes nothing (the serialized
 * state is the same byte for byte), and a state the FMU wrote restores into
 * a fresh instance reading the same outputs. */
#ifndef OC_CELLS_TESTS_H
#define OC_CELLS_TESTS_H
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cells/cells_fields.h"
#include "check.h"
#include "fmi2Functions.h"
#include "random_values.h"

enum { CAP = 1 << 17 };
static unsigned char before[CAP], after[CAP];

/* The serialized state of c into buf (CAP bytes at most): its size, or 0. */
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

/* ---- derivatives against central differences ------------------------------ */

/* From initialization mode: the inputs x (u1, u2, theta, the normal input
 * x[3], then the model's) set and initialization ended, then `steps`
 * doSteps of 1 ms along a random path: u1, u2, theta drifting, x[3] =
 * scale (lo + span U); then u1 and theta moved once more, not yet set: the
 * point whose derivatives are checked. */
static void random_path(fmi2Component c, const fmi2ValueReference *known, int nk, double x[],
                        int steps, double scale, double lo, double span) {
    fmi2SetReal(c, known, (size_t)nk, x);
    fmi2ExitInitializationMode(c);
    double t = 0;
    for (int k = 0; k < steps; ++k, t += 1e-3) {
        x[0] += 1e-4 * (uniform() - 0.2);
        x[1] += 4e-5 * (uniform() - 0.5);
        x[2] += 1e-2 * (uniform() - 0.2);
        x[3] = scale * (lo + span * uniform());
        fmi2SetReal(c, known, (size_t)nk, x);
        fmi2DoStep(c, t, 1e-3, fmi2True);
    }
    x[0] += 1e-5;
    x[2] += 1e-3;
}

/* The derivatives of the pending step by columns: col[j nu + i] =
 * d unknown[i] / d known[j], each known seeded alone. */
static void derivative_columns(fmi2Component c, const fmi2ValueReference *known, int nk,
                               const fmi2ValueReference *unknown, int nu, double *col) {
    for (int j = 0; j < nk; ++j) {
        const double seed = 1.0;
        CHECK(fmi2GetDirectionalDerivative(c, unknown, (size_t)nu, &known[j], 1, &seed,
                                           col + (size_t)j * (size_t)nu) == fmi2OK,
              "derivative column %d", j);
    }
}

/* The points x + h e_j and x - h e_j of a central difference along j. */
static void central_points(const double x[], int n, int j, double h, double xp[], double xm[]) {
    memcpy(xp, x, (size_t)n * sizeof x[0]);
    memcpy(xm, x, (size_t)n * sizeof x[0]);
    xp[j] += h;
    xm[j] -= h;
}

/* ---- random call sequences ------------------------------------------------ */

/* A model's random call sequences: its instance, its inputs set together
 * (plausible() makes half of them the model's scale), its outputs read, the
 * value references 1 to `last` set one at a time with any value, and the
 * size of each doStep. */
enum { CELLS_MAX_IO = 8 };
typedef struct {
    fmi2Component (*make)(void);
    const fmi2ValueReference *known;
    int nk;
    const fmi2ValueReference *unknown;
    int nu;
    void (*plausible)(double v[]);
    fmi2ValueReference last;
    double (*step_size)(void);
} cells_random;

static void random_sequences(const cells_random *M) {
    rng_state = 0x2545f4914f6cdd1dull;
    long refused = 0, restored = 0;
    for (int episode = 0; episode < 40; ++episode) {
        fmi2Component c = M->make();
        double t = 0;
        for (int k = 0; k < 150; ++k) {
            const size_t nb = serialize(c, before);
            fmi2Status s = fmi2OK;
            switch (pick(9)) {
            case 0:
            case 1:
            case 2: { /* inputs, sometimes hostile */
                double v[CELLS_MAX_IO];
                for (int i = 0; i < M->nk; ++i)
                    v[i] = pick(6) ? (uniform() - 0.5) * 0.02 : hostile();
                if (pick(2)) M->plausible(v);
                s = fmi2SetReal(c, M->known, (size_t)M->nk, v);
                break;
            }
            case 3: { /* a parameter, any value */
                const fmi2ValueReference vr = 1 + (fmi2ValueReference)pick(M->last);
                const double v = pick(3) ? uniform() * 40 : hostile();
                const fmi2Integer iv = (fmi2Integer)(pick(3) ? pick(40) : (unsigned)next());
                s = (vr == CELLS_VR_n1 || vr == CELLS_VR_n2 || vr == CELLS_VR_slidingRule ||
                     vr == CELLS_VR_initialSlip)
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
                s = fmi2DoStep(c, t, M->step_size(), fmi2True);
                if (s == fmi2OK) t += 1e-3;
                break;
            default: { /* a state round trip into a fresh instance */
                const size_t n = serialize(c, before);
                if (!n) break;
                fmi2Component d = M->make();
                fmi2FMUstate st = NULL;
                CHECK(fmi2DeSerializeFMUstate(d, (const fmi2Byte *)before, n, &st) == fmi2OK,
                      "deserialize own state");
                CHECK(fmi2SetFMUstate(d, st) == fmi2OK, "set own state in a fresh instance");
                fmi2FreeFMUstate(d, &st);
                double a[CELLS_MAX_IO], b[CELLS_MAX_IO];
                const fmi2Status ra = fmi2GetReal(c, M->unknown, (size_t)M->nu, a),
                                 rb = fmi2GetReal(d, M->unknown, (size_t)M->nu, b);
                CHECK(ra == rb, "restored reads with status %d, original %d", rb, ra);
                if (ra == fmi2OK)
                    CHECK(memcmp(a, b, (size_t)M->nu * sizeof a[0]) == 0,
                          "restored outputs differ");
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
            double y[CELLS_MAX_IO];
            if (fmi2GetReal(c, M->unknown, (size_t)M->nu, y) == fmi2OK)
                for (int i = 0; i < M->nu; ++i)
                    CHECK(isfinite(y[i]), "output %d = %g read with OK", i, y[i]);
        }
        fmi2FreeInstance(c);
    }
    CHECK(refused > 100 && restored > 100, "refused %ld, restored %ld", refused, restored);
    printf("random sequences: %ld calls refused unchanged, %ld states restored\n", refused,
           restored);
}
#endif
