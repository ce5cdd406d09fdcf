/* The ContactPatch model through its FMI 2.0 functions, linked with its own
 * sources (models/ContactPatch/model.c, the law, the glue):
 *   - the directional derivatives against central differences of the
 *     pending step, over random grids, rules, pressures and paths, column
 *     by column wherever no cell changes between stick and slip within the
 *     difference;
 *   - the step against the plain per-cell step written out here (the
 *     reference: each cell's kinematics from its index, the law's own
 *     oc_law_step, the sums in cell order; models/ContactPatch/model.c's step loop forms
 *     the same numbers more cheaply), every output and every committed
 *     state bit for bit, over random grids, parameters, rules, initial
 *     slips, pressures, turns, open cells, pending re-sets and restores;
 *   - random call sequences with hostile values: every call returns a
 *     defined status, a successful read is finite, a refused call changes
 *     nothing (the serialized state is the same byte for byte), and a state
 *     the FMU wrote restores into a fresh instance reading the same outputs. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cells_tests.h"
#include "check.h"
#include "fmi2Functions.h"
#include "host_support.h"
#include "models/ContactPatch/model.h"
#include "models/ContactPatch/table.h"
#include "random_values.h"

static const fmi2ValueReference KNOWN[6] = {PATCH_VR_u1, PATCH_VR_u2, PATCH_VR_theta,
                                            PATCH_VR_N,  PATCH_VR_p1, PATCH_VR_p2};
static const fmi2ValueReference UNKNOWN[4] = {PATCH_VR_T1, PATCH_VR_T2, PATCH_VR_Mz,
                                              PATCH_VR_dissipatedEnergy};

static fmi2Component make(void) {
    return fmi2Instantiate("patch", fmi2CoSimulation, FMU_GUID, "", &host_keep2_cb, 0, 0);
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
        const fmi2ValueReference pvr[4] = {PATCH_VR_alpha, PATCH_VR_beta, PATCH_VR_length,
                                           PATCH_VR_width};
        const double pv[4] = {3 * uniform(), 3 * uniform(), 0.02 + 0.1 * uniform(),
                              0.02 + 0.1 * uniform()};
        fmi2SetReal(c, pvr, 4, pv);
        fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0);
        fmi2EnterInitializationMode(c);
        double x[6] = {0, 0, 0, 20, 0, 0};
        /* off the axis only where the grid has more than one cell across it */
        x[4] = iv[0] > 1 ? (uniform() - 0.5) * pv[2] / 7 : 0.0;
        x[5] = iv[1] > 1 ? (uniform() - 0.5) * pv[3] / 7 : 0.0;
        random_path(c, KNOWN, 6, x, 30, 1.0, 10, 20);
        double y[5];
        pending(c, x, y);
        episodes_slipping += y[4] > 0;
        double col[6][4]; /* column j: d(T1, T2, Mz, energy)/d(known j) */
        derivative_columns(c, KNOWN, 6, UNKNOWN, 4, &col[0][0]);
        static const double H[6] = {1e-9, 1e-9, 1e-8, 1e-6, 1e-8, 1e-8};
        for (int j = 0; j < 6; ++j) {
            double xp[6], xm[6], yp[5], ym[5];
            central_points(x, 6, j, H[j], xp, xm);
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
    printf("derivatives: %d columns checked, %d of 60 states slipping\n", checked,
           episodes_slipping);
}

/* ---- the reference: the patch's step the plain way, cell by cell --------- */

typedef struct {
    double length, width, u[2], theta, N, p[2];
    int n1, n2;
} ref_setup;

/* The inputs u1, u2, theta, N, p1, p2 (KNOWN's order) into a setup. */
static void ref_set_inputs(ref_setup *g, const double x[6]) {
    g->u[0] = x[0];
    g->u[1] = x[1];
    g->theta = x[2];
    g->N = x[3];
    g->p[0] = x[4];
    g->p[1] = x[5];
}

