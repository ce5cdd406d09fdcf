"""The patch's closed forms (orthocontact.closed_forms.patch) against each
other and against sums written out here: the grid's torsional stiffness
against its own formula and the continuum, the polar quadrature against the
isotropic square's closed form and a brute-force midpoint sum, the midpoint
rule's rate."""
import math

import numpy as np
import pytest

from orthocontact.closed_forms import patch as cp
from orthocontact.closed_forms.paper import friction_tensor


@pytest.mark.parametrize("eps1,eps2,alpha", [(1e4, 1e4, 0.0), (1.2e4, 3e3, 0.7)])
@pytest.mark.parametrize("n1,n2", [(1, 1), (3, 2), (8, 5)])
def test_grid_stiffness_is_the_continuum_with_the_midpoints_second_moments(eps1, eps2, alpha, n1, n2):
    """The grid's sum is the continuum's with L^2 (1 - 1/n^2): the midpoints'
    mean square of a unit interval is (1 - 1/n^2)/12."""
    L, W = 0.3, 0.1
    k_grid = cp.torsional_stiffness_grid(eps1, eps2, alpha, L, W, n1, n2)
    shrunk = cp.torsional_stiffness(eps1, eps2, alpha, L * math.sqrt(1 - 1 / n1**2),
                                    W * math.sqrt(1 - 1 / n2**2))
    assert k_grid == pytest.approx(shrunk, rel=1e-13, abs=1e-13 * eps1 * L**2)


def test_isotropic_continuum_stiffness_is_the_polar_moment():
    assert cp.torsional_stiffness(5e3, 5e3, 1.1, 0.2, 0.1) == pytest.approx(5e3 * (0.04 + 0.01) / 12,
                                                                           rel=1e-15)


def test_grid_stiffness_converges_to_the_continuum_as_one_over_n_squared():
    k = cp.torsional_stiffness(1e4, 2e4, 0.3, 0.2, 0.1)
    errs = [k - cp.torsional_stiffness_grid(1e4, 2e4, 0.3, 0.2, 0.1, n, n) for n in (4, 8, 16)]
    assert all(e > 0 for e in errs)
    assert errs[0] / errs[1] == pytest.approx(4, rel=1e-9)
    assert errs[1] / errs[2] == pytest.approx(4, rel=1e-9)


def test_stick_torque_is_minus_k_sin_theta():
    L, W = 0.2, 0.1
    k = cp.torsional_stiffness(1e4, 1e4, 0.0, L, W)
    assert cp.stick_rotation_torque(1e4, L, W, 0.01) == pytest.approx(-k * math.sin(0.01), rel=1e-15)


@pytest.mark.parametrize("eps1,eps2,alpha", [(1e4, 1e4, 0.3), (1e4, 3e4, 0.0), (1e4, 3e4, math.pi / 2),
                                             (1e4, 3e4, 0.3)])
@pytest.mark.parametrize("n1,n2", [(5, 3), (4, 4), (1, 6)])
def test_stick_torque_of_any_stiffness_is_the_cells_sum(eps1, eps2, alpha, n1, n2):
    """The grid's stuck torque at finite theta against the sum of (R r) x
    (-w B (R - I) r) over the cells, written out; -k sin(theta) where the
    stiffness is isotropic or the grid's second moments are equal (a square
    of n x n cells), not otherwise."""
    L, W = 0.08, 0.08 if n1 == n2 else 0.05   # a square grid: S1 = S2
    B = np.array([[math.cos(alpha), -math.sin(alpha)], [math.sin(alpha), math.cos(alpha)]])
    B = B @ np.diag([eps1, eps2]) @ B.T
    k = cp.torsional_stiffness_grid(eps1, eps2, alpha, L, W, n1, n2)
    for theta in (1e-3, 0.2, -0.7):
        c, s = math.cos(theta), math.sin(theta)
        Mz = 0.0
        for i in range(n1):
            for j in range(n2):
                r = np.array([((i + 0.5) / n1 - 0.5) * L, ((j + 0.5) / n2 - 0.5) * W])
                Rr = np.array([c * r[0] - s * r[1], s * r[0] + c * r[1]])
                T = -B @ (Rr - r) / (n1 * n2)
                Mz += Rr[0] * T[1] - Rr[1] * T[0]
        got = cp.stick_rotation_torque_grid(eps1, eps2, alpha, L, W, n1, n2, theta)
        assert got == pytest.approx(Mz, rel=1e-12, abs=1e-15 * eps1 * L**2)
        if eps1 == eps2 or n1 == n2:
            assert got == pytest.approx(-k * s, rel=1e-12)
        elif theta == -0.7:
            assert abs(got / (-k * s) - 1) > 1e-3   # not -k sin(theta) at a finite turn


