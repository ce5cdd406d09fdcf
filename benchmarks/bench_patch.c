/* Benchmark (not a test): the ContactPatch FMU's step, all cells in one FMI
 * call, against what the same cells cost otherwise, at 1, 16, 100 and 400
 * cells (square grids), stick and slip:
 *   - patch:  fmi2SetReal(u1, u2, theta, N) + fmi2DoStep + fmi2GetReal(T1, T2, Mz);
 *   - points: n OrthotropicContact instances, each given its cell's inputs
 *             (its displacement d_c and normal force N_c, its stiffness the
 *             cell's share) through fmi2SetReal(u1, u2, N) + fmi2DoStep +
 *             fmi2GetReal(T1, T2): what a user wiring one point FMU per
 *             point pays;
 *   - law:    oc_law_step called directly (contact_law.c linked in) on each
 *             cell, each cell's committed state the one before: the point
 *             law's own step, the floor a cell's cost is held to.
 *   - pad:    the ContactPad FMU, the same cells on a Winkler foundation
 *             (kn = 1e7 N/m^3), given u1, u2, theta and the
 *             approach d = N/(kn A) that presses each cell as the patch
 *             does: fmi2SetReal(u1, u2, theta, d, phi1, phi2) + fmi2DoStep +
 *             fmi2GetReal(T1, T2, Mz, Fn, M1, M2);
 *   - lifted: the pad tilted by phi2 = 2 d/length at half that approach, so
 *             that its trailing quarter lifts and the cells along the line
 *             are clipped (its figures only: its forces are not the patch's);
 *   - rolling: the pad rolling by 1e-6 cells a step: every step moves
 *             every cell's state by a fractional shift (the dearer case),
 *             while the cells stick or slip as the pad's, so that the
 *             figure is what rolling adds to a cell's step (its figures
 *             only).
 * The four compute the same cells: at the end of every run the patch's T
 * must equal the points', the law's and the pad's sums (cell order, as the
 * patch sums) to 1e-12 relative, and the slip fraction be 0 (stick) or 1
 * (slip), else the program says so and exits 1.  The FMUs are the host
 * build's binaries (FMI 2.0), loaded with dlopen as an importer loads them.
 *
 * Runs are interleaved (for each grid and path: patch, points, law, pad,
 * lifted), `rounds`
 * rounds; each figure is the least disturbed (smallest) of its rounds, thread
 * CPU time, and each ratio is that of those figures with the range of the
 * rounds' own ratios beside it.  Targets: a cell's cost in the
 * patch <= 1.2x the law's own step, a 100-cell patch step <= 0.5x of 100
 * point steps through the FMI calls, a pad's cell <= 1.3x a patch's at
 * 100 and 400 cells, and a rolling pad's cell <= 1.3x a pad's there.
 *
 * Paths (bench_common.h's, plus a turn): stick, the body oscillates inside
 * every cell's sticking ellipse (u as bench_inputs, theta within 2e-4 rad);
 * slip, pushed at 0.244 m/s with 0.1 ms steps while turning back and forth
 * by 1e-4 rad a step, so that every cell slips every step, each in its own
 * direction.  The patch's default parameters (0.1 m x 0.1 m, the aged mat,
 * coupled rule), uniform pressure.
 *
 *   bench_patch [cell_steps [rounds]]   cell_steps: cells x steps a run
 * Environment: BENCH_PATCH_FMI2, BENCH_POINT_FMI2, BENCH_PAD_FMI2 (binaries
 * to run instead of the host build's).
 */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "fmi2Functions.h"
#include "host_support.h"
#include "law/contact_law.h"
#include "models/ContactPatch/table.h"

/* bench_patch_point.c: the point FMU's table */
extern const char *const BENCH_POINT_TOKEN;
extern const char *const BENCH_POINT_LAW_NAMES[];
extern const unsigned int BENCH_POINT_LAW_VRS[];
extern const unsigned int BENCH_POINT_VRS[8];
enum { P_RULE, P_INITIAL, P_U1, P_U2, P_N, P_T1, P_T2, P_STATE };
/* bench_patch_pad.c: the pad FMU's table */
extern const char *const BENCH_PAD_TOKEN;
extern const unsigned int BENCH_PAD_VRS[18];
enum { D_U1, D_T1 = 6, D_N1 = 12, D_N2, D_KN, D_SLIP, D_CONTACT, D_VR };

