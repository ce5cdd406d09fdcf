"""uq's results (orthocontact.uq.outputs): the share of the measured angles
inside the measurement band and the widest parameter band, by hand."""
from pathlib import Path

import numpy as np

from orthocontact.experiment.scenario import load
from orthocontact.uq.estimates import Estimates
from orthocontact.uq.outputs import inside_measurement_band, widest_band
from paths import SCENARIOS


def estimates(points, alpha_offset_deg=90.0):
    return Estimates(Path("identified.json"), ["mu1", "mu2"], np.array([0.4, 0.6]), np.diag([1e-4, 1e-4]),
                     "coupled", alpha_offset_deg, 0.0, points, 0.3)


def test_measured_angles_inside_the_band_by_hand():
    sc = load(SCENARIOS / "mat_aged.toml")       # alpha = a + 90 deg, beta = a
    angles = np.array([0.0, 45.0])
    band = {"lo": np.array([0.0, -9.0]), "hi": np.array([4.0, 0.0])}
    # at 10 deg: lo -2, hi 3.111; at 30 deg: lo -6, hi 1.333; 60 deg lies outside the swept range
    points = np.array([[10.0, 1.0], [10.0, 3.5], [30.0, -5.9], [30.0, -6.1], [60.0, 0.0]])
    assert inside_measurement_band(angles, band, estimates(points), sc) == \
        {"inside": 2, "points": 4, "fraction": 0.5}
    # another geometry
    assert inside_measurement_band(angles, band, estimates(points, alpha_offset_deg=0.0), sc) is None
    assert inside_measurement_band(angles, band, estimates(None), sc) is None
    nan_band = {"lo": np.array([np.nan, 0.0]), "hi": np.array([1.0, 1.0])}
    assert inside_measurement_band(angles, nan_band, estimates(points), sc) is None


def test_the_widest_band():
    angles = np.array([0.0, 10.0, 20.0, 30.0])
    band = {"lo": np.array([-1.0, -2.0, np.nan, -1.5]), "hi": np.array([1.0, 1.5, np.nan, 2.25])}
    assert widest_band(angles, band) == {"angle_deg": 30.0, "width_deg": 3.75}
