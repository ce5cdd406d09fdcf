"""The pad's closed forms (orthocontact.closed_forms.pad) against each other
and against sums written out here: the clipped integrals' corner formula
against full contact, the one-axis lift-off and a brute-force midpoint sum;
the push at a height's equilibrium against the clipped integrals; the step
limits against the central-difference scheme they bound."""
import math

import numpy as np
import pytest

from orthocontact.closed_forms import pad as cp

KN, L, W = 2e8, 0.09, 0.06


def brute(kn, length, width, d, phi1, phi2, theta, n=1500):
    """Fn, M1, M2 and the contact fraction by the midpoint rule on n x n
    points of the body's rectangle, each point turned into the surface
    frame and pressed by kn max(0, d + phi2 X - phi1 Y)."""
    x = (np.arange(n) + 0.5) / n * length - length / 2
    y = (np.arange(n) + 0.5) / n * width - width / 2
    x, y = np.meshgrid(x, y)
    c, s = math.cos(theta), math.sin(theta)
    X, Y = c * x - s * y, s * x + c * y
    p = kn * np.maximum(d + phi2 * X - phi1 * Y, 0.0)
    dA = length * width / n**2
    return p.sum() * dA, (Y * p).sum() * dA, -(X * p).sum() * dA, float(np.mean(p > 0))


POSES = [(1e-4, 2e-4, -3e-3, 0.0), (5e-5, 1e-3, 3e-3, 0.4), (2e-5, -2e-3, 1e-3, -1.1),
         (1e-4, 0.0, 4e-3, 0.0), (1e-4, 3e-3, 0.0, 0.0), (-1e-5, 1e-3, 2e-3, 0.3)]


@pytest.mark.parametrize("d,phi1,phi2,theta", [(1e-4, 1e-4, -2e-3, 0.0), (2e-4, 1e-3, 2e-3, 0.7),
                                               (1e-4, 0.0, 0.0, 1.3), (3e-5, -5e-4, 1e-4, -2.0)])
def test_the_corner_formula_in_full_contact_is_the_linear_pressures_integral(d, phi1, phi2, theta):
    assert cp.in_full_contact(L, W, d, phi1, phi2, theta)
    full = cp.full_contact(KN, L, W, d, phi1, phi2, theta)
    assert cp.clipped(KN, L, W, d, phi1, phi2, theta) == pytest.approx(full, rel=1e-11, abs=1e-12 * KN * L**4)
    assert full[0] == cp.area_approach_force(KN, L, W, d)
    assert cp.contact_fraction(L, W, d, phi1, phi2, theta) == pytest.approx(1.0, rel=1e-12)


def test_tilt_stiffness_is_the_full_contacts_moment_per_tilt():
    k1, k2 = cp.tilt_stiffness(KN, L, W)
    assert k1 == KN * L * W**3 / 12 and k2 == KN * W * L**3 / 12
    _, M1, M2 = cp.full_contact(KN, L, W, 1e-4, 2e-4, -3e-4)
    assert M1 == pytest.approx(-k1 * 2e-4, rel=1e-15) and M2 == pytest.approx(k2 * 3e-4, rel=1e-15)
    # both restoring, and a quarter turn swaps the sides' roles
    _, M1q, M2q = cp.full_contact(KN, W, L, 1e-4, 2e-4, -3e-4, math.pi / 2)
    assert (M1q, M2q) == pytest.approx((M1, M2), rel=1e-12)


@pytest.mark.parametrize("d,phi1,phi2,theta", POSES)
def test_the_clipped_closed_form_is_the_brute_force_sum(d, phi1, phi2, theta):
    """The midpoint rule on 1500^2 points, first order near the lift-off
    line: within 1e-4 of the closed form."""
    Fn, M1, M2 = cp.clipped(KN, L, W, d, phi1, phi2, theta)
    bFn, bM1, bM2, frac = brute(KN, L, W, d, phi1, phi2, theta)
    scale = max(abs(Fn), 1e-30)
    assert abs(bFn - Fn) <= 1e-4 * scale
    assert abs(bM1 - M1) <= 1e-4 * scale * L and abs(bM2 - M2) <= 1e-4 * scale * L
    assert cp.contact_fraction(L, W, d, phi1, phi2, theta) == pytest.approx(frac, abs=2e-3)


def test_one_axis_lift_off_is_the_clipped_integral_and_the_triangle():
    d, phi2 = 5e-5, 4e-3
    x0, Fn, M2 = cp.one_axis_lift_off(KN, L, W, d, phi2)
    assert x0 == pytest.approx(-d / phi2) and -L / 2 < x0 < L / 2
    got = cp.clipped(KN, L, W, d, 0.0, phi2)
    assert got == pytest.approx((Fn, 0.0, M2), rel=1e-13, abs=1e-15 * Fn * L)
    # a pad of sides swapped turned a quarter has the same footprint: the same numbers
    turned = cp.clipped(KN, W, L, d, 0.0, phi2, math.pi / 2)
    assert turned == pytest.approx((Fn, 0.0, M2), rel=1e-12, abs=1e-14 * Fn * L)
    # the triangle's resultant at x0 + 2c/3, integrated from the pressure directly
    c = L / 2 - x0
    assert -M2 / Fn == pytest.approx(x0 + 2 * c / 3, rel=1e-13)
    assert cp.contact_fraction(L, W, d, 0.0, phi2) == pytest.approx(c / L, rel=1e-13)
    with pytest.raises(ValueError, match="not on the pad"):
        cp.one_axis_lift_off(KN, L, W, 1.0, phi2)


