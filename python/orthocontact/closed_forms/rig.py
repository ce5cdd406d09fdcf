"""Closed forms of the rig beyond the paper: steady sliding when the Teflon
strip resists the drift with Coulomb friction and viscosity (the lateral
force left on the block, its first root from rest), and the dynamic rig's
settling length.  Angles in rad, forces in N, velocities in m/s."""
from __future__ import annotations

import math

import numpy as np

from .paper import friction_entries, rotated_diagonal


def slip_force_tensor(mu1, mu2, eps1, eps2, alpha, beta, rule):
    """(h11, h12, h22) of a symmetric positive definite H with q parallel to
    H d when the slip runs along d: G q is parallel to d, so q is parallel to
    G^-1 d, and H is G^-1 up to a positive factor (F^-1 for the associated
    rule, A = B F B for the coupled one: eq. 20's rule slides as the coupled
    one in steady state).  Plain arithmetic: floats, numpy arrays of angles,
    or casadi symbols."""
    if rule == "associated":
        return rotated_diagonal(mu1**2, mu2**2, beta)
    if rule not in ("coupled", "eq20"):
        raise ValueError(f"unknown sliding rule {rule!r}")
    f11, f12, f22 = rotated_diagonal(1 / mu1**2, 1 / mu2**2, beta)
    b11, b12, b22 = rotated_diagonal(eps1, eps2, alpha)
    bf11, bf12 = b11 * f11 + b12 * f12, b11 * f12 + b12 * f22
    bf21, bf22 = b12 * f11 + b22 * f12, b12 * f12 + b22 * f22
    return bf11 * b11 + bf12 * b12, bf11 * b12 + bf12 * b22, bf21 * b12 + bf22 * b22


def strip_lateral_force(h, f, t, sign, mu_strip, c_times_v, normal_force):
    """(F2, q1) [N] of sliding along slope t = tan(phi) = v2/v1 under the
    strip: q = N H d / |H d|_F with d = (1, t) is the mat's force on the yield
    ellipse, q1 > 0 the push P, and F2 = -q2 - mu_strip sign P - c_strip v t
    the lateral force left on the block (sign: the sign of the lateral
    motion, 0 when held).  The block is in steady sliding where F2 = 0; it
    drifts towards larger t where F2 > 0.  h from slip_force_tensor, f the
    entries of F.  Smooth in t (H is positive definite, so H d never
    vanishes): no pole, no square root of a negative number.  Plain
    arithmetic: floats, numpy arrays, or casadi symbols (with sign fixed and
    P = q1 > 0 assumed)."""
    (h11, h12, h22), (f11, f12, f22) = h, f
    w1, w2 = h11 + h12 * t, h12 + h22 * t
    scale = normal_force / (f11 * w1 * w1 + 2 * f12 * w1 * w2 + f22 * w2 * w2) ** 0.5
    q1, q2 = scale * w1, scale * w2
    push = np.maximum(q1, 0.0) if isinstance(q1, np.ndarray) else q1
    return -q2 - mu_strip * sign * push - c_times_v * t, q1


STRIP_GRID = 512         # samples of the motion's direction on each side of X1


STRIP_BISECTIONS = 60    # halvings of the bracketing cell: past double precision


