/* The rolling pad's transport (cells/transport.c) on hand-made states:
 *   - a whole shift moves every state exactly (bit for bit), each cell
 *     keeping its own committed displacement and dissipated energy, the
 *     material beyond the leading edge the mirror image of the cells inside
 *     it, negated (the edge's unloaded material), and rolling backwards
 *     (a negative shift) the same from the other edge;
 *   - a fractional shift weights the two columns it falls between linearly,
 *     and a field linear in x (steady stick) stays linear, its value on the
 *     leading edge 0, whatever the shift;
 *   - an open cell's material is unloaded; a weighted state stays inside the
 *     yield surface; a shift beyond the grid leaves every cell unloaded. */
#include <math.h>

#include "cells/transport.h"
#include "check.h"

enum { N1 = 6, N2 = 2 };

/* A loaded state of column i, row j: u, elastic displacement e = u - s,
 * force a = 0.5 e (as if the law's P were 0.5), N, energy. */
static oc_state state_of(int i, int j) {
    const double e[2] = {1e-3 * (i + 1) + 1e-4 * j, -2e-4 * (i + 1)};
    oc_state s = {
        {0.01 * i + 0.5, 0.02 * j - 0.3}, 10.0 + i, {0.5 * e[0], 0.5 * e[1]}, {0, 0}, 0.25 * i + j};
    s.s[0] = s.u[0] - e[0];
    s.s[1] = s.u[1] - e[1];
    return s;
}

static cells_setup grid(void) {
    const cells_setup g = {0.1, 0.05, {N1, N2}, 1, {0, 0}, {0, 0}, 0};
    return g;
}

static oc_state in[N1 * N2], out[N1 * N2];

static void fill(void) {
    for (int j = 0; j < N2; ++j)
        for (int i = 0; i < N1; ++i) in[i + N1 * j] = state_of(i, j);
}

static cells_source source(void) {
    const cells_source s = {CELLS_FROM_ARRAY, in, NULL, -1, NULL};
    return s;
}

/* out[c] has the elastic state sign * in[from] with its own u and energy. */
static void check_moved(int c, int from, double sign) {
    const oc_state *o = &out[c], *f = &in[from], *own = &in[c];
    CHECK(o->u[0] == own->u[0] && o->u[1] == own->u[1] && o->energy == own->energy,
          "cell %d keeps its u and energy", c);
    CHECK(o->N == f->N && o->a[0] == sign * f->a[0] && o->a[1] == sign * f->a[1],
          "cell %d takes the force of %d (sign %g)", c, from, sign);
    CHECK_CLOSE(o->u[0] - o->s[0], sign * (f->u[0] - f->s[0]), 1e-18, "elastic displacement 1");
    CHECK_CLOSE(o->u[1] - o->s[1], sign * (f->u[1] - f->s[1]), 1e-18, "elastic displacement 2");
}

static void whole_shifts_move_the_states_exactly(void) {
    const cells_setup g = grid();
    const cells_source src = source();
    fill();
    for (int k = -2; k <= 2; ++k) {
        cells_transport(&g, (double)k, &src, out);
        for (int j = 0; j < N2; ++j)
            for (int i = 0; i < N1; ++i) {
                const int m = i + k; /* the column the material comes from */
                if (m >= N1)
                    check_moved(i + N1 * j, 2 * N1 - 1 - m + N1 * j, -1.0);
                else if (m < 0)
                    check_moved(i + N1 * j, -1 - m + N1 * j, -1.0);
                else
                    check_moved(i + N1 * j, m + N1 * j, 1.0);
            }
    }
}

static void fractional_shifts_interpolate_linearly(void) {
    const cells_setup g = grid();
    const cells_source src = source();
    fill();
    const double f = 0.3;
    cells_transport(&g, 1.0 + f, &src, out);
    /* column 2 takes 0.7 of column 3 and 0.3 of column 4 */
    const oc_state *a = &in[3], *b = &in[4];
    CHECK_CLOSE(out[2].N, (1 - f) * a->N + f * b->N, 1e-14, "N");
    CHECK_CLOSE(out[2].a[0], (1 - f) * a->a[0] + f * b->a[0], 1e-18, "a1");
    /* a field linear in x, 0 on the edge where the material enters (its
     * steady stick): moved by any shift, still that field, the material
     * from beyond the edge its continuation (the ghost's mirror image) */
    for (double shift = -2.0; shift <= 2.0; shift += 0.25) {
        const double edge = shift > 0 ? N1 - 0.5 : -0.5; /* in columns */
        for (int i = 0; i < N1; ++i) {
            const double e = 1e-3 * (shift > 0 ? edge - i : i - edge);
            in[i] = state_of(i, 0);
            in[i].a[0] = 0.5 * e;
            in[i].a[1] = 0.0;
            in[i].s[0] = in[i].u[0] - e;
            in[i].s[1] = in[i].u[1];
        }
        cells_transport(&g, shift, &src, out);
        for (int i = 0; i < N1; ++i) {
            const double x = i + shift, e = 1e-3 * (shift > 0 ? edge - x : x - edge);
            CHECK_CLOSE(out[i].u[0] - out[i].s[0], e, 1e-15, "the linear field moved");
            CHECK_CLOSE(out[i].a[0], 0.5 * e, 1e-15, "its force");
        }
    }
}

static void unloaded_material_and_the_yield_surface(void) {
    const cells_setup g = grid();
    const cells_source src = source();
    fill();
    in[4].N = 0.0; /* open: no force, its slip where the body is */
    in[4].a[0] = in[4].a[1] = 0.0;
    in[4].s[0] = in[4].u[0];
    in[4].s[1] = in[4].u[1];
    cells_transport(&g, 1.0, &src, out);
    CHECK(out[3].N == 0.0 && out[3].a[0] == 0.0 && out[3].s[0] == out[3].u[0] &&
              out[3].s[1] == out[3].u[1],
          "the open material arrives open");
    cells_transport(&g, 0.5, &src, out);
    for (int c = 0; c < N1 * N2; ++c)
        CHECK(hypot(out[c].a[0], out[c].a[1]) <= out[c].N || out[c].N == 0.0,
              "cell %d inside the yield surface", c);
    const double far[3] = {2.0 * N1, 1e300, -1e300};
    for (int k = 0; k < 3; ++k) {
        cells_transport(&g, far[k], &src, out);
        for (int c = 0; c < N1 * N2; ++c)
            CHECK(out[c].N == 0.0 && out[c].s[0] == out[c].u[0] && out[c].energy == in[c].energy,
                  "shift %g: cell %d unloaded", far[k], c);
    }
}

int main(void) {
    whole_shifts_move_the_states_exactly();
    fractional_shifts_interpolate_linearly();
    unloaded_material_and_the_yield_surface();
    return oc_report();
}
