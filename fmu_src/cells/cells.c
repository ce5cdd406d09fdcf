#include "cells/cells.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "glue/fmu_bytes.h"
#include "glue/fmu_fields.h"
#include "law/law_fields.h"

/* ---- kinematics --------------------------------------------------------- */

cells_cell cells_cell_of(const cells_setup *g, int c) {
    const int i = c % g->n[0], j = c / g->n[0];
    const double h = sin(0.5 * g->theta);
    /* cos(theta) - 1 as -2 sin^2(theta/2): exact for small theta */
    const double cm1 = -2.0 * h * h, sn = sin(g->theta);
    cells_cell x;
    x.xi = cells_coordinate(i, g->n[0]);
    x.eta = cells_coordinate(j, g->n[1]);
    x.r[0] = x.xi * g->length;
    x.r[1] = x.eta * g->width;
    /* (R - I) r; none added at the centre, so that a one-cell grid's cell
     * sees u itself, the sign of a zero included */
    x.d[0] = g->u[0];
    x.d[1] = g->u[1];
    x.Rr[0] = x.r[0];
    x.Rr[1] = x.r[1];
    if (x.r[0] != 0.0 || x.r[1] != 0.0) {
        const double dr0 = cm1 * x.r[0] - sn * x.r[1];
        const double dr1 = sn * x.r[0] + cm1 * x.r[1];
        x.d[0] += dr0;
        x.d[1] += dr1;
        x.Rr[0] += dr0;
        x.Rr[1] += dr1;
    }
    return x;
}

/* ---- where the committed states lie ------------------------------------- */

/* A serialized cell: its committed state (law/law_fields.h), all f64. */
static size_t cell_bytes(void) { return fmu_fields_size(&OC_STATE_FIELDS); }

static oc_state cell_of_bytes(const unsigned char *bytes, int c) {
    oc_state s;
    const unsigned char *p = bytes + (size_t)c * 8 * OC_STATE_FIELDS.n;
    for (unsigned int k = 0; k < OC_STATE_FIELDS.n; ++k)
        p = fmu_get_f64(p, (double *)(void *)((char *)&s + OC_STATE_FIELDS.field[k].offset));
    return s;
}

/* Cell c's committed state; d its displacement (for the initial slip at inputs). */
static oc_state source_cell(const cells_source *src, const cells_setup *g, const double d[2],
                            int c) {
    switch (src->kind) {
    case CELLS_FROM_ARRAY: return src->array[c];
    case CELLS_FROM_STEPS: return src->steps[c].next;
    case CELLS_FROM_BYTES: return cell_of_bytes(src->bytes, c);
    default:
        return g->initial_slip == PATCH_INITIAL_EXPLICIT
                   ? oc_state_unloaded(g->s_start[0], g->s_start[1], 0.0)
                   : oc_state_unloaded(d[0], d[1], 0.0);
    }
}

cells_source cells_initial(void) {
    const cells_source s = {CELLS_FROM_INITIAL, NULL, NULL, -1, NULL};
    return s;
}

cells_source cells_committed(const cells_grid *G) {
    cells_source s = {CELLS_FROM_ARRAY, G->from < 0 ? G->moved : G->start, NULL, -1, NULL};
    if (G->result_committed || G->from > 0) {
        s.kind = CELLS_FROM_STEPS;
        s.buffer = G->result_committed ? G->shown : G->from - 1;
        s.steps = G->steps[s.buffer];
    }
    return s;
}

const oc_state *cells_start_of(const cells_grid *G, int c) {
    return G->from > 0 ? &G->steps[G->from - 1][c].next : G->from < 0 ? &G->moved[c] : &G->start[c];
}

oc_state *cells_move_target(cells_grid *G) { return G->from < 0 ? G->start : G->moved; }

int cells_free_buffer(const cells_grid *G) {
    int b = 0;
    while (b == G->shown || b == G->from - 1) ++b;
    return b;
}

