#include "models/ContactPad/model.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "cells/transport.h"
#include "models/ContactPad/pressure.h"

/* Where each of the pad's own variables lives (cells/cells_model.inc has the
 * law's, the cells' and their sums'). */
#define FMU_SLOT_kn offsetof(pad_model, kn)
#define FMU_SLOT_dn offsetof(pad_model, dn)
#define FMU_SLOT_d offsetof(pad_model, d)
#define FMU_SLOT_phi1 offsetof(pad_model, phi[0])
#define FMU_SLOT_phi2 offsetof(pad_model, phi[1])
#define FMU_SLOT_vr offsetof(pad_model, vr)
#define FMU_SLOT_Fn offsetof(pad_model, Fn)
#define FMU_SLOT_M1 offsetof(pad_model, M[0])
#define FMU_SLOT_M2 offsetof(pad_model, M[1])
#define FMU_SLOT_contactFraction offsetof(pad_model, contact_fraction)

/* The Jacobian: rows T1, T2, Mz, Fn, M1, M2, dissipatedEnergy; columns
 * u1, u2, theta, d, phi1, phi2. */
enum { P_ROWS = 7, P_COLS = 6 };
#define MODEL_JAC_ROWS P_ROWS
#define MODEL_JAC_COLS P_COLS
#define MODEL_JAC_OUTPUTS                                                                          \
    PAD_VR_T1, PAD_VR_T2, PAD_VR_Mz, PAD_VR_Fn, PAD_VR_M1, PAD_VR_M2, PAD_VR_dissipatedEnergy
#define MODEL_JAC_INPUTS PAD_VR_u1, PAD_VR_u2, PAD_VR_theta, PAD_VR_d, PAD_VR_phi1, PAD_VR_phi2

#include "cells/cells_model.inc"

/* ---- the foundation ------------------------------------------------------- */

/* The pressure over the pad is kn e+ with e(r) = f0 + g . r in body
 * coordinates: the approach d + (phi2, -phi1) . R(theta) r, plus (dn/kn)
 * times its rate over the previous step, the difference from the
 * reference pose's approach of the same body point divided by ref.h.
 * With a = (dn/kn)/ref.h, f0 = d + a (d - d_ref) and g = g_b + a (g_b -
 * g_ref), g_b = R(theta)^T (phi2, -phi1): each a linear function of the
 * pose, f0' = (1 + a) d' and g' = (1 + a) g_b'.  With a > 0 (damped) the
 * layer presses only where it touches, the approach d + g_b . r > 0, as
 * well (a Kelvin-Voigt layer): the pressed part is clipped by both lines. */
typedef struct {
    double f0, g[2];
    double df0;        /* df0/dd [-] */
    double dg[3][2];   /* dg/d(theta, phi1, phi2) [1/rad] */
    int damped;        /* a > 0: the touching line d + gb . r = 0 clips too */
    double d, gb[2];   /* the approach's field, d + gb . r */
    double dgb[3][2];  /* dgb/d(theta, phi1, phi2) [1/rad] */
    double a;          /* (dn/kn)/ref.h [-] */
    double dd, ddg[2]; /* the approach's change over the step, dd + ddg . r [m] */
} pad_field;

/* R(theta)^T (phi2, -phi1): the approach's slopes along the body's axes. */
static void body_slopes(double theta, double phi1, double phi2, double g[2]) {
    const double c = cos(theta), s = sin(theta);
    g[0] = c * phi2 - s * phi1;
    g[1] = -s * phi2 - c * phi1;
}

