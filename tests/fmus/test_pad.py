"""The ContactPad FMU through fmpy (orthocontact.fmu.pad), both FMI versions,
against independent truths: closed_forms.pad's exact integrals of the
foundation (full contact, lift-off, a turned pad) on every grid, the
ContactPatch FMU with N = kn A d under uniform pressure, the friction's
moment converging at the grid's second order, central differences for the
directional derivatives, a block settling on the pad and the explicit
couplings' step limits; the damping's rate over the previous step, a
pressure that never pulls, a state restored mid-run."""
import math

import numpy as np
import pytest

from orthocontact.closed_forms import pad as cpad
from orthocontact.fmu.contact import FMUError
from orthocontact.fmu.pad import WRENCH, Foundation, PadFMU
from orthocontact.fmu.params import ContactParams
from orthocontact.fmu.patch import PatchFMU, PatchGeometry

AGED = ContactParams.from_degrees(0.408, 0.625, 1.251e4, 1e4, 129.2, 39.2, "coupled")
ISO = ContactParams(0.5, 0.5, 1e4, 1e4, 0.0, 0.0, "coupled")
L, W, KN = 0.09, 0.06, 2e8
STIFF = Foundation(KN)
GRIDS = [(1, 1), (2, 3), (8, 8), (5, 1), (32, 32)]


@pytest.fixture(params=[2, 3])
def version(request):
    return request.param


def pad(version, grid=(8, 8), params=AGED, foundation=STIFF, pose=(0.0,) * 6, size=(L, W)):
    """A pad FMU initialized at `pose` (the caller closes it)."""
    f = PadFMU(fmi_version=version)
    f.initialize(params, PatchGeometry(*size, *grid), foundation, pose)
    return f


def wrench(f) -> dict:
    return dict(zip(WRENCH, f.load()))


@pytest.mark.parametrize("grid", GRIDS)
def test_full_contact_is_kn_a_d_and_the_tilt_stiffnesses_on_every_grid(version, grid):
    """Fn = kn A d, M1 = -kn phi1 L W^3/12, M2 = -kn phi2 W L^3/12: the
    continuum's, exact (not the grid's second moments)."""
    k1, k2 = cpad.tilt_stiffness(KN, L, W)
    with pad(version, grid) as f:
        for d, phi1, phi2 in ((1e-4, 0.0, 0.0), (1e-4, 2e-4, -3e-4), (3e-5, -1e-4, 5e-4)):
            assert cpad.in_full_contact(L, W, d, phi1, phi2)
            f.set_inputs(0.0, 0.0, 0.0, d, phi1, phi2)
            w = wrench(f)
            assert w["Fn"] == pytest.approx(KN * L * W * d, rel=1e-12)
            assert w["M1"] == pytest.approx(-k1 * phi1, rel=1e-12, abs=1e-12 * w["Fn"] * L)
            assert w["M2"] == pytest.approx(-k2 * phi2, rel=1e-12, abs=1e-12 * w["Fn"] * L)
            assert f.outputs()["contactFraction"] == 1.0


POSES = [(0.0, 5e-5, 0.0, 4e-3), (0.4, 5e-5, 1e-3, 3e-3), (-1.1, 2e-5, -2e-3, 1e-3),
         (2.0, -1e-5, 1e-3, 2e-3), (0.0, -1e-4, 0.0, 1e-3)]