fmu_status cells_law(const oc_params *p, const cells_setup *g, oc_law *law, fmu_msg *msg) {
    const char *why = oc_params_check(p);
    if (why) return fmu_fail(msg, "%s", why);
    if (g->n[0] * g->n[1] > PATCH_MAX_CELLS)
        return fmu_fail(msg, "n1 x n2 = %d x %d cells: at most %d cells in all", g->n[0], g->n[1],
                        PATCH_MAX_CELLS);
    const double w = 1.0 / ((double)g->n[0] * (double)g->n[1]);
    oc_params cell = *p;
    cell.eps1 = p->eps1 * w;
    cell.eps2 = p->eps2 * w;
    if (oc_law_init(law, &cell) != 0)
        return fmu_fail(msg,
                        "parameters mu=(%g, %g) eps=(%g, %g) over %d x %d cells give "
                        "non-finite tensors",
                        p->mu1, p->mu2, p->eps1, p->eps2, g->n[0], g->n[1]);
    return FMU_OK;
}

/* ---- the step ----------------------------------------------------------- */

/* The running sums of the outputs, in the order c = i + n1 j. */
typedef struct {
    double T0, T1, Mz, energy;
    double nonfinite; /* 0 while every cell's next.a and next.s are finite, else NaN */
    int pressed, slipping;
} running_sums;

/* 0.0 - q rather than -q: an open cell reads +0.0, as the point FMU.  A
 * cell's q and energy enter the sums, which stay non-finite once one is;
 * whether it presses, the count of pressed cells.  What every step adds. */
static OC_ALWAYS_INLINE void add_force(running_sums *R, const oc_step *st, double Rr0, double Rr1) {
    const double t0 = 0.0 - st->q[0], t1 = 0.0 - st->q[1];
    R->T0 += t0;
    R->T1 += t1;
    R->Mz += Rr0 * t1 - Rr1 * t0;
    R->energy += st->next.energy;
    R->pressed += st->contact != OC_OPEN;
}

/* add_force, and the step's next.a and next.s into `nonfinite` as x * 0.0
 * (0 for a finite x, NaN otherwise). */
static OC_ALWAYS_INLINE void add_cell(running_sums *R, const oc_step *st, double Rr0, double Rr1) {
    add_force(R, st, Rr0, Rr1);
    R->nonfinite +=
        (st->next.a[0] * 0.0 + st->next.a[1] * 0.0) + (st->next.s[0] * 0.0 + st->next.s[1] * 0.0);
    R->slipping += st->contact == OC_SLIP;
}

/* add_cell for an open or stick step of oc_law_step_begin, whose next.a is
 * 0 or the trial, finite (its square passed as normal). */
static OC_ALWAYS_INLINE void add_begun(running_sums *R, const oc_step *st, double Rr0, double Rr1) {
    add_force(R, st, Rr0, Rr1);
    R->nonfinite += st->next.s[0] * 0.0 + st->next.s[1] * 0.0;
}

/* What oc_law_step_begin writes of a step (all of an open or stick step). */
static OC_ALWAYS_INLINE void put_begun(oc_step *to, const oc_step *from) {
    to->q[0] = from->q[0];
    to->q[1] = from->q[1];
    to->next = from->next;
    to->contact = from->contact;
}

/* cells_cell_of's products along one axis, each of one coordinate only,
 * formed once a row (i) or column (j): a cell is then their sums, in
 * cells_cell_of's order.  r the coordinate [m], cr (cos(theta) - 1) r, sr
 * sin(theta) r. */
typedef struct {
    double r[PATCH_MAX_SIDE], cr[PATCH_MAX_SIDE], sr[PATCH_MAX_SIDE];
} axis_products;

static OC_ALWAYS_INLINE void axis_products_of(int n, double side, double cm1, double sn,
                                              axis_products *A) {
    for (int i = 0; i < n; ++i) {
        A->r[i] = cells_coordinate(i, n) * side;
        A->cr[i] = cm1 * A->r[i];
        A->sr[i] = sn * A->r[i];
    }
}

/* Where cell c's committed state lies: base + c stride bytes, or (from
 * bytes or the initial slip: base NULL) a copy the step makes. */
typedef struct {
    const unsigned char *base;
    size_t stride;
} states_at;

static OC_ALWAYS_INLINE states_at states_of(const cells_source *src) {
    states_at at = {NULL, 0};
    if (src->kind == CELLS_FROM_STEPS) {
        at.base = (const unsigned char *)&src->steps[0].next;
        at.stride = sizeof(oc_step);
    } else if (src->kind == CELLS_FROM_ARRAY) {
        at.base = (const unsigned char *)src->array;
        at.stride = sizeof(oc_state);
    }
    return at;
}

