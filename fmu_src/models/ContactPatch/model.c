#include "models/ContactPatch/model.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "glue/fmu_bytes.h"
#include "glue/fmu_instance.h"

/* Where each variable of the table lives.  The law's parameters (the
 * table's L rows) live in params under their own names. */
#define LAW_ROW(name, vr, type, caus, var, init, start, lo, hi, unit, ...)                         \
    [vr] = {#name, FMU_T_##type, FMU_C_##caus, FMU_SET_##caus,                                     \
            start, lo,           hi,           offsetof(patch_model, params.name),                 \
            unit},
#define FMU_SLOT_time offsetof(patch_model, time)
#define FMU_SLOT_slidingRule offsetof(patch_model, params.rule)
#define FMU_SLOT_initialSlip offsetof(patch_model, g.initial_slip)
#define FMU_SLOT_s1Start offsetof(patch_model, g.s_start[0])
#define FMU_SLOT_s2Start offsetof(patch_model, g.s_start[1])
#define FMU_SLOT_length offsetof(patch_model, g.length)
#define FMU_SLOT_width offsetof(patch_model, g.width)
#define FMU_SLOT_n1 offsetof(patch_model, g.n[0])
#define FMU_SLOT_n2 offsetof(patch_model, g.n[1])
#define FMU_SLOT_u1 offsetof(patch_model, g.u[0])
#define FMU_SLOT_u2 offsetof(patch_model, g.u[1])
#define FMU_SLOT_theta offsetof(patch_model, g.theta)
#define FMU_SLOT_N offsetof(patch_model, g.N)
#define FMU_SLOT_p1 offsetof(patch_model, g.p[0])
#define FMU_SLOT_p2 offsetof(patch_model, g.p[1])
#define FMU_SLOT_T1 offsetof(patch_model, T[0])
#define FMU_SLOT_T2 offsetof(patch_model, T[1])
#define FMU_SLOT_Mz offsetof(patch_model, Mz)
#define FMU_SLOT_dissipatedEnergy offsetof(patch_model, energy)
#define FMU_SLOT_slipFraction offsetof(patch_model, slip_fraction)
#define FMU_SLOT_contactState offsetof(patch_model, contact)

enum { FMU_ENUM_TYPES(FMU_ENUM_KIND) PATCH_ENUM_KINDS_END };

static const fmu_var VARS[PATCH_VR_COUNT_PLUS_ONE] = {PATCH_VARIABLES(FMU_VAR_ROW, LAW_ROW)};

static fmu_status derivative(const patch_model *m, const unsigned int unknown[], size_t n_unknown,
                             const unsigned int known[], size_t n_known, const double seed[],
                             double out[], int adjoint, fmu_msg *msg);
static fmu_status exit_init(patch_model *m, fmu_msg *msg);

/* ---- FMI 3.0: the cells as arrays (models/ContactPatch/table.h's FMU_ARRAYS) --------- */

static size_t array_size(const patch_model *m, unsigned int vr, int *type) {
    switch (vr) {
    case PATCH_VR_cellT1:
    case PATCH_VR_cellT2: *type = FMU_T_Float64; break;
    case PATCH_VR_cellState: *type = FMU_T_Int32; break;
    default: return 0;
    }
    return (size_t)m->g.n[0] * (size_t)m->g.n[1];
}

/* Element [i][j] (row-major, shape (n1, n2)) is cell c = i + n1 j of the
 * shown step, its force as the sums take it (0.0 - q). */
static void array_get(const patch_model *m, unsigned int vr, void *out) {
    const int n1 = m->g.n[0], n2 = m->g.n[1];
    const oc_step *steps = m->steps[m->shown];
    for (int i = 0; i < n1; ++i)
        for (int j = 0; j < n2; ++j) {
            const oc_step *st = &steps[i + n1 * j];
            const size_t k = (size_t)i * (size_t)n2 + (size_t)j;
            if (vr == PATCH_VR_cellState)
                ((int32_t *)out)[k] = (int32_t)st->contact;
            else
                ((double *)out)[k] = 0.0 - st->q[vr == PATCH_VR_cellT1 ? 0 : 1];
        }
}

static const unsigned int STRUCTURAL[] = {PATCH_VR_n1, PATCH_VR_n2};
static const fmu_arrays ARRAYS = {array_size, array_get, STRUCTURAL, 2};