@pytest.mark.parametrize("grid", GRIDS)
def test_lift_off_is_the_continuums_clipped_integral_on_every_grid(version, grid):
    """The cells the lift-off line crosses are clipped exactly: Fn, M1, M2
    and the contact fraction are the continuum's (closed_forms.pad.clipped,
    written independently) to 1e-12 on every grid, turned pads included, a
    lifted pad 0 and every cell open."""
    with pad(version, grid) as f:
        for theta, d, phi1, phi2 in POSES:
            f.set_inputs(0.0, 0.0, theta, d, phi1, phi2)
            w = wrench(f)
            Fn, M1, M2 = cpad.clipped(KN, L, W, d, phi1, phi2, theta)
            scale = max(Fn, 1e-300)
            assert w["Fn"] == pytest.approx(Fn, rel=1e-12, abs=1e-300)
            assert abs(w["M1"] - M1) <= 1e-12 * scale * L and abs(w["M2"] - M2) <= 1e-12 * scale * L
            frac = f.outputs()["contactFraction"]
            assert frac == pytest.approx(cpad.contact_fraction(L, W, d, phi1, phi2, theta), abs=1e-13)
            if Fn == 0:
                assert f.outputs()["contactState"] == 0 and frac == 0.0


def test_the_fmi3_cells_carry_the_normal_forces_and_lifted_cells_open():
    with pad(3, (6, 4)) as f:
        d, phi2 = 2e-5, 2e-3                       # lifts where x < -0.01 m
        f.set_inputs(3e-4, 0.0, 0.0, d, 0.0, phi2)
        cells, states = np.array(f.cell_normal_forces()), np.array(f.cell_states())
        assert cells.sum() == pytest.approx(wrench(f)["Fn"], rel=1e-14)
        x_right = (np.arange(6) + 1) / 6 * L - L / 2          # each column's leading edge
        lifted = x_right <= -d / phi2
        assert lifted.any() and not lifted.all()
        assert np.all(cells[lifted] == 0) and np.all(states[lifted] == 0)
        assert np.all(cells[~lifted] > 0) and np.all(states[~lifted] > 0)


@pytest.mark.parametrize("grid", [(1, 1), (4, 3), (8, 8)])
def test_without_tilt_the_pad_is_the_patch_pressed_with_kn_a_d(version, grid):
    """Uniform pressure: T1, T2, Mz of the pad are the patch's with
    N = kn A d, p = 0, along a path that sticks, slides and turns."""
    d = 1e-5
    N = KN * L * W * d
    with pad(version, grid, pose=(0, 0, 0, d, 0, 0)) as f, PatchFMU(fmi_version=version) as p:
        p.initialize(AGED, PatchGeometry(L, W, *grid), (0.0, 0.0, 0.0, N))
        slid = False
        for k in range(1, 60):
            u1, u2, th = 3e-5 * k, 1e-5 * k * math.sin(0.2 * k), 2e-3 * math.sin(0.1 * k)
            f.set_inputs(u1, u2, th, d)
            p.set_inputs(u1, u2, th, N)
            got, want = f.load()[:3], p.load()
            assert got == pytest.approx(want, rel=1e-12, abs=1e-12 * N * L)
            slid |= f.outputs()["contactState"] >= 2
            f.do_step(1e-3)
            p.do_step(1e-3)
        assert slid


def sliding_moment(version, grid, d, phi2):
    """Mz of the pad (isotropic mu = 0.5) slid along X2 in one step from
    rest, every pressed cell at its limit, tilted about X2."""
    with pad(version, grid, params=ISO, pose=(0, 0, 0, d, 0, phi2)) as f:
        f.set_inputs(0.0, 0.05, 0.0, d, 0.0, phi2)
        return f.load()[2], wrench(f)["M2"]


def test_the_frictions_moment_converges_at_the_grids_second_order(version):
    """Every cell's friction acts at its centre: in full slip along X2 with
    isotropic mu the moment is -mu sum N_i x_i, the continuum's mu M2 short
    by exactly 1/n1^2 in full contact (the cells' own second moments), and
    converging as 1/n1^2 under lift-off."""
    mu = 0.5
    for n in (2, 4, 8):
        Mz, M2 = sliding_moment(version, (n, 3), 1e-4, 2e-4)
        assert Mz == pytest.approx(mu * M2 * (1 - 1 / n**2), rel=1e-11)
    _, M2 = sliding_moment(version, (4, 3), 2e-5, 2e-3)
    errors = [abs(sliding_moment(version, (n, 3), 2e-5, 2e-3)[0] / (mu * M2) - 1) for n in (8, 16, 32)]
    assert 3.0 < errors[0] / errors[1] < 5.0 and 3.0 < errors[1] / errors[2] < 5.0