/* What every cell of a step shares. */
typedef struct {
    const oc_law *law; /* the law, for oc_law_step_finish */
    const oc_law *lq;  /* its copy that no store to out[] can reach, for the begin */
    const cells_setup *g;
    const double *Nc;
    const cells_source *src;
    states_at at;
    const axis_products *a0, *a1;
    int n1;
    double u0, u1;
    oc_step *out;
} step_cells;

/* The cells first .. first + count - 1, the first at (*i, *j), which move
 * on with them: each begun (oc_law_step_begin), the open and stick ones
 * summed at once up to the first that is not, the rest summed in order
 * once those are finished together (oc_law_step_finish). */
static OC_ALWAYS_INLINE void step_batch(const step_cells *x, int first, int count, int *i, int *j,
                                        running_sums *R) {
    oc_state local[OC_BATCH_MAX];
    oc_unfinished pending[OC_BATCH_MAX];
    double Rr[OC_BATCH_MAX][2];      /* the moment arms of the cells summed after the finish */
    int n_pending = 0, wait = count; /* the cells from `wait` on are summed after the finish */
    for (int k = 0; k < count; ++k) {
        const int c = first + k;
        double d[2] = {x->u0, x->u1}, rr[2] = {x->a0->r[*i], x->a1->r[*j]};
        if (rr[0] != 0.0 || rr[1] != 0.0) { /* the centre cell sees u itself */
            const double dr0 = x->a0->cr[*i] - x->a1->sr[*j], dr1 = x->a0->sr[*i] + x->a1->cr[*j];
            d[0] += dr0;
            d[1] += dr1;
            rr[0] += dr0;
            rr[1] += dr1;
        }
        const oc_state *start;
        if (x->at.base) {
            start = (const oc_state *)(const void *)(x->at.base + (size_t)c * x->at.stride);
        } else {
            local[k] = source_cell(x->src, x->g, d, c);
            start = &local[k];
        }
        if (++*i == x->n1) *i = 0, ++*j;
        /* the step in a local first, which the compiler keeps in registers
         * for the sums: read back from out[c], just stored field by field,
         * loads would wait on the stores */
        oc_step st;
        oc_unfinished *r = &pending[n_pending];
        oc_step *out = &x->out[c];
        if (oc_law_step_begin(x->lq, start, d, x->Nc[c], &st, r->a)) {
            put_begun(out, &st);
            if (k < wait)
                add_begun(R, &st, rr[0], rr[1]);
            else
                Rr[k][0] = rr[0], Rr[k][1] = rr[1];
            continue;
        }
        out->next.u[0] = st.next.u[0];
        out->next.u[1] = st.next.u[1];
        out->next.N = st.next.N;
        r->start = start;
        r->out = out;
        ++n_pending;
        if (k < wait) wait = k;
        Rr[k][0] = rr[0];
        Rr[k][1] = rr[1];
    }
    if (n_pending == 0) return;
    oc_law_step_finish(x->law, pending, n_pending);
    for (int k = wait; k < count; ++k) add_cell(R, &x->out[first + k], Rr[k][0], Rr[k][1]);
}

/* The step's sums into S, and -1; or, if a number is not finite, the first
 * cell whose step is not (n if a sum), S untouched. */
static OC_ALWAYS_INLINE int sums_of(const running_sums *R, const oc_step out[], int n,
                                    cells_sums *S) {
    if (!(R->nonfinite == 0.0) || !isfinite(R->T0) || !isfinite(R->T1) || !isfinite(R->Mz) ||
        !isfinite(R->energy)) {
        for (int c = 0; c < n; ++c)
            if (!oc_step_is_finite(&out[c])) return c;
        return n;
    }
    S->T[0] = R->T0;
    S->T[1] = R->T1;
    S->Mz = R->Mz;
    S->energy = R->energy;
    S->slip_fraction = (double)R->slipping / (double)n;
    S->contact = R->pressed == 0 ? 0 : R->slipping == 0 ? 1 : R->slipping == R->pressed ? 3 : 2;
    return -1;
}

/* Each cell is the law's step on its own kinematics (cells_cell_of's) and
 * normal force Nc[c], summed in the order c = i + n1 j: the cells'
 * coordinates are formed once a step (n1 + n2 divisions, not two a cell
 * and an integer division: axis_products_of), a committed state is read
 * where it lies, not copied (states_of), and each cell's kinematics go
 * straight into the law's open and stick steps (oc_law_step_begin) and its
 * result into the sums; the cells those leave are finished OC_BATCH_MAX at
 * a time by oc_law_step_finish (the slipping ones' solves interleaved, each
 * the cell's own step bit for bit), and summed after (step_batch).
 * Whether every number is finite is read off the sums once a step; only a
 * step that fails looks for its first non-finite cell (sums_of).
 * tests/c/ContactPatch/test_patch_model.c holds the result to the plain
 * per-cell step, bit for bit. */