const fmu_model_info FMU_MODEL_INFO = {FMU_MODEL_IDENTIFIER,
                                       FMU_TOKEN,
                                       FMU_STATE_TAG,
                                       VARS,
                                       PATCH_VR_COUNT_PLUS_ONE,
                                       sizeof(patch_model),
                                       NULL /* the outputs live in their slots */,
                                       exit_init,
                                       derivative,
                                       &ARRAYS};

/* ---- the cells' kinematics and loads --------------------------------------- */

/* What every cell of a step shares. */
typedef struct {
    double cm1, sn; /* cos(theta) - 1 (as -2 sin^2(theta/2): exact for small theta), sin(theta) */
    double w;       /* a cell's share of the area, 1/(n1 n2) */
    double c[2];    /* the pressure's slope per unit xi (eta) and unit p1/length (p2/width) */
    double k[2];    /* c[0] p1/length, c[1] p2/width: the pressure's slopes per unit xi, eta */
} patch_frame;

/* The cells' normal forces N_c = N w (1 + p1 x/S1 + p2 y/S2), S1 = sum of
 * w x^2 over the cells = length^2 (1 - 1/n1^2)/12 (likewise S2): resultant N
 * and first moment N (p1, p2) on the grid exactly (the continuum's pressure
 * sampled at the centres, 12 p1 x/length^2, has N p1 (1 - 1/n1^2)).  Per unit
 * xi = x/length that is 12 n1^2/(n1^2 - 1) (p1/length) xi.  One cell along an
 * axis has S = 0 and carries no p along it (check_pressure refuses one), nor
 * does an open contact (N <= 0): there the slopes are 0 and every cell gets
 * N w <= 0, whatever p is. */
static double pressure_slope(int n, double N) {
    const double nn = (double)n * (double)n;
    return n > 1 && N > 0.0 ? 12.0 * nn / (nn - 1.0) : 0.0;
}

static patch_frame frame_of(const patch_setup *g) {
    const double h = sin(0.5 * g->theta);
    const double c0 = pressure_slope(g->n[0], g->N), c1 = pressure_slope(g->n[1], g->N);
    patch_frame f = {-2.0 * h * h,
                     sin(g->theta),
                     1.0 / ((double)g->n[0] * (double)g->n[1]),
                     {c0, c1},
                     {c0 * (g->p[0] / g->length), c1 * (g->p[1] / g->width)}};
    return f;
}

/* One cell: its centre in body coordinates r [m], relative coordinates
 * xi, eta in (-1/2, 1/2), the centre in the surface frame R r, its
 * displacement d [m] and its share nu of the normal force (N_c = N nu). */
typedef struct {
    double xi, eta, r[2], Rr[2], d[2], nu;
} patch_cell;

/* (2i + 1 - n) / (2n): mirror cells get exactly opposite coordinates */
static inline double cell_coordinate(int i, int n) {
    return (double)(2 * i + 1 - n) / (double)(2 * n);
}

/* The cell at relative coordinates xi, eta (cell_coordinate's). */
static inline patch_cell cell_at(const patch_setup *g, const patch_frame *f, double xi,
                                 double eta) {
    patch_cell x;
    x.xi = xi;
    x.eta = eta;
    x.r[0] = x.xi * g->length;
    x.r[1] = x.eta * g->width;
    /* (R - I) r; none added at the centre, so that a one-cell patch's cell
     * sees u itself, the sign of a zero included */
    x.d[0] = g->u[0];
    x.d[1] = g->u[1];
    x.Rr[0] = x.r[0];
    x.Rr[1] = x.r[1];
    if (x.r[0] != 0.0 || x.r[1] != 0.0) {
        const double dr0 = f->cm1 * x.r[0] - f->sn * x.r[1];
        const double dr1 = f->sn * x.r[0] + f->cm1 * x.r[1];
        x.d[0] += dr0;
        x.d[1] += dr1;
        x.Rr[0] += dr0;
        x.Rr[1] += dr1;
    }
    /* the grid's linear pressure (frame_of) */
    x.nu = f->w * (1.0 + f->k[0] * x.xi + f->k[1] * x.eta);
    return x;
}