static pad_field field_of(const pad_model *m, const pad_pose *ref) {
    pad_field F;
    const double c = cos(m->g.theta), s = sin(m->g.theta);
    double gb[2];
    body_slopes(m->g.theta, m->phi[0], m->phi[1], gb);
    const double a = ref->h > 0.0 && m->dn > 0.0 ? m->dn / m->kn / ref->h : 0.0;
    F.f0 = m->d;
    F.g[0] = gb[0];
    F.g[1] = gb[1];
    F.damped = a > 0.0;
    F.d = m->d;
    F.gb[0] = gb[0];
    F.gb[1] = gb[1];
    F.a = a;
    F.dd = F.ddg[0] = F.ddg[1] = 0.0;
    if (a > 0.0) { /* as differences, so that held inputs add exactly nothing */
        double gr[2];
        body_slopes(ref->theta, ref->phi[0], ref->phi[1], gr);
        F.dd = m->d - ref->d;
        F.ddg[0] = gb[0] - gr[0];
        F.ddg[1] = gb[1] - gr[1];
        F.f0 += a * (m->d - ref->d);
        F.g[0] += a * (gb[0] - gr[0]);
        F.g[1] += a * (gb[1] - gr[1]);
    }
    const double k = 1.0 + a;
    F.dgb[0][0] = -s * m->phi[1] - c * m->phi[0];
    F.dgb[0][1] = -c * m->phi[1] + s * m->phi[0];
    F.dgb[1][0] = -s;
    F.dgb[1][1] = -c;
    F.dgb[2][0] = c;
    F.dgb[2][1] = -s;
    F.df0 = k;
    for (int q = 0; q < 3; ++q) {
        F.dg[q][0] = k * F.dgb[q][0];
        F.dg[q][1] = k * F.dgb[q][1];
    }
    return F;
}

/* The moments of the part of a cell (centre r = (x, y), half sides hx,
 * hy) that presses, e its effective approach at the centre; 1 if all of
 * it.  Damped, the part that touches too, and its edge on the touching
 * line (when `edge` is given). */
static int pressed_part(const pad_field *F, double x, double y, double e, double hx, double hy,
                        pad_moments *M, pad_edge *edge) {
    pad_edge none;
    if (!edge) edge = &none;
    edge->n = 0;
    if (!F->damped) return pad_clip_moments(e, F->g, hx, hy, M);
    const double dl = (F->d + F->gb[0] * x) + F->gb[1] * y;
    return pad_clip_moments_touching(e, F->g, dl, F->gb, hx, hy, M, edge);
}

/* The cells' half sides and centres [m]. */
typedef struct {
    double hx, hy;
    double x[PATCH_MAX_SIDE], y[PATCH_MAX_SIDE];
} pad_grid;

static void grid_of(const cells_setup *g, pad_grid *G) {
    G->hx = g->length / (2.0 * g->n[0]);
    G->hy = g->width / (2.0 * g->n[1]);
    for (int i = 0; i < g->n[0]; ++i) G->x[i] = cells_coordinate(i, g->n[0]) * g->length;
    for (int j = 0; j < g->n[1]; ++j) G->y[j] = cells_coordinate(j, g->n[1]) * g->width;
}

/* The pressure's resultant and first moment (body axes), and the share of
 * the area that presses. */
typedef struct {
    double Fn, mb[2], contact_fraction;
    double damper; /* the damper's work in the step [J] (change_squared) */
} pad_normal;

/* The integral of dd_r^2 over a cell's pressed part (moments M about its
 * centre r), dd_r = dd + ddg . r the approach's change over the step.  The
 * damper's work on the body over the step [J] is kn a times its sum over
 * the cells: its pressure dn dd_r/h = kn a dd_r over the change dd_r on the
 * part that presses (>= 0); where the body leaves the layer faster than it
 * recovers (p clipped at 0) nothing acts on the body. */
static double change_squared(const pad_field *F, const double r[2], const pad_moments *M) {
    const double c = (F->dd + F->ddg[0] * r[0]) + F->ddg[1] * r[1];
    const double *g = F->ddg;
    return c * c * M->area + 2.0 * c * (g[0] * M->m1[0] + g[1] * M->m1[1]) +
           (g[0] * g[0] * M->m2[0] + 2.0 * g[0] * g[1] * M->m2[1] + g[1] * g[1] * M->m2[2]);
}

/* Every cell's normal force Nc[c] [N] and their sums: a cell's force kn
 * (e A + g . m1) and first moment about the pad centre r N + kn (e m1 +
 * m2 g), of the moments (A, m1 about its centre, m2) of its pressed part
 * (pad_clip_moments: its own rectangle's where it presses wholly).  Where
 * every corner of the pad presses, so does every cell: the pressure is
 * linear, each cell's force kn A e at its centre and the sums the whole
 * rectangle's, Fn = kn L W f0 and first moments kn g (W L^3/12, L W^3/12),
 * with no test or sum a cell (the step's cost is the cells'). */
