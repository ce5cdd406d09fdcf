"""The rig's closed forms (orthocontact.closed_forms.rig: the steady state
with the Teflon strip) against independent truth: the rig running the FMU,
and the tests' own reference simulator."""
import math

import numpy as np
import pytest

import rig_reference
from orthocontact import closed_forms as cf
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.params import ContactParams
from orthocontact.rig.compiled import CMaster
from orthocontact.rig.harness import Rig

N_RIG = 1.875 * cf.G_STANDARD


def random_laws(n, seed):
    """Laws with friction ratios up to ~30 and stiffness ratios up to 100
    either way, any axes, both implicit rules, with and without each strip
    term, at lab velocities; steep steady angles (near 90 deg) included."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        mu1, mu2 = 10 ** rng.uniform(-1.3, 0.2, 2)
        eps2 = 10 ** rng.uniform(3, 5)
        eps1 = eps2 * 10 ** rng.uniform(-2, 2)
        alpha, beta = rng.uniform(0, math.pi, 2)
        mu_strip = float(rng.uniform(0, 0.3)) if i % 3 else 0.0
        c_strip = float(rng.uniform(0, 60)) if i % 4 > 1 else 0.0
        out.append(dict(mu1=mu1, mu2=mu2, eps1=eps1, eps2=eps2, alpha=alpha, beta=beta,
                        rule=("coupled", "associated")[i % 2], mu_strip=mu_strip, c_strip=c_strip,
                        velocity=float(rng.uniform(0.05, 0.5))))
    return out


def closed_form_deg(law):
    t = cf.steady_tan_phi_with_strip(law["mu1"], law["mu2"], law["eps1"], law["eps2"], law["alpha"],
                                     law["beta"], law["rule"], law["mu_strip"], law["c_strip"],
                                     law["velocity"], N_RIG)
    return math.degrees(math.atan(t))


def stable_steady_angles_deg(law, samples=20000):
    """Every stable steady state of the strip's lateral balance, by a fine
    scan of the motion's direction (test-side, independent of the closed
    form's search): where the lateral force F2 turns from driving the block
    up to driving it down, the jump at 0 (the strip's friction) included."""
    h = cf.slip_force_tensor(law["mu1"], law["mu2"], law["eps1"], law["eps2"], law["alpha"],
                             law["beta"], law["rule"])
    f = cf.friction_entries(law["mu1"], law["mu2"], law["beta"])
    theta = np.linspace(-math.pi / 2, math.pi / 2, samples)[1:-1]
    theta = np.concatenate([theta[theta < 0], [-0.0, 0.0], theta[theta > 0]])
    sign = np.where(theta < 0, -1.0, 1.0) * (theta != 0)
    sign[np.flatnonzero(theta == 0)] = (-1.0, 1.0)
    F2 = cf.strip_lateral_force(h, f, np.tan(theta), sign, law["mu_strip"],
                                law["c_strip"] * law["velocity"], N_RIG)[0]
    down = np.flatnonzero((F2[:-1] > 0) & (F2[1:] <= 0))
    return [math.degrees(0.5 * (theta[k] + theta[k + 1])) for k in down]


def rig_for(law, mode="quasistatic", steps=1500):
    # long enough for the elastic transient: 40 elastic lengths mu N / eps
    travel = 40 * max(law["mu1"], law["mu2"]) * N_RIG / min(law["eps1"], law["eps2"]) + 0.1
    return Rig(mode=mode, mu_strip=law["mu_strip"], c_strip=law["c_strip"],
               velocity_m_s=law["velocity"], travel_m=travel,
               step_s=travel / law["velocity"] / steps)


def params(law):
    return ContactParams(law["mu1"], law["mu2"], law["eps1"], law["eps2"], law["alpha"], law["beta"],
                         law["rule"])


@pytest.fixture(scope="module")
def thousand_laws_in_the_rig():
    laws = random_laws(1000, seed=7)
    cm = CMaster(find_fmu())
    try:
        phis = [r[0] for r in cm.run([(params(law), rig_for(law)) for law in laws])]
    finally:
        cm.close()
    return laws, phis


def test_strip_steady_state_matches_the_rig_on_1000_random_laws(thousand_laws_in_the_rig):
    laws, phis = thousand_laws_in_the_rig
    assert sum(law["mu_strip"] > 0 for law in laws) > 600 and sum(law["c_strip"] > 0 for law in laws) > 400
    assert sum(law["mu_strip"] == 0 and law["c_strip"] == 0 for law in laws) > 150
    assert max(abs(p) for p in phis) > 60  # steep regimes are in the set
    scalar = np.array([closed_form_deg(law) for law in laws])
    assert np.all(np.isfinite(scalar))
    other_basin = 0
    for law, phi, closed in zip(laws, phis, scalar):
        if abs(phi - closed) <= 1e-6:
            continue
        # the quasi-static rig may start into another stable state's basin
        # where there are several; it must then sit on one of them
        stable = stable_steady_angles_deg(law)
        assert len(stable) > 1, (law, phi, closed, stable)
        assert min(abs(phi - s) for s in stable) < 0.02, (law, phi, closed, stable)
        other_basin += 1
    assert other_basin <= 3


def test_array_form_equals_the_scalar_form(thousand_laws_in_the_rig):
    laws, _ = thousand_laws_in_the_rig
    for rule in ("coupled", "associated"):
        group = [law for law in laws if law["rule"] == rule][:200]
        for law in group:
            a = np.array([law["alpha"], law["alpha"] + 0.3, law["alpha"] - 1.1])
            b = np.array([law["beta"], law["beta"] + 0.3, law["beta"] - 1.1])
            arr = cf.steady_tan_phi_with_strip_array(law["mu1"], law["mu2"], law["eps1"], law["eps2"],
                                                     a, b, rule, law["mu_strip"], law["c_strip"],
                                                     law["velocity"], N_RIG)
            one = [cf.steady_tan_phi_with_strip(law["mu1"], law["mu2"], law["eps1"], law["eps2"], x, y,
                                                rule, law["mu_strip"], law["c_strip"], law["velocity"],
                                                N_RIG) for x, y in zip(a, b)]
            assert arr.tolist() == one


def test_the_dynamic_rig_reaches_the_closed_forms_state_where_it_settles(thousand_laws_in_the_rig):
    """The state the closed form picks is the one reached from rest
    (lateral velocity 0): the dynamic rig, on the laws whose two halves of
    the fitted path agree (it settled; inertia makes some laws settle over
    metres), lands there."""
    laws, _ = thousand_laws_in_the_rig
    laws = [law for law in laws if law["c_strip"] > 0][:150]
    cm = CMaster(find_fmu())
    try:
        tasks = []
        for law in laws:
            r = rig_for(law, mode="dynamic", steps=20000)
            tasks.append((params(law), Rig(**{**r.__dict__, "travel_m": max(r.travel_m, 2.0),
                                              "step_s": max(r.travel_m, 2.0) / law["velocity"] / 20000,
                                              "fit_from": 0.75})))
        res = cm.run(tasks)
    finally:
        cm.close()
    deviations = []
    for law, r in zip(laws, res):
        if abs(r.phi_head_deg - r.phi_tail_deg) <= 1e-3:
            deviations.append(abs(r.phi_deg - closed_form_deg(law)))
    assert len(deviations) >= 100
    # A soft contact under a strip with both friction and viscosity can
    # settle into a stick-slip cycle instead of steady sliding (measured:
    # eps1 = 206 N/m, the contact alternating stick and slip, lateral velocity
    # 0.028-0.039 m/s, 0.22 deg off at every step size while the quasi-static
    # rig sits on the closed form): its two halves agree, its mean differs.
    assert sum(d <= 0.01 for d in deviations) >= 0.98 * len(deviations), sorted(deviations)[-5:]
    assert max(deviations) < 0.5


def test_strip_steady_state_matches_the_independent_reference_simulator():
    laws = [law for law in random_laws(400, seed=11) if law["mu_strip"] > 0 or law["c_strip"] > 0][:20]
    for law in laws:
        elastic = max(law["mu1"], law["mu2"]) * N_RIG / min(law["eps1"], law["eps2"])
        travel = 40 * elastic + 0.1
        x1, x2, _ = rig_reference.run_rig(law["mu1"], law["mu2"], law["eps1"], law["eps2"], law["alpha"],
                                          law["beta"], law["rule"], N_RIG, travel, 800,
                                          mu_strip=law["mu_strip"], c_strip=law["c_strip"],
                                          velocity=law["velocity"])
        k = 3 * len(x1) // 4
        slope = np.polyfit(x1[k:], x2[k:], 1)[0]
        phi = math.degrees(math.atan(slope))
        closed = closed_form_deg(law)
        if abs(phi - closed) > 1e-4:
            stable = stable_steady_angles_deg(law)
            assert len(stable) > 1 and min(abs(phi - s) for s in stable) < 0.02, (law, phi, closed)


def test_no_nan_and_no_exception_in_any_regime():
    rng = np.random.default_rng(3)
    n = 4000
    mu1, mu2 = 10 ** rng.uniform(-3, 1, n), 10 ** rng.uniform(-3, 1, n)
    eps2 = 10 ** rng.uniform(0, 8, n)
    eps1 = eps2 * 10 ** rng.uniform(-4, 4, n)
    alpha, beta = rng.uniform(-7, 7, n), rng.uniform(-7, 7, n)
    for rule in ("coupled", "associated", "eq20"):
        for mu_strip, c_strip in ((0.0, 0.0), (0.5, 0.0), (0.0, 500.0), (2.0, 1e4)):
            for i in range(0, n, 400):
                t = cf.steady_tan_phi_with_strip_array(mu1[i], mu2[i], eps1[i], eps2[i], alpha, beta, rule,
                                                       mu_strip, c_strip, 0.3, 20.0)
                assert np.all(np.isfinite(t))
