"""The identification's estimates (orthocontact.uq.estimates): draws are
physical, seeded and follow the covariance; a bad identified.json is one line."""
import json
import math
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from cli_run import CMD, one_error_line, run_cli
from orthocontact.uq.estimates import Estimates, draw, load_estimates
from paths import SCENARIOS


def test_draws_are_physical_seeded_and_follow_the_covariance(identified):
    est = load_estimates(identified)
    x, kept = draw(est, 20000, seed=7)
    assert x.shape == (20000, len(est.names)) and np.all(x > 0) and kept == 1.0
    assert np.array_equal(x, draw(est, 20000, seed=7)[0])
    assert not np.array_equal(x, draw(est, 20000, seed=8)[0])
    se = np.sqrt(np.diag(est.cov) / len(x))
    assert np.all(np.abs(x.mean(axis=0) - est.mean) < 5 * se)
    rel = np.abs(np.cov(x.T) - est.cov) / np.sqrt(np.outer(np.diag(est.cov), np.diag(est.cov)))
    assert rel.max() < 0.05  # sampling error of a covariance from 20,000 draws: ~0.01


def test_truncation_keeps_only_positive_draws():
    # mu1 = 0.01 +- 0.01: about 16 % of the normal draws are not physical
    est = Estimates(Path("x.json"), ["mu1", "mu2"], np.array([0.01, 0.6]), np.diag([1e-4, 1e-4]),
                    "coupled", 90.0, 0.0, None, None)
    x, kept = draw(est, 5000, seed=1)
    assert np.all(x > 0) and len(x) == 5000
    assert kept == pytest.approx(1 - 0.5 * math.erfc(1 / math.sqrt(2)), abs=0.02)


def _uq(identified, scenario, out, *extra, timeout=300):
    return subprocess.run(CMD + ["uq", str(identified), "--scenario", str(scenario), "--out", str(out),
                                 *extra], capture_output=True, text=True, timeout=timeout)


@pytest.mark.parametrize("change,says", [
    (lambda d: d.pop("covariance"), "covariance: expected parameters, values and matrix"),
    (lambda d: d["covariance"].__setitem__("matrix", [[1.0]]), "covariance: expected 4 values and a 4x4"),
    (lambda d: d["covariance"]["matrix"][0].__setitem__(0, -1.0), "positive semidefinite"),
    (lambda d: d["assumptions"].__setitem__("rule", "eq20"), "law.rule: expected 'eq20'"),
])
def test_bad_identification_file_one_line_and_nothing_written(identified, tmp_path, change, says):
    d = json.loads(identified.read_text())
    change(d)
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(d))
    p = _uq(bad, SCENARIOS / "mat_aged.toml", tmp_path / "o", "--samples", "10")
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and says in lines[0] and "Traceback" not in p.stderr, p.stderr
    assert not (tmp_path / "o").exists()


def test_hand_mixed_outputs_of_two_identify_runs_are_refused(identified, tmp_path):
    """A run's folder with the identified.json of another run (of other data)
    put in its place: uq and export name the file, exit 2, write nothing."""
    mine = tmp_path / "mine"
    shutil.copytree(identified.parent, mine)          # a run's folder, its manifest included
    data = tmp_path / "data"
    shutil.copytree(SCENARIOS / "example_identification", data)
    forces = data / "forces.csv"
    forces.write_text("".join(forces.read_text().splitlines(keepends=True)[:-1]))   # one run fewer
    other = tmp_path / "other"
    p = run_cli(["identify", data, "--out", other, "--no-validate"], tmp_path)
    assert p.returncode == 0, p.stderr
    assert load_estimates(mine / "identified.json").names    # the run's own files: read
    shutil.copy(other / "identified.json", mine / "identified.json")
    for args in (["uq", mine / "identified.json", "--scenario", SCENARIOS / "mat_aged.toml",
                  "--samples", 10, "--out", tmp_path / "o"],
                 ["export", mine / "identified.json", "--out", tmp_path / "o"]):
        p = run_cli(args, tmp_path)
        one_error_line(p, f"{mine / 'identified.json'}: not the file `orthocontact identify` run")
        assert not (tmp_path / "o").exists()