enum { N_GRIDS = 4, MAX_CELLS = 400, PERIOD = 16 };
static const int SIDES[N_GRIDS] = {1, 4, 10, 20};

typedef struct {
    void *lib;
    fmi2InstantiateTYPE *inst;
    fmi2FreeInstanceTYPE *free_inst;
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter;
    fmi2ExitInitializationModeTYPE *exit_init;
    fmi2SetRealTYPE *set_real;
    fmi2GetRealTYPE *get_real;
    fmi2SetIntegerTYPE *set_int;
    fmi2GetIntegerTYPE *get_int;
    fmi2DoStepTYPE *do_step;
} fmi2_api;

static int load(fmi2_api *a, const char *path) {
    a->lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!a->lib) return fprintf(stderr, "%s\n", dlerror()), -1;
#define SYM(field, name, type)                                                                     \
    if (!(a->field = (type *)dlsym(a->lib, name)))                                                 \
        return fprintf(stderr, "%s: no %s\n", path, name), -1;
    SYM(inst, "fmi2Instantiate", fmi2InstantiateTYPE)
    SYM(free_inst, "fmi2FreeInstance", fmi2FreeInstanceTYPE)
    SYM(setup, "fmi2SetupExperiment", fmi2SetupExperimentTYPE)
    SYM(enter, "fmi2EnterInitializationMode", fmi2EnterInitializationModeTYPE)
    SYM(exit_init, "fmi2ExitInitializationMode", fmi2ExitInitializationModeTYPE)
    SYM(set_real, "fmi2SetReal", fmi2SetRealTYPE)
    SYM(get_real, "fmi2GetReal", fmi2GetRealTYPE)
    SYM(set_int, "fmi2SetInteger", fmi2SetIntegerTYPE)
    SYM(get_int, "fmi2GetInteger", fmi2GetIntegerTYPE)
    SYM(do_step, "fmi2DoStep", fmi2DoStepTYPE)
#undef SYM
    return 0;
}

/* Step k's turn [rad]: stick, within 2e-4 rad in the period of bench_inputs'
 * u; slip, a triangle wave of 1e-4 rad steps (a cell's turn moves it at most
 * 1e-5 m a step, less than the push, so that no cell reverses). */
static double theta_of(long k, int slip) {
    if (slip) {
        const long t = k & 15;
        return 1e-4 * (double)(t < 8 ? t - 4 : 12 - t);
    }
    return 2e-4 * ((double)(k & 7) - 3.5) / 3.5;
}

/* A grid's cells as the patch forms them (models/ContactPatch/model.c's frame_of and
 * cell_of, written out again here): for each of the PERIOD turns of the
 * paths, each cell's displacement relative to u, (R(theta) - I) r; its share
 * of N; and its stiffness. */
typedef struct {
    int side, n;
    double off[2][PERIOD][MAX_CELLS][2]; /* [slip][k mod PERIOD][cell] */
    int centre[MAX_CELLS];               /* r = 0: d = u itself, as the patch has it */
    double nu[MAX_CELLS];
    oc_params cell; /* the law's parameters with eps times the cell's share */
    oc_law law;
} grid;