static patch_cell cell_of(const patch_setup *g, const patch_frame *f, int c) {
    const int i = c % g->n[0], j = c / g->n[0];
    return cell_at(g, f, cell_coordinate(i, g->n[0]), cell_coordinate(j, g->n[1]));
}

static int n_cells(const patch_setup *g) { return g->n[0] * g->n[1]; }

/* Where each cell's committed state comes from. */
typedef enum { FROM_INITIAL, FROM_ARRAY, FROM_STEPS, FROM_BYTES } source_kind;
typedef struct {
    source_kind kind;
    const oc_state *array;      /* FROM_ARRAY: cell c's state is array[c] */
    const oc_step *steps;       /* FROM_STEPS: steps[c].next, */
    int buffer;                 /*   steps = the model's steps[buffer] */
    const unsigned char *bytes; /* FROM_BYTES: serialized, cell_bytes() a cell */
} cell_source;

/* A serialized cell: its committed state (law/law_fields.h), all f64. */
static size_t cell_bytes(void) { return fmu_fields_size(&OC_STATE_FIELDS); }

static oc_state cell_of_bytes(const unsigned char *bytes, int c) {
    oc_state s;
    const unsigned char *p = bytes + (size_t)c * 8 * OC_STATE_FIELDS.n;
    for (unsigned int k = 0; k < OC_STATE_FIELDS.n; ++k)
        p = fmu_get_f64(p, (double *)(void *)((char *)&s + OC_STATE_FIELDS.field[k].offset));
    return s;
}

/* Cell c's committed state; x its kinematics (for the initial slip at inputs). */
static oc_state source_cell(const cell_source *src, const patch_setup *g, const patch_cell *x,
                            int c) {
    switch (src->kind) {
    case FROM_ARRAY: return src->array[c];
    case FROM_STEPS: return src->steps[c].next;
    case FROM_BYTES: return cell_of_bytes(src->bytes, c);
    default:
        return g->initial_slip == PATCH_INITIAL_EXPLICIT
                   ? oc_state_unloaded(g->s_start[0], g->s_start[1], 0.0)
                   : oc_state_unloaded(x->d[0], x->d[1], 0.0);
    }
}

/* The sums the outputs are. */
typedef struct {
    double T[2], Mz, energy, slip_fraction;
    int contact;
} patch_sums;

/* The centre of pressure of a closed contact (N > 0; an open one has no
 * pressure, and p is not looked at): in the kern, where the linear pressure
 * of resultant N at (p1, p2) is >= 0 at every corner (and so every cell's
 * N_c, frame_of's, is > 0), with a few roundings of slack so that
 * p1 = length/6 typed as such is in; and 0 along an axis of one cell, whose
 * cells all lie on the other axis and cannot move the resultant off it. */
static fmu_status check_pressure(const patch_setup *g, fmu_msg *msg) {
    if (!(g->N > 0.0)) return FMU_OK;
    const double e = fabs(g->p[0]) / g->length + fabs(g->p[1]) / g->width;
    if (!(6.0 * e <= 1.0 + 8 * DBL_EPSILON))
        return fmu_fail(msg,
                        "centre of pressure p1=%g m, p2=%g m outside the kern of the %g m x %g m "
                        "patch: |p1|/length + |p2|/width = %g > 1/6, where a linear pressure "
                        "would pull at a corner (no-tension pressure is not modelled)",
                        g->p[0], g->p[1], g->length, g->width, e);
    for (int a = 0; a < 2; ++a)
        if (g->n[a] == 1 && g->p[a] != 0.0)
            return fmu_fail(msg,
                            "centre of pressure p%d=%g m off the axis of a grid with n%d = 1: "
                            "one cell along %s has its centre on that axis and cannot carry a "
                            "centre of pressure off it (set p%d = 0, or n%d >= 2)",
                            a + 1, g->p[a], a + 1, a ? "width" : "length", a + 1, a + 1);
    return FMU_OK;
}

/* Cell (i, j)'s message: its force or slip would not be finite. */
static fmu_status cell_overflow(const patch_setup *g, int c, fmu_msg *msg) {
    return fmu_fail(msg,
                    "inputs u1=%g m, u2=%g m, theta=%g rad, N=%g N overflow the force or "
                    "slip of cell (%d, %d)",
                    g->u[0], g->u[1], g->theta, g->N, c % g->n[0] + 1, c / g->n[0] + 1);
}