int cells_step(const oc_law *law, const cells_setup *g, const double Nc[], const cells_source *src,
               oc_step *out, cells_sums *S) {
    const int n1 = g->n[0], n2 = g->n[1], n = n1 * n2;
    const double h = sin(0.5 * g->theta);
    const double cm1 = -2.0 * h * h, sn = sin(g->theta);
    axis_products a0, a1;
    axis_products_of(n1, g->length, cm1, sn, &a0);
    axis_products_of(n2, g->width, cm1, sn, &a1);
    running_sums R = {0.0, 0.0, 0.0, 0.0, 0.0, 0, 0};
    const states_at at = states_of(src);
    if (n == 1) { /* nothing to batch: the law's own step on the centre cell, d = u */
        const double d[2] = {g->u[0], g->u[1]};
        const oc_state one =
            at.base ? *(const oc_state *)(const void *)at.base : source_cell(src, g, d, 0);
        oc_law_step(law, &one, d, Nc[0], &out[0]);
        add_cell(&R, &out[0], a0.r[0], a1.r[0]);
    } else {
        /* The law's tensors in a copy of its own that no store to out[] can
         * reach: the compiler keeps them in registers across the cells. */
        const oc_law lq = *law;
        const step_cells x = {law, &lq, g, Nc, src, at, &a0, &a1, n1, g->u[0], g->u[1], out};
        for (int first = 0, i = 0, j = 0; first < n; first += OC_BATCH_MAX)
            step_batch(&x, first, n - first < OC_BATCH_MAX ? n - first : OC_BATCH_MAX, &i, &j, &R);
    }
    return sums_of(&R, out, n, S);
}

/* The committed states a step starts from stay where they lie: the shown
 * step's start is then that buffer, not a copy of it. */
int cells_evaluate(cells_grid *G, const oc_law *law, const cells_setup *g, const double Nc[],
                   const cells_source *src, cells_sums *S) {
    const int into = cells_free_buffer(G);
    const int bad = cells_step(law, g, Nc, src, G->steps[into], S);
    if (bad >= 0) return bad;
    if (src->kind == CELLS_FROM_STEPS) {
        G->from = src->buffer + 1;
    } else if (src->kind == CELLS_FROM_ARRAY && src->array == G->moved) {
        G->from = -1; /* states moved (cells_move_target), where they lie */
    } else if (src->kind == CELLS_FROM_ARRAY && src->array == G->start) {
        G->from = 0;
    } else {
        for (int c = 0, n = cells_count(g); c < n; ++c) {
            const cells_cell x = cells_cell_of(g, c);
            G->start[c] = source_cell(src, g, x.d, c);
        }
        G->from = 0;
    }
    if (law != &G->law) G->law = *law;
    G->shown = into;
    G->result_committed = 0;
    return -1;
}

/* ---- derivatives -------------------------------------------------------- */

void cells_jacobian(const cells_grid *G, const cells_setup *g, cells_normal_tangent normal,
                    const void *model, double P[CELLS_JAC_ROWS][CELLS_JAC_COLS]) {
    memset(P, 0, sizeof(double) * CELLS_JAC_ROWS * CELLS_JAC_COLS);
    for (int c = 0, n = cells_count(g); c < n; ++c) {
        const cells_cell x = cells_cell_of(g, c);
        const oc_step *st = &G->steps[G->shown][c];
        double J[OC_JAC_ROWS][OC_JAC_COLS];
        oc_law_jacobian(&G->law, cells_start_of(G, c), x.d, st->next.N, st, J);
        /* d(d)/dx and dN_c/dx over x = (u1, u2, theta, load 1, load 2, load 3) */
        const double dd[2][CELLS_JAC_COLS] = {{1, 0, -x.Rr[1], 0, 0, 0}, {0, 1, x.Rr[0], 0, 0, 0}};
        double dN[4];
        normal(model, c, dN);
        const double dn[CELLS_JAC_COLS] = {0, 0, dN[0], dN[1], dN[2], dN[3]};
        const int law_row[3] = {0, 1, 4}; /* T1, T2, energy in the law's rows */
        double dy[3][CELLS_JAC_COLS];
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < CELLS_JAC_COLS; ++k)
                dy[r][k] = J[law_row[r]][0] * dd[0][k] + J[law_row[r]][1] * dd[1][k] +
                           J[law_row[r]][2] * dn[k];
        const double t0 = 0.0 - st->q[0], t1 = 0.0 - st->q[1];
        for (int k = 0; k < CELLS_JAC_COLS; ++k) {
            P[0][k] += dy[0][k];
            P[1][k] += dy[1][k];
            P[2][k] += x.Rr[0] * dy[1][k] - x.Rr[1] * dy[0][k];
            P[3][k] += dy[2][k];
        }
        P[2][2] -= x.Rr[0] * t0 + x.Rr[1] * t1;
    }
}

