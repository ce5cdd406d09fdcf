#include "cells/transport.h"

#include <float.h>
#include <math.h>

/* Where the committed states lie: base + c stride bytes. */
typedef struct {
    const unsigned char *base;
    size_t stride;
} moved_from;

static const oc_state *moved_state(moved_from at, int c) {
    return (const oc_state *)(const void *)(at.base + (size_t)c * at.stride);
}

/* What a cell takes: normal force, yield coordinates, elastic displacement u - s. */
typedef struct {
    double N, a[2], e[2];
} cells_material;

/* The material of state s: N clipped at 0 (an open state may hold the
 * N <= 0 it opened at, and carries no force or elastic displacement). */
static OC_ALWAYS_INLINE cells_material material_of(const oc_state *s) {
    const cells_material t = {
        s->N > 0 ? s->N : 0.0, {s->a[0], s->a[1]}, {s->u[0] - s->s[0], s->u[1] - s->s[1]}};
    return t;
}

/* The material of column m of the row starting at cell `row`: beyond the
 * grid the ghost (the mirror image, its force and elastic displacement
 * negated), beyond the mirror's reach none (unloaded). */
static OC_ALWAYS_INLINE cells_material column_material(moved_from at, int row, int n1, int m) {
    if (m >= 0 && m < n1) return material_of(moved_state(at, row + m));
    const int mirror = m >= n1 ? 2 * n1 - 1 - m : -1 - m;
    cells_material t = {0.0, {0.0, 0.0}, {0.0, 0.0}};
    if (mirror < 0 || mirror >= n1) return t;
    t = material_of(moved_state(at, row + mirror));
    t.a[0] = -t.a[0];
    t.a[1] = -t.a[1];
    t.e[0] = -t.e[0];
    t.e[1] = -t.e[1];
    return t;
}

/* Cell o takes w0 of m0 and f of m1, keeping its own u and energy.
 * Material with N = 0 is open without a test: both its parts are open or
 * weighted 0, so its force and elastic displacement are zeros (of either
 * sign) and its slip exactly u. */
static OC_ALWAYS_INLINE void take(oc_state *o, const oc_state *own, const cells_material *m0,
                                  const cells_material *m1, double w0, double f) {
    o->u[0] = own->u[0];
    o->u[1] = own->u[1];
    o->energy = own->energy;
    o->N = w0 * m0->N + f * m1->N;
    o->a[0] = w0 * m0->a[0] + f * m1->a[0];
    o->a[1] = w0 * m0->a[1] + f * m1->a[1];
    o->s[0] = own->u[0] - (w0 * m0->e[0] + f * m1->e[0]);
    o->s[1] = own->u[1] - (w0 * m0->e[1] + f * m1->e[1]);
}

/* Cells lo .. hi of a row (out and in at its first cell), each taking
 * w0 of the state k columns on and f of the next, both inside the grid: the
 * bulk of the cells, without a test, each source's material formed once
 * (a cell's second source is the next one's first). */
static void move_inside_cells(oc_state *restrict out, const unsigned char *restrict in,
                              size_t stride, int lo, int hi, int k, double w0, double f) {
    cells_material m0 =
        material_of((const oc_state *)(const void *)(in + (size_t)(lo + k) * stride));
    for (int i = lo; i <= hi; ++i) {
        const oc_state *own = (const oc_state *)(const void *)(in + (size_t)i * stride);
        const cells_material m1 =
            material_of((const oc_state *)(const void *)(in + (size_t)(i + k + 1) * stride));
        take(&out[i], own, &m0, &m1, w0, f);
        m0 = m1;
    }
}

/* Cell i of a row whose sources are not both inside: ghosts, unloaded
 * material. */
static OC_ALWAYS_INLINE void move_edge_cell(oc_state *out, moved_from at, int row, int n1, int i,
                                            int k, double w0, double f) {
    const cells_material m0 = column_material(at, row, n1, i + k);
    const cells_material m1 = column_material(at, row, n1, i + k + 1);
    take(&out[row + i], moved_state(at, row + i), &m0, &m1, w0, f);
}

void cells_transport(const cells_setup *g, double shift, const cells_source *src, oc_state out[]) {
    const int n1 = g->n[0], n2 = g->n[1];
    /* a shift within rounding of a whole number of cells is that number: exact */
    const double whole = nearbyint(shift);
    if (fabs(shift - whole) <= 8.0 * DBL_EPSILON * fabs(shift)) shift = whole;
    /* beyond 2 n1 columns every source is unloaded: the shift's whole part bounded */
    const double k_floor = fmax(-3.0 * n1, fmin(3.0 * n1, floor(shift)));
    const double f = fmin(1.0, fmax(0.0, shift - k_floor)), w0 = 1.0 - f;
    const int k = (int)k_floor;
    moved_from at = {(const unsigned char *)src->array, sizeof(oc_state)};
    if (src->kind == CELLS_FROM_STEPS) {
        at.base = (const unsigned char *)&src->steps[0].next;
        at.stride = sizeof(oc_step);
    }
    /* the columns whose two sources lie inside the grid */
    const int lo = k < 0 ? -k : 0, hi = n1 - 2 - k < n1 - 1 ? n1 - 2 - k : n1 - 1;
    for (int j = 0; j < n2; ++j) {
        const int row = n1 * j;
        for (int i = 0; i < n1 && i < lo; ++i) move_edge_cell(out, at, row, n1, i, k, w0, f);
        if (lo <= hi)
            move_inside_cells(out + row, at.base + (size_t)row * at.stride, at.stride, lo, hi, k,
                              w0, f);
        for (int i = hi + 1 > lo ? hi + 1 : lo; i < n1; ++i)
            move_edge_cell(out, at, row, n1, i, k, w0, f);
    }
}
