"""The block pushed at a height on the ContactPad FMU (orthocontact.rig.pushed)
through the real FMU against closed_forms.pad and closed_forms.paper: the
regime on either side of the thresholds mu h = length/6 and length/2, the
steady pose and contact of closed_forms.pad.pushed_at_height, the
trajectory angle the height does not change, tipping as a result."""
import math

import numpy as np
import pytest

from orthocontact.closed_forms import pad as cpad
from orthocontact.closed_forms.paper import G_STANDARD, of_law, steady_drive_force, steady_tan_phi
from orthocontact.fmu.pad import Foundation
from orthocontact.fmu.params import ContactParams
from orthocontact.fmu.patch import PatchGeometry
from orthocontact.rig import pushed

MASS, L, W, KN = 1.875, 0.09, 0.06, 1e8


def mat(a_deg, rule="coupled"):
    """The aged mat at mat angle a (beta = a, alpha = a + 90 deg), stiff (eps2 = 1e6 N/m)."""
    return ContactParams.from_degrees(0.408, 0.625, 1.251e6, 1e6, a_deg + 90.0, a_deg, rule)


def mu_of(p) -> float:
    return steady_drive_force(p.mu1, p.mu2, p.beta, 0.0, 1.0, 1.0)


def block(h, grid=(6, 4), kn=KN):
    return pushed.PushedBlock(MASS, G_STANDARD, PatchGeometry(L, W, *grid), Foundation(kn), h)


def run(p, h, fmi_version=2, **kw):
    return pushed.push(p, block(h, **kw), 4e-3, 2e-4, fmi_version)


def test_without_height_the_block_settles_level_and_slides_at_the_point_laws_angle():
    p = mat(30.0)
    r = run(p, 0.0)
    assert r.regime == cpad.FULL_CONTACT
    assert np.all(r.phi1 == 0) and np.all(np.abs(r.phi2) < 1e-18)
    assert r.d[-1] == pytest.approx(cpad.settled_approach(MASS, G_STANDARD, KN, L, W), rel=1e-12)
    assert r.trajectory_tan_phi() == pytest.approx(of_law(steady_tan_phi, p, p.alpha, p.beta), rel=1e-9)
    assert r.slip_fraction[-1] == 1.0


@pytest.mark.parametrize("fmi_version", [2, 3])
@pytest.mark.parametrize("share, regime", [(0.9 / 6, cpad.FULL_CONTACT), (1.1 / 6, cpad.LIFT_OFF),
                                           (0.45, cpad.LIFT_OFF), (0.55, cpad.TIPS)])
def test_the_regime_turns_at_the_thresholds_and_the_pose_is_the_closed_forms(share, regime, fmi_version):
    """At mu h / length = share: the regime of pushed_at_height, and in
    steady sliding its approach and tilt (1e-7) and contact fraction."""
    p = mat(0.0)
    mu = mu_of(p)
    h = share * L / mu
    r = run(p, h, fmi_version)
    assert r.regime == regime
    want = cpad.pushed_at_height(KN, L, W, MASS * G_STANDARD, mu * h)
    if regime == cpad.TIPS:
        assert r.tipped_at_m is not None and want[1] is None
        return
    assert r.tipped_at_m is None
    assert r.d[-1] == pytest.approx(want[1], rel=1e-7, abs=1e-7 * want[2] * L)
    assert r.phi2[-1] == pytest.approx(want[2], rel=1e-7)
    assert -r.M2[-1] / r.Fn[-1] == pytest.approx(mu * h, rel=1e-7)
    assert r.contact_fraction[-1] == pytest.approx(cpad.contact_fraction(L, W, want[1], 0.0, want[2]),
                                                   rel=1e-6)


@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_the_height_moves_the_pressure_not_the_path(rule):
    """tan(phi) of the settled path is the point law's at every height,
    full contact and lift-off alike (every cell slides the same way)."""
    p = mat(30.0, rule)
    want = of_law(steady_tan_phi, p, p.alpha, p.beta)
    L_mu = L / mu_of(p)
    for h in (0.0, 0.1 * L_mu, 0.3 * L_mu):
        assert run(p, h).trajectory_tan_phi() == pytest.approx(want, rel=1e-9)


def test_a_tipping_block_stops_the_run_with_its_travel_and_no_angle():
    r = run(mat(90.0), 0.6 * L / 0.625)
    assert r.regime == cpad.TIPS and r.tipped_at_m > 0
    assert len(r.x1) == 0 or r.x1[-1] < r.tipped_at_m
    assert math.isnan(r.trajectory_tan_phi())


def test_a_push_beyond_the_small_tilts_is_refused_naming_the_tilt():
    """A soft foundation tilts the block by more than MAX_TILT_RAD before
    the push tips it: not a number of this model."""
    with pytest.raises(pushed.PushNotSolved, match="beyond the small tilts the pad models"):
        pushed.push(mat(0.0), block(0.45 * L / 0.408, kn=1e6), 4e-3, 2e-4)


def test_a_push_whose_newton_leaves_the_pads_poses_is_refused_saying_so():
    """A soft, nearly frictionless-stiff mat (eps = (100, 1) N/m) on a soft
    foundation at mat angle 30 deg, pushed a metre a step: where every cell
    slides T2 does not follow u2, the lateral balance's Newton ran to u2 =
    -inf and the FMU's refusal of it ended the run in a traceback."""
    p = ContactParams.from_degrees(1.0, 1.0, 100.0, 1.0, 120.0, 30.0, "coupled")
    soft = pushed.PushedBlock(MASS, G_STANDARD, PatchGeometry(1.0, 1.0, 8, 8), Foundation(1e3), 0.0)
    why = r"Newton did not reach equilibrium \(its pose not finite\)"
    with pytest.raises(pushed.PushNotSolved, match=why):
        pushed.push(p, soft, 10.0, 1.0)


@pytest.mark.parametrize("kw, word", [(dict(mass_kg=0.0), "mass_kg"), (dict(height_m=-0.01), "height_m"),
                                      (dict(g=math.inf), "g"), (dict(height_m=True), "height_m"),
                                      # > 0, but its tolerances underflow (a division by 0 before)
                                      (dict(mass_kg=1e-320), "mass_kg = 1e-320 gives a weight")])
def test_a_bad_block_is_refused_naming_it(kw, word):
    args = dict(mass_kg=MASS, g=G_STANDARD, pad=PatchGeometry(L, W, 2, 2), foundation=Foundation(KN),
                height_m=0.0)
    with pytest.raises(ValueError, match=f"PushedBlock: {word}"):
        pushed.PushedBlock(**{**args, **kw})