/* The running sums of the outputs, in the order c = i + n1 j. */
typedef struct {
    double T0, T1, Mz, energy;
    double nonfinite; /* 0 while every cell's next.a and next.s are finite, else NaN */
    int pressed, slipping;
} running_sums;

/* 0.0 - q rather than -q: an open cell reads +0.0, as the point FMU.  A
 * cell's q and energy enter the sums, which stay non-finite once one is;
 * its next.a and next.s enter `nonfinite` as x * 0.0 (0 for a finite x,
 * NaN otherwise). */
static OC_ALWAYS_INLINE void add_cell(running_sums *R, const oc_step *st, double Rr0, double Rr1) {
    const double t0 = 0.0 - st->q[0], t1 = 0.0 - st->q[1];
    R->T0 += t0;
    R->T1 += t1;
    R->Mz += Rr0 * t1 - Rr1 * t0;
    R->energy += st->next.energy;
    R->nonfinite +=
        (st->next.a[0] * 0.0 + st->next.a[1] * 0.0) + (st->next.s[0] * 0.0 + st->next.s[1] * 0.0);
    R->pressed += st->contact != OC_OPEN;
    R->slipping += st->contact == OC_SLIP;
}

/* add_cell for an open or stick step of oc_law_step_begin, whose next.a is
 * 0 or the trial, finite (its square passed as normal). */
static OC_ALWAYS_INLINE void add_begun(running_sums *R, const oc_step *st, double Rr0, double Rr1) {
    const double t0 = 0.0 - st->q[0], t1 = 0.0 - st->q[1];
    R->T0 += t0;
    R->T1 += t1;
    R->Mz += Rr0 * t1 - Rr1 * t0;
    R->energy += st->next.energy;
    R->nonfinite += st->next.s[0] * 0.0 + st->next.s[1] * 0.0;
    R->pressed += st->contact != OC_OPEN;
}

/* What oc_law_step_begin writes of a step (all of an open or stick step). */
static OC_ALWAYS_INLINE void put_begun(oc_step *to, const oc_step *from) {
    to->q[0] = from->q[0];
    to->q[1] = from->q[1];
    to->next = from->next;
    to->contact = from->contact;
}

/* Steps every cell with `law` from `src` into out[] and sums the outputs;
 * or fails, having written nothing but out[], if a cell's result or a sum
 * would not be finite (naming the first such cell, as a check cell by cell
 * in that order would).  Each cell is the law's step on its own kinematics
 * (cell_of's), summed in the order c = i + n1 j: the cells' coordinates are
 * formed once a step (n1 + n2 divisions, not two a cell and an integer
 * division), a committed state is read where it lies, not copied, and each
 * cell's kinematics go straight into the law's open and stick steps
 * (oc_law_step_begin) and its result into the sums; the cells those leave
 * are finished OC_BATCH_MAX at a time by oc_law_step_finish (the slipping
 * ones' solves interleaved, each the cell's own step bit for bit), and
 * summed after.  Whether every number is finite is read off the sums once
 * a step; only a step that fails looks for its first non-finite cell.
 * tests/c/ContactPatch/test_patch_model.c holds the result to the plain per-cell step,
 * bit for bit. */