def test_a_vanishing_second_tilt_tends_to_the_one_axis_forms():
    """Fn is even in the second tilt: off by its square, with no digits lost
    however small it is (no division by it)."""
    d, phi2 = 5e-5, 4e-3
    _, Fn, M2 = cp.one_axis_lift_off(KN, L, W, d, phi2)
    for e in (1e-5, 1e-9, 1e-14):
        got = cp.clipped(KN, L, W, d, e, phi2)
        assert abs(got[0] / Fn - 1) <= 10 * (e / phi2) ** 2 + 1e-14
        assert abs(got[2] / M2 - 1) <= 10 * (e / phi2) ** 2 + 1e-14


def test_a_pad_lifted_everywhere_carries_nothing():
    assert cp.clipped(KN, L, W, -1e-3, 1e-3, 2e-3, 0.3) == (0.0, 0.0, 0.0)
    assert cp.clipped(KN, L, W, -1e-3, 0.0, 0.0) == (0.0, 0.0, 0.0)
    assert cp.contact_fraction(L, W, -1e-3, 1e-3, 2e-3, 0.3) == 0.0


@pytest.mark.parametrize("e", [0.0, 0.004, L / 6, 0.02, 0.03, 0.04, 0.0449])
def test_the_block_pushed_at_a_height_is_in_equilibrium(e):
    """The pose pushed_at_height gives carries the weight with its centre of
    pressure at e: Fn = m g and -M2 = m g e through the clipped integrals."""
    weight = 18.39
    regime, d, phi2 = cp.pushed_at_height(KN, L, W, weight, e)
    assert regime == (cp.FULL_CONTACT if e <= L / 6 else cp.LIFT_OFF)
    Fn, M1, M2 = cp.clipped(KN, L, W, d, 0.0, phi2)
    assert Fn == pytest.approx(weight, rel=1e-11)
    assert -M2 == pytest.approx(weight * e, rel=1e-11, abs=1e-14 * weight * L)
    assert M1 == 0.0
    if e != L / 6:   # at L/6 the trailing edge touches, delta 0 to rounding
        assert cp.in_full_contact(L, W, d, 0.0, phi2) == (e < L / 6)


def test_the_push_tips_the_block_past_half_the_length_and_the_regimes_meet():
    assert cp.pushed_at_height(KN, L, W, 18.39, L / 2) == (cp.TIPS, None, None)
    below = cp.pushed_at_height(KN, L, W, 18.39, L / 6)
    above = cp.pushed_at_height(KN, L, W, 18.39, L / 6 * (1 + 1e-12))
    assert above[0] == cp.LIFT_OFF
    assert above[1:] == pytest.approx(below[1:], rel=1e-10)
    # trailing edge just touching: d = phi2 L/2 at the threshold
    assert below[1] == pytest.approx(below[2] * L / 2, rel=1e-13)
    assert cp.regime_heights(0.5, L) == (L / 3, L)
    with pytest.raises(ValueError):
        cp.pushed_at_height(KN, L, W, 18.39, -0.01)


def test_a_settled_block_is_carried_by_the_uniform_approach():
    d = cp.settled_approach(1.875, 9.806, KN, L, W)
    assert cp.area_approach_force(KN, L, W, d) == pytest.approx(1.875 * 9.806, rel=1e-15)


def central_differences(h, k, m, steps, x0=1.0):
    """x[n+1] - 2 x[n] + x[n-1] = -h^2 k x[n] / m from rest at x0: the largest |x|."""
    x_prev, x, top = x0, x0, abs(x0)
    for _ in range(steps):
        x_prev, x = x, 2 * x - x_prev - h * h * k / m * x
        top = max(top, abs(x))
    return top


@pytest.mark.parametrize("limit, k, m", [
    (lambda: cp.normal_step_limit(1.875, KN, L, W), KN * L * W, 1.875),
    (lambda: cp.tilt_step_limit(2e-3, KN, L, W), cp.tilt_stiffness(KN, L, W)[1], 2e-3),
    (lambda: cp.tilt_step_limit(2e-3, KN, L, W, axis=1), cp.tilt_stiffness(KN, L, W)[0], 2e-3)])
def test_the_step_limits_bound_the_central_difference_scheme(limit, k, m):
    h = limit()
    assert h == pytest.approx(2 * math.sqrt(m / k), rel=1e-15)
    assert central_differences(0.99 * h, k, m, 2000) < 20      # bounded below the limit
    assert central_differences(1.01 * h, k, m, 2000) > 1e6     # grows above it