static void make_grid(grid *G, int side, double length, double width, const oc_params *p) {
    G->side = side;
    G->n = side * side;
    const double w = 1.0 / ((double)side * (double)side);
    for (int c = 0; c < G->n; ++c) {
        const int i = c % side, j = c / side;
        const double xi = (double)(2 * i + 1 - side) / (double)(2 * side);
        const double eta = (double)(2 * j + 1 - side) / (double)(2 * side);
        const double r0 = xi * length, r1 = eta * width;
        G->centre[c] = r0 == 0.0 && r1 == 0.0;
        G->nu[c] = w * (1.0 + 12.0 * (0.0 / length) * xi + 12.0 * (0.0 / width) * eta);
        for (int slip = 0; slip < 2; ++slip)
            for (int k = 0; k < PERIOD; ++k) {
                const double th = theta_of(k, slip), h = sin(0.5 * th);
                const double cm1 = -2.0 * h * h, sn = sin(th);
                G->off[slip][k][c][0] = cm1 * r0 - sn * r1;
                G->off[slip][k][c][1] = sn * r0 + cm1 * r1;
            }
    }
    G->cell = *p;
    G->cell.eps1 = p->eps1 * w;
    G->cell.eps2 = p->eps2 * w;
    if (oc_law_init(&G->law, &G->cell) != 0) fprintf(stderr, "oc_law_init failed\n"), exit(2);
}

static inline void cell_inputs(const grid *G, int slip, long k, int c, const double u[3],
                               double d[2], double *Nc) {
    const double *o = G->off[slip][k % PERIOD][c];
    d[0] = G->centre[c] ? u[0] : u[0] + o[0];
    d[1] = G->centre[c] ? u[1] : u[1] + o[1];
    *Nc = u[2] * G->nu[c];
}

/* What a run measured: ns per step of the whole grid, and what it computed
 * at its last step. */
typedef struct {
    double ns, T[2], slip_fraction;
} run_result;

static const fmi2ValueReference PATCH_IN[4] = {PATCH_VR_u1, PATCH_VR_u2, PATCH_VR_theta,
                                               PATCH_VR_N};
static const fmi2ValueReference PATCH_OUT[3] = {PATCH_VR_T1, PATCH_VR_T2, PATCH_VR_Mz};

static run_result run_patch(const fmi2_api *a, const grid *G, int slip, long steps) {
    fmi2Component c = a->inst("patch", fmi2CoSimulation, FMU_TOKEN, "", &host_print2_cb, 0, 0);
    const fmi2ValueReference vn[2] = {PATCH_VR_n1, PATCH_VR_n2};
    const fmi2Integer nn[2] = {G->side, G->side};
    a->set_int(c, vn, 2, nn);
    a->setup(c, fmi2False, 0, 0, fmi2False, 0);
    a->enter(c);
    double u[3];
    bench_inputs(0, slip, u);
    const double v0[4] = {u[0], u[1], theta_of(0, slip), u[2]};
    a->set_real(c, PATCH_IN, 4, v0);
    a->exit_init(c);
    double t = 0, h = 1e-4, sink = 0, y[3] = {0, 0, 0};
    const double t0 = now();
    for (long k = 0; k < steps; ++k) {
        bench_inputs(k, slip, u);
        const double v[4] = {u[0], u[1], theta_of(k, slip), u[2]};
        a->set_real(c, PATCH_IN, 4, v);
        a->do_step(c, t, h, fmi2True);
        t += h;
        a->get_real(c, PATCH_OUT, 3, y);
        sink += y[2];
    }
    run_result r = {1e9 * (now() - t0) / steps, {y[0], y[1]}, 0};
    const fmi2ValueReference vsf = PATCH_VR_slipFraction;
    a->get_real(c, &vsf, 1, &r.slip_fraction);
    a->free_inst(c);
    if (sink == 12345.6789) printf(" ");
    return r;
}

/* The pad's foundation [N/m^3] and the patch's sides (its table's defaults). */
enum { PAD_KN = 10000000 };
static double pad_area, pad_length;

/* The pad given the patch's inputs: d = N/(kn A) presses each cell with the
 * patch's N/n; lifted, half that approach and phi2 = 2 d/length, so that
 * the part x < -length/4 lifts and the cells along that line are clipped;
 * rolling, by 1e-6 cells a step. */