/* The pressure's slope per unit xi and unit p/side along a side of n cells
 * while the contact is closed: 1/S of models/ContactPatch/table.h in those units,
 * 12 n^2/(n^2 - 1); 0 for one cell (which carries no p) and for N <= 0. */
static double ref_slope(int n, double N) {
    return n > 1 && N > 0.0 ? 12.0 * ((double)n * (double)n) / ((double)n * (double)n - 1.0) : 0.0;
}

/* Cell c's displacement d, share nu of N and moment arm R r, as
 * models/ContactPatch/table.h defines them, formed cell by cell from the index. */
static void ref_cell(const ref_setup *g, int c, double d[2], double *nu, double Rr[2]) {
    const double h = sin(0.5 * g->theta), cm1 = -2.0 * h * h, sn = sin(g->theta);
    const double w = 1.0 / ((double)g->n1 * (double)g->n2);
    const int i = c % g->n1, j = c / g->n1;
    const double xi = (double)(2 * i + 1 - g->n1) / (double)(2 * g->n1);
    const double eta = (double)(2 * j + 1 - g->n2) / (double)(2 * g->n2);
    const double r0 = xi * g->length, r1 = eta * g->width;
    d[0] = g->u[0];
    d[1] = g->u[1];
    Rr[0] = r0;
    Rr[1] = r1;
    if (r0 != 0.0 || r1 != 0.0) { /* the centre cell sees u itself */
        const double dr0 = cm1 * r0 - sn * r1, dr1 = sn * r0 + cm1 * r1;
        d[0] += dr0;
        d[1] += dr1;
        Rr[0] += dr0;
        Rr[1] += dr1;
    }
    *nu = w * (1.0 + (ref_slope(g->n1, g->N) * (g->p[0] / g->length)) * xi +
               (ref_slope(g->n2, g->N) * (g->p[1] / g->width)) * eta);
}

/* The outputs T1, T2, Mz, dissipatedEnergy, slipFraction and contactState
 * of every cell stepped from from[] into out[]. */
static void ref_step(const oc_law *law, const ref_setup *g, const oc_state *from, oc_step *out,
                     double y[5], int *state) {
    const int n = g->n1 * g->n2;
    double T0 = 0.0, T1 = 0.0, Mz = 0.0, E = 0.0;
    int pressed = 0, slipping = 0;
    for (int c = 0; c < n; ++c) {
        double d[2], nu, Rr[2];
        ref_cell(g, c, d, &nu, Rr);
        oc_law_step(law, &from[c], d, g->N * nu, &out[c]);
        const double t0 = 0.0 - out[c].q[0], t1 = 0.0 - out[c].q[1];
        T0 += t0;
        T1 += t1;
        Mz += Rr[0] * t1 - Rr[1] * t0;
        E += out[c].next.energy;
        pressed += out[c].contact != OC_OPEN;
        slipping += out[c].contact == OC_SLIP;
    }
    y[0] = T0;
    y[1] = T1;
    y[2] = Mz;
    y[3] = E;
    y[4] = (double)slipping / (double)n;
    *state = pressed == 0 ? 0 : slipping == 0 ? 1 : slipping == pressed ? 3 : 2;
}

/* 1 if the committed cell states the FMU serialized (the last
 * PATCH_MAX_CELLS x 8 doubles of its state, little-endian, as
 * models/ContactPatch/model.c writes them) are those of `ref`, bit for bit. */
static int states_equal(fmi2Component c, const oc_state *ref, int n) {
    const size_t size = serialize(c, before);
    if (size < (size_t)PATCH_MAX_CELLS * 64) return 0;
    const unsigned char *cells = before + size - (size_t)PATCH_MAX_CELLS * 64;
    for (int k = 0; k < n; ++k) {
        const oc_state *s = &ref[k];
        const double v[8] = {s->u[0], s->u[1], s->N, s->a[0], s->a[1], s->s[0], s->s[1], s->energy};
        for (int i = 0; i < 8; ++i) {
            uint64_t b = 0, r;
            for (int byte = 0; byte < 8; ++byte)
                b |= (uint64_t)cells[(size_t)k * 64 + 8 * i + byte] << (8 * byte);
            memcpy(&r, &v[i], 8);
            if (b != r) return 0;
        }
    }
    return 1;
}

