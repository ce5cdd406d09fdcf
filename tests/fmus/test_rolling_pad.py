"""The rolling ContactPad FMU (input vr) against the brush's closed forms
(orthocontact.closed_forms.brush), both FMI versions: a pad 0.1 x 0.05 m
rolling at 1 m/s on kn = 1e8 N/m^3 at d = 0.1 mm, mu = (0.5, 0.7), eps =
(1e4, 2e4) N/m, alpha = beta = 0, 64 cells along the rolling axis, under a
steady longitudinal creepage xi (u1 = xi vr t) and a lateral one eta (u2 =
eta vr t), in full adhesion and in partial slip, at Courant numbers vr h /
(length/n1) of 1 (whole shifts: exact transport) and 0.7 (interpolated);
the slip zone's dissipated power; the spin's coefficients; a tilted pad's
profile integral; FMI 3.0 equal to FMI 2.0 bit for bit; rolling backwards
the mirror image.  The figures measured are in docs/guides/contact-pad.md,
"Rolling"."""
import math

import numpy as np
import pytest

from orthocontact.closed_forms import brush
from orthocontact.fmu.pad import Foundation, PadFMU
from orthocontact.fmu.params import ContactParams
from orthocontact.fmu.patch import PatchGeometry

VR, L, W, KN, D = 1.0, 0.1, 0.05, 1e8, 1e-4
MU, EPS = (0.5, 0.7), (1e4, 2e4)
LAW = ContactParams(MU[0], MU[1], EPS[0], EPS[1], 0.0, 0.0, "coupled")
FN = KN * L * W * D   # uniform pressure: 50 N
N2 = 4                # across the width: the pressure and the creep are uniform there


def roll(version, n1, courant, creep=(0.0, 0.0), spin=0.0, phi2=0.0, vr=VR, lengths=3.0, every=False):
    """The outputs of the pending step after the pad (n1 x N2 cells) has
    rolled `lengths` pad lengths at vr with u = creep vr t, theta = spin vr
    t, h = courant (length/n1)/|vr|; every step's if `every`."""
    h = courant * L / n1 / abs(vr)
    steps = int(math.ceil(lengths * n1 / courant))
    rows = []
    with PadFMU(fmi_version=version) as f:
        f.initialize(LAW, PatchGeometry(L, W, n1, N2), Foundation(KN), (0.0, 0.0, 0.0, D, 0.0, phi2), vr)
        for k in range(steps + 1):
            t = k * h
            f.set_inputs(creep[0] * abs(vr) * t, creep[1] * abs(vr) * t, spin * abs(vr) * t, D, 0.0,
                         phi2, vr)
            if every or k == steps:
                rows.append(f.outputs())
            f.do_step(h)
    return rows if every else rows[0]


def error(got, want):
    return abs(got - want) / abs(want)


# (axis, creepage): full adhesion at 0.4 of the slip onset; partial slip at
# twice it (the adhesion zone ends on a cell's edge) and at 1.37 times (inside a cell)
ONSET = [brush.slip_onset(EPS[a], MU[a], FN, L) for a in (0, 1)]
CASES = [(a, f * ONSET[a]) for f in (0.4, 2.0, 1.37) for a in (0, 1)]


@pytest.mark.parametrize("courant", [1.0, 0.7])
@pytest.mark.parametrize("axis,creepage", CASES)
def test_steady_creep_meets_the_brush_closed_form_at_64_cells(axis, creepage, courant):
    """T along the creepage's axis is brush.steady_force within 0.2 %
    (measured: full adhesion and the zone ending on a cell's edge to
    rounding, the deflection being linear in x; at 1.37 times the onset
    2.4e-4 at Courant 1, 2.1e-5 at 0.7); the other axis carries nothing."""
    creep = tuple(creepage if a == axis else 0.0 for a in (0, 1))
    out = roll(2, 64, courant, creep)
    want = brush.steady_force(EPS[axis], MU[axis], FN, L, creepage)
    assert error(out[f"T{axis + 1}"], want) <= 2e-3
    assert abs(out[f"T{2 - axis}"]) <= 1e-9 * abs(want)
    assert (out["slipFraction"] > 0) == (creepage > ONSET[axis])


