"""Sweeps (orthocontact.runs.sweep): the same results with any number of
workers, and the closed forms' array form equal to the scalar one."""
from dataclasses import replace

import numpy as np

from orthocontact.experiment.scenario import load
from orthocontact.runs.sweep import run_sweep
from paths import SCENARIOS


def _coarse(name, **sweep):
    sc = load(SCENARIOS / f"{name}.toml")
    sc.sweep = dict(sc.sweep, **sweep)
    return sc


def test_sweep_does_not_depend_on_the_number_of_workers():
    sc = _coarse("case5", step_deg=10.0, refine_extremum=False, trajectory_angles_deg=[0.0])
    sc.rig = replace(sc.rig, mode="dynamic", step_s=5e-4)
    one = run_sweep(sc, workers=1, progress=False)
    two = run_sweep(sc, workers=2, progress=False)
    assert np.array_equal(one.phi_deg, two.phi_deg)
    assert np.array_equal(one.drive_mean_N, two.drive_mean_N)


def test_vectorized_closed_forms_equal_the_scalar_ones():
    """The report's 90,001-point scans use the array form: same numbers."""

    import numpy as np

    from orthocontact.runs.sweep import closed_form_phi_deg, closed_form_phi_deg_array
    a = np.linspace(-30, 120, 301)
    for f in sorted(SCENARIOS.glob("*.toml")):
        sc = load(f)
        for rule in (None, "associated", "coupled", "eq20"):
            v = closed_form_phi_deg_array(sc, a, rule)
            s = np.array([closed_form_phi_deg(sc, x, rule) for x in a])
            np.testing.assert_allclose(v, s, rtol=0, atol=1e-12)