static oc_state ref_from[PATCH_MAX_CELLS];
static oc_step ref_out[PATCH_MAX_CELLS], ref_bad[PATCH_MAX_CELLS];

static void step_matches_the_plain_per_cell_step(void) {
    static const fmi2ValueReference OUT[5] = {PATCH_VR_T1, PATCH_VR_T2, PATCH_VR_Mz,
                                              PATCH_VR_dissipatedEnergy, PATCH_VR_slipFraction};
    const fmi2ValueReference vstate = PATCH_VR_contactState;
    long compared = 0, restored = 0, refused = 0, off_axis_refused = 0, open_far = 0;
    int seen[4] = {0, 0, 0, 0};
    for (int episode = 0; episode < 60; ++episode) {
        ref_setup g;
        g.n1 = 1 + (int)pick(episode % 5 == 4 ? PATCH_MAX_SIDE : 12);
        const int most = PATCH_MAX_CELLS / g.n1; /* n1 n2 <= PATCH_MAX_CELLS */
        g.n2 =
            1 + (int)pick(episode % 5 == 4 ? (most < PATCH_MAX_SIDE ? most : PATCH_MAX_SIDE) : 12);
        g.length = 0.02 + 0.2 * uniform();
        g.width = 0.02 + 0.2 * uniform();
        oc_params q = {0.2 + uniform(),       0.2 + uniform(),   5e3 + 5e4 * uniform(),
                       5e3 + 5e4 * uniform(), 6 * uniform() - 3, 6 * uniform() - 3,
                       1 + (int)pick(3)};
        const int initial = 1 + (int)pick(2);
        const double s_start[2] = {1e-4 * (uniform() - 0.5), 1e-4 * (uniform() - 0.5)};
        fmi2Component c = make();
        const fmi2ValueReference ivr[4] = {PATCH_VR_n1, PATCH_VR_n2, PATCH_VR_slidingRule,
                                           PATCH_VR_initialSlip};
        const fmi2Integer iv[4] = {g.n1, g.n2, q.rule, initial};
        const fmi2ValueReference pvr[10] = {
            PATCH_VR_mu1,  PATCH_VR_mu2,    PATCH_VR_eps1,  PATCH_VR_eps2,    PATCH_VR_alpha,
            PATCH_VR_beta, PATCH_VR_length, PATCH_VR_width, PATCH_VR_s1Start, PATCH_VR_s2Start};
        const double pv[10] = {q.mu1,  q.mu2,    q.eps1,  q.eps2,     q.alpha,
                               q.beta, g.length, g.width, s_start[0], s_start[1]};
        CHECK(fmi2SetInteger(c, ivr, 4, iv) == fmi2OK && fmi2SetReal(c, pvr, 10, pv) == fmi2OK,
              "episode %d: parameters", episode);
        /* the cells' law: eps shared by area */
        const double w = 1.0 / ((double)g.n1 * (double)g.n2);
        oc_params cell = q;
        cell.eps1 = q.eps1 * w;
        cell.eps2 = q.eps2 * w;
        oc_law law;
        CHECK(oc_law_init(&law, &cell) == 0, "episode %d: the cells' law", episode);
        fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0);
        fmi2EnterInitializationMode(c);
        double x[6] = {
            1e-5 * (uniform() - 0.5), 1e-5 * (uniform() - 0.5), 0.01 * (uniform() - 0.5), 20, 0, 0};
        fmi2SetReal(c, KNOWN, 6, x);
        CHECK(fmi2ExitInitializationMode(c) == fmi2OK, "episode %d: initialization", episode);
        g.u[0] = x[0];
        g.u[1] = x[1];
        g.theta = x[2];
        g.N = x[3];
        g.p[0] = g.p[1] = 0;
        for (int k = 0; k < g.n1 * g.n2; ++k) {
            double d[2], nu, Rr[2];
            ref_cell(&g, k, d, &nu, Rr);
            ref_from[k] = initial == PATCH_INITIAL_EXPLICIT
                              ? oc_state_unloaded(s_start[0], s_start[1], 0.0)
                              : oc_state_unloaded(d[0], d[1], 0.0);
        }
        double t = 0;
        const double push = pick(2) ? 3e-4 : 3e-5; /* mostly slipping, or mostly sticking */
        for (int k = 0; k < 25; ++k) {
            x[0] += push * (uniform() - 0.3);
            x[1] += push * (uniform() - 0.5);
            x[2] += 0.02 * (uniform() - 0.5);
            x[3] = pick(8) ? 5 + 30 * uniform() : -uniform(); /* sometimes open */
            const double e1 = uniform() / 6, e2 = uniform() * (1.0 / 6 - e1);
            x[4] = (pick(2) ? 1 : -1) * e1 * g.length;
            x[5] = (pick(2) ? 1 : -1) * e2 * g.width;
            if (g.n1 == 1) x[4] = 0.0; /* a side of one cell carries no p */
            if (g.n2 == 1) x[5] = 0.0;
            if (pick(6) == 0) { /* a step that overflows: refused, it changes nothing */
                fmi2FMUstate saved = NULL;
                CHECK(fmi2GetFMUstate(c, &saved) == fmi2OK, "episode %d: get state", episode);
                double bad[6];
                memcpy(bad, x, sizeof bad);
                bad[pick(2)] = (pick(2) ? 1 : -1) * 1e308;
                bad[3] = 1e300;
                host_log.message[0] = 0;
                if (fmi2SetReal(c, KNOWN, 6, bad) != fmi2OK) {
                    ++refused;
                    /* it names the first cell (in the order c = i + n1 j) whose
                     * result is not finite, else the sums */
                    ref_setup gb = g;
                    ref_set_inputs(&gb, bad);
                    double yb[5];
                    int sb;
                    ref_step(&law, &gb, ref_from, ref_bad, yb, &sb);
                    char want[64] = "overflow the patch's force, moment or energy";
                    for (int cell = 0; cell < g.n1 * g.n2; ++cell)
                        if (!oc_step_is_finite(&ref_bad[cell])) {
                            snprintf(want, sizeof want, "force or slip of cell (%d, %d)",
                                     cell % g.n1 + 1, cell / g.n1 + 1);
                            break;
                        }
                    CHECK(strstr(host_log.message, want) != NULL,
                          "episode %d: refused with \"%s\", not naming \"%s\"", episode,
                          host_log.message, want);
                } else
                    CHECK(fmi2SetFMUstate(c, saved) == fmi2OK, "episode %d: restore", episode);
                fmi2FreeFMUstate(c, &saved);
            }
            /* sometimes p off the axis of a side of one cell (refused while
             * pressed) or, open, p outside the kern (not looked at) */
            if (g.n1 == 1 && pick(5) == 0) x[4] = 0.01 * g.length, x[5] *= 0.9; /* in the kern */
            if (g.n2 == 1 && pick(5) == 0) x[5] = -0.01 * g.width, x[4] *= 0.9;
            if (x[3] <= 0 && pick(2) == 0) x[4] = (pick(2) ? 1 : -1) * 10 * g.length;
            const int off_axis = (g.n1 == 1 && x[4] != 0.0) || (g.n2 == 1 && x[5] != 0.0);
            host_log.message[0] = 0;
            if (fmi2SetReal(c, KNOWN, 6, x) != fmi2OK) { /* refused: nothing changed */
                CHECK(off_axis && x[3] > 0 &&
                          strstr(host_log.message, "cannot carry a centre of pressure"),
                      "episode %d step %d: p = (%g, %g) on %d x %d cells, N = %g refused: %s",
                      episode, k, x[4], x[5], g.n1, g.n2, x[3], host_log.message);
                ++off_axis_refused;
                continue;
            }
            CHECK(!(off_axis && x[3] > 0), "episode %d step %d: p off a side of one cell accepted",
                  episode, k);
            open_far += x[3] <= 0 && fabs(x[4]) > g.length;
            ref_set_inputs(&g, x);
            double want[5], got[5];
            int want_state, got_state;
            ref_step(&law, &g, ref_from, ref_out, want, &want_state);
            CHECK(fmi2GetReal(c, OUT, 5, got) == fmi2OK &&
                      fmi2GetInteger(c, &vstate, 1, &got_state) == fmi2OK,
                  "episode %d step %d: outputs", episode, k);
            CHECK(memcmp(got, want, sizeof got) == 0 && got_state == want_state,
                  "episode %d step %d (%d x %d cells): T1 %.17g vs %.17g, Mz %.17g vs %.17g, "
                  "state %d vs %d",
                  episode, k, g.n1, g.n2, got[0], want[0], got[2], want[2], got_state, want_state);
            CHECK(states_equal(c, ref_from, g.n1 * g.n2),
                  "episode %d step %d: the committed cell states differ", episode, k);
            ++seen[want_state];
            ++compared;
            if (pick(4) == 0) continue; /* inputs set again before a step: the same start */
            CHECK(fmi2DoStep(c, t, 1e-3, fmi2True) == fmi2OK, "episode %d step %d", episode, k);
            t += 1e-3;
            for (int i = 0; i < g.n1 * g.n2; ++i) ref_from[i] = ref_out[i].next;
            if (pick(6) == 0) { /* continue in a fresh instance from the state */
                const size_t n = serialize(c, before);
                fmi2Component d = make();
                fmi2FMUstate st = NULL;
                CHECK(n && fmi2DeSerializeFMUstate(d, (const fmi2Byte *)before, n, &st) == fmi2OK &&
                          fmi2SetFMUstate(d, st) == fmi2OK,
                      "episode %d step %d: restore", episode, k);
                fmi2FreeFMUstate(d, &st);
                fmi2FreeInstance(c);
                c = d;
                ++restored;
            }
        }
        fmi2FreeInstance(c);
    }
    CHECK(compared > 1000 && restored > 50 && refused > 50 && off_axis_refused > 10 &&
              open_far > 10,
          "compared %ld steps, restored %ld, refused %ld overflowing and %ld off a side of one "
          "cell, %ld open with p far outside the kern",
          compared, restored, refused, off_axis_refused, open_far);
    CHECK(seen[0] > 20 && seen[1] > 20 && seen[2] > 20 && seen[3] > 20,
          "patch states seen: open %d, stick %d, partly %d, all slipping %d", seen[0], seen[1],
          seen[2], seen[3]);
    printf("plain per-cell step: %ld steps bit for bit (open %d, stick %d, partly slipping %d, "
           "all slipping %d), %ld restores, %ld overflowing steps and %ld p off a side of one "
           "cell refused, %ld open steps with p far outside the kern\n",
           compared, seen[0], seen[1], seen[2], seen[3], restored, refused, off_axis_refused,
           open_far);
}