def central(f, base, k, outputs, h):
    x = list(base)
    x[k] += h
    f.set_inputs(*x)
    up = np.array([wrench(f)[o] for o in outputs])
    x[k] -= 2 * h
    f.set_inputs(*x)
    down = np.array([wrench(f)[o] for o in outputs])
    f.set_inputs(*base)
    return (up - down) / (2 * h)


@pytest.mark.parametrize("case", ["stick", "slip", "lift-off", "damped", "damped closing"])
def test_directional_derivatives_match_central_differences(version, case):
    """d(T1, T2, Mz, Fn, M1, M2)/d(u1, u2, theta, d, phi1, phi2) of the
    pending step against central differences of the pending outputs (the
    pose away from any cell's switch between stick and slip or contact).
    Damped closing: the pad came down 20 um in the last step, so the
    damper presses where the rate term alone would reach past the touching
    line (delta = 0), which bounds the pressed part: the pressure's jump
    there moves with the pose."""
    foundation = Foundation(KN, 5e4 if case.startswith("damped") else 0.0)
    lift = case in ("lift-off", "damped closing")
    start = (1e-5, 0.0, 1e-3, 2e-5, 5e-4, 2e-3) if lift else (1e-5, 0.0, 1e-3, 1e-4, 2e-4, 5e-4)
    if case == "damped closing":
        start = (0.0, 0.0, 0.0, -1e-5, 0.0, 1e-3)
    push = 1e-7 if case == "stick" else 2e-2   # the elastic length mu N / eps: ~5 mm
    base = (start[0] + push, -0.5 * push, start[2] + 3 * push, start[3] * 1.1, start[4] * 0.9,
            start[5] * 1.05)
    if case == "damped closing":
        base = (push, -0.5 * push, 3 * push, 1e-5, 1e-4, 1e-3)
    with pad(version, (6, 5), foundation=foundation, pose=start) as f:
        f.do_step(1e-3)
        f.set_inputs(*base)
        J = np.array(f.jacobian(f.INPUTS))
        state = f.outputs()["contactState"]
        assert state == (1 if case == "stick" else 3)
        assert (f.outputs()["contactFraction"] < 1) == lift
        if case == "damped closing":   # the share where delta > 0 (the rate term reaches further)
            assert f.outputs()["contactFraction"] == pytest.approx(
                cpad.contact_fraction(L, W, *base[3:], base[2]), rel=1e-12)
        for k, name in enumerate(f.INPUTS):
            h = 1e-7 * max(abs(base[k]), 1e-4)
            fd = central(f, base, k, WRENCH, h)
            scale = np.abs(J).max(axis=1) + 1e-300
            assert np.all(np.abs(J[:, k] - fd) <= 1e-6 * scale), (name, J[:, k], fd)


def test_damping_takes_the_rate_over_the_previous_step_and_never_pulls(version):
    """Fn = kn A d + dn A (d - d_prev)/h_prev: none before the first step,
    then the previous step's size; a pad withdrawn faster than the
    foundation follows is not pulled (Fn = 0, every cell open)."""
    dn = 1e5
    A = L * W
    with pad(version, (4, 4), foundation=Foundation(KN, dn), pose=(0, 0, 0, 1e-5, 0, 0)) as f:
        f.set_inputs(0, 0, 0, 2e-5)
        assert wrench(f)["Fn"] == pytest.approx(KN * A * 2e-5, rel=1e-13)   # no step yet: no rate
        f.do_step(2e-3)
        f.set_inputs(0, 0, 0, 3e-5)
        assert wrench(f)["Fn"] == pytest.approx(KN * A * 3e-5 + dn * A * 1e-5 / 2e-3, rel=1e-12)
        f.do_step(1e-3)
        f.do_step(1e-3)                              # held: no rate left
        assert wrench(f)["Fn"] == pytest.approx(KN * A * 3e-5, rel=1e-12)
        f.set_inputs(0, 0, 0, 5e-6)                  # withdrawn at 25 mm/s: dn A v > kn A d
        assert wrench(f)["Fn"] == 0.0 and f.outputs()["contactState"] == 0
        assert f.outputs()["contactFraction"] == 0.0


