"""Closed forms of a rolling pad (the brush model of tyre mechanics), written
independently of the ContactPad FMU: the steady tangential force of a pad
length x width [m] whose surface passes through the contact at vr [m/s]
along its axis 1, under a creepage.

Conventions (the FMU's).  Material enters the pad at its leading edge
x = +length/2 unloaded, travels to x = -length/2 in length/vr, and is
deflected by the body's motion beyond rolling: the creepages are
xi = u1'/vr (longitudinal), eta = u2'/vr (lateral) and the spin
phi_s = theta'/vr [1/m].  A point at distance a = length/2 - x from the
leading edge has, while it sticks, the deflection xi a along axis 1 (eta a
along axis 2).  The pad's stiffness eps [N/m] is shared by area,
c = eps/A per unit area, and its friction is mu times the pressure; the
force on the body opposes the deflection (full adhesion: T = -eps
length xi/2).  The texture's axes are the pad's (alpha = beta = 0), so a
creepage along a principal axis deflects along it alone: each axis has its
own eps and mu (eps1, mu1 along axis 1; eps2, mu2 along axis 2).

The forms hold in steady state (the pad has rolled past one length since
the creepage was last changed), without inertia of the material and with
a rigid body behind the brush (no carcass)."""
from __future__ import annotations

import math

import numpy as np


def creep_stiffness(eps, length) -> float:
    """C [N]: the force per unit creepage in full adhesion, eps length/2
    (eps [N/m] the pad's stiffness along the creepage's axis)."""
    return eps * length / 2.0


def slip_onset(eps, mu, fn, length) -> float:
    """xi* [-]: the creepage at which the trailing edge starts to slide,
    mu fn/(eps length); full adhesion below it."""
    return mu * fn / (eps * length)


def adhesion_length(eps, mu, fn, length, creepage) -> float:
    """a* [m]: the length of the adhesion zone from the leading edge, where
    a point's deflection c xi a stays below mu p: mu fn/(eps |xi|), the whole
    length at or below slip_onset; under uniform pressure p = fn/A."""
    if creepage == 0.0:
        return length
    return min(length, mu * fn / (eps * abs(creepage)))


def steady_force(eps, mu, fn, length, creepage) -> float:
    """T [N] along the creepage's axis under uniform pressure: full adhesion
    -eps length xi/2 up to slip_onset, then partial slip
    -sign(xi) mu fn (1 - mu fn/(2 eps |xi| length)), tending to -sign(xi) mu fn.
    eps [N/m], mu [-], fn [N] the normal force, length [m] the pad's length
    along the rolling direction, creepage xi [-]."""
    if fn <= 0.0:
        return 0.0
    if abs(creepage) <= slip_onset(eps, mu, fn, length):
        return -creep_stiffness(eps, length) * creepage
    return -math.copysign(mu * fn * (1.0 - mu * fn / (2.0 * eps * abs(creepage) * length)), creepage)


def slip_power(eps, mu, fn, length, creepage, vr) -> float:
    """P [W]: the power the friction dissipates in steady rolling at vr
    [m/s] under uniform pressure: a point past the adhesion zone slides on
    the friction limit mu p at the creep rate |xi| vr, so P = mu fn |xi| vr
    (1 - a*/length), a* = adhesion_length (0 in full adhesion).  The energy
    balance: the body's work |T| |xi| vr less the elastic energy the leaving
    material takes, (mu p)^2/(2 c) per area, c = eps/A."""
    if fn <= 0.0:
        return 0.0
    return mu * fn * abs(creepage) * abs(vr) * (1.0 - adhesion_length(eps, mu, fn, length, creepage) / length)


def spin_coefficients(eps1, eps2, length, width) -> tuple[float, float]:
    """(k_T2 [N m], k_Mz [N m^2]): in full adhesion a spin phi_s = theta'/vr
    [1/m] gives T2 = -k_T2 phi_s and Mz = -k_Mz phi_s (T1 = 0).  In stick the
    point (x, y) is deflected by phi_s (-y (length/2 - x), (length^2/4 - x^2)/2)
    (the pad turned while the point travelled from the leading edge), so
    T2 = -c2 width integral of (length^2/4 - x^2)/2 = -eps2 length^2 phi_s/12
    and Mz = -c1 integral of y^2 (length/2 - x) = -eps1 length width^2 phi_s/24,
    with c = eps/(length width)."""
    return eps2 * length**2 / 12.0, eps1 * length * width**2 / 24.0


def deflection_profile(pressure, c, mu, creepage, length, n=20000) -> tuple[np.ndarray, np.ndarray]:
    """(x [m], w [m]) of the steady brush under any pressure profile
    pressure(x) [Pa] along the rolling axis (uniform across the width): from
    the leading edge, a point sticks (dw/da = xi) until its deflection
    reaches the friction limit mu p/c and slides on it while it binds; a
    point where p = 0 carries nothing (w = 0, it is open).  The recursion
    w(a + da) = min(w(a) + |xi| da, mu p(a + da)/c) is the limit's exact
    solution at the nodes where p is linear between them; n intervals.
    c [N/m^3] the stiffness per area, xi the creepage (w takes its sign)."""
    a = np.linspace(0.0, length, n + 1)
    x = length / 2.0 - a
    cap = mu * np.maximum(np.asarray(pressure(x), dtype=float), 0.0) / c
    w = np.empty_like(a)
    w[0] = 0.0
    step = abs(creepage) * (a[1] - a[0])
    for k in range(n):
        w[k + 1] = min(w[k] + step, cap[k + 1])
    return x, math.copysign(1.0, creepage) * w


def steady_force_profile(pressure, eps, mu, length, width, creepage, n=20000) -> float:
    """T [N] along the creepage's axis under the pressure profile
    pressure(x) [Pa] (deflection_profile), integrated by the trapezoidal
    rule: -c width integral of w, c = eps/(length width).  Uniform pressure
    gives steady_force; a tilt about axis 2 (the trapezoidal or, past
    lift-off, triangular pressure of the pad) has no simpler closed form."""
    c = eps / (length * width)
    _, w = deflection_profile(pressure, c, mu, creepage, length, n)
    return float(-c * width * (length / n) * (w.sum() - (w[0] + w[-1]) / 2.0))
