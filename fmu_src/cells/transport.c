#include "cells/transport.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "compiler.h"
#include "law/contact_law.h"

/* Where the committed states lie: base + c stride bytes. */
typedef struct {
    const unsigned char *base;
    size_t stride;
} moved_from;

static OC_ALWAYS_INLINE const oc_state *moved_state(moved_from at, int c) {
    return (const oc_state *)(const void *)(at.base + (size_t)c * at.stride);
}

/* Two neighbouring numbers of a state at once: a vector of two doubles
 * where the compiler has them (OC_VECTORS: compiler.h), else a struct;
 * each operation lane by lane, so that each number is the scalar
 * arithmetic's bit for bit.  A state's pairs: (u1,
 * u2), (N, a1), (a2, s1), (s2, energy), and (s1, s2) across them. */
typedef char state_in_pairs[offsetof(oc_state, N) == 16 && offsetof(oc_state, a) == 24 &&
                                    offsetof(oc_state, s) == 40 && offsetof(oc_state, energy) == 56
                                ? 1
                                : -1];
#if OC_VECTORS
typedef double pair __attribute__((vector_size(16)));
typedef long long pair_mask __attribute__((vector_size(16)));
#define pair_get(x, l) ((x)[l])
static OC_ALWAYS_INLINE pair pair_make(double a, double b) {
    const pair r = {a, b};
    return r;
}
static OC_ALWAYS_INLINE pair pair_add(pair a, pair b) { return a + b; }
static OC_ALWAYS_INLINE pair pair_sub(pair a, pair b) { return a - b; }
static OC_ALWAYS_INLINE pair pair_mul(pair a, pair b) { return a * b; }
/* (x1 > 0 ? x1 : 0, x2) */
static OC_ALWAYS_INLINE pair pair_clip_first(pair x) {
    const pair zero = {0.0, 0.0};
    const pair_mask second = {0, -1};
    return (pair)((pair_mask)x & ((pair_mask)(x > zero) | second));
}
#else
typedef struct {
    double v[2];
} pair;
#define pair_get(x, l) ((x).v[l])
static OC_ALWAYS_INLINE pair pair_make(double a, double b) {
    const pair r = {{a, b}};
    return r;
}
static OC_ALWAYS_INLINE pair pair_add(pair a, pair b) {
    return pair_make(a.v[0] + b.v[0], a.v[1] + b.v[1]);
}
static OC_ALWAYS_INLINE pair pair_sub(pair a, pair b) {
    return pair_make(a.v[0] - b.v[0], a.v[1] - b.v[1]);
}
static OC_ALWAYS_INLINE pair pair_mul(pair a, pair b) {
    return pair_make(a.v[0] * b.v[0], a.v[1] * b.v[1]);
}
static OC_ALWAYS_INLINE pair pair_clip_first(pair x) {
    return pair_make(x.v[0] > 0 ? x.v[0] : 0.0, x.v[1]);
}
#endif

/* The pair at byte `offset` of state s; one stored there. */
static OC_ALWAYS_INLINE pair pair_at(const oc_state *s, size_t offset) {
    pair v;
    memcpy(&v, (const unsigned char *)s + offset, sizeof v);
    return v;
}
static OC_ALWAYS_INLINE void pair_put(oc_state *s, size_t offset, pair v) {
    memcpy((unsigned char *)s + offset, &v, sizeof v);
}

/* What a cell takes, in pairs: (N, a1) (normal force, yield coordinate
 * 1), e = u - s (elastic displacement), and a2. */
typedef struct {
    pair na, e;
    double a2;
} cells_material;

/* The material of state s: N clipped at 0 (an open state may hold the
 * N <= 0 it opened at, and carries no force or elastic displacement). */
static OC_ALWAYS_INLINE cells_material material_of(const oc_state *s) {
    const cells_material m = {
        pair_clip_first(pair_at(s, offsetof(oc_state, N))),
        pair_sub(pair_at(s, offsetof(oc_state, u)), pair_at(s, offsetof(oc_state, s))), s->a[1]};
    return m;
}

/* Material m times the signs: of (N, a1), of e and of a2 (1, -1 or 0: exact). */
typedef struct {
    pair na, e;
    double a2;
} material_signs;

static OC_ALWAYS_INLINE cells_material signed_material(cells_material m, const material_signs *s) {
    m.na = pair_mul(m.na, s->na);
    m.e = pair_mul(m.e, s->e);
    m.a2 *= s->a2;
    return m;
}

/* The ghost of material m: its force and elastic displacement negated. */
static OC_ALWAYS_INLINE cells_material ghost_of(cells_material m) {
    const material_signs ghost = {pair_make(1.0, -1.0), pair_make(-1.0, -1.0), -1.0};
    return signed_material(m, &ghost);
}

/* Cell o takes w0 of m0 and f of m1 (W and F: w0 and f in both lanes),
 * keeping its own u and energy.  Material with N = 0 is open without a
 * test: both its parts are open or weighted 0, so its force and elastic
 * displacement are zeros (of either sign) and its slip exactly u. */