def test_a_damped_pad_that_approaches_and_never_touches_carries_nothing(version):
    """Closing at 0.1 m/s from 0.2 mm above, dn = 1e5 N s/m^3 (dn/kn = 0.5
    ms: dn v is the pressure of 50 um of approach): no point touches, so
    nothing presses (a Kelvin-Voigt layer presses only where it touches),
    however fast it comes; at the touch the damper's pressure dn v appears
    at once over the area that touches."""
    dn, v, h = 1e5, 0.1, 1e-4
    with pad(version, (4, 4), foundation=Foundation(KN, dn), pose=(0, 0, 0, -2e-4, 0, 0)) as f:
        for k in range(1, 20):
            f.do_step(h)
            f.set_inputs(0, 0, 0, -2e-4 + v * h * k)
            assert wrench(f)["Fn"] == 0.0 and f.outputs()["contactFraction"] == 0.0, k
        f.do_step(h)
        f.set_inputs(0, 0, 0, 1e-5)          # 10 um in, from 10 um above
        assert wrench(f)["Fn"] == pytest.approx(L * W * (KN * 1e-5 + dn * 2e-5 / h), rel=1e-12)


def brute_touching(d, phi2, rate_d, rate_phi2, dn, n=200_000):
    """Fn of a damped layer by the midpoint rule along the length (no
    turn, phi1 = 0): kn delta + dn delta', clipped at 0, where delta > 0."""
    x = (np.arange(n) + 0.5) / n * L - L / 2
    delta = d + phi2 * x
    p = np.where(delta > 0, np.maximum(KN * delta + dn * (rate_d + rate_phi2 * x), 0.0), 0.0)
    return p.sum() * L / n * W


def test_a_tilted_pad_closing_presses_where_it_touches_by_spring_and_damper(version):
    """Tilted and closing: the pressed part is where the approach is > 0 and
    the pressure with its rate term too, each cell's share exact (the
    midpoint rule on 200 000 strips: first order at the lines, 1e-7)."""
    dn, h = 5e4, 1e-3
    with pad(version, (6, 5), foundation=Foundation(KN, dn), pose=(0, 0, 0, -1e-5, 0, 1e-3)) as f:
        f.do_step(h)
        f.set_inputs(0, 0, 0, 1e-5, 0, 1.2e-3)
        Fn = wrench(f)["Fn"]
        assert Fn == pytest.approx(brute_touching(1e-5, 1.2e-3, 2e-5 / h, 0.2e-3 / h, dn), rel=1e-6)
        # where delta > 0: x > -d/phi2, whatever the rate term adds below
        assert f.outputs()["contactFraction"] == pytest.approx((L / 2 + 1e-5 / 1.2e-3) / L, rel=1e-12)


def test_the_damping_rate_is_exact_for_a_ramp_over_steps_of_varying_size(version):
    """Steps alternating 0.1 and 0.2 ms, the approach ramped at 10 mm/s and
    set at each step's start (the FMI's convention): every step's damping
    pressure is dn v exactly, the backward difference over the step that
    brought the inputs, whatever the sizes."""
    dn, v = 1e5, 0.01
    with pad(version, (4, 4), foundation=Foundation(KN, dn), pose=(0, 0, 0, 1e-5, 0, 0)) as f:
        t = 0.0
        for k in range(12):
            d = 1e-5 + v * t
            f.set_inputs(0, 0, 0, d)
            if k > 0:
                assert wrench(f)["Fn"] - KN * L * W * d == pytest.approx(dn * L * W * v, rel=1e-9), k
            h = (1e-4, 2e-4)[k % 2]
            f.do_step(h)
            t += h


