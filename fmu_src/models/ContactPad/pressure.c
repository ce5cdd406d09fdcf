#include "models/ContactPad/pressure.h"

#include <math.h>

/* A polygon's moments about its origin, exact for any simple polygon of
 * counterclockwise vertices (x, y): each edge's cross product c_k = x_k
 * y_k+1 - x_k+1 y_k weighs the integrals of 1, x, y, x^2, xy, y^2 over the
 * triangle it spans with the origin. */
static void polygon_moments(const double x[], const double y[], int n, pad_moments *out) {
    double a = 0, mx = 0, my = 0, xx = 0, xy = 0, yy = 0;
    for (int k = 0; k < n; ++k) {
        const int l = k + 1 == n ? 0 : k + 1;
        const double c = x[k] * y[l] - x[l] * y[k];
        a += c;
        mx += (x[k] + x[l]) * c;
        my += (y[k] + y[l]) * c;
        xx += (x[k] * x[k] + x[k] * x[l] + x[l] * x[l]) * c;
        yy += (y[k] * y[k] + y[k] * y[l] + y[l] * y[l]) * c;
        xy += (x[k] * y[l] + 2 * x[k] * y[k] + 2 * x[l] * y[l] + x[l] * y[k]) * c;
    }
    out->area = a / 2;
    out->m1[0] = mx / 6;
    out->m1[1] = my / 6;
    out->m2[0] = xx / 12;
    out->m2[1] = xy / 24;
    out->m2[2] = yy / 12;
}

int pad_clip_moments(double e, const double g[2], double hx, double hy, pad_moments *out) {
    const double spread = fabs(g[0]) * hx + fabs(g[1]) * hy;
    if (e - spread > 0) { /* the whole cell presses: the rectangle's own moments */
        const double a = 4 * hx * hy;
        out->area = a;
        out->m1[0] = out->m1[1] = 0.0;
        out->m2[0] = a * hx * hx / 3;
        out->m2[1] = 0.0;
        out->m2[2] = a * hy * hy / 3;
        return 1;
    }
    out->area = out->m1[0] = out->m1[1] = out->m2[0] = out->m2[1] = out->m2[2] = 0.0;
    if (!(e + spread > 0)) return 0; /* lifted everywhere (or a field not finite) */
    /* Sutherland-Hodgman: the corners counterclockwise, kept where e > 0,
     * each edge that crosses the line cut where e = 0 (at most 5 vertices) */
    const double cx[4] = {-hx, hx, hx, -hx}, cy[4] = {-hy, -hy, hy, hy};
    double ce[4], x[5], y[5];
    for (int k = 0; k < 4; ++k) ce[k] = e + g[0] * cx[k] + g[1] * cy[k];
    int n = 0;
    for (int k = 0; k < 4; ++k) {
        const int l = (k + 1) & 3;
        const int in_k = ce[k] > 0, in_l = ce[l] > 0;
        if (in_k) x[n] = cx[k], y[n] = cy[k], ++n;
        if (in_k != in_l) {
            const double t = ce[k] / (ce[k] - ce[l]);
            x[n] = cx[k] + t * (cx[l] - cx[k]);
            y[n] = cy[k] + t * (cy[l] - cy[k]);
            ++n;
        }
    }
    if (n >= 3) polygon_moments(x, y, n, out);
    return 0;
}
