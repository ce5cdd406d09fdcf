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

/* Sutherland-Hodgman: the vertices of the polygon (x, y) kept where
 * c + gc . (x, y) > 0, each edge that crosses the line cut where it is 0;
 * returns their number (at most n + 1). */
static int clip_polygon(const double x[], const double y[], int n, double c, const double gc[2],
                        double ox[], double oy[]) {
    double v[6];
    for (int k = 0; k < n; ++k) v[k] = c + gc[0] * x[k] + gc[1] * y[k];
    int m = 0;
    for (int k = 0; k < n; ++k) {
        const int l = k + 1 == n ? 0 : k + 1;
        const int in_k = v[k] > 0, in_l = v[l] > 0;
        if (in_k) ox[m] = x[k], oy[m] = y[k], ++m;
        if (in_k != in_l) {
            const double t = v[k] / (v[k] - v[l]);
            ox[m] = x[k] + t * (x[l] - x[k]);
            oy[m] = y[k] + t * (y[l] - y[k]);
            ++m;
        }
    }
    return m;
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
    /* the corners counterclockwise, kept where e > 0, each edge that crosses
     * the line cut where e = 0 (at most 5 vertices) */
    const double cx[4] = {-hx, hx, hx, -hx}, cy[4] = {-hy, -hy, hy, hy};
    double x[5], y[5];
    const int n = clip_polygon(cx, cy, 4, e, g, x, y);
    if (n >= 3) polygon_moments(x, y, n, out);
    return 0;
}

void pad_line_part(double lc, const double lg[2], double cc, const double cg[2], double hx,
                   double hy, pad_edge *edge) {
    edge->n = 0;
    const double cx[4] = {-hx, hx, hx, -hx}, cy[4] = {-hy, -hy, hy, hy};
    double px[2], py[2];
    int found = 0;
    for (int k = 0; k < 4 && found < 2; ++k) {
        const int l = (k + 1) & 3;
        const double vk = lc + lg[0] * cx[k] + lg[1] * cy[k];
        const double vl = lc + lg[0] * cx[l] + lg[1] * cy[l];
        if ((vk > 0) != (vl > 0)) {
            const double t = vk / (vk - vl);
            px[found] = cx[k] + t * (cx[l] - cx[k]);
            py[found] = cy[k] + t * (cy[l] - cy[k]);
            ++found;
        }
    }
    if (found < 2) return;
    const double ea = cc + cg[0] * px[0] + cg[1] * py[0], eb = cc + cg[0] * px[1] + cg[1] * py[1];
    if (!(ea > 0) && !(eb > 0)) return;
    const double ta = ea > 0 ? 0.0 : ea / (ea - eb), tb = eb > 0 ? 1.0 : ea / (ea - eb);
    edge->n = 1;
    edge->a[0] = px[0] + ta * (px[1] - px[0]);
    edge->a[1] = py[0] + ta * (py[1] - py[0]);
    edge->b[0] = px[0] + tb * (px[1] - px[0]);
    edge->b[1] = py[0] + tb * (py[1] - py[0]);
}

int pad_clip_moments_touching(double e, const double g[2], double dl, const double gl[2], double hx,
                              double hy, pad_moments *out, pad_edge *edge) {
    edge->n = 0;
    if (dl - (fabs(gl[0]) * hx + fabs(gl[1]) * hy) > 0) return pad_clip_moments(e, g, hx, hy, out);
    out->area = out->m1[0] = out->m1[1] = out->m2[0] = out->m2[1] = out->m2[2] = 0.0;
    if (!(dl + (fabs(gl[0]) * hx + fabs(gl[1]) * hy) > 0)) return 0; /* touching nowhere */
    const double cx[4] = {-hx, hx, hx, -hx}, cy[4] = {-hy, -hy, hy, hy};
    double tx[5], ty[5], px[6], py[6];
    const int nt = clip_polygon(cx, cy, 4, dl, gl, tx, ty);
    const int np = clip_polygon(tx, ty, nt, e, g, px, py);
    if (np >= 3) polygon_moments(px, py, np, out);
    pad_line_part(dl, gl, e, g, hx, hy, edge);
    return 0;
}