def test_dissipated_energy_counts_the_dampers_work(version):
    """Pressed and pumped in full contact (d = 20 +- 5 um), steps of 0.1 and
    0.2 ms: no cell slips, so the energy is the damper's alone, each step
    the damping pressure dn (d - d_prev)/h_prev over the change d - d_prev
    on the whole area, summed here from the inputs (to 1e-12); it grows
    with every step that moves and never falls."""
    dn = 1e5
    with pad(version, (4, 4), foundation=Foundation(KN, dn), pose=(0, 0, 0, 2e-5, 0, 0)) as f:
        t, d_prev, h_prev, expected, last = 0.0, 2e-5, None, 0.0, 0.0
        for k in range(40):
            d = 2e-5 + 5e-6 * math.sin(2 * math.pi * t / 2e-3)
            f.set_inputs(0, 0, 0, d)
            if h_prev is not None:
                expected += dn * L * W * (d - d_prev) ** 2 / h_prev
            energy = f.outputs()["dissipatedEnergy"]
            assert energy == pytest.approx(expected, rel=1e-12, abs=1e-18) and energy >= last, k
            assert f.outputs()["slipFraction"] == 0.0
            last, h_prev, d_prev = energy, (1e-4, 2e-4)[k % 2], d
            f.do_step(h_prev)
            t += h_prev
        assert expected > 0


def test_a_state_restored_mid_run_continues_bit_for_bit_rate_included(version):
    """The damping's reference pose and step size travel in the state."""
    def path(f, k):
        return (1e-5 * k, 0.0, 1e-3 * k, 1e-5 + 2e-6 * math.sin(k), 1e-4 * math.cos(k), 0.0)

    with pad(version, (4, 3), foundation=Foundation(KN, 2e5)) as f, \
            pad(version, (4, 3), foundation=Foundation(KN, 2e5)) as g:
        for k in range(5):
            f.set_inputs(*path(f, k))
            f.do_step(1e-3)
        blob = bytes(f._slave.serializeFMUState(f._slave.getFMUState()))
        g.time = f.time
        rest = []
        for k in range(5, 10):
            f.set_inputs(*path(f, k))
            rest.append(f.load())
            f.do_step(1e-3)
        g._slave.setFMUState(g._slave.deserializeFMUState(blob))
        for k in range(5, 10):
            g.set_inputs(*path(g, k))
            assert g.load() == rest[k - 5]
            g.do_step(1e-3)


def linear_scheme(h, k, m, x0, steps, force0=0.0):
    """Symplectic Euler on m x'' = force0 - k x from rest at x0: x at each step."""
    x, v, out = x0, 0.0, []
    for _ in range(steps):
        v += h * (force0 - k * x) / m
        x += h * v
        out.append(x)
    return np.array(out)


def pressed_block(version, h, steps, m=2.0, dn=0.0, start=0.9):
    """A block of mass m [kg] under g = 9.81 on the pad, let go at rest at
    `start` times its settled approach, coupled explicitly (symplectic
    Euler: the velocity from the pad's force held, then the approach):
    its approach at each step and the settled approach."""
    d_eq = cpad.settled_approach(m, 9.81, KN, L, W)
    d, v, out = start * d_eq, 0.0, []
    with pad(version, (4, 4), foundation=Foundation(KN, dn), pose=(0, 0, 0, d, 0, 0)) as f:
        Fn = wrench(f)["Fn"]
        for _ in range(steps):
            v += h * (9.81 - Fn / m)
            d += h * v
            f.set_inputs(0.0, 0.0, 0.0, d)
            Fn = wrench(f)["Fn"]
            f.do_step(h)
            out.append(d)
    return np.array(out), d_eq


