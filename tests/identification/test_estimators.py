"""The estimators (orthocontact.identification.estimators): the joint fit
recovers the truth from the independent simulator's noise-free data, and
its intervals cover honestly."""
from pathlib import Path

import numpy as np
import pytest

from orthocontact.experiment.rig_setup import RigSetup
from orthocontact.identification.estimators import joint_fit, start_values
from orthocontact.identification.measurements import MeasurementSet
RIG = RigSetup(mass_kg=1.875, f_int_N=5.0)
FA, AA = [0, 15, 30, 45, 60, 75, 90], list(range(5, 90, 5))


@pytest.fixture(scope="module")
def reference_data():
    """Noise-free data of the issue's truth (mu 0.30 / 0.55, eps1/eps2 0.8,
    eps2 3e4 N/m) from the independent simulator (tools/rig_reference.py)."""
    import math

    import rig_reference as ref
    t = {"mu1": 0.30, "mu2": 0.55, "eps_ratio": 0.8, "eps2": 3.0e4}
    N = RIG.mass_kg * RIG.g
    al, be = math.radians(RIG.alpha_offset_deg), math.radians(RIG.beta_offset_deg)
    m = ref.measure(t["mu1"], t["mu2"], 0.8 * 3e4, 3e4, RIG.rule, al, be, sorted(set(FA) | set(AA)), N,
                    RIG.f_int_N)
    r = ref.ramp(t["mu1"], t["mu2"], 0.8 * 3e4, 3e4, RIG.rule, al, be, RIG.ramp_angle_deg, N, RIG.f_int_N,
                 2e-3)
    return dict(t, eps1=0.8 * 3e4), {"forces": np.array([[a, m[a][1]] for a in FA * 3]),
                                     "angles": np.array([[a, m[a][0]] for a in AA * 2]),
                                     "ramp": np.array(r)[::8]}


def test_independent_simulators_noise_free_data_give_the_truth(reference_data):
    truth, d = reference_data
    fit = joint_fit(MeasurementSet(Path("ref"), RIG, d["forces"], d["angles"], d["ramp"]),
                    start_values(MeasurementSet(Path("ref"), RIG, d["forces"], d["angles"], d["ramp"])))
    for k, v in truth.items():
        assert fit.values[k] == pytest.approx(v, rel=1e-6), k


def test_intervals_are_honest_coverage_over_200_replicates(reference_data):
    """The fast version of benchmarks/bench_coverage.py (400 replicates x 3
    truths, 92-98 %): one truth, 200 replicates, a wider band (90-99 %) for
    the smaller sample; noise added per replicate to the independent
    simulator's data."""
    truth, d = reference_data
    hits = dict.fromkeys(truth, 0)
    n = 200
    for i in range(n):
        rng = np.random.default_rng(1000 + i)
        noisy = MeasurementSet(Path("mc"), RIG,
                               d["forces"] + np.c_[np.zeros(len(d["forces"])), rng.normal(0, 0.05, len(d["forces"]))],
                               d["angles"] + np.c_[np.zeros(len(d["angles"])), rng.normal(0, 0.3, len(d["angles"]))],
                               d["ramp"] + np.c_[np.zeros(len(d["ramp"])), rng.normal(0, 0.02, len(d["ramp"]))])
        fit = joint_fit(noisy, start_values(noisy))
        for k in truth:
            lo, hi = fit.ci95[k]
            hits[k] += lo <= truth[k] <= hi
    coverage = {k: v / n for k, v in hits.items()}
    for k, c in coverage.items():
        assert 0.90 <= c <= 0.99, coverage