enum { PAD_PLAIN, PAD_LIFTED, PAD_ROLLING };
static run_result run_pad(const fmi2_api *a, const grid *G, int slip, long steps, int mode) {
    const int lifted = mode == PAD_LIFTED;
    fmi2Component c = a->inst("pad", fmi2CoSimulation, BENCH_PAD_TOKEN, "", &host_print2_cb, 0, 0);
    const fmi2ValueReference vn[2] = {BENCH_PAD_VRS[D_N1], BENCH_PAD_VRS[D_N2]};
    const fmi2Integer nn[2] = {G->side, G->side};
    a->set_int(c, vn, 2, nn);
    const fmi2ValueReference vkn = BENCH_PAD_VRS[D_KN];
    const double kn = PAD_KN;
    a->set_real(c, &vkn, 1, &kn);
    a->setup(c, fmi2False, 0, 0, fmi2False, 0);
    a->enter(c);
    fmi2ValueReference in[6], out[6];
    for (int i = 0; i < 6; ++i) in[i] = BENCH_PAD_VRS[D_U1 + i], out[i] = BENCH_PAD_VRS[D_T1 + i];
    const double scale = lifted ? 0.5 : 1.0;
    double u[3];
    bench_inputs(0, slip, u);
    const double d0 = u[2] / (kn * pad_area);
    const double v0[6] = {u[0],       u[1], theta_of(0, slip),
                          scale * d0, 0.0,  lifted ? 2 * d0 / pad_length : 0.0};
    a->set_real(c, in, 6, v0);
    const double h = 1e-4;
    if (mode == PAD_ROLLING) {
        const fmi2ValueReference vvr = BENCH_PAD_VRS[D_VR];
        const double vr = 1e-6 * pad_length / G->side / h;
        a->set_real(c, &vvr, 1, &vr);
    }
    a->exit_init(c);
    double t = 0, sink = 0, y[6] = {0, 0, 0, 0, 0, 0};
    const double t0 = now();
    for (long k = 0; k < steps; ++k) {
        bench_inputs(k, slip, u);
        const double d = u[2] / (kn * pad_area);
        const double v[6] = {u[0],      u[1], theta_of(k, slip),
                             scale * d, 0.0,  lifted ? 2 * d / pad_length : 0.0};
        a->set_real(c, in, 6, v);
        a->do_step(c, t, h, fmi2True);
        t += h;
        a->get_real(c, out, 6, y);
        sink += y[2] + y[3];
    }
    run_result r = {1e9 * (now() - t0) / steps, {y[0], y[1]}, 0};
    const fmi2ValueReference vsf = BENCH_PAD_VRS[D_SLIP];
    a->get_real(c, &vsf, 1, &r.slip_fraction);
    a->free_inst(c);
    if (sink == 12345.6789) printf(" ");
    return r;
}

static fmi2Component points[MAX_CELLS];