static OC_ALWAYS_INLINE void take(oc_state *o, const oc_state *own, const cells_material *m0,
                                  const cells_material *m1, pair W, pair F) {
    const pair u = pair_at(own, offsetof(oc_state, u));
    const pair s = pair_sub(u, pair_add(pair_mul(W, m0->e), pair_mul(F, m1->e)));
    const double a2 = pair_get(W, 0) * m0->a2 + pair_get(F, 0) * m1->a2;
    pair_put(o, offsetof(oc_state, u), u);
    pair_put(o, offsetof(oc_state, N), pair_add(pair_mul(W, m0->na), pair_mul(F, m1->na)));
    pair_put(o, offsetof(oc_state, a[1]), pair_make(a2, pair_get(s, 0)));
    pair_put(o, offsetof(oc_state, s[1]), pair_make(pair_get(s, 1), own->energy));
}

/* A shift of less than a cell (k = 0: toward -x; k = -1: toward +x), as a
 * step moves at a Courant number below 1: each row's cells in order, each
 * source's material formed once (a cell's second source is the next one's
 * first), the one ghost that of the entering edge's cell. */
static void move_rows_by_less_than_a_cell(oc_state *out, moved_from at, int n1, int n2, int k,
                                          pair W, pair F) {
    for (int row = 0; row < n1 * n2; row += n1) {
        oc_state *o = out + row;
        cells_material m0 = material_of(moved_state(at, row));
        int i = 0;
        if (k < 0) { /* cell 0 takes w0 of the ghost of column 0, f of column 0 */
            const cells_material ghost = ghost_of(m0);
            take(&o[0], moved_state(at, row), &ghost, &m0, W, F);
            i = 1;
        }
        for (; i < n1 - 1 - k; ++i) {
            const cells_material m1 = material_of(moved_state(at, row + i + k + 1));
            take(&o[i], moved_state(at, row + i), &m0, &m1, W, F);
            m0 = m1;
        }
        if (k == 0) { /* cell n1 - 1 takes w0 of itself, f of its ghost */
            const cells_material ghost = ghost_of(m0);
            take(&o[n1 - 1], moved_state(at, row + n1 - 1), &m0, &ghost, W, F);
        }
    }
}

/* Where the material of column m comes from: column `column` of the same
 * row, times `signs`: beyond the grid the ghost (the mirror image),
 * beyond the mirror's reach none (unloaded: 0). */
typedef struct {
    int column;
    material_signs signs;
} column_source;

static column_source column_source_of(int n1, int m) {
    const int mirror = m >= n1 ? 2 * n1 - 1 - m : -1 - m;
    const double sign = m >= 0 && m < n1 ? 1.0 : mirror >= 0 && mirror < n1 ? -1.0 : 0.0;
    const column_source c = {
        m >= 0 && m < n1 ? m
        : sign != 0.0    ? mirror
                         : 0,
        {pair_make(sign != 0.0 ? 1.0 : 0.0, sign), pair_make(sign, sign), sign}};
    return c;
}

/* Any shift of k + f columns: cell i takes w0 of the material at column
 * i + k and f of the next, each column's source found once, and each
 * source's material formed once a row. */
static void move_columns(oc_state *out, moved_from at, int n1, int n2, int k, pair W, pair F) {
    column_source from[PATCH_MAX_SIDE + 1]; /* n1 <= PATCH_MAX_SIDE: the table's range */
    for (int i = 0; i <= n1; ++i) from[i] = column_source_of(n1, i + k);
    for (int row = 0; row < n1 * n2; row += n1) {
        cells_material m0 =
            signed_material(material_of(moved_state(at, row + from[0].column)), &from[0].signs);
        for (int i = 0; i < n1; ++i) {
            const cells_material m1 = signed_material(
                material_of(moved_state(at, row + from[i + 1].column)), &from[i + 1].signs);
            take(&out[row + i], moved_state(at, row + i), &m0, &m1, W, F);
            m0 = m1;
        }
    }
}

/* floor(x) for |x| < 2^53 without a call (x86-64's baseline has no
 * instruction for it): a shift is bounded by 3 n1 first. */
static double floor_of(double x) {
    const double t = (double)(long long)x; /* toward zero */
    return t > x ? t - 1.0 : t;
}

void cells_transport(const cells_setup *g, double shift, const cells_source *src, oc_state out[]) {
    const int n1 = g->n[0], n2 = g->n[1];
    /* beyond 2 n1 columns every source is unloaded: the shift bounded */
    const double bound = 3.0 * n1;
    shift = shift < -bound ? -bound : shift > bound ? bound : shift;
    /* a shift within rounding of a whole number of cells is that number: exact */
    const double below = floor_of(shift), whole = shift - below > 0.5 ? below + 1.0 : below;
    if (fabs(shift - whole) <= 8.0 * DBL_EPSILON * fabs(shift)) shift = whole;
    const double k_floor = floor_of(shift);
    const double f = shift - k_floor; /* in [0, 1] */
    const pair W = pair_make(1.0 - f, 1.0 - f), F = pair_make(f, f);
    const int k = (int)k_floor;
    moved_from at = {(const unsigned char *)src->array, sizeof(oc_state)};
    if (src->kind == CELLS_FROM_STEPS) {
        at.base = (const unsigned char *)&src->steps[0].next;
        at.stride = sizeof(oc_step);
    }
    if (k == 0 || k == -1)
        move_rows_by_less_than_a_cell(out, at, n1, n2, k, W, F);
    else
        move_columns(out, at, n1, n2, k, W, F);
}