/* The cells' normal forces, read from the committed states the FMU
 * serialized (each cell's N, the third of its 8 doubles): their resultant is
 * N and their first moment about the centre N (p1, p2), to 1e-12, on every
 * grid (models/ContactPatch/table.h's pressure; the continuum's sampled at the cell
 * centres falls short by 1 - 1/n^2).  Along a side of one cell p must be 0
 * while pressed: refused otherwise, with the reason, and nothing changed;
 * an open contact (N <= 0) takes any p, outside the kern too, and so does
 * one call that opens it.  Then closing it with p still outside is refused. */
static void normal_forces_have_resultant_n_and_first_moment_n_p(void) {
    static const int GRIDS[][2] = {{1, 1}, {2, 2}, {3, 1}, {1, 3},
                                   {4, 2}, {8, 8}, {5, 7}, {32, 32}};
    int checked = 0;
    for (size_t gi = 0; gi < sizeof GRIDS / sizeof GRIDS[0]; ++gi) {
        for (int trial = 0; trial < 5; ++trial) {
            const int n1 = GRIDS[gi][0], n2 = GRIDS[gi][1];
            const double L = 0.02 + 0.2 * uniform(), W = 0.02 + 0.2 * uniform(),
                         N = 1 + 50 * uniform();
            /* in the kern, |p|/side at least 1/60 wherever the side has cells to carry it */
            const double e1 = n1 > 1 ? (0.1 + 0.8 * uniform()) / 6 : 0.0;
            const double e2 = n2 > 1 ? (0.1 + 0.8 * uniform()) * (1.0 / 6 - e1) : 0.0;
            const double p[2] = {(pick(2) ? 1 : -1) * e1 * L, (pick(2) ? 1 : -1) * e2 * W};
            fmi2Component c = make();
            const fmi2ValueReference ivr[2] = {PATCH_VR_n1, PATCH_VR_n2};
            const fmi2Integer iv[2] = {n1, n2};
            const fmi2ValueReference gvr[2] = {PATCH_VR_length, PATCH_VR_width};
            const double gv[2] = {L, W};
            CHECK(fmi2SetInteger(c, ivr, 2, iv) == fmi2OK && fmi2SetReal(c, gvr, 2, gv) == fmi2OK,
                  "%d x %d: geometry", n1, n2);
            fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0);
            fmi2EnterInitializationMode(c);
            const double x[6] = {
                1e-4 * uniform(), 1e-4 * uniform(), 0.01 * uniform(), N, p[0], p[1]};
            CHECK(fmi2SetReal(c, KNOWN, 6, x) == fmi2OK && fmi2ExitInitializationMode(c) == fmi2OK,
                  "%d x %d: p = (%g, %g) refused: %s", n1, n2, p[0], p[1], host_log.message);
            /* the state holds the shown step's start: a second step with the
             * inputs held starts from the first one's, which carry N_c */
            CHECK(fmi2DoStep(c, 0.0, 1e-3, fmi2True) == fmi2OK &&
                      fmi2DoStep(c, 1e-3, 1e-3, fmi2True) == fmi2OK,
                  "%d x %d: doStep", n1, n2);
            const size_t size = serialize(c, before);
            CHECK(size >= (size_t)PATCH_MAX_CELLS * 64, "%d x %d: state", n1, n2);
            const unsigned char *cells = before + size - (size_t)PATCH_MAX_CELLS * 64;
            double sum = 0, m[2] = {0, 0}, m_abs[2] = {0, 0};
            for (int k = 0; k < n1 * n2; ++k) {
                double Nc;
                memcpy(&Nc, cells + (size_t)k * 64 + 16, 8); /* little-endian hosts */
                const int i = k % n1, j = k / n1;
                const double r[2] = {(2 * i + 1 - n1) / (2.0 * n1) * L,
                                     (2 * j + 1 - n2) / (2.0 * n2) * W};
                CHECK(Nc > 0, "%d x %d: cell %d pressed by %g", n1, n2, k, Nc);
                sum += Nc;
                for (int a = 0; a < 2; ++a) {
                    m[a] += Nc * r[a];
                    m_abs[a] += fabs(Nc * r[a]);
                }
            }
            CHECK(fabs(sum - N) <= 1e-12 * N, "%d x %d: resultant %.17g, N %.17g", n1, n2, sum, N);
            for (int a = 0; a < 2; ++a) {
                const double want = N * p[a];
                CHECK(fabs(m[a] - want) <= 1e-12 * (p[a] != 0 ? fabs(want) : m_abs[a]),
                      "%d x %d: first moment %d %.17g, N p %.17g", n1, n2, a + 1, m[a], want);
            }
            ++checked;
            /* a side of one cell refuses p off its axis while pressed, whole */
            for (int a = 0; a < 2; ++a) {
                if (iv[a] != 1) continue;
                double y[6];
                memcpy(y, x, sizeof y);
                y[4 + a] = 0.01 * (a ? W : L); /* in the kern: e1 + e2 <= 0.15 + 0.01 */
                const size_t nb = serialize(c, before);
                host_log.message[0] = 0;
                CHECK(fmi2SetReal(c, KNOWN, 6, y) == fmi2Error,
                      "%d x %d: p%d off the axis accepted", n1, n2, a + 1);
                char want[48];
                snprintf(want, sizeof want, "off the axis of a grid with n%d = 1", a + 1);
                CHECK(strstr(host_log.message, want) != NULL, "%d x %d: refused with \"%s\"", n1,
                      n2, host_log.message);
                CHECK(serialize(c, after) == nb && memcmp(before, after, nb) == 0,
                      "%d x %d: the refused set changed the instance", n1, n2);
            }
            /* open, p anywhere: accepted, every cell open; closing with p outside: refused */
            const double open[6] = {x[0], x[1], x[2], -N * uniform(), 3 * L, -2 * W};
            CHECK(fmi2SetReal(c, KNOWN, 6, open) == fmi2OK,
                  "%d x %d: open with p outside the kern "
                  "refused: %s",
                  n1, n2, host_log.message);
            const fmi2ValueReference vstate = PATCH_VR_contactState;
            fmi2Integer state = -1;
            double T[3];
            CHECK(fmi2GetInteger(c, &vstate, 1, &state) == fmi2OK && state == 0 &&
                      fmi2GetReal(c, UNKNOWN, 3, T) == fmi2OK && T[0] == 0 && T[1] == 0 &&
                      T[2] == 0,
                  "%d x %d: open contact state %d", n1, n2, (int)state);
            CHECK(fmi2DoStep(c, 2e-3, 1e-3, fmi2True) == fmi2OK, "%d x %d: open doStep", n1, n2);
            const fmi2ValueReference vN = PATCH_VR_N;
            const double press = N;
            host_log.message[0] = 0;
            CHECK(fmi2SetReal(c, &vN, 1, &press) == fmi2Error &&
                      strstr(host_log.message, "outside the kern"),
                  "%d x %d: closed with p outside the kern: %s", n1, n2, host_log.message);
            CHECK(fmi2SetReal(c, KNOWN, 6, x) == fmi2OK, "%d x %d: closed again", n1, n2);
            fmi2Terminate(c);
            fmi2FreeInstance(c);
        }
    }
    printf("normal forces: resultant N and first moment N p to 1e-12 on %d grids\n", checked);
}