static run_result run_points(const fmi2_api *a, const grid *G, int slip, long steps) {
    const fmi2ValueReference in[3] = {BENCH_POINT_VRS[P_U1], BENCH_POINT_VRS[P_U2],
                                      BENCH_POINT_VRS[P_N]};
    const fmi2ValueReference out[2] = {BENCH_POINT_VRS[P_T1], BENCH_POINT_VRS[P_T2]};
    /* the cell's law by the patch table's names, set by the point table's */
#define CELL_VALUE(name, ...) G->cell.name,
#define CELL_NAME(name, ...) #name,
    const double law[] = {OC_LAW_PARAMETERS(CELL_VALUE)};
    const char *order[] = {OC_LAW_PARAMETERS(CELL_NAME)};
#undef CELL_VALUE
#undef CELL_NAME
    enum { N_LAW = sizeof law / sizeof law[0] };
    double u[3];
    bench_inputs(0, slip, u);
    for (int i = 0; i < G->n; ++i) {
        fmi2Component c =
            a->inst("point", fmi2CoSimulation, BENCH_POINT_TOKEN, "", &host_print2_cb, 0, 0);
        for (int j = 0; BENCH_POINT_LAW_NAMES[j]; ++j)
            for (int q = 0; q < N_LAW; ++q)
                if (strcmp(BENCH_POINT_LAW_NAMES[j], order[q]) == 0)
                    a->set_real(c, &BENCH_POINT_LAW_VRS[j], 1, &law[q]);
        const fmi2Integer rule = G->cell.rule;
        a->set_int(c, &BENCH_POINT_VRS[P_RULE], 1, &rule);
        a->setup(c, fmi2False, 0, 0, fmi2False, 0);
        a->enter(c);
        double x[3];
        cell_inputs(G, slip, 0, i, u, x, &x[2]);
        a->set_real(c, in, 3, x);
        a->exit_init(c);
        points[i] = c;
    }
    double t = 0, h = 1e-4, sink = 0, T[2] = {0, 0};
    const double t0 = now();
    for (long k = 0; k < steps; ++k) {
        bench_inputs(k, slip, u);
        T[0] = T[1] = 0.0;
        for (int i = 0; i < G->n; ++i) {
            double x[3], y[2];
            cell_inputs(G, slip, k, i, u, x, &x[2]);
            a->set_real(points[i], in, 3, x);
            a->do_step(points[i], t, h, fmi2True);
            a->get_real(points[i], out, 2, y);
            T[0] += y[0];
            T[1] += y[1];
        }
        t += h;
        sink += T[0];
    }
    run_result r = {1e9 * (now() - t0) / steps, {T[0], T[1]}, 0};
    int slipping = 0;
    for (int i = 0; i < G->n; ++i) {
        fmi2Integer s;
        a->get_int(points[i], &BENCH_POINT_VRS[P_STATE], 1, &s);
        slipping += s == OC_SLIP;
        a->free_inst(points[i]);
    }
    r.slip_fraction = (double)slipping / G->n;
    if (sink == 12345.6789) printf(" ");
    return r;
}

static oc_step law_steps[2][MAX_CELLS];

static run_result run_law(const grid *G, int slip, long steps) {
    double u[3];
    bench_inputs(0, slip, u);
    for (int i = 0; i < G->n; ++i) {
        double d[2], Nc;
        cell_inputs(G, slip, 0, i, u, d, &Nc);
        law_steps[0][i].next = oc_state_unloaded(d[0], d[1], 0.0);
    }
    double sink = 0, T[2] = {0, 0};
    const double t0 = now();
    for (long k = 0; k < steps; ++k) {
        bench_inputs(k, slip, u);
        const oc_step *from = law_steps[k & 1];
        oc_step *to = law_steps[(k & 1) ^ 1];
        T[0] = T[1] = 0.0;
        for (int i = 0; i < G->n; ++i) {
            double d[2], Nc;
            cell_inputs(G, slip, k, i, u, d, &Nc);
            oc_law_step(&G->law, &from[i].next, d, Nc, &to[i]);
            T[0] += 0.0 - to[i].q[0];
            T[1] += 0.0 - to[i].q[1];
        }
        sink += T[0];
    }
    run_result r = {1e9 * (now() - t0) / steps, {T[0], T[1]}, 0};
    int slipping = 0;
    for (int i = 0; i < G->n; ++i) slipping += law_steps[steps & 1][i].contact == OC_SLIP;
    r.slip_fraction = (double)slipping / G->n;
    if (sink == 12345.6789) printf(" ");
    return r;
}

static double rel(const double a[2], const double b[2]) {
    const double d = fmax(fabs(a[0] - b[0]), fabs(a[1] - b[1]));
    const double m = fmax(fmax(fabs(a[0]), fabs(a[1])), fmax(fabs(b[0]), fabs(b[1])));
    return d == 0 ? 0 : d / m;
}