/* ---- FMI 3.0 arrays ----------------------------------------------------- */

void cells_array(const cells_grid *G, const cells_setup *g, int what, void *out) {
    const int n1 = g->n[0], n2 = g->n[1];
    const oc_step *steps = G->steps[G->shown];
    for (int i = 0; i < n1; ++i)
        for (int j = 0; j < n2; ++j) {
            const oc_step *st = &steps[i + n1 * j];
            const size_t k = (size_t)i * (size_t)n2 + (size_t)j;
            if (what == CELLS_ARRAY_STATE)
                ((int32_t *)out)[k] = (int32_t)st->contact;
            else if (what == CELLS_ARRAY_N)
                ((double *)out)[k] = st->contact == OC_OPEN ? 0.0 : st->next.N;
            else
                ((double *)out)[k] = 0.0 - st->q[what == CELLS_ARRAY_T1 ? 0 : 1];
        }
}

/* ---- serialized state --------------------------------------------------- */

size_t cells_state_size(void) { return (size_t)PATCH_MAX_CELLS * cell_bytes(); }

void cells_state_write(const cells_grid *G, const cells_setup *g, unsigned char *p) {
    const int n = cells_count(g);
    for (int c = 0; c < n; ++c) p = fmu_fields_write(&OC_STATE_FIELDS, cells_start_of(G, c), p);
    memset(p, 0, (size_t)(PATCH_MAX_CELLS - n) * cell_bytes());
}

fmu_status cells_state_check(const oc_law *law, const cells_setup *g, const unsigned char *p,
                             fmu_msg *msg) {
    const int n = cells_count(g);
    for (int c = 0; c < PATCH_MAX_CELLS; ++c) {
        const oc_state s = cell_of_bytes(p, c);
        if (c >= n) {
            if (!fmu_fields_zero(&OC_STATE_FIELDS, &s))
                return fmu_fail(msg, "serialized state: cell %d of a %d x %d grid holds a state",
                                c + 1, g->n[0], g->n[1]);
            continue;
        }
        const char *bad = oc_state_check(law, &s);
        if (bad) return fmu_fail(msg, "serialized state: cell %d: %s", c + 1, bad);
    }
    return FMU_OK;
}

fmu_status cells_restored_law(const cells_grid *G, const oc_params *was, const cells_setup *was_g,
                              const oc_params *params, const cells_setup *g, const unsigned char *p,
                              oc_law *law, fmu_msg *msg) {
    fmu_msg why;
    if (fmu_fields_same(&OC_PARAMS_FIELDS, was, params) && was_g->n[0] == g->n[0] &&
        was_g->n[1] == g->n[1])
        *law = G->law;
    else if (cells_law(params, g, law, &why) != FMU_OK)
        return fmu_fail(msg, "serialized state: %s", why.text);
    return cells_state_check(law, g, p, msg);
}

int cells_state_read(cells_grid *G, const oc_law *law, const cells_setup *g, const double Nc[],
                     const unsigned char *p, cells_sums *S) {
    const cells_source src = {CELLS_FROM_BYTES, NULL, NULL, -1, p};
    const int into = cells_free_buffer(G);
    const int bad = cells_step(law, g, Nc, &src, G->steps[into], S);
    if (bad >= 0) return bad;
    /* accepted: nothing below can fail */
    G->law = *law;
    for (int c = 0, n = cells_count(g); c < n; ++c) G->start[c] = cell_of_bytes(p, c);
    G->from = 0;
    G->shown = into;
    return -1;
}
