"""Closed forms of a rectangular pad (length x width [m]) of a rigid body on a
Winkler foundation (kn [N/m^3]: pressure per unit approach), written
independently of the ContactPad FMU: its normal force and the pressure's
moments from the pad's pose, where it lifts off, the equilibrium of a block
pushed at a height, and the explicit couplings' step limits.

Conventions (the FMU's): the surface frame X1, X2 in the surface, X3 its
outward normal; the pad turned by theta [rad] counterclockwise about X3, a
point at body coordinates r (origin at the pad centre, x along `length`)
lying at R(theta) r in the surface frame.  The pad's pose: the approach d [m]
of its centre into the surface (> 0 pressed) and small tilts phi1, phi2
[rad] about X1, X2 (right-handed): a point at (X, Y) in the surface frame
approaches by

    delta(X, Y) = d + phi2 X - phi1 Y,

and the pressure there is kn max(0, delta).  A force +X3 at (X, Y, 0) has
the moment (Y F, -X F, 0) about the centre, so the pressure's normal force
and moments on the body are

    Fn = integral of p,   M1 = integral of Y p,   M2 = -integral of X p,

both restoring (M1 = -k1 phi1, M2 = -k2 phi2 in full contact at theta = 0).
In body coordinates the approach is d + g . r with g = R(theta)^T (phi2,
-phi1), and the moments turn with the pad: (X, Y)-moment = R(theta) times
the body's (x, y)-moment."""
from __future__ import annotations

import math

import numpy as np

# The regimes of a block pushed at a height (pushed_at_height).
FULL_CONTACT, LIFT_OFF, TIPS = "full contact", "lift-off", "tips"


def area_approach_force(kn, length, width, d) -> float:
    """Fn [N] of the pad in full contact with no tilt: kn A d, A = length width."""
    return kn * length * width * d


def tilt_stiffness(kn, length, width) -> tuple[float, float]:
    """(k1, k2) [N m/rad] of the pad in full contact at theta = 0:
    M1 = -k1 phi1, M2 = -k2 phi2 with k1 = kn length width^3/12 (the tilt
    about X1 bends across the width) and k2 = kn width length^3/12."""
    return kn * length * width**3 / 12.0, kn * width * length**3 / 12.0


def body_gradient(phi1, phi2, theta) -> tuple[float, float]:
    """(gx, gy) [-]: the approach's slope along the body's axes, R(theta)^T
    (phi2, -phi1)."""
    c, s = math.cos(theta), math.sin(theta)
    return c * phi2 - s * phi1, -s * phi2 - c * phi1


def corner_approaches(length, width, d, phi1, phi2, theta=0.0) -> np.ndarray:
    """delta [m] at the pad's four corners (body corners (+-length/2, +-width/2))."""
    gx, gy = body_gradient(phi1, phi2, theta)
    return np.array([d + gx * sx * length / 2 + gy * sy * width / 2
                     for sx in (-1, 1) for sy in (-1, 1)])


def in_full_contact(length, width, d, phi1, phi2, theta=0.0) -> bool:
    """Whether the approach is > 0 at every corner (then everywhere: it is linear)."""
    return bool(np.all(corner_approaches(length, width, d, phi1, phi2, theta) > 0))


def _to_surface(theta, mx, my) -> tuple[float, float]:
    """The pressure's first moment (integral of r p) turned from body axes
    to the surface's, as (M1, M2) = (Y-moment, -X-moment)."""
    c, s = math.cos(theta), math.sin(theta)
    X, Y = c * mx - s * my, s * mx + c * my
    return Y, -X


def full_contact(kn, length, width, d, phi1, phi2, theta=0.0) -> tuple[float, float, float]:
    """(Fn [N], M1 [N m], M2 [N m]) of the pad in full contact (in_full_contact):
    the pressure is linear, Fn = kn A d, and its first moment along the body's
    axes is kn (gx Ix, gy Iy) with the rectangle's second moments Ix =
    width length^3/12, Iy = length width^3/12; at theta = 0,
    M1 = -kn phi1 length width^3/12 and M2 = -kn phi2 width length^3/12."""
    gx, gy = body_gradient(phi1, phi2, theta)
    Ix, Iy = width * length**3 / 12.0, length * width**3 / 12.0
    M1, M2 = _to_surface(theta, kn * gx * Ix, kn * gy * Iy)
    return kn * length * width * d, M1, M2


