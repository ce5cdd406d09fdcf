"""The planar body on the ContactPatch FMU (orthocontact.rig.planar) through
the real FMU against the closed forms of closed_forms.patch and
closed_forms.paper: the twist test's elastic slope and full-slip plateau,
the towed block's steady yaw at several mat angles under both rules."""
import math

import numpy as np
import pytest

from orthocontact.closed_forms.paper import G_STANDARD, steady_tan_phi
from orthocontact.closed_forms.patch import torsional_stiffness_grid
from orthocontact.fmu.params import ContactParams
from orthocontact.fmu.patch import PatchGeometry
from orthocontact.rig import planar

MASS = 1.875            # the paper's steel block [kg]
N = MASS * G_STANDARD


def mat(a_deg, rule, eps2=1e4):
    """The aged mat of scenarios/mat_aged.toml at mat angle a: beta = a,
    alpha = a + 90 deg, eps1/eps2 = 1.251."""
    return ContactParams.from_degrees(0.408, 0.625, 1.251 * eps2, eps2, a_deg + 90.0, a_deg, rule)


def block(n1=8, n2=4):
    return planar.PlanarBody.uniform(MASS, PatchGeometry(0.1, 0.05, n1, n2), N)


# -- the twist test --------------------------------------------------------------------


@pytest.mark.parametrize("fmi_version", [2, 3])
@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_twist_starts_on_the_grids_torsional_stiffness(rule, fmi_version):
    """While every cell sticks, -Mz / theta = k (1 + c theta) with k the
    grid's exact torsional stiffness (the arm R r adds the first-order term):
    extrapolated from theta and 2 theta it is k to O(theta^2)."""
    p, body = mat(39.2, rule, eps2=1e5), block()
    r = planar.twist(p, body, rate_rad_s=1.0, angle_rad=0.02, step_s=1e-4, fmi_version=fmi_version)
    stick = r.contact_state == 1
    assert stick[:2].all() and not stick.all()   # the test passes through the onset of slip
    slope = -r.Mz[:2] / r.theta[:2]
    k = torsional_stiffness_grid(p.eps1, p.eps2, p.alpha, 0.1, 0.05, 8, 4)
    assert planar.twist_stiffness(p, body.patch) == k
    assert 2 * slope[0] - slope[1] == pytest.approx(k, rel=1e-6)
    assert slope == pytest.approx(k, rel=3 * r.theta[1])    # and within the first-order term


@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_twist_reaches_the_full_slip_plateau_as_the_elastic_lag_fades(rule):
    """Past the onset (theta >= 0.05 rad, five times the angle at which the
    innermost cell slides) every cell slides and Mz is the grid's steady
    full-slip torque with the texture seen turned by -theta, up to the
    elastic lag: a cell trails its circular path by l = mu N / eps, an error
    below l / r_mean (r_mean = (length + width) / 4) that falls with l."""
    body = block()
    errs = []
    for eps2 in (1e5, 1e6):
        p = mat(39.2, rule, eps2=eps2)
        r = planar.twist(p, body, rate_rad_s=1.0, angle_rad=0.5, step_s=1e-4)
        past = r.theta >= 0.05
        assert (r.contact_state[past] == 3).all() and (r.slip_fraction[past] == 1.0).all()
        th, Mz = r.theta[past][::100], r.Mz[past][::100]
        plateau = planar.twist_plateau(p, body, th)
        assert np.all(plateau < 0)                 # turning counterclockwise, held back
        assert np.ptp(plateau) > 0.05 * abs(plateau).max()   # the texture makes the plateau vary
        lag = max(p.mu1, p.mu2) * N / min(p.eps1, p.eps2) / ((0.1 + 0.05) / 4)
        rel = np.abs(Mz / plateau - 1)
        assert rel.max() < lag, (eps2, rel.max(), lag)
        errs.append(rel.max())
    assert errs[1] < errs[0] / 3