static fmu_status step_cells(const oc_law *law, const patch_setup *g, const cell_source *src,
                             oc_step *out, patch_sums *S, fmu_msg *msg) {
    const patch_frame f = frame_of(g);
    const int n1 = g->n[0], n2 = g->n[1], n = n1 * n2;
    /* cell_at's products, each of one coordinate only, formed once a row
     * (i) or column (j): a cell is then its sums, in cell_at's order. */
    double r0[PATCH_MAX_SIDE], cr0[PATCH_MAX_SIDE], sr0[PATCH_MAX_SIDE], p0[PATCH_MAX_SIDE];
    double r1[PATCH_MAX_SIDE], cr1[PATCH_MAX_SIDE], sr1[PATCH_MAX_SIDE], p1[PATCH_MAX_SIDE];
    for (int i = 0; i < n1; ++i) {
        const double xi = cell_coordinate(i, n1);
        r0[i] = xi * g->length;
        cr0[i] = f.cm1 * r0[i];
        sr0[i] = f.sn * r0[i];
        p0[i] = 1.0 + f.k[0] * xi;
    }
    for (int j = 0; j < n2; ++j) {
        const double eta = cell_coordinate(j, n2);
        r1[j] = eta * g->width;
        cr1[j] = f.cm1 * r1[j];
        sr1[j] = f.sn * r1[j];
        p1[j] = f.k[1] * eta;
    }
    const double N = g->N, u0 = g->u[0], u1 = g->u[1], w = f.w;
    running_sums R = {0.0, 0.0, 0.0, 0.0, 0.0, 0, 0};
    /* Where cell c's committed state lies: base + c stride bytes, or (from
     * bytes or the initial slip) a copy in local[]. */
    const unsigned char *base = NULL;
    size_t stride = 0;
    if (src->kind == FROM_STEPS) {
        base = (const unsigned char *)&src->steps[0].next;
        stride = sizeof(oc_step);
    } else if (src->kind == FROM_ARRAY) {
        base = (const unsigned char *)src->array;
        stride = sizeof(oc_state);
    }
    if (n == 1) { /* nothing to batch: the law's own step on the centre cell, d = u */
        const double d[2] = {u0, u1}, Nc = N * (w * (p0[0] + p1[0]));
        oc_state one;
        patch_cell x;
        x.d[0] = u0;
        x.d[1] = u1;
        one = base ? *(const oc_state *)(const void *)base : source_cell(src, g, &x, 0);
        oc_law_step(law, &one, d, Nc, &out[0]);
        add_cell(&R, &out[0], r0[0], r1[0]);
    } else {
        oc_state local[OC_BATCH_MAX];
        oc_unfinished pending[OC_BATCH_MAX];
        /* The law's tensors in a copy of its own that no store to out[] can
         * reach: the compiler keeps them in registers across the cells. */
        const oc_law lq = *law;
        double Rr[OC_BATCH_MAX][2]; /* the moment arms of the cells summed after the finish */
        for (int first = 0, i = 0, j = 0; first < n; first += OC_BATCH_MAX) {
            const int count = n - first < OC_BATCH_MAX ? n - first : OC_BATCH_MAX;
            int n_pending = 0,
                wait = count; /* the cells from `wait` on are summed after the finish */
            for (int k = 0; k < count; ++k) {
                const int c = first + k;
                double d[2] = {u0, u1}, rr[2] = {r0[i], r1[j]};
                if (rr[0] != 0.0 || rr[1] != 0.0) { /* the centre cell sees u itself */
                    const double dr0 = cr0[i] - sr1[j], dr1 = sr0[i] + cr1[j];
                    d[0] += dr0;
                    d[1] += dr1;
                    rr[0] += dr0;
                    rr[1] += dr1;
                }
                /* the grid's linear pressure (frame_of) */
                const double Nc = N * (w * (p0[i] + p1[j]));
                const oc_state *start;
                if (base) {
                    start = (const oc_state *)(const void *)(base + (size_t)c * stride);
                } else {
                    patch_cell x;
                    x.d[0] = d[0];
                    x.d[1] = d[1];
                    local[k] = source_cell(src, g, &x, c);
                    start = &local[k];
                }
                if (++i == n1) i = 0, ++j;
                /* the step in a local first, which the compiler keeps in registers
                 * for the sums: read back from out[c], just stored field by field,
                 * loads would wait on the stores */
                oc_step st;
                oc_unfinished *r = &pending[n_pending];
                if (oc_law_step_begin(&lq, start, d, Nc, &st, r->a)) {
                    put_begun(&out[c], &st);
                    if (k < wait)
                        add_begun(&R, &st, rr[0], rr[1]);
                    else
                        Rr[k][0] = rr[0], Rr[k][1] = rr[1];
                    continue;
                }
                out[c].next.u[0] = st.next.u[0];
                out[c].next.u[1] = st.next.u[1];
                out[c].next.N = st.next.N;
                r->start = start;
                r->out = &out[c];
                ++n_pending;
                if (k < wait) wait = k;
                Rr[k][0] = rr[0];
                Rr[k][1] = rr[1];
            }
            if (n_pending == 0) continue;
            oc_law_step_finish(law, pending, n_pending);
            for (int k = wait; k < count; ++k) add_cell(&R, &out[first + k], Rr[k][0], Rr[k][1]);
        }
    }
    if (!(R.nonfinite == 0.0) || !isfinite(R.T0) || !isfinite(R.T1) || !isfinite(R.Mz) ||
        !isfinite(R.energy)) {
        for (int c = 0; c < n; ++c)
            if (!oc_step_is_finite(&out[c])) return cell_overflow(g, c, msg);
        return fmu_fail(msg,
                        "inputs u1=%g m, u2=%g m, theta=%g rad, N=%g N overflow the patch's "
                        "force, moment or energy",
                        g->u[0], g->u[1], g->theta, g->N);
    }
    S->T[0] = R.T0;
    S->T[1] = R.T1;
    S->Mz = R.Mz;
    S->energy = R.energy;
    S->slip_fraction = (double)R.slipping / (double)n;
    S->contact = R.pressed == 0 ? 0 : R.slipping == 0 ? 1 : R.slipping == R.pressed ? 3 : 2;
    return FMU_OK;
}