# 3-point Gauss-Legendre on [-1, 1]: exact for polynomials of degree 5
GAUSS3 = ((-math.sqrt(0.6), 5 / 9), (0.0, 8 / 9), (math.sqrt(0.6), 5 / 9))


def _across(a, gy, hy) -> tuple[float, float, float]:
    """Over y in [-hy, hy], at a point x of the body's axis where the
    approach is a + gy y: (integral of (a + gy y)+, of y (a + gy y)+, the
    length where it is > 0).  Where the line crosses, the integrals of the
    clipped linear field from its zero to the edge: hi^2/(2|gy|) and
    sign(gy) (hy hi^2/(2|gy|) - hi^3/(6 gy^2)), hi = a + |gy| hy."""
    g = abs(gy)
    lo, hi = a - g * hy, a + g * hy
    if lo >= 0:
        return 2 * hy * a, gy * 2 * hy**3 / 3, 2 * hy
    if hi <= 0:
        return 0.0, 0.0, 0.0
    return hi * hi / (2 * g), math.copysign(hy * hi * hi / (2 * g) - hi**3 / (6 * g * g), gy), hi / g


def _along(d, gx, gy, hx, hy) -> tuple[float, float, float, float]:
    """The integrals over the body's rectangle [-hx, hx] x [-hy, hy] of
    e+ = (d + gx x + gy y)+, x e+, y e+ and of the step (e > 0): _across's
    integrals over y are piecewise polynomials of degree <= 3 in x, whose
    pieces end where the line d + gx x +- |gy| hy = 0 meets the rectangle's
    rows; each piece's integral is exact by 3-point Gauss-Legendre."""
    cuts = [-hx, hx]
    if gx != 0.0:
        cuts += [x for x in ((-d - abs(gy) * hy) / gx, (-d + abs(gy) * hy) / gx) if -hx < x < hx]
    cuts.sort()
    F = Fx = Fy = S = 0.0
    for x0, x1 in zip(cuts[:-1], cuts[1:]):
        mid, half = (x0 + x1) / 2, (x1 - x0) / 2
        for t, w in GAUSS3:
            x = mid + half * t
            if gy == 0.0:
                e = max(d + gx * x, 0.0)
                i, j, k = 2 * hy * e, 0.0, 2 * hy if e > 0 else 0.0
            else:
                i, j, k = _across(d + gx * x, gy, hy)
            F += w * half * i
            Fx += w * half * x * i
            Fy += w * half * j
            S += w * half * k
    return F, Fx, Fy, S


def clipped(kn, length, width, d, phi1, phi2, theta=0.0) -> tuple[float, float, float]:
    """(Fn [N], M1 [N m], M2 [N m]) of the continuum's clipped pressure
    kn max(0, delta) over the pad, any pose: the integrals over the body's
    rectangle of (d + gx x + gy y)+ and of x, y times it, across the width in
    closed form and along the length piece by piece between the lift-off
    line's crossings of the sides, exactly (_along); then turned into the
    surface frame.  Full contact gives full_contact's numbers."""
    gx, gy = body_gradient(phi1, phi2, theta)
    F, Fx, Fy, _ = _along(d, gx, gy, length / 2.0, width / 2.0)
    return (kn * F, *_to_surface(theta, kn * Fx, kn * Fy))


def lift_off_line(d, phi1, phi2) -> tuple[float, float, float]:
    """The line where the approach is 0, a X + b Y = c in the surface frame:
    (a, b, c) = (phi2, -phi1, -d); the pad presses where a X + b Y > c."""
    return phi2, -phi1, -d