def test_twist_records_each_cells_state_in_fmi_3_as_the_scalars_count_them():
    """cells=True: every step's (n1, n2) states; with equal cells, the share
    slipping is slipFraction and contactState says none, some or all; the
    same torque as without them.  FMI 2.0 has no arrays: refused."""
    p, body = mat(39.2, "coupled", eps2=1e5), block()
    r = planar.twist(p, body, rate_rad_s=1.0, angle_rad=0.06, step_s=1e-3, fmi_version=3, cells=True)
    assert r.cell_state.shape == (60, 8, 4)
    slipping = (r.cell_state == 2).mean(axis=(1, 2))
    np.testing.assert_array_equal(slipping, r.slip_fraction)
    np.testing.assert_array_equal(np.where(slipping == 0, 1, np.where(slipping == 1, 3, 2)), r.contact_state)
    assert set(r.contact_state) == {1, 2, 3}
    plain = planar.twist(p, body, rate_rad_s=1.0, angle_rad=0.06, step_s=1e-3, fmi_version=3)
    np.testing.assert_array_equal(plain.Mz, r.Mz)
    assert plain.cell_state is None
    with pytest.raises(ValueError, match="FMI 2.0 has no arrays"):
        planar.twist(p, body, rate_rad_s=1.0, angle_rad=0.06, step_s=1e-3, fmi_version=2, cells=True)


def test_twist_refuses_a_rate_that_is_not_positive():
    with pytest.raises(ValueError, match="rate_rad_s must be a finite number > 0"):
        planar.twist(mat(0.0, "coupled"), block(), rate_rad_s=0.0, angle_rad=0.1, step_s=1e-3)


# -- the towed block ---------------------------------------------------------------------


def towed(p, body=None, step_s=5e-3, duration_s=20.0, **kw):
    return planar.towed_block(p, body or block(4, 2), velocity_m_s=0.244, pin_m=0.1,
                              duration_s=duration_s, step_s=step_s, **kw)


@pytest.mark.parametrize("rule", ["associated", "coupled"])
@pytest.mark.parametrize("a_deg", [20.0, 39.2, 60.0])
def test_towed_block_settles_at_the_yaw_of_the_steady_sliding_force(a_deg, rule):
    """Pulled along X1 from theta = 0 at rest, the block turns and settles
    where its axis lines up with the law's steady sliding force for sliding
    along X1 (the closed form steady_yaw); the same yaw solves the paper's
    relation read from the force's side, theta = -phi(alpha - theta,
    beta - theta).  Tolerance 1e-9 rad: the steady state depends neither on
    the grid nor on the step (test below); what is left after 20 s is the
    transient, which falls by e every ~0.6 s from at most 0.4 rad."""
    p = mat(a_deg, rule)
    r = towed(p)
    yaw = planar.steady_yaw(p)
    assert abs(yaw) > math.radians(5)           # the texture turns the block visibly
    assert abs(planar.steady_yaw_residual(p, yaw)) < 1e-14
    assert r.theta[-1] == pytest.approx(yaw, abs=1e-9)
    assert abs(r.omega[-1]) < 1e-9
    assert r.slip_fraction[-1] == 1.0
    # the pin pulls with -T: along the body's axis, ahead
    pull = -np.array([r.T1[-1], r.T2[-1]])
    assert math.atan2(pull[1], pull[0]) == pytest.approx(yaw, abs=1e-9)
    assert abs(r.Mz[-1]) < 1e-9 * N * 0.1       # uniform sliding: no moment about the centre


@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_the_papers_phi_comes_back_as_the_towed_blocks_yaw(rule):
    """The paper's phi at mat angle a0 (force along X1, slip at phi) is the
    towed block's steady state turned by -phi: towed at mat angle a0 - phi
    the block settles at yaw -phi.  Checked through the FMU against
    closed_forms.paper alone, at the paper's extremal angle 39.2 deg."""
    a0 = 39.2
    p0 = mat(a0, rule)
    phi = math.degrees(math.atan(steady_tan_phi(p0.mu1, p0.mu2, p0.eps1, p0.eps2, p0.alpha, p0.beta, rule)))
    r = towed(mat(a0 - phi, rule))
    assert r.theta[-1] == pytest.approx(math.radians(-phi), abs=1e-9)


def test_towed_block_steady_yaw_depends_neither_on_grid_nor_on_step():
    """Every cell carries the same force in uniform sliding, and backward
    Euler's fixed point is the continuous steady state: another grid, another
    step, the FMI 3.0 FMU settle at the same yaw."""
    p = mat(20.0, "associated")
    yaw = planar.steady_yaw(p)
    runs = [towed(p), towed(p, body=block(8, 4)), towed(p, step_s=1e-2),
            towed(p, fmi_version=3)]
    for r in runs:
        assert r.theta[-1] == pytest.approx(yaw, abs=1e-9)
    # the transients differ (the grid and step do matter there) ...
    assert abs(runs[0].theta[100] - runs[1].theta[100]) > 1e-6