static void normal_forces(const pad_model *m, const pad_field *F, double Nc[], pad_normal *S) {
    const cells_setup *g = &m->g;
    const int n1 = g->n[0], n2 = g->n[1];
    pad_grid G;
    grid_of(g, &G);
    double ex[PATCH_MAX_SIDE], ey[PATCH_MAX_SIDE];
    for (int i = 0; i < n1; ++i) ex[i] = F->f0 + F->g[0] * G.x[i];
    for (int j = 0; j < n2; ++j) ey[j] = F->g[1] * G.y[j];
    const double kn = m->kn, cell_area = 4.0 * G.hx * G.hy, kA = kn * cell_area;
    const double L = g->length, W = g->width;
    if (F->f0 - (fabs(F->g[0]) * (0.5 * L) + fabs(F->g[1]) * (0.5 * W)) > 0 &&
        (!F->damped || F->d - (fabs(F->gb[0]) * (0.5 * L) + fabs(F->gb[1]) * (0.5 * W)) > 0)) {
        for (int j = 0, c = 0; j < n2; ++j)
            for (int i = 0; i < n1; ++i, ++c) Nc[c] = kA * (ex[i] + ey[j]);
        S->Fn = kn * (L * W) * F->f0;
        S->mb[0] = kn * F->g[0] * (W * L * L * L / 12.0);
        S->mb[1] = kn * F->g[1] * (L * W * W * W / 12.0);
        S->contact_fraction = 1.0;
        /* the whole rectangle's integral of dd_r^2 (dd_r linear) */
        S->damper = kn * F->a *
                    (L * W * F->dd * F->dd + F->ddg[0] * F->ddg[0] * (W * L * L * L / 12.0) +
                     F->ddg[1] * F->ddg[1] * (L * W * W * W / 12.0));
        return;
    }
    double Fn = 0.0, mx = 0.0, my = 0.0, full = 0.0, part = 0.0, damper = 0.0;
    for (int j = 0, c = 0; j < n2; ++j) {
        double row_N = 0.0, row_my = 0.0; /* a row's cells share y: its force's moment once */
        for (int i = 0; i < n1; ++i, ++c) {
            const double e = ex[i] + ey[j];
            pad_moments M;
            const int whole = pressed_part(F, G.x[i], G.y[j], e, G.hx, G.hy, &M, NULL);
            if (F->damped) damper += change_squared(F, (const double[2]){G.x[i], G.y[j]}, &M);
            if (whole) {
                const double N = kA * e;
                Nc[c] = N;
                row_N += N;
                mx += G.x[i] * N;
                full += 1.0;
                continue;
            }
            const double N = kn * (e * M.area + (F->g[0] * M.m1[0] + F->g[1] * M.m1[1]));
            Nc[c] = N;
            row_N += N;
            mx += G.x[i] * N + kn * (e * M.m1[0] + M.m2[0] * F->g[0] + M.m2[1] * F->g[1]);
            row_my += kn * (e * M.m1[1] + M.m2[1] * F->g[0] + M.m2[2] * F->g[1]);
            part += M.area / cell_area;
        }
        Fn += row_N;
        my += G.y[j] * row_N + row_my;
    }
    /* the wholly pressed cells' own second moments, A h^2/3 each, once */
    mx += kn * (full * (cell_area * G.hx * G.hx / 3.0)) * F->g[0];
    my += kn * (full * (cell_area * G.hy * G.hy / 3.0)) * F->g[1];
    S->Fn = Fn;
    S->mb[0] = mx;
    S->mb[1] = my;
    S->contact_fraction = (full + part) / (double)cells_count(g);
    S->damper = kn * F->a * damper;
}

/* (M1, M2) of a first moment in body axes: turned into the surface's, a
 * force +X3 at (X, Y) has the moment (Y F, -X F). */
static void moments_of(double theta, const double mb[2], double M[2]) {
    const double c = cos(theta), s = sin(theta);
    M[0] = s * mb[0] + c * mb[1];
    M[1] = -(c * mb[0] - s * mb[1]);
}

/* ---- the step ------------------------------------------------------------- */

/* Why a step was refused: cells_step's index `bad` (the first cell whose
 * force or slip would not be finite, or n1 n2 for a sum), or -1 for the
 * foundation's force or moments. */