/* Half the inputs pressing. */
static void plausible(double v[6]) { v[3] = 5 + 20 * uniform(); }

static double step_size(void) { return 1e-3; }

/* Each side up to PATCH_MAX_SIDE, but no more than PATCH_MAX_CELLS cells in
 * all: a grid beyond is refused, saying why. */
static void grids_up_to_the_cells_storage(void) {
    const fmi2ValueReference vn[2] = {PATCH_VR_n1, PATCH_VR_n2};
    const fmi2Integer ok[2] = {PATCH_MAX_SIDE, PATCH_MAX_CELLS / PATCH_MAX_SIDE},
                      wide[2] = {PATCH_MAX_SIDE, PATCH_MAX_CELLS / PATCH_MAX_SIDE + 1};
    fmi2Component c = make();
    CHECK(fmi2SetInteger(c, vn, 2, ok) == fmi2OK, "%d x %d cells", ok[0], ok[1]);
    host_log.message[0] = 0;
    CHECK(fmi2SetInteger(c, vn, 2, wide) == fmi2Error && strstr(host_log.message, "at most 1024"),
          "%d x %d cells refused: %s", wide[0], wide[1], host_log.message);
    fmi2FreeInstance(c);
}

int main(void) {
    rng_state = 0x9e3779b97f4a7c15ull;
    grids_up_to_the_cells_storage();
    derivatives_match_differences();
    step_matches_the_plain_per_cell_step();
    normal_forces_have_resultant_n_and_first_moment_n_p();
    const cells_random M = {make, KNOWN, 6, UNKNOWN, 4, plausible, PATCH_VR_p2, step_size};
    random_sequences(&M);
    return oc_report();
}