def steady_strip_state_array(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip, c_strip=0.0,
                             velocity=0.0, normal_force=1.0):
    """(tan(phi), push [N]) of steady sliding when the Teflon strip resists the
    drift (beyond the paper): Coulomb friction mu_strip on the push P and a
    viscous force c_strip [N s/m] on the lateral velocity v2 = velocity
    tan(phi) [m/s]; for arrays of angles alpha, beta [rad].

    The block starts moving along X1 (v2 = 0) and drifts the way the lateral
    force F2 of strip_lateral_force pushes it, until F2 vanishes: the first
    root of F2 from phi = 0 in that direction, a stable one.  If F2 pushes
    neither way at phi = 0 (its jump there is the strip's friction), the
    strip holds the block on the X1 axis (tan phi = 0).  Each side is
    sampled over the direction's angle in (0, 90 deg); the first cell whose
    ends bracket the root is bisected.  A root between two samples that F2
    crosses back out of again within one cell (1/512 of 90 deg) is passed
    over: test_closed_forms compares with the rig on random laws.  A law far
    outside the plausible ranges (export --force) may give nan, without
    numpy's warning text."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return _steady_strip_state(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip, c_strip, velocity,
                                   normal_force)


def _steady_strip_state(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip, c_strip, velocity,
                        normal_force):
    alpha, beta = np.asarray(alpha, dtype=float), np.asarray(beta, dtype=float)
    shape = np.broadcast(alpha, beta).shape
    h = [np.broadcast_to(x, shape).astype(float) for x in
         slip_force_tensor(mu1, mu2, eps1, eps2, alpha, beta, rule)]
    norm = np.abs(h[0]) + np.abs(h[2])    # the direction of H d does not depend on H's size
    h = tuple(x / norm for x in h)
    f = tuple(np.broadcast_to(x, shape) for x in friction_entries(mu1, mu2, beta))
    cv = c_strip * velocity

    def force(theta, sign):
        return strip_lateral_force(h, f, np.tan(theta), sign, mu_strip, cv, normal_force)[0]

    zero = np.zeros(shape)
    out = np.zeros(shape)
    for sign in (1.0, -1.0):
        moving = force(zero, sign) * sign > 0      # F2 drives the block this way from rest
        if not moving.any():
            continue
        lo = zero.copy()
        hi = np.full(shape, sign * math.pi / 2)
        found = ~moving
        for k in range(1, STRIP_GRID + 1):
            theta = np.full(shape, sign * (math.pi / 2) * k / STRIP_GRID)
            if k == STRIP_GRID:
                theta = np.nextafter(theta, 0.0)  # tan stays finite
            crossed = (force(theta, sign) * sign <= 0) & ~found
            hi = np.where(crossed, theta, hi)
            found |= crossed
            lo = np.where(found, lo, theta)
            if found.all():
                break
        for _ in range(STRIP_BISECTIONS):
            mid = 0.5 * (lo + hi)
            right = force(mid, sign) * sign > 0
            lo, hi = np.where(right, mid, lo), np.where(right, hi, mid)
        out = np.where(moving, np.tan(0.5 * (lo + hi)), out)
    push = strip_lateral_force(h, f, out, np.sign(out), mu_strip, cv, normal_force)[1]
    return out, push


def steady_tan_phi_with_strip_array(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip, c_strip=0.0,
                                    velocity=0.0, normal_force=1.0) -> np.ndarray:
    """tan(phi) of steady_strip_state_array, for arrays of angles [rad]."""
    return steady_strip_state_array(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip, c_strip,
                                    velocity, normal_force)[0]


def steady_tan_phi_with_strip(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip, c_strip=0.0,
                              velocity=0.0, normal_force=1.0) -> float:
    """tan(phi) of steady_strip_state_array for one pair of angles [rad]
    (normal_force [N] matters only with c_strip)."""
    return float(steady_tan_phi_with_strip_array(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip,
                                                 c_strip, velocity, normal_force))


def settling_length_array(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip, c_strip, velocity,
                          normal_force, mass_kg) -> np.ndarray:
    """Length [m] of carriage travel over which a lateral disturbance of
    steady sliding decays by the factor e in the dynamic rig (beyond the
    paper): linearised about the steady slope t*, m dv2/dt = F2(v2 / v)
    decays at the rate -F2'(t*) / (m v), so over L = m v^2 / -F2'(t*)
    (F2: strip_lateral_force).  0 where the strip holds the block (no drift
    to settle); inf where F2 does not fall through t* (no restoring force).
    For Case 2 at its extremum, 0.244 m/s, 1.875 kg: 0.40 m."""
    alpha, beta = np.asarray(alpha, dtype=float), np.asarray(beta, dtype=float)
    t, _ = steady_strip_state_array(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip, c_strip,
                                    velocity, normal_force)
    h = slip_force_tensor(mu1, mu2, eps1, eps2, alpha, beta, rule)
    f = friction_entries(mu1, mu2, beta)
    sign = np.sign(t)
    d = 1e-6 * (1 + np.abs(t))
    cv = c_strip * velocity
    slope = (strip_lateral_force(h, f, t + d, sign, mu_strip, cv, normal_force)[0]
             - strip_lateral_force(h, f, t - d, sign, mu_strip, cv, normal_force)[0]) / (2 * d)
    with np.errstate(divide="ignore"):
        L = np.where(slope < 0, mass_kg * velocity**2 / -np.minimum(slope, -1e-300), np.inf)
    return np.where((t == 0) & (mu_strip > 0), 0.0, L)