def one_axis_lift_off(kn, length, width, d, phi2) -> tuple[float, float, float]:
    """(x0 [m], Fn [N], M2 [N m]) of a pad tilted about X2 alone (theta = 0,
    phi2 > 0) that lifts at x0 = -d/phi2 > -length/2: contact where x > x0,
    Fn = kn width phi2 c^2/2 with the contact length c = length/2 - x0, and
    the pressure's resultant at x0 + 2c/3 (a triangle), M2 = -Fn (x0 + 2c/3)."""
    if not phi2 > 0:
        raise ValueError(f"one_axis_lift_off: phi2 must be > 0, got {phi2!r}")
    x0 = -d / phi2
    if not -length / 2 < x0 < length / 2:
        raise ValueError(f"one_axis_lift_off: the line x0 = {x0!r} m is not on the pad")
    c = length / 2 - x0
    Fn = kn * width * phi2 * c * c / 2
    return x0, Fn, -Fn * (x0 + 2 * c / 3)


def contact_fraction(length, width, d, phi1, phi2, theta=0.0) -> float:
    """The share of the pad's area where the approach is > 0 (clipped's
    integral of the step)."""
    gx, gy = body_gradient(phi1, phi2, theta)
    return _along(d, gx, gy, length / 2.0, width / 2.0)[3] / (length * width)


def pushed_at_height(kn, length, width, weight_N, e) -> tuple[str, float | None, float | None]:
    """(regime, d [m], phi2 [rad]) of a block of weight weight_N [N] on the
    pad (theta = 0) whose pressure must have its centre at x = e [m] >= 0
    (a push P at height h: e = P h / weight, mu h for P = mu weight):
    full contact while e <= length/6, d = weight/(kn A), phi2 = weight e /
    (kn width length^3/12); lift-off beyond, the contact a triangle of length
    c = 3 (length/2 - e) from x0 = length/2 - c, phi2 = 2 weight/(kn width
    c^2), d = -phi2 x0; and no equilibrium ("tips", None, None) for
    e >= length/2, where the resultant would leave the pad."""
    if e < 0:
        raise ValueError(f"pushed_at_height: e must be >= 0 (push along +X1), got {e!r}")
    if e <= length / 6:
        return FULL_CONTACT, weight_N / (kn * length * width), weight_N * e / tilt_stiffness(kn, length,
                                                                                              width)[1]
    if e < length / 2:
        c = 3 * (length / 2 - e)
        phi2 = 2 * weight_N / (kn * width * c * c)
        return LIFT_OFF, -phi2 * (length / 2 - c), phi2
    return TIPS, None, None


def regime_heights(mu, length) -> tuple[float, float]:
    """(h_lift, h_tip) [m]: the heights at which a push mu times the weight
    lifts the trailing edge (mu h = length/6) and tips the block (mu h = length/2)."""
    return length / (6 * mu), length / (2 * mu)


def settled_approach(mass_kg, g, kn, length, width) -> float:
    """d [m] of a free block of mass_kg [kg] at rest on the pad under gravity
    g [m/s^2] in full contact: kn A d = m g."""
    return mass_kg * g / (kn * length * width)


def normal_step_limit(mass_kg, kn, length, width) -> float:
    """The largest stable communication step [s] of an explicit coupling of
    the block's normal motion with the pad (central differences on the
    spring kn A): h < 2 sqrt(m / (kn A))."""
    return 2.0 * math.sqrt(mass_kg / (kn * length * width))


def tilt_step_limit(inertia_kg_m2, kn, length, width, axis: int = 2) -> float:
    """The same for the tilt about X2 (axis 2: stiffness kn width length^3/12)
    or X1 (axis 1: kn length width^3/12) of a body of that moment of inertia
    [kg m^2] about the axis through the pad centre: h < 2 sqrt(I / k)."""
    k1, k2 = tilt_stiffness(kn, length, width)
    return 2.0 * math.sqrt(inertia_kg_m2 / (k2 if axis == 2 else k1))