static fmu_status overflow(const pad_model *m, int bad, fmu_msg *msg) {
    const cells_setup *g = &m->g;
    const char *what = bad < 0                ? "the foundation's normal force or moments"
                       : bad < cells_count(g) ? "the force or slip of cell"
                                              : "the pad's force, moment or energy";
    char cell[32] = "";
    if (bad >= 0 && bad < cells_count(g))
        snprintf(cell, sizeof cell, " (%d, %d)", bad % g->n[0] + 1, bad / g->n[0] + 1);
    return fmu_fail(msg,
                    "inputs u1=%g m, u2=%g m, theta=%g rad, d=%g m, phi1=%g rad, phi2=%g rad "
                    "overflow %s%s",
                    g->u[0], g->u[1], g->theta, m->d, m->phi[0], m->phi[1], what, cell);
}

/* Computes the pending step of every cell for the inputs in m from `src`
 * with `law`, its rate against `ref` (which commits nothing); or fails and
 * changes nothing. */
static fmu_status evaluate(pad_model *m, const oc_law *law, const cells_source *src,
                           const pad_pose *ref, double damper, fmu_msg *msg) {
    double Nc[PATCH_MAX_CELLS];
    const pad_field F = field_of(m, ref);
    pad_normal S;
    normal_forces(m, &F, Nc, &S);
    double M[2];
    moments_of(m->g.theta, S.mb, M);
    if (!isfinite(S.Fn) || !isfinite(M[0]) || !isfinite(M[1]) || !isfinite(damper + S.damper))
        return overflow(m, -1, msg);
    cells_sums out;
    const int bad = cells_evaluate(&m->cells, law, &m->g, Nc, src, &out);
    if (bad >= 0) return overflow(m, bad, msg);
    m->out = out;
    m->damper = damper;
    m->damper_step = S.damper;
    m->out.energy += damper + S.damper;
    m->Fn = S.Fn;
    m->M[0] = M[0];
    m->M[1] = M[1];
    m->contact_fraction = S.contact_fraction;
    if (ref != &m->ref) m->ref = *ref;
    return FMU_OK;
}

/* The pose of the inputs, its rate over h. */
static pad_pose pose_now(const pad_model *m, double h) {
    const pad_pose p = {m->d, {m->phi[0], m->phi[1]}, m->g.theta, h, m->vr};
    return p;
}

/* Where a step from the committed result starts: the committed states
 * moved with the material by the committed step's vr h, in cells
 * (cells/transport.h), where the shown step does not start from; none
 * moved, where they lie. */
static cells_source rolled_from_commit(pad_model *m) {
    const cells_source src = cells_committed(&m->cells);
    const double shift = m->commit.vr * m->commit.h / (m->g.length / m->g.n[0]);
    if (shift == 0.0) return src;
    oc_state *to = cells_move_target(&m->cells);
    cells_transport(&m->g, shift, &src, to);
    const cells_source moved = {CELLS_FROM_ARRAY, to, NULL, -1, NULL};
    return moved;
}

fmu_status fmu_model_update(pad_model *m, int changed, int allow, fmu_msg *msg) {
    oc_law law;
    const oc_law *use = law_for(m, changed, &law, msg);
    if (!use) return FMU_ERR;
    /* Before the end of initialization the cells start where the inputs or
     * the explicit slip put them, with no rate; afterwards from what was
     * committed, the rate against the pose it was committed at. */
    if (allow & FMU_ALLOW_PARAMETERS) {
        const cells_source init = cells_initial();
        const pad_pose none = pose_now(m, 0.0);
        return evaluate(m, use, &init, &none, 0.0, msg);
    }
    /* from the committed result, the damper's work up to its end */
    const int after = m->cells.result_committed;
    const cells_source src = after ? rolled_from_commit(m) : cells_committed(&m->cells);
    return evaluate(m, use, &src, after ? &m->commit : &m->ref,
                    after ? m->damper + m->damper_step : m->damper, msg);
}

/* Every set in initialization already derived the start from the values it
 * left; deriving it once more here makes the end of initialization the
 * moment that counts, whatever was restored before it. */