static void show(patch_model *m, const patch_sums *S) {
    m->T[0] = S->T[0];
    m->T[1] = S->T[1];
    m->Mz = S->Mz;
    m->energy = S->energy;
    m->slip_fraction = S->slip_fraction;
    m->contact = S->contact;
}

/* The steps buffer a new step is computed into: neither the shown step's
 * nor its start's. */
static int free_buffer(const patch_model *m) {
    int b = 0;
    while (b == m->shown || b == m->from - 1) ++b;
    return b;
}

/* Cell c's start of the shown step. */
static const oc_state *start_of(const patch_model *m, int c) {
    return m->from > 0 ? &m->steps[m->from - 1][c].next : &m->start[c];
}

/* Computes the pending step of every cell for the inputs in m from `src`
 * with `law` (which commits nothing); or fails and changes nothing (but the
 * free buffer, which nothing reads).  The committed states a step starts
 * from stay where they lie: the shown step's start is then that buffer, not
 * a copy of it. */
static fmu_status evaluate(patch_model *m, const oc_law *law, const cell_source *src,
                           fmu_msg *msg) {
    const int into = free_buffer(m);
    patch_sums S;
    if (step_cells(law, &m->g, src, m->steps[into], &S, msg) != FMU_OK) return FMU_ERR;
    if (src->kind == FROM_STEPS) {
        m->from = src->buffer + 1;
    } else if (!(src->kind == FROM_ARRAY && src->array == m->start)) {
        const int n = n_cells(&m->g);
        const patch_frame f = frame_of(&m->g);
        for (int c = 0; c < n; ++c) {
            const patch_cell x = cell_of(&m->g, &f, c);
            m->start[c] = source_cell(src, &m->g, &x, c);
        }
        m->from = 0;
    }
    if (law != &m->law) m->law = *law;
    m->shown = into;
    show(m, &S);
    m->result_committed = 0;
    return FMU_OK;
}

/* The committed states: the start before a commit, the shown step's after. */
static cell_source committed(const patch_model *m) {
    cell_source s = {FROM_ARRAY, m->start, NULL, -1, NULL};
    if (m->result_committed || m->from > 0) {
        s.kind = FROM_STEPS;
        s.buffer = m->result_committed ? m->shown : m->from - 1;
        s.steps = m->steps[s.buffer];
    }
    return s;
}

