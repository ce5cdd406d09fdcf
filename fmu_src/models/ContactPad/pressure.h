/*
 * The Winkler foundation under the pad's cells: each point of the pad
 * presses with kn max(0, e), e the (effective) approach at that point, a
 * linear field over the pad in body coordinates r (origin at the pad
 * centre, x along length):
 *
 *     e(r) = f0 + g . r   [m]
 *
 * (models/ContactPad/model.c forms f0 and g from the pose and its rate).
 * A cell's normal force and first moment are the exact integrals of
 * kn e+ over its rectangle: in full contact (e > 0 at its four corners, so
 * everywhere) its area times kn e at its centre and, for the first moment,
 * its own second moments beside; a cell the line e = 0 crosses is clipped
 * to the polygon where e > 0 and its moments (area, first, second about the
 * cell centre) integrated exactly.  Damped, e is the approach plus its rate
 * term and the layer presses only where the approach itself is > 0 too:
 * the polygon is clipped by both lines.  No FMI in it.
 */
#ifndef PAD_PRESSURE_H
#define PAD_PRESSURE_H

#ifdef __cplusplus
extern "C" {
#endif

/* The pressed part of a cell: its area [m^2], its first moments about the
 * cell centre [m^3] and its second moments xx, xy, yy about it [m^4]. */
typedef struct {
    double area, m1[2], m2[3];
} pad_moments;

/* The moments of the part of the rectangle [-hx, hx] x [-hy, hy] where
 * e + g . rho > 0 (rho about the cell centre, e the field there); 1 if that
 * is all of it, 0 otherwise (none or a clipped polygon). */
int pad_clip_moments(double e, const double g[2], double hx, double hy, pad_moments *out);

/* The part of the line delta = 0 inside a cell where e > 0, from a to b
 * (about the cell centre [m]); n = 0 if there is none.  Where the damping
 * presses (e > delta), the pressure jumps from 0 to kn e across it. */
typedef struct {
    int n;
    double a[2], b[2];
} pad_edge;

/* The part of the line lc + lg . rho = 0 inside the rectangle [-hx, hx] x
 * [-hy, hy] where cc + cg . rho > 0 (rho about the cell centre). */
void pad_line_part(double lc, const double lg[2], double cc, const double cg[2], double hx,
                   double hy, pad_edge *edge);

/* pad_clip_moments for a damped foundation: the moments of the part of the
 * cell where both the approach delta = dl + gl . rho and the effective
 * approach e + g . rho are > 0 (a Kelvin-Voigt layer presses only where it
 * touches, and never pulls), and the edge of it on delta = 0.  Where delta
 * > 0 at the cell's four corners, pad_clip_moments's result, bit for bit. */
int pad_clip_moments_touching(double e, const double g[2], double dl, const double gl[2], double hx,
                              double hy, pad_moments *out, pad_edge *edge);

/* A cell's normal force kn * integral of e+ [N] and its derivatives with
 * respect to (f0, g0, g1) [N/m], from its pressed part's moments, the field
 * at its centre e and the centre r [m]. */
static inline double pad_cell_force(double kn, const pad_moments *M, double e, const double g[2],
                                    const double r[2], double dN[3]) {
    dN[0] = kn * M->area;
    dN[1] = kn * (r[0] * M->area + M->m1[0]);
    dN[2] = kn * (r[1] * M->area + M->m1[1]);
    return kn * (e * M->area + g[0] * M->m1[0] + g[1] * M->m1[1]);
}

#ifdef __cplusplus
}
#endif
#endif