static fmu_status exit_init(pad_model *m, fmu_msg *msg) {
    const cells_source init = cells_initial();
    const pad_pose none = pose_now(m, 0.0);
    return evaluate(m, &m->cells.law, &init, &none, 0.0, msg);
}

/* A further step with held inputs steps every cell again from what the
 * last doStep committed (the rate against that step's pose: none). */
fmu_status fmu_model_do_step(pad_model *m, double h, fmu_msg *msg) {
    if (m->cells.result_committed) {
        const cells_source src = rolled_from_commit(m);
        const pad_pose was = m->commit;
        if (evaluate(m, &m->cells.law, &src, &was, m->damper + m->damper_step, msg) != FMU_OK)
            return FMU_ERR;
    }
    m->cells.result_committed = 1;
    m->commit = pose_now(m, h);
    return FMU_OK;
}

/* ---- directional derivatives ------------------------------------------------ */

/* A cell of the shown step's foundation: its centre, its field, its
 * pressed part's moments and (damped) its edge on the touching line. */
typedef struct {
    double r[2], e;
    pad_moments M;
    pad_edge E;
} pad_cell;

static pad_cell pad_cell_of(const pad_model *m, const pad_field *F, int c) {
    const cells_setup *g = &m->g;
    pad_cell x;
    const double hx = g->length / (2.0 * g->n[0]), hy = g->width / (2.0 * g->n[1]);
    x.r[0] = cells_coordinate(c % g->n[0], g->n[0]) * g->length;
    x.r[1] = cells_coordinate(c / g->n[0], g->n[1]) * g->width;
    x.e = (F->f0 + F->g[0] * x.r[0]) + F->g[1] * x.r[1];
    pressed_part(F, x.r[0], x.r[1], x.e, hx, hy, &x.M, &x.E);
    return x;
}

/* s_q = d delta/dq at the body point r over (theta, d, phi1, phi2) [m/rad,
 * -]: dgb/dq . r for a turn or tilt, 1 for the approach. */
static void pose_slopes(const pad_field *F, const double r[2], double sq[4]) {
    sq[0] = F->dgb[0][0] * r[0] + F->dgb[0][1] * r[1];
    sq[1] = 1.0;
    sq[2] = F->dgb[1][0] * r[0] + F->dgb[1][1] * r[1];
    sq[3] = F->dgb[2][0] * r[0] + F->dgb[2][1] * r[1];
}

/* The two-point Gauss-Legendre rule along an edge of the cell centred at
 * rc: its points r[k] in body coordinates; returns each one's weight (half
 * the edge's length).  Exact for a cubic along the edge. */
static double edge_points(const double rc[2], const pad_edge *E, double r[2][2]) {
    static const double node[2] = {0.21132486540518711775, 0.78867513459481288225};
    for (int k = 0; k < 2; ++k) {
        r[k][0] = rc[0] + E->a[0] + node[k] * (E->b[0] - E->a[0]);
        r[k][1] = rc[1] + E->a[1] + node[k] * (E->b[1] - E->a[1]);
    }
    return 0.5 * hypot(E->b[0] - E->a[0], E->b[1] - E->a[1]);
}

/* Where the layer presses only where it touches (damped), the pressure
 * jumps to kn e across the touching line delta = 0, which the pose moves:
 * by s_q / |gb| along its normal per unit of a pose variable q, s_q =
 * d delta / dq at the point (1 for d, dgb/dq . r for a turn or tilt).  The
 * integrals of Fn and of the first moment r p gain kn times those of e s_q
 * and of e r s_q along the cell's edge on it, /|gb| (two-point
 * Gauss-Legendre: exact, the integrand a cubic along the line).  dN[q] and
 * dmb[axis][q] over (theta, d, phi1, phi2). */
static void touching_terms(const pad_field *F, const pad_cell *x, double kn, double dN[4],
                           double dmb[2][4]) {
    for (int q = 0; q < 4; ++q) dN[q] = dmb[0][q] = dmb[1][q] = 0.0;
    if (!x->E.n) return;
    double r[2][2], sq[4];
    const double half = edge_points(x->r, &x->E, r) / hypot(F->gb[0], F->gb[1]);
    for (int k = 0; k < 2; ++k) {
        const double e = x->e + F->g[0] * (r[k][0] - x->r[0]) + F->g[1] * (r[k][1] - x->r[1]);
        const double w = kn * e * half;
        pose_slopes(F, r[k], sq);
        for (int q = 0; q < 4; ++q) {
            dN[q] += w * sq[q];
            dmb[0][q] += w * sq[q] * r[k][0];
            dmb[1][q] += w * sq[q] * r[k][1];
        }
    }
}