@pytest.mark.parametrize("courant", [1.0, 0.7])
def test_the_error_falls_with_the_grid(courant):
    """Where the adhesion zone ends inside a cell the error falls from 32 to
    64 cells along the rolling axis (measured 9.2e-4 to 2.4e-4 at Courant 1,
    1.4e-4 to 2.1e-5 at 0.7)."""
    creepage = 1.37 * ONSET[0]
    want = brush.steady_force(EPS[0], MU[0], FN, L, creepage)
    e32, e64 = (error(roll(2, n, courant, (creepage, 0.0))["T1"], want) for n in (32, 64))
    assert e64 < 0.5 * e32 <= 1e-3


@pytest.mark.parametrize("courant", [1.0, 0.7])
def test_the_slip_zones_energy_is_counted(courant):
    """Steady partial slip: dissipatedEnergy grows at brush.slip_power
    (the energy balance), converging at first order, the cell where the
    slide zone begins sliding part of its creep only: measured 6.3 % low at
    32 cells, 3.1 % at 64 (Courant 1); 3.1 %, 1.6 % (0.7).  The cells that
    leave keep what they counted."""
    creepage = 2.0 * ONSET[0]
    want = brush.slip_power(EPS[0], MU[0], FN, L, creepage, VR)

    def power(n):
        rows = roll(2, n, courant, (creepage, 0.0), every=True)
        return (rows[-1]["dissipatedEnergy"] - rows[-2]["dissipatedEnergy"]) / (courant * L / n / VR)

    e32, e64 = (error(power(n), want) for n in (32, 64))
    assert e64 <= 0.04 and e64 < 0.6 * e32


def test_spin_converges_to_the_brush_coefficients():
    """A spin phi_s = theta'/vr in full adhesion: T2 -> -k_T2 phi_s and Mz ->
    -k_Mz phi_s (brush.spin_coefficients) at first order in vr h: a step
    adds each cell the creep at its own place, not the mean along the
    material's path (half a shift upstream).  Measured at Courant 1: T2
    9.2 % off at 32 cells, 4.6 % at 64; Mz 16 %, 5.7 %.  The turn stays
    small (2 mrad), so that the body's and the surface's axes agree."""
    spin = 0.01  # 1/m
    kT2, kMz = brush.spin_coefficients(EPS[0], EPS[1], L, W)
    (t32, m32), (t64, m64) = ((error(o["T2"], -kT2 * spin), error(o["Mz"], -kMz * spin))
                              for o in (roll(2, n, 1.0, spin=spin, lengths=2.0) for n in (32, 64)))
    assert t64 <= 0.05 and t64 < 0.6 * t32
    assert m64 <= 0.06 and m64 < 0.6 * m32


@pytest.mark.parametrize("courant", [1.0, 0.7])
def test_a_tilted_pads_force_is_the_profile_integral(courant):
    """A tilt about axis 2 that lifts the trailing third off, the pressure
    kn max(0, d + phi2 x): T1 = brush.steady_force_profile within 0.2 % at
    64 cells (measured 1.6e-5).  Lifting the leading third instead, the
    material enters the pressed part where the lift-off line crosses a cell,
    unloaded at that cell's end and not its edge: within 2 % and converging
    (measured 2.9 % at 32 cells, 1.1 % at 64)."""
    creepage = 0.03

    def err(phi2, n):
        out = roll(2, n, courant, (creepage, 0.0), phi2=phi2)
        assert out["contactFraction"] == pytest.approx(5 / 6, rel=1e-12)
        want = brush.steady_force_profile(lambda x: KN * np.maximum(D + phi2 * x, 0.0), EPS[0], MU[0],
                                          L, W, creepage)
        return error(out["T1"], want)

    assert err(3e-3, 64) <= 2e-3
    e32, e64 = err(-3e-3, 32), err(-3e-3, 64)
    assert e64 <= 2e-2 and e64 < 0.6 * e32


@pytest.mark.parametrize("courant", [1.0, 0.7])
def test_fmi3_equals_fmi2_bit_for_bit_while_rolling(courant):
    creep = (2.0 * ONSET[0], 0.4 * ONSET[1])
    runs = [roll(v, 16, courant, creep, spin=0.05, lengths=1.5, every=True) for v in (2, 3)]
    assert runs[0] == runs[1]


def test_rolling_backwards_is_the_mirror_image():
    """vr < 0 enters at -length/2: under the same creep rates the force is
    the same (the brush's is even in the direction of rolling for a
    creepage along an axis), within rounding."""
    creep = (2.0 * ONSET[0], 0.0)
    ahead, back = roll(2, 32, 0.7, creep), roll(2, 32, 0.7, creep, vr=-VR)
    assert back["T1"] == pytest.approx(ahead["T1"], rel=1e-12)

