"""From a run's recordings to the fit's values (orthocontact.identification.
reduction), on synthetic runs whose answer is known by construction: a
straight path at a known angle after a curved transient, a known mean force."""
import math
from pathlib import Path

import numpy as np
import pytest

import make_recordings as mr
from orthocontact.errors import InputError
from orthocontact.identification.recordings import Run
from orthocontact.identification.reduction import line_fit, reduce_ramp, reduce_slide


def test_line_fit_against_the_normal_equations():
    x = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
    y = np.array([1.1, 2.9, 5.2, 7.1, 8.8])
    a, b, se = line_fit(x, y)
    # by hand: mean x 2, mean y 5.02, Sxx 10, Sxy 19.6
    assert b == pytest.approx(1.96, rel=1e-12) and a == pytest.approx(5.02 - 1.96 * 2, rel=1e-12)
    r = y - a - b * x
    assert se == pytest.approx(math.sqrt(float(r @ r) / 3 / 10), rel=1e-12)


def slide_run(phi_deg, force_N, v=0.244, n=2000, transient_m=0.02, seed=0, noise_m=2e-6):
    """A slide run: the carriage accelerates for 0.1 s, cruises at v; the
    block settles from x2 = 0 onto the line x2 = c + x1 tan(phi) over
    `transient_m` (an exponential), tracker noise `noise_m`."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 0.6 / v + 0.1, n)
    x1 = np.where(t < 0.1, 0.5 * v / 0.1 * t ** 2, 0.5 * v * 0.1 + v * (t - 0.1))
    tan = math.tan(math.radians(phi_deg))
    x2 = tan * (x1 - transient_m * (1 - np.exp(-x1 / transient_m))) + rng.normal(0, noise_m, n)
    forces = np.column_stack([t, force_N + rng.normal(0, 0.05, n)])
    return Run("s1", "slide", 30.0, v, 2, np.column_stack([t, x1, x2]), forces, Path("s1.csv"),
               Path("s1_forces.csv"))


@pytest.mark.parametrize("phi_deg", [-11.5, 0.0, 25.0])
def test_a_slide_gives_its_paths_angle_and_mean_force(phi_deg):
    warnings = []
    r = reduce_slide(slide_run(phi_deg, 14.2), warnings)
    assert warnings == [] and r.flags == []
    assert r.phi_deg == pytest.approx(phi_deg, abs=max(4 * r.phi_se_deg, 1e-9))
    assert r.phi_se_deg < 2e-3
    if phi_deg:   # the curved start (2.5 of its lengths by 0.05 m) is left out
        assert r.window_x1_m[0] > 0.05
    assert r.speed_m_s == pytest.approx(0.244, rel=1e-3)
    assert r.force_N == pytest.approx(14.2, abs=4 * r.force_se_N)


def test_positions_in_mm_are_refused_naming_the_unit():
    run = slide_run(10.0, 14.2)
    run.trajectory[:, 1:] *= 1000.0
    with pytest.raises(InputError, match=r"positions in mm\?"):
        reduce_slide(run, [])


# -- the ramp's stiffness on the independent generator's recordings ----------

RAMP_TRUTH = mr.Truth(c_strip=0.0)
QUIET = dict(tracker_noise_m=0.0, tracker_drift_m_s=0.0, force_noise_N=0.0, force_tare_N=0.0,
             force_drift_N_s=0.0, friction_scatter=0.0)


def _ramp_stiffness(sensors: mr.Sensors, runs: int, seed: int):
    """(stiffness, its within-run error) of `runs` ramp runs of the small
    design's truth, each through the reduction as `identify` reduces it."""
    design = mr.Design(angles_deg=[], velocities={0.244: 1}, carriage_runs=0, ramp_runs=runs)
    made = mr.make_runs(RAMP_TRUTH, sensors, design, np.random.default_rng(seed), {},
                        mr.ramp_path(RAMP_TRUTH, design.ramp_travel_m))
    out = []
    for name, (kind, a, v, traj, forces) in made.items():
        # rounded as write_folder writes them
        run = Run(name, kind, a, v, 1, np.round(traj, 6), np.round(forces, 4), Path(f"{name}.csv"),
                  Path(f"{name}.csv"))
        r = reduce_ramp(run, [])
        out.append((r.stiffness_N_m, r.stiffness_se_N_m))
    return np.array(out)


def test_ramp_stiffness_is_unbiased_under_the_force_sensors_noise():
    """The force sensor's white noise alone (0.05 N): the stick stiffness's
    mean over 300 runs is the truth's eps2 (the stick stiffness at the ramp
    angle, alpha = 90 deg) within 4 standard errors of the mean.  Choosing
    the stick window by each sample's own force biased it by -0.13 %
    (12 standard errors here)."""
    k = _ramp_stiffness(mr.Sensors(**dict(QUIET, force_noise_N=0.05)), 300, 11)[:, 0]
    rel = k / RAMP_TRUTH.eps2 - 1
    se = rel.std(ddof=1) / math.sqrt(len(rel))
    assert abs(rel.mean()) < 4 * se + 1e-4, (rel.mean(), se)


def test_ramp_stiffness_error_includes_the_tracked_speeds():
    """The tracker's noise alone (0.05 mm): the runs' stiffness scatters by
    the tracked speed's error (about 1.3 %); the within-run error each run
    reports is as large (rms within 25 % of the scatter over 80 runs).  The
    line fit's error alone was 0.5 N/m against 130 N/m."""
    k, se = _ramp_stiffness(mr.Sensors(**dict(QUIET, tracker_noise_m=5e-5)), 80, 12).T
    ratio = math.sqrt(np.mean(se**2)) / k.std(ddof=1)
    assert 0.75 < ratio < 1.25, ratio