/* dN/d(theta, d, phi1, phi2) of a cell whose dN/d(f0, g0, g1) is dn. */
static void pose_tangent(const pad_field *F, const double dn[3], double dN[4]) {
    dN[0] = dn[1] * F->dg[0][0] + dn[2] * F->dg[0][1];
    dN[1] = dn[0] * F->df0;
    dN[2] = dn[1] * F->dg[1][0] + dn[2] * F->dg[1][1];
    dN[3] = dn[1] * F->dg[2][0] + dn[2] * F->dg[2][1];
}

/* What the cells' Jacobian asks of a cell: its normal force's tangent. */
typedef struct {
    const pad_model *m;
    pad_field F;
} pad_tangent_ctx;

static void normal_tangent(const void *ctx, int c, double dN[4]) {
    const pad_tangent_ctx *t = ctx;
    const pad_cell x = pad_cell_of(t->m, &t->F, c);
    double dn[3], edge[4], unused[2][4];
    pad_cell_force(t->m->kn, &x.M, x.e, t->F.g, x.r, dn);
    pose_tangent(&t->F, dn, dN);
    touching_terms(&t->F, &x, t->m->kn, edge, unused);
    for (int q = 0; q < 4; ++q) dN[q] += edge[q];
}

/* The integral along an edge (about a cell centre r) of dd_r^2 s_q
 * [m^3 per unit of q], s_q = d delta/dq at the point, over (theta, d,
 * phi1, phi2): two-point Gauss-Legendre, exact for the cubic. */
static void edge_change_squared(const pad_field *F, const double rc[2], const pad_edge *E,
                                double out[4]) {
    for (int q = 0; q < 4; ++q) out[q] = 0.0;
    if (!E->n) return;
    double r[2][2], sq[4];
    const double half = edge_points(rc, E, r);
    for (int k = 0; k < 2; ++k) {
        const double c = (F->dd + F->ddg[0] * r[k][0]) + F->ddg[1] * r[k][1];
        pose_slopes(F, r[k], sq);
        for (int q = 0; q < 4; ++q) out[q] += c * c * half * sq[q];
    }
}

/* A cell's share of d(the damper's work)/d(theta, d, phi1, phi2), over kn
 * a: inside its pressed part twice the integral of dd_r s_q (dd_r's own
 * derivative, the reference being fixed); the part grows across the
 * touching line (speed s_q/|gb|) and across e = 0 (speed (1 + a) s_q/|g|),
 * where the integrand dd_r^2 is not 0. */
static void damper_terms(const pad_model *m, const pad_field *F, const pad_cell *x, double dW[4]) {
    const pad_moments *M = &x->M;
    const double *d = F->ddg;
    const double dc = (F->dd + d[0] * x->r[0]) + d[1] * x->r[1];
    double s0[4];
    pose_slopes(F, x->r, s0);
    /* s_q = s0 + s1 . rho about the centre: s1 the slope dgb/dq (theta, phi1,
     * phi2), none for the approach d */
    const double zero[2] = {0.0, 0.0};
    const double *slope[4] = {F->dgb[0], zero, F->dgb[1], F->dgb[2]};
    for (int q = 0; q < 4; ++q) {
        const double *s1 = slope[q];
        dW[q] = 2.0 * (dc * s0[q] * M->area + (dc * s1[0] + s0[q] * d[0]) * M->m1[0] +
                       (dc * s1[1] + s0[q] * d[1]) * M->m1[1] +
                       (d[0] * s1[0] * M->m2[0] + (d[0] * s1[1] + d[1] * s1[0]) * M->m2[1] +
                        d[1] * s1[1] * M->m2[2]));
    }
    double on_touch[4], on_zero[4];
    edge_change_squared(F, x->r, &x->E, on_touch);
    pad_edge Z;
    const double hx = m->g.length / (2.0 * m->g.n[0]), hy = m->g.width / (2.0 * m->g.n[1]);
    const double dl = (F->d + F->gb[0] * x->r[0]) + F->gb[1] * x->r[1];
    pad_line_part(x->e, F->g, dl, F->gb, hx, hy, &Z);
    edge_change_squared(F, x->r, &Z, on_zero);
    for (int q = 0; q < 4; ++q) /* an edge exists only where its field has a slope */
        dW[q] += (x->E.n ? on_touch[q] / hypot(F->gb[0], F->gb[1]) : 0.0) +
                 (Z.n ? (1.0 + F->a) * on_zero[q] / hypot(F->g[0], F->g[1]) : 0.0);
}

