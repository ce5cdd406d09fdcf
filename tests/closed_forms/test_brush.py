"""The rolling pad's closed forms (orthocontact.closed_forms.brush) against
each other and against integrals written out here: the steady force's two
regimes meet at the slip onset and tend to the friction limit, the profile
integral under uniform pressure is the closed form, the adhesion zone is
where the profile leaves the line xi a, the spin's coefficients are the
midpoint sums of the stick deflection they state, and the slip's power is
the energy balance of the body's work and the elastic energy that leaves."""
import math

import numpy as np
import pytest

from orthocontact.closed_forms import brush

EPS, MU, FN, L, W = 1e4, 0.5, 500.0, 0.1, 0.05   # N/m, -, N, m, m


def test_full_adhesion_is_the_creep_stiffness_and_meets_partial_slip_at_the_onset():
    xi0 = brush.slip_onset(EPS, MU, FN, L)
    assert xi0 == pytest.approx(MU * FN / (EPS * L), rel=1e-15)
    assert brush.steady_force(EPS, MU, FN, L, 0.1 * xi0) == pytest.approx(-EPS * L * 0.1 * xi0 / 2, rel=1e-15)
    below = brush.steady_force(EPS, MU, FN, L, xi0 * (1 - 1e-12))
    above = brush.steady_force(EPS, MU, FN, L, xi0 * (1 + 1e-12))
    assert below == pytest.approx(-MU * FN / 2, rel=1e-9) and above == pytest.approx(below, rel=1e-9)
    # odd in the creepage; saturates at the friction limit
    assert brush.steady_force(EPS, MU, FN, L, -3 * xi0) == -brush.steady_force(EPS, MU, FN, L, 3 * xi0)
    assert brush.steady_force(EPS, MU, FN, L, 1e6 * xi0) == pytest.approx(-MU * FN, rel=1e-6)
    assert brush.steady_force(EPS, MU, 0.0, L, xi0) == 0.0


@pytest.mark.parametrize("factor", [0.3, 1.0, 1.7, 4.0, 25.0])
def test_the_profile_integral_under_uniform_pressure_is_the_closed_form(factor):
    xi = factor * brush.slip_onset(EPS, MU, FN, L)
    p = FN / (L * W)
    T = brush.steady_force_profile(lambda x: np.full_like(x, p), EPS, MU, L, W, xi)
    assert T == pytest.approx(brush.steady_force(EPS, MU, FN, L, xi), rel=1e-7)


def test_the_adhesion_zone_is_where_the_profile_leaves_the_stick_line():
    xi = 2.5 * brush.slip_onset(EPS, MU, FN, L)
    c, p = EPS / (L * W), FN / (L * W)
    x, w = brush.deflection_profile(lambda x: np.full_like(x, p), c, MU, xi, L, n=100000)
    a = L / 2 - x
    stuck = np.isclose(w, xi * a, rtol=0, atol=1e-15)
    assert a[stuck].max() == pytest.approx(brush.adhesion_length(EPS, MU, FN, L, xi), abs=L / 1e5)
    assert brush.adhesion_length(EPS, MU, FN, L, xi) == pytest.approx(L / 2.5, rel=1e-12)
    assert brush.adhesion_length(EPS, MU, FN, L, 0.5 * xi / 2.5) == L


def test_full_adhesion_holds_under_any_pressure_that_binds_nowhere():
    """Below the onset of the least pressed point, the force is eps L xi/2 whatever the profile."""
    xi = 1e-4
    T = brush.steady_force_profile(lambda x: 1e5 * (1 + 8 * x), EPS, MU, L, W, xi)
    assert T == pytest.approx(-EPS * L * xi / 2, rel=1e-9)


@pytest.mark.parametrize("k", [-10.0, -4.0, 4.0, 10.0])   # 1/m
def test_a_trapezoid_is_the_integral_of_the_lesser_of_stick_line_and_limit(k):
    """Pressure p0 (1 + k x), linear and positive: the limit mu p/c is a line
    in a, so the deflection is min(xi a, g(a)), one crossing at a1 =
    g(0)/(xi + s), s = -g'(a): T = -c W (xi a1^2/2 + the limit's integral
    from a1 to L), written out here."""
    xi = 3 * brush.slip_onset(EPS, MU, FN, L)
    p0, c = FN / (L * W), EPS / (L * W)
    g0, s = MU * p0 * (1 + k * L / 2) / c, MU * p0 * k / c
    a1 = g0 / (xi + s)
    assert 0 < a1 < L
    exact = -c * W * (xi * a1**2 / 2 + g0 * (L - a1) - s * (L**2 - a1**2) / 2)
    T = brush.steady_force_profile(lambda x: p0 * (1 + k * x), EPS, MU, L, W, xi)
    assert T == pytest.approx(exact, rel=1e-7)
    # more pressure where the deflection is large (the trailing end, k < 0) carries more
    even = brush.steady_force(EPS, MU, FN, L, xi)
    assert (abs(T) > abs(even)) == (k < 0)


def test_the_spin_coefficients_are_the_stick_deflections_sums():
    n = 400
    x = (np.arange(n) + 0.5) / n * L - L / 2
    y = (np.arange(n) + 0.5) / n * W - W / 2
    x, y = np.meshgrid(x, y)
    spin, eps1, eps2 = 0.2, 1e4, 2e4   # 1/m, N/m
    dA = L * W / n**2
    w1, w2 = -spin * y * (L / 2 - x), spin * (L**2 / 4 - x**2) / 2
    T1 = -(eps1 / (L * W)) * w1.sum() * dA
    T2 = -(eps2 / (L * W)) * w2.sum() * dA
    Mz = ((x * -(eps2 / (L * W)) * w2) - (y * -(eps1 / (L * W)) * w1)).sum() * dA
    kT2, kMz = brush.spin_coefficients(eps1, eps2, L, W)
    assert abs(T1) < 1e-12 * kT2 * spin
    assert T2 == pytest.approx(-kT2 * spin, rel=1e-5) and Mz == pytest.approx(-kMz * spin, rel=1e-5)
    assert math.isclose(kT2, eps2 * L**2 / 12) and math.isclose(kMz, eps1 * L * W**2 / 24)


@pytest.mark.parametrize("factor", [0.5, 1.0, 1.37, 4.0])
def test_slip_power_is_the_energy_balance(factor):
    """The friction's power is the body's work |T| |xi| vr less the elastic
    energy flux the leaving material takes, (mu p)^2/(2 c) W vr past the
    onset (the trailing edge on the limit); none in full adhesion."""
    xi, vr = factor * brush.slip_onset(EPS, MU, FN, L), 2.0
    T = brush.steady_force(EPS, MU, FN, L, xi)
    c, p = EPS / (L * W), FN / (L * W)
    leaving = (MU * p) ** 2 / (2 * c) * W * vr if factor >= 1 else c * (xi * L) ** 2 / 2 * W * vr
    assert brush.slip_power(EPS, MU, FN, L, xi, vr) == pytest.approx(abs(T) * xi * vr - leaving, rel=1e-12,
                                                                     abs=1e-12 * MU * FN * vr)
    assert brush.slip_power(EPS, MU, FN, L, -xi, -vr) == brush.slip_power(EPS, MU, FN, L, xi, vr)