int main(int argc, char **argv) {
    const long cell_steps = argc > 1 ? atol(argv[1]) : 200000;
    const int rounds = argc > 2 ? atoi(argv[2]) : 7;
    const char *patch_path = getenv("BENCH_PATCH_FMI2") ? getenv("BENCH_PATCH_FMI2") : PATCH_FMI2;
    const char *point_path = getenv("BENCH_POINT_FMI2") ? getenv("BENCH_POINT_FMI2") : POINT_FMI2;
    const char *pad_path = getenv("BENCH_PAD_FMI2") ? getenv("BENCH_PAD_FMI2") : PAD_FMI2;
    fmi2_api pa, pt, pd;
    if (load(&pa, patch_path) || load(&pt, point_path) || load(&pd, pad_path)) return 2;

        /* the patch's defaults: the table's start values */
#define START_OF(name, vr, type, caus, var, init, start, ...) [vr] = start,
    static const double START[PATCH_VR_COUNT_PLUS_ONE] = {PATCH_VARIABLES(START_OF, START_OF)};
#undef START_OF
#define START_FIELD(name, vr, ...) .name = START[vr],
    const oc_params p = {OC_LAW_PARAMETERS(START_FIELD).rule = (int)START[PATCH_VR_slidingRule]};
#undef START_FIELD
    const double d[8] = {0, 0, 0, 0, 0, 0, START[PATCH_VR_length], START[PATCH_VR_width]};

    static grid grids[N_GRIDS];
    for (int g = 0; g < N_GRIDS; ++g) make_grid(&grids[g], SIDES[g], d[6], d[7], &p);
    pad_area = d[6] * d[7];
    pad_length = d[6];

    /* [grid][slip][patch, points, law, pad, lifted, rolling]: best ns; ratio ranges over rounds */
    double best[N_GRIDS][2][6], cell_lo[N_GRIDS][2], cell_hi[N_GRIDS][2], pts_lo[N_GRIDS][2],
        pts_hi[N_GRIDS][2], pad_lo[N_GRIDS][2], pad_hi[N_GRIDS][2], worst_diff = 0, sf[N_GRIDS][2];
    int failed = 0;
    for (int g = 0; g < N_GRIDS; ++g)
        for (int s = 0; s < 2; ++s) {
            for (int r = 0; r < 6; ++r) best[g][s][r] = 1e30;
            cell_lo[g][s] = pts_lo[g][s] = pad_lo[g][s] = 1e30;
            cell_hi[g][s] = pts_hi[g][s] = pad_hi[g][s] = 0;
        }
    for (int round = 0; round < rounds; ++round)
        for (int g = 0; g < N_GRIDS; ++g)
            for (int s = 0; s < 2; ++s) {
                const grid *G = &grids[g];
                long steps = cell_steps / G->n;
                if (steps < 64) steps = 64;
                const run_result a = run_patch(&pa, G, s, steps);
                const run_result b = run_points(&pt, G, s, steps);
                const run_result l = run_law(G, s, steps);
                const run_result q = run_pad(&pd, G, s, steps, PAD_PLAIN);
                const run_result z = run_pad(&pd, G, s, steps, PAD_LIFTED);
                const run_result o = run_pad(&pd, G, s, steps, PAD_ROLLING);
                const double dp = rel(a.T, b.T), dl = rel(a.T, l.T), dq = rel(a.T, q.T);
                worst_diff = fmax(worst_diff, fmax(fmax(dp, dl), dq));
                const double want = s ? 1.0 : 0.0;
                if (!(dp <= 1e-12 && dl <= 1e-12 && dq <= 1e-12) || a.slip_fraction != want ||
                    b.slip_fraction != want || l.slip_fraction != want || q.slip_fraction != want ||
                    !isfinite(z.T[0] + z.T[1]) || !isfinite(o.T[0] + o.T[1])) {
                    fprintf(stderr,
                            "%d cells, %s: patch T (%.17g, %.17g) slip %g; points (%.17g, %.17g) "
                            "slip %g; law (%.17g, %.17g) slip %g; pad (%.17g, %.17g) slip %g\n",
                            G->n, s ? "slip" : "stick", a.T[0], a.T[1], a.slip_fraction, b.T[0],
                            b.T[1], b.slip_fraction, l.T[0], l.T[1], l.slip_fraction, q.T[0],
                            q.T[1], q.slip_fraction);
                    failed = 1;
                }
                best[g][s][3] = fmin(best[g][s][3], q.ns);
                best[g][s][4] = fmin(best[g][s][4], z.ns);
                best[g][s][5] = fmin(best[g][s][5], o.ns);
                pad_lo[g][s] = fmin(pad_lo[g][s], q.ns / a.ns);
                pad_hi[g][s] = fmax(pad_hi[g][s], q.ns / a.ns);
                sf[g][s] = a.slip_fraction;
                best[g][s][0] = fmin(best[g][s][0], a.ns);
                best[g][s][1] = fmin(best[g][s][1], b.ns);
                best[g][s][2] = fmin(best[g][s][2], l.ns);
                const double rc = a.ns / l.ns, rp = a.ns / b.ns;
                cell_lo[g][s] = fmin(cell_lo[g][s], rc);
                cell_hi[g][s] = fmax(cell_hi[g][s], rc);
                pts_lo[g][s] = fmin(pts_lo[g][s], rp);
                pts_hi[g][s] = fmax(pts_hi[g][s], rp);
            }

    printf(
        "# ContactPatch step (FMI 2.0: set u1 u2 theta N, doStep, get T1 T2 Mz) against n point\n"
        "# FMU steps (set u1 u2 N, doStep, get T1 T2 each) and n linked-in oc_law_step calls;\n"
        "# %ld cell steps a run, interleaved, least disturbed of %d rounds, thread CPU time\n",
        cell_steps, rounds);
    printf("%5s %-5s %10s %9s %9s %17s %11s %17s %5s %10s %17s %10s %10s\n", "cells", "path",
           "patch_ns", "cell_ns", "law_ns", "cell/law [rounds]", "points_ns", "patch/points",
           "slip", "pad_ns", "pad/patch", "lifted_ns", "rolling_ns");
    for (int g = 0; g < N_GRIDS; ++g)
        for (int s = 0; s < 2; ++s) {
            const int n = grids[g].n;
            const double *b = best[g][s];
            printf("%5d %-5s %10.1f %9.2f %9.2f %5.2f [%4.2f-%4.2f] %11.1f %5.3f [%4.2f-%4.2f] "
                   "%5.2f %10.1f %5.2f [%4.2f-%4.2f] %10.1f %10.1f\n",
                   n, s ? "slip" : "stick", b[0], b[0] / n, b[2] / n, b[0] / b[2], cell_lo[g][s],
                   cell_hi[g][s], b[1], b[0] / b[1], pts_lo[g][s], pts_hi[g][s], sf[g][s], b[3],
                   b[3] / b[0], pad_lo[g][s], pad_hi[g][s], b[4], b[5]);
        }
    for (int s = 0; s < 2; ++s) {
        const double rc = best[3][s][0] / best[3][s][2], rp = best[2][s][0] / best[2][s][1];
        printf("%s: a cell's cost at 400 cells / the law's step %.2f, target <= 1.20 %s; "
               "100-cell patch / 100 point steps %.3f, target <= 0.50 %s\n",
               s ? "slip " : "stick", rc, rc <= 1.2 ? "met" : "NOT MET", rp,
               rp <= 0.5 ? "met" : "NOT MET");
    }
    for (int s = 0; s < 2; ++s) {
        const double r100 = best[2][s][3] / best[2][s][0], r400 = best[3][s][3] / best[3][s][0];
        printf("%s: a pad's cell / a patch's at 100 cells %.2f, at 400 cells %.2f, target <= 1.30 "
               "%s\n",
               s ? "slip " : "stick", r100, r400, fmax(r100, r400) <= 1.3 ? "met" : "NOT MET");
    }
    for (int s = 0; s < 2; ++s) {
        const double r100 = best[2][s][5] / best[2][s][3], r400 = best[3][s][5] / best[3][s][3];
        printf("%s: pad rolling cell / a pad's cell at 100 cells %.2f, at 400 cells %.2f, target "
               "<= 1.30 %s\n",
               s ? "slip " : "stick", r100, r400, fmax(r100, r400) <= 1.3 ? "met" : "NOT MET");
    }
    printf("patch, points, law and pad agree: max relative difference of T %.1e %s\n", worst_diff,
           failed ? "-- FAILED (> 1e-12 or a cell in the wrong state)" : "(<= 1e-12)");
    dlclose(pa.lib);
    dlclose(pt.lib);
    dlclose(pd.lib);
    return failed;
}