/* What damping adds to the pad's Jacobian, in one pass over the cells:
 * the touching line's terms (touching_terms) of d(Fn, mbx, mby)/d(theta,
 * d, phi1, phi2) into dq, and d(the damper's work)/d(the same) into dW. */
static void damped_terms(const pad_model *m, const pad_field *F, double dq[3][4], double dW[4]) {
    for (int q = 0; q < 4; ++q) dW[q] = 0.0;
    if (!F->damped) return;
    for (int c = 0, n = cells_count(&m->g); c < n; ++c) {
        const pad_cell x = pad_cell_of(m, F, c);
        double dN[4], dmb[2][4], dw[4];
        touching_terms(F, &x, m->kn, dN, dmb);
        damper_terms(m, F, &x, dw);
        for (int q = 0; q < 4; ++q) {
            dq[0][q] += dN[q];
            dq[1][q] += dmb[0][q];
            dq[2][q] += dmb[1][q];
            dW[q] += m->kn * F->a * dw[q];
        }
    }
}

/* The pad's Jacobian of the shown step: the cells' (cells_jacobian) for
 * T1, T2, Mz, dissipatedEnergy; Fn's and the first moment's from the
 * pressed parts' moments: d/df0 of the integrals of e+ and r e+ are those
 * of 1 and r, d/dg those of r and r r^T, over the part that presses (the
 * integrand vanishes on the line e = 0 that bounds it; the touching line's
 * terms besides, damped_terms); then M = (Y, -X) of
 * R(theta) mb, whose own turning adds (X, Y) to dM/dtheta. */
static void partials(const pad_model *m, double *Jflat) {
    double(*P)[P_COLS] = (double(*)[P_COLS])Jflat;
    pad_tangent_ctx t = {m, field_of(m, &m->ref)};
    double C[CELLS_JAC_ROWS][CELLS_JAC_COLS];
    cells_jacobian(&m->cells, &m->g, normal_tangent, &t, C);
    memset(P, 0, sizeof(double) * P_ROWS * P_COLS);
    for (int k = 0; k < P_COLS; ++k) {
        P[0][k] = C[0][k];
        P[1][k] = C[1][k];
        P[2][k] = C[2][k];
        P[6][k] = C[3][k];
    }
    /* the foundation: d(Fn, mbx, mby)/d(f0, g0, g1) summed over the cells */
    double D[3][3] = {{0}};
    const double kn = m->kn;
    for (int c = 0, n = cells_count(&m->g); c < n; ++c) {
        const pad_cell x = pad_cell_of(m, &t.F, c);
        const pad_moments *M = &x.M;
        const double I1[2] = {x.r[0] * M->area + M->m1[0], x.r[1] * M->area + M->m1[1]};
        const double I2[3] = {x.r[0] * x.r[0] * M->area + 2 * x.r[0] * M->m1[0] + M->m2[0],
                              x.r[0] * x.r[1] * M->area + x.r[0] * M->m1[1] + x.r[1] * M->m1[0] +
                                  M->m2[1],
                              x.r[1] * x.r[1] * M->area + 2 * x.r[1] * M->m1[1] + M->m2[2]};
        D[0][0] += kn * M->area;
        D[0][1] += kn * I1[0];
        D[0][2] += kn * I1[1];
        D[1][0] += kn * I1[0];
        D[1][1] += kn * I2[0];
        D[1][2] += kn * I2[1];
        D[2][0] += kn * I1[1];
        D[2][1] += kn * I2[1];
        D[2][2] += kn * I2[2];
    }
    /* through the field to (theta, d, phi1, phi2), columns 2 to 5 */
    double dq[3][4];
    for (int r = 0; r < 3; ++r) pose_tangent(&t.F, D[r], dq[r]);
    double dW[4];
    damped_terms(m, &t.F, dq, dW);
    const double c = cos(m->g.theta), s = sin(m->g.theta);
    /* the first moment in the surface's axes, X = -M2, Y = M1, for the turning of R(theta) */
    const double X = -m->M[1], Y = m->M[0];
    for (int k = 0; k < 4; ++k) {
        P[3][k + 2] = dq[0][k];
        P[4][k + 2] = s * dq[1][k] + c * dq[2][k];
        P[5][k + 2] = -(c * dq[1][k] - s * dq[2][k]);
    }
    P[4][2] += X;
    P[5][2] += Y;
    for (int k = 0; k < 4; ++k) P[6][k + 2] += dW[k];
}