def test_quadrature_gives_the_isotropic_squares_closed_form():
    """mu N a (sqrt 2 + ln(1 + sqrt 2))/6, for both rules (isotropic: the same)."""
    for rule in ("associated", "coupled"):
        T1, T2, Mz = cp.full_slip_rotation(0.4, 0.4, 1e4, 1e4, 0.3, 1.0, rule, 0.5, 0.5, 3.0)
        assert Mz == pytest.approx(-cp.full_slip_torque_square(0.4, 3.0, 0.5), rel=1e-13)
        assert abs(T1) < 1e-14 and abs(T2) < 1e-14
    assert cp.FULL_SLIP_SQUARE_FACTOR == pytest.approx(0.38260, abs=5e-6)


@pytest.mark.parametrize("n1,n2,p", [(2, 2, (0.01, -0.004)), (3, 1, (-0.02, 0.0)), (1, 3, (0.0, 0.006)),
                                      (8, 8, (0.012, 0.005)), (4, 2, (0.004, 0.002)), (1, 1, (0.0, 0.0)),
                                      (32, 32, (-0.02, 0.003))])
def test_grid_normal_forces_have_resultant_n_and_first_moment_n_p(n1, n2, p):
    """Every grid, one cell along a side included: sum N_i = N and
    sum N_i (x_i, y_i) = N (p1, p2) to 1e-12, every N_i > 0 in the kern."""
    L, W, N = 0.2, 0.05, 7.0
    assert abs(p[0]) / L + abs(p[1]) / W <= 1 / 6
    Nc = cp.grid_normal_forces(L, W, n1, n2, N, *p)
    x, y = cp.cell_centres(L, W, n1, n2)
    assert Nc.sum() == pytest.approx(N, rel=1e-14)
    for r, pk, side in ((x, p[0], L), (y, p[1], W)):
        assert np.sum(Nc * r) == pytest.approx(N * pk, rel=1e-12, abs=1e-15 * N * side)
    assert np.all(Nc > 0)


def test_the_continuums_pressure_sampled_at_the_centres_falls_short_by_one_minus_one_over_n_squared():
    """Why the grid has its own pressure: 12 p1 x / L^2 sampled at the cell
    centres gives the first moment N p1 (1 - 1/n1^2), 25 % short at n1 = 2."""
    L, W, N, p1 = 0.2, 0.05, 7.0, 0.01
    for n in (2, 3, 8):
        x, _ = cp.cell_centres(L, W, n, 1)
        sampled = N / n * (1 + 12 * p1 * x / L**2)
        assert np.sum(sampled * x) == pytest.approx(N * p1 * (1 - 1 / n**2), rel=1e-13)
        assert np.sum(cp.grid_normal_forces(L, W, n, 1, N, p1) * x) == pytest.approx(N * p1, rel=1e-13)


def test_a_side_of_one_cell_carries_no_centre_of_pressure_unless_open():
    with pytest.raises(ValueError, match="n1 = 1: its cells all lie on the axis"):
        cp.grid_normal_forces(0.2, 0.05, 1, 4, 7.0, 0.001, 0.0)
    with pytest.raises(ValueError, match="n2 = 1"):
        cp.grid_normal_forces(0.2, 0.05, 4, 1, 7.0, 0.0, -0.001)
    # open (N <= 0): no pressure, p not looked at, outside the kern too
    for N in (0.0, -3.0):
        assert cp.grid_normal_forces(0.2, 0.05, 1, 4, N, 5.0, -2.0) == pytest.approx(np.full(4, N / 4))


@pytest.mark.parametrize("n1,n2", [(2, 2), (3, 1), (8, 8), (4, 2)])
def test_full_slip_in_translation_is_mu_n_at_the_centre_of_pressure(n1, n2):
    """Isotropic mu, every cell sliding along s: the grid's sum of
    r_i x (-mu N_i s) is full_slip_translation's p x T, to rounding."""
    L, W, N, mu = 0.2, 0.05, 7.0, 0.4
    p = (0.01, -0.003 if n2 > 1 else 0.0)
    x, y = cp.cell_centres(L, W, n1, n2)
    Nc = cp.grid_normal_forces(L, W, n1, n2, N, *p)
    for psi in (0.0, 0.7, 2.5, -1.2):
        s = np.array([math.cos(psi), math.sin(psi)])
        T1, T2, Mz = cp.full_slip_translation(mu, N, *p, psi)
        assert (T1, T2) == pytest.approx(tuple(-mu * N * s), rel=1e-15)
        grid = np.sum(x * (-mu * Nc * s[1]) - y * (-mu * Nc * s[0]))
        assert grid == pytest.approx(Mz, rel=1e-12, abs=1e-15 * mu * N * L)
    # the sign: pressed ahead (p1 > 0) and pushed along +X2, the body is turned clockwise
    assert cp.full_slip_translation(mu, N, 0.01, 0.0, math.pi / 2)[2] < 0