def test_towed_block_pulled_along_another_direction_turns_with_it():
    """Turning the motion and the texture together by 30 deg turns the
    steady yaw by 30 deg (frame invariance)."""
    p = mat(39.2, "coupled")
    turned = p.replace(alpha=p.alpha + math.radians(30), beta=p.beta + math.radians(30))
    yaw = planar.steady_yaw(p)
    assert planar.steady_yaw(turned, math.radians(30)) == pytest.approx(yaw + math.radians(30), abs=1e-12)
    r = towed(turned, direction_rad=math.radians(30), theta0_rad=math.radians(30))
    assert r.theta[-1] == pytest.approx(yaw + math.radians(30), abs=1e-9)


def test_towed_block_refuses_a_pin_not_ahead_of_the_centre():
    with pytest.raises(ValueError, match="pin_m must be a finite number > 0"):
        planar.towed_block(mat(0.0, "coupled"), block(), velocity_m_s=0.2, pin_m=-0.1,
                           duration_s=1.0, step_s=1e-3)


# -- the towed block's implicit step: a root wherever the law bounds the moment ------------------


def test_a_high_friction_tow_whose_newton_had_no_descent_settles_on_the_closed_form():
    """mu1 = 3.0 (inside the usual range) on scenarios/towed_block.toml's
    block, pin and step, coupled at 15 deg: at t = 0.02 s the step's tangent
    dR/dtheta is negative at Newton's iterate (a cell's stick-slip switch),
    where the harness raised RuntimeError.  It now bisects there, and the
    yaw settles at the closed form (an FMU coupled explicitly at 1 ms
    settles there too)."""
    body = planar.PlanarBody.uniform(MASS, PatchGeometry(0.05, 0.025, 4, 2), N)
    p = ContactParams.from_degrees(3.0, 0.625, 1.251e5, 1e5, 15.0 + 90.0, 15.0, "coupled")
    r = planar.towed_block(p, body, velocity_m_s=0.244, pin_m=0.015, duration_s=30.0, step_s=1e-2)
    assert r.theta[-1] == pytest.approx(planar.steady_yaw(p), abs=1e-9)
    assert abs(math.degrees(r.theta[-1])) > 60   # the block turned far: mu1 / mu2 = 4.8


def test_step_root_bisects_where_newton_leaves_its_bracket_or_stalls():
    """R = cbrt(x - 0.1): Newton from any x != 0.1 overshoots by twice its
    distance and diverges; with the bracket it converges to tol."""
    calls = []

    def cube_root(x):
        calls.append(x)
        d = x - 0.1
        return math.copysign(abs(d) ** (1 / 3), d), (abs(d) ** (-2 / 3) / 3 if d else math.inf)
    x = planar.step_root(cube_root, 1.0, 2.0, 1e-13, 30)
    assert abs(x - 0.1) <= 1e-13 and len(calls) < 100


def test_step_root_bisects_where_the_tangent_has_the_wrong_sign():
    """A kink whose one-sided tangent points away from the root (as a cell
    switching from stick to slip can give): Newton has no descent there."""
    def kinked(x):
        return (x - 0.25, -1.0) if x > 0.3 else (x - 0.25, 1.0)
    assert planar.step_root(kinked, 1.0, 1.0, 1e-13, 30) == pytest.approx(0.25, abs=1e-13)


def test_step_root_refuses_a_residual_it_cannot_bracket_in_one_line():
    """A non-finite residual, or ends whose signs break the law's bound:
    StepNotSolved (an InputError: one line naming the cause), never a
    RuntimeError's traceback."""
    from orthocontact.errors import InputError
    assert issubclass(planar.StepNotSolved, InputError)
    with pytest.raises(planar.StepNotSolved, match="residual is nan"):
        planar.step_root(lambda x: (math.nan, 1.0), 0.0, 1.0, 1e-13, 30)
    with pytest.raises(planar.StepNotSolved, match="beyond the bound of the law's forces"):
        planar.step_root(lambda x: (x - 5.0, -1.0), 0.0, 1.0, 1e-13, 30)