/* ---- serialized state: the field list of model.h ------------------------ */

/* What the serialized head reads into m, kept to be put back. */
typedef struct {
    oc_params params;
    cells_setup g;
    double kn, dn, d, phi[2], vr;
    int result_committed;
    pad_pose ref, commit;
    double damper;
} pad_head;

static pad_head head_of(const pad_model *m) {
    const pad_head h = {m->params, m->g,
                        m->kn,     m->dn,
                        m->d,      {m->phi[0], m->phi[1]},
                        m->vr,     m->cells.result_committed,
                        m->ref,    m->commit,
                        m->damper};
    return h;
}

static void put_head(pad_model *m, const pad_head *h) {
    m->params = h->params;
    m->g = h->g;
    m->kn = h->kn;
    m->dn = h->dn;
    m->d = h->d;
    m->phi[0] = h->phi[0];
    m->phi[1] = h->phi[1];
    m->vr = h->vr;
    m->cells.result_committed = h->result_committed;
    m->ref = h->ref;
    m->commit = h->commit;
    m->damper = h->damper;
}

/* fmu_model_state_read once the head is in m: the steps' sizes checked,
 * the cells checked where they lie in the buffer, then the shown result
 * recomputed (into the free buffer, which nothing reads) from the committed
 * states, the inputs and the rate's reference, of which it is a function.
 * `was` holds the head before. */
static fmu_status read_cells(pad_model *m, const pad_head *was, const unsigned char *cells,
                             fmu_msg *msg) {
    if (!(m->ref.h >= 0.0) || !(m->commit.h >= 0.0))
        return fmu_fail(msg, "serialized state: a step size h=%g s, %g s below 0", m->ref.h,
                        m->commit.h);
    if (!(m->damper >= 0.0))
        return fmu_fail(msg, "serialized state: the damper's work %g J is below 0", m->damper);
    oc_law law;
    if (cells_restored_law(&m->cells, &was->params, &was->g, &m->params, &m->g, cells, &law, msg) !=
        FMU_OK)
        return FMU_ERR;
    double Nc[PATCH_MAX_CELLS];
    const pad_field F = field_of(m, &m->ref);
    pad_normal S;
    normal_forces(m, &F, Nc, &S);
    double M[2];
    moments_of(m->g.theta, S.mb, M);
    if (!isfinite(S.Fn) || !isfinite(M[0]) || !isfinite(M[1]) || !isfinite(m->damper + S.damper))
        return refused_state(m, -1, msg);
    if (restored_cells(m, &law, Nc, cells, msg) != FMU_OK) return FMU_ERR;
    m->damper_step = S.damper;
    m->out.energy += m->damper + S.damper;
    m->Fn = S.Fn;
    m->M[0] = M[0];
    m->M[1] = M[1];
    m->contact_fraction = S.contact_fraction;
    return FMU_OK;
}

/* Reads the head into m, checked field by field, and the cells; a refused
 * state puts the head back and changes nothing else. */
fmu_status fmu_model_state_read(pad_model *m, const unsigned char *p, fmu_msg *msg) {
    const pad_head head = head_of(m);
    fmu_status st = fmu_fields_read(&CELLS_HEAD_FIELDS, m, &p, msg);
    if (st == FMU_OK) st = read_cells(m, &head, p, msg);
    if (st != FMU_OK) put_head(m, &head);
    return st;
}

#include "glue/fmu_model_defaults.inc"