def _brute_midpoint(mu1, mu2, eps1, eps2, alpha, beta, rule, L, W, N, n, p1, p2):
    """The steady force summed point by point in plain Python: q parallel
    to H v with |q|_F = N_c, H = F^-1 (associated) or B F B (coupled)."""
    F = friction_tensor(mu1, mu2, beta)
    c, s = math.cos(alpha), math.sin(alpha)
    Q = np.array([[c, -s], [s, c]])
    B = Q @ np.diag([eps1, eps2]) @ Q.T
    H = np.linalg.inv(F) if rule == "associated" else B @ F @ B
    T, Mz = np.zeros(2), 0.0
    # the grid's second moments, summed: the pressure's first moment is N p on the grid
    S1 = sum((((i + 0.5) / n - 0.5) * L) ** 2 for i in range(n)) / n
    W_S2 = sum((((j + 0.5) / n - 0.5) * W) ** 2 for j in range(n)) / n
    for i in range(n):
        for j in range(n):
            x, y = ((i + 0.5) / n - 0.5) * L, ((j + 0.5) / n - 0.5) * W
            Nc = N / n**2 * (1 + p1 * x / S1 + p2 * y / W_S2)
            q = H @ np.array([-y, x])
            q = Nc * q / math.sqrt(q @ F @ q)
            T -= q
            Mz -= x * q[1] - y * q[0]
    return T[0], T[1], Mz


ORTHO = dict(mu1=0.3, mu2=0.7, eps1=1e4, eps2=3e4, alpha=0.4, beta=1.0)


@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_grid_sum_is_the_brute_force_midpoint_sum(rule):
    o = ORTHO
    args = (o["mu1"], o["mu2"], o["eps1"], o["eps2"], o["alpha"], o["beta"], rule, 0.2, 0.1, 2.0)
    grid = cp.full_slip_rotation_grid(*args, 6, 6, p1=0.01, p2=-0.005)
    brute = _brute_midpoint(*args, 6, 0.01, -0.005)
    assert grid == pytest.approx(brute, rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_midpoint_grid_converges_to_the_quadrature(rule):
    """Orthotropic mu, linear pressure: the grid's resultant tends to the
    quadrature; with a mild contrast at the midpoint rule's rate, 1/n^2."""
    mild = dict(mu1=0.4, mu2=0.6, eps1=1e4, eps2=1.5e4, alpha=0.4, beta=1.0)
    for o, rate in ((mild, True), (ORTHO, False)):
        args = (o["mu1"], o["mu2"], o["eps1"], o["eps2"], o["alpha"], o["beta"], rule, 0.2, 0.1, 2.0)
        exact = np.array(cp.full_slip_rotation(*args, p1=0.01, p2=-0.005))
        # the quadrature itself has converged
        assert exact == pytest.approx(np.array(cp.full_slip_rotation(*args, p1=0.01, p2=-0.005,
                                                                       points=768)), rel=1e-13)
        errs = [abs(cp.full_slip_rotation_grid(*args, n, n, p1=0.01, p2=-0.005)[2] - exact[2])
                for n in (32, 64, 128)]
        assert errs[0] > errs[1] > errs[2] and errs[2] < 1e-4 * abs(exact[2])
        if rate:
            assert errs[0] / errs[1] == pytest.approx(4, rel=0.1)
            assert errs[1] / errs[2] == pytest.approx(4, rel=0.1)


def test_pressure_centre_moves_the_resultant_by_the_quadratures_linear_part():
    """The linear pressure's share: the quadrature with (p1, p2) minus the
    uniform one is linear in (p1, p2)."""
    args = (0.3, 0.7, 1e4, 3e4, 0.4, 1.0, "associated", 0.2, 0.1, 2.0)
    base = np.array(cp.full_slip_rotation(*args))
    a = np.array(cp.full_slip_rotation(*args, p1=0.01)) - base
    b = np.array(cp.full_slip_rotation(*args, p1=0.02)) - base
    assert b == pytest.approx(2 * a, rel=1e-12, abs=1e-16)
    assert np.abs(a).max() > 1e-4