def test_a_free_block_settles_at_m_g_over_kn_a(version):
    """Critically damped (dn A = 2 sqrt(kn A m)), the block comes to rest at
    d = m g / (kn A), to rounding."""
    m = 2.0
    dn = 2 * math.sqrt(KN * L * W * m) / (L * W)
    d, d_eq = pressed_block(version, 0.2 * cpad.normal_step_limit(m, KN, L, W), 600, m, dn, start=0.0)
    assert d[-1] == pytest.approx(d_eq, rel=1e-12)


def test_the_explicit_normal_coupling_is_stable_below_its_limit_and_grows_above(version):
    """Undamped and in full contact the pad is the spring kn A: the coupling
    is the central-difference scheme on it, which the FMU follows to 1e-9
    below h = 2 sqrt(m/(kn A)) (bounded), and which grows above it (until
    the block leaves the pad: it never pulls)."""
    m = 2.0
    limit = cpad.normal_step_limit(m, KN, L, W)
    k = KN * L * W
    d, d_eq = pressed_block(version, 0.95 * limit, 300, m)
    scheme = linear_scheme(0.95 * limit, k, m, 0.9 * d_eq, 300, m * 9.81)
    np.testing.assert_allclose(d, scheme, rtol=1e-9)
    assert np.abs(d - d_eq).max() < 0.5 * d_eq
    d, _ = pressed_block(version, 1.05 * limit, 40, m)
    assert np.abs(d - d_eq).max() > 1.0 * d_eq


def tilting_block(version, h, steps, inertia, phi0=1e-4, d=1e-4):
    """A block held at approach d, free to tilt about X2 from phi0 at rest,
    coupled explicitly: its tilt at each step."""
    phi, omega, out = phi0, 0.0, []
    with pad(version, (4, 4), pose=(0, 0, 0, d, 0, phi0)) as f:
        M2 = wrench(f)["M2"]
        for _ in range(steps):
            omega += h * M2 / inertia
            phi += h * omega
            f.set_inputs(0.0, 0.0, 0.0, d, 0.0, phi)
            M2 = wrench(f)["M2"]
            f.do_step(h)
            out.append(phi)
    return np.array(out)


def test_the_explicit_tilt_coupling_is_stable_below_its_limit_and_grows_above(version):
    """The same for the tilt about X2 with the body's inertia: the scheme on
    kn W L^3/12 below h = 2 sqrt(I/k), growing past the full contact above."""
    inertia = 1e-3
    limit = cpad.tilt_step_limit(inertia, KN, L, W)
    k2 = cpad.tilt_stiffness(KN, L, W)[1]
    below = tilting_block(version, 0.95 * limit, 300, inertia)
    np.testing.assert_allclose(below, linear_scheme(0.95 * limit, k2, inertia, 1e-4, 300), rtol=1e-9,
                               atol=1e-16)
    above = tilting_block(version, 1.05 * limit, 40, inertia)
    assert np.abs(above).max() > 2 * 1e-4 / (L / 2)   # past the lift-off tilt d / (L/2)


def test_nonfinite_and_overflowing_poses_are_refused_and_change_nothing(version):
    with pad(version, (3, 3), pose=(0, 0, 0, 1e-5, 0, 0)) as f:
        before = f.load()
        for bad in ((0, 0, 0, math.nan, 0, 0), (0, 0, 0, 1e-5, math.inf, 0), (0, 0, 0, 1e305, 0, 0)):
            with pytest.raises(FMUError):
                f.set_inputs(*bad)
            assert f.load() == before
        assert any("overflow" in m for m in f.messages), f.messages


@pytest.mark.parametrize("kw,word", [(dict(kn=0.0), "kn"), (dict(kn=1.0, dn=-1.0), "dn"),
                                     (dict(kn=math.nan), "kn")])
def test_a_foundation_the_fmu_refuses_is_refused_first(kw, word):
    with pytest.raises(ValueError, match=f"Foundation: {word}"):
        Foundation(**kw)
