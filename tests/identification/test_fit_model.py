"""The joint fit's model (orthocontact.identification.fit_model): residuals
of data made by the closed forms vanish at the truth, and the Jacobian is
the finite differences' of the residuals, with and without the strip."""
from pathlib import Path

import numpy as np
import pytest

from orthocontact import closed_forms as cf
from orthocontact.experiment.rig_setup import RigSetup
from orthocontact.identification import fit_model
from orthocontact.identification.estimators import identifiability
from orthocontact.identification.measurements import MeasurementSet

TRUTH = {"mu1": 0.408, "mu2": 0.625, "eps_ratio": 1.251, "c_strip": 10.0}


def _data(c_strip, velocities):
    """Forces and angles of the aged mat from closed_forms (with the strip's
    viscosity at each velocity when c_strip > 0)."""
    rig = RigSetup(mass_kg=1.875, f_int_N=5.0)
    rows, vel = [], []
    for v in velocities:
        for a in (0.0, 20.0, 40.0, 60.0, 90.0):
            al, be = rig.axes(a)
            t, q1 = cf.steady_strip_state_array(0.408, 0.625, 1.251, 1.0, np.array([al]), np.array([be]),
                                                rig.rule, 0.0, c_strip, v, rig.normal_force)
            rows.append((a, float(np.degrees(np.arctan(t[0]))), 5.0 + float(q1[0])))
            vel.append(v)
    rows = np.array(rows)
    return MeasurementSet(Path("m"), rig, rows[:, [0, 2]], rows[:, [0, 1]], None, np.array(vel),
                          force_velocities=np.array(vel))


@pytest.mark.parametrize("c_strip, velocities", [(0.0, (0.244,)), (10.0, (0.125, 0.244))])
def test_residuals_vanish_at_the_truth_and_the_jacobian_is_the_finite_differences(c_strip, velocities):
    data = _data(c_strip, velocities)
    free, _ = identifiability(data)
    assert set(free) == {"mu1", "mu2", "eps_ratio"} | ({"c_strip"} if c_strip else set())
    model = fit_model.build(data, dict(TRUTH, c_strip=c_strip), free)
    x = model.x_of(dict(TRUTH, c_strip=c_strip))
    r, J = model.evaluate(x)
    assert np.max(np.abs(r)) < 1e-9
    assert [g.name for g in model.groups] == ["forces", "angles"]
    for j in range(len(free)):
        h = np.zeros(len(free))
        h[j] = 1e-6
        fd = (model.evaluate(x + h)[0] - model.evaluate(x - h)[0]) / 2e-6
        assert np.allclose(J[:, j], fd, rtol=1e-5, atol=1e-7), free[j]