/* The cells' law: the patch's parameters with its stiffness shared by area. */
static fmu_status cell_law(const oc_params *p, const patch_setup *g, oc_law *law, fmu_msg *msg) {
    const char *why = oc_params_check(p);
    if (why) return fmu_fail(msg, "%s", why);
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

fmu_status fmu_model_update(patch_model *m, int changed, int allow, fmu_msg *msg) {
    if (check_pressure(&m->g, msg) != FMU_OK) return FMU_ERR;
    oc_law law;
    const oc_law *use = &m->law;
    if (changed & FMU_CHANGED_PARAMETERS) {
        if (cell_law(&m->params, &m->g, &law, msg) != FMU_OK) return FMU_ERR;
        use = &law;
    }
    /* Before the end of initialization the cells start where the inputs or
     * the explicit slip put them; afterwards from what was committed. */
    const cell_source init = {FROM_INITIAL, NULL, NULL, -1, NULL};
    const cell_source src = (allow & FMU_ALLOW_PARAMETERS) ? init : committed(m);
    return evaluate(m, use, &src, msg);
}

/* Every set in initialization already derived the start from the values it
 * left; deriving it once more here makes the end of initialization the
 * moment that counts, whatever was restored before it. */
static fmu_status exit_init(patch_model *m, fmu_msg *msg) {
    const cell_source init = {FROM_INITIAL, NULL, NULL, -1, NULL};
    return evaluate(m, &m->law, &init, msg);
}

/* A further step with held inputs steps every cell again from what the
 * last doStep committed. */
fmu_status fmu_model_do_step(patch_model *m, double h, fmu_msg *msg) {
    (void)h; /* rate-independent: the step size does not enter the law */
    if (m->result_committed) {
        const cell_source src = committed(m);
        if (evaluate(m, &m->law, &src, msg) != FMU_OK) return FMU_ERR;
    }
    m->result_committed = 1;
    return FMU_OK;
}

/* ---- directional derivatives ------------------------------------------------ */

/* Rows: T1, T2, Mz, dissipatedEnergy; columns: u1, u2, theta, N, p1, p2. */
enum { P_ROWS = 4, P_COLS = 6 };

static int jac_row(unsigned int vr) {
    switch (vr) {
    case PATCH_VR_T1: return 0;
    case PATCH_VR_T2: return 1;
    case PATCH_VR_Mz: return 2;
    case PATCH_VR_dissipatedEnergy: return 3;
    default: return -1;
    }
}

static int jac_col(unsigned int vr) {
    switch (vr) {
    case PATCH_VR_u1: return 0;
    case PATCH_VR_u2: return 1;
    case PATCH_VR_theta: return 2;
    case PATCH_VR_N: return 3;
    case PATCH_VR_p1: return 4;
    case PATCH_VR_p2: return 5;
    default: return -1;
    }
}

/* The patch's Jacobian of the shown step: each cell's consistent tangent
 * (oc_law_jacobian, with respect to its d and N_c) through the cell's
 * kinematics d = u + (R(theta) - I) r, N_c = N nu(p), and the moment arm
 * R r of Mz = sum (R r) x T_c, whose own turning adds -(R r) . T_c to
 * dMz/dtheta. */
static void patch_jacobian(const patch_model *m, double P[P_ROWS][P_COLS]) {
    const patch_setup *g = &m->g;
    const patch_frame f = frame_of(g);
    memset(P, 0, sizeof(double) * P_ROWS * P_COLS);
    for (int c = 0, n = n_cells(g); c < n; ++c) {
        const patch_cell x = cell_of(g, &f, c);
        const oc_step *st = &m->steps[m->shown][c];
        double J[OC_JAC_ROWS][OC_JAC_COLS];
        oc_law_jacobian(&m->law, start_of(m, c), x.d, g->N * x.nu, st, J);
        /* d(d)/dx and dN_c/dx over x = (u1, u2, theta, N, p1, p2) */
        const double dd[2][P_COLS] = {{1, 0, -x.Rr[1], 0, 0, 0}, {0, 1, x.Rr[0], 0, 0, 0}};
        const double dN[P_COLS] = {0,
                                   0,
                                   0,
                                   x.nu,
                                   g->N * f.w * f.c[0] * x.xi / g->length,
                                   g->N * f.w * f.c[1] * x.eta / g->width};
        const int law_row[3] = {0, 1, 4}; /* T1, T2, energy in the law's rows */
        double dy[3][P_COLS];
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < P_COLS; ++k)
                dy[r][k] = J[law_row[r]][0] * dd[0][k] + J[law_row[r]][1] * dd[1][k] +
                           J[law_row[r]][2] * dN[k];
        const double t0 = 0.0 - st->q[0], t1 = 0.0 - st->q[1];
        for (int k = 0; k < P_COLS; ++k) {
            P[0][k] += dy[0][k];
            P[1][k] += dy[1][k];
            P[2][k] += x.Rr[0] * dy[1][k] - x.Rr[1] * dy[0][k];
            P[3][k] += dy[2][k];
        }
        P[2][2] -= x.Rr[0] * t0 + x.Rr[1] * t1;
    }
}

static void partials(const patch_model *m, double *J) { patch_jacobian(m, (double(*)[P_COLS])J); }

/* J fits the glue's buffer (a negative size fails to compile) */
typedef char jacobian_fits[P_ROWS * P_COLS <= FMU_JACOBIAN_MAX ? 1 : -1];
static const fmu_jacobian JACOBIAN = {
    P_ROWS,  P_COLS, jac_row, jac_col, "T1, T2, Mz, dissipatedEnergy", "u1, u2, theta, N, p1, p2",
    partials};

static fmu_status derivative(const patch_model *m, const unsigned int unknown[], size_t n_unknown,
                             const unsigned int known[], size_t n_known, const double seed[],
                             double out[], int adjoint, fmu_msg *msg) {
    return fmu_jacobian_derivative(&JACOBIAN, m, unknown, n_unknown, known, n_known, seed, out,
                                   adjoint, msg);
}

/* ---- serialized state: the field list of model.h ------------------------ */

size_t fmu_model_state_size(void) { return fmu_fields_size(&FMU_STATE_FIELDS); }

void fmu_model_state_write(const patch_model *m, unsigned char *p) {
    p = fmu_fields_write(&PATCH_HEAD_FIELDS, m, p);
    const int n = n_cells(&m->g);
    for (int c = 0; c < n; ++c) p = fmu_fields_write(&OC_STATE_FIELDS, start_of(m, c), p);
    memset(p, 0, (size_t)(PATCH_MAX_CELLS - n) * cell_bytes());
}

/* What the serialized head reads into m, kept to be put back. */
typedef struct {
    oc_params params;
    patch_setup g;
    int result_committed;
} patch_head;

/* fmu_model_state_read once the head is in m: the cells checked where they
 * lie in the buffer, then the shown result recomputed (into the free
 * buffer, which nothing reads) from the committed states and the inputs,
 * of which it is a function.  `was` holds the head before. */
static fmu_status read_cells(patch_model *m, const patch_head *was, const unsigned char *cells,
                             fmu_msg *msg) {
    if (check_pressure(&m->g, msg) != FMU_OK) return FMU_ERR;
    /* A master that saves and restores every step restores the parameters
     * it already has: keep their tensors instead of recomputing them.  Bit
     * patterns, not ==: -0.0 and +0.0 give tensors that differ in the sign
     * of zero entries, and a restored state must continue bit for bit. */
    oc_law law;
    fmu_msg why;
    if (fmu_fields_same(&OC_PARAMS_FIELDS, &was->params, &m->params) && was->g.n[0] == m->g.n[0] &&
        was->g.n[1] == m->g.n[1])
        law = m->law;
    else if (cell_law(&m->params, &m->g, &law, &why) != FMU_OK)
        return fmu_fail(msg, "serialized state: %s", why.text);
    const int n = n_cells(&m->g);
    for (int c = 0; c < PATCH_MAX_CELLS; ++c) {
        const oc_state s = cell_of_bytes(cells, c);
        if (c >= n) {
            if (!fmu_fields_zero(&OC_STATE_FIELDS, &s))
                return fmu_fail(msg, "serialized state: cell %d of a %d x %d patch holds a state",
                                c + 1, m->g.n[0], m->g.n[1]);
            continue;
        }
        const char *bad = oc_state_check(&law, &s);
        if (bad) return fmu_fail(msg, "serialized state: cell %d: %s", c + 1, bad);
    }
    const cell_source src = {FROM_BYTES, NULL, NULL, -1, cells};
    const int into = free_buffer(m);
    patch_sums S;
    if (step_cells(&law, &m->g, &src, m->steps[into], &S, &why) != FMU_OK)
        return fmu_fail(msg, "serialized state: %s", why.text);
    /* accepted: nothing below can fail */
    m->law = law;
    for (int c = 0; c < n; ++c) m->start[c] = cell_of_bytes(cells, c);
    m->from = 0;
    m->shown = into;
    show(m, &S);
    return FMU_OK;
}

/* Reads the head into m, checked field by field, and the cells; a refused
 * state puts the head back and changes nothing else. */
fmu_status fmu_model_state_read(patch_model *m, const unsigned char *p, fmu_msg *msg) {
    const patch_head head = {m->params, m->g, m->result_committed};
    fmu_status st = fmu_fields_read(&PATCH_HEAD_FIELDS, m, &p, msg);
    if (st == FMU_OK) st = read_cells(m, &head, p, msg);
    if (st != FMU_OK) {
        m->params = head.params;
        m->g = head.g;
        m->result_committed = head.result_committed;
    }
    return st;
}
