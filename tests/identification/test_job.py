"""Identification against the paper's calibration numbers, against synthetic
data made by the FMU harness (not by the closed forms the fit uses) and by an
independent simulator of the rig (tools/rig_reference.py, none of the
package's code): exact recovery, honest intervals, clear non-identifiability."""
import dataclasses
import json
import shutil
import subprocess
from pathlib import Path

import pytest

from orthocontact import closed_forms as cf
from orthocontact.cli.main import main
from orthocontact.experiment.rig_setup import RigSetup
from orthocontact.fmu.params import ContactParams
from orthocontact.identification.estimators import eq40_fit
from orthocontact.identification.job import identify, simulate_measurements
from orthocontact.identification.measurements import MeasurementSet, load_data, write_measurements
from paths import SCENARIOS

EXAMPLE = SCENARIOS / "example_identification"
TRUTH = ContactParams(0.408, 0.625, 12510.0, 10000.0)
TV = {"mu1": 0.408, "mu2": 0.625, "eps_ratio": 1.251, "eps2": 1e4, "eps1": 12510.0}
RIG = RigSetup(mass_kg=1.875, f_int_N=5.0)
FA, AA = [0, 15, 30, 45, 60, 75, 90], list(range(5, 90, 5))


@pytest.fixture(scope="module")
def fmu_data():
    """Noise-free measurements from the FMU harness (once per module)."""
    return simulate_measurements(TRUTH, RIG, FA, AA, ramp_max_x1_m=2e-3, workers=2)


def test_paper_calibration_numbers(tmp_path):
    """Forces 12.50/16.50 N give mu = 0.408/0.625 (eq. 1); phi_max = 11.5 deg
    gives l1/l2 = 0.817 and eps1/eps2 = 1.251 (eq. 38, 39)."""
    write_measurements(tmp_path, RIG, forces=[(0.0, 12.50), (90.0, 16.50)],
                       angles=[(30.0, -9.0), (39.2, -11.5), (60.0, -8.0)])
    data = load_data(tmp_path)
    res = identify(data, validate=False)
    assert round(res.eq1["mu1"], 3) == 0.408 and round(res.eq1["mu2"], 3) == 0.625
    # with two forces the ellipse fit is eq. (1) exactly
    assert res.fit.values["mu1"] == pytest.approx(res.eq1["mu1"], rel=1e-9)
    assert round(res.max_rule["l1_l2_ratio"], 3) == 0.817
    # eq. (39) with the unrounded mu of these forces (the fit's, which the maximum
    # rule is given) gives 1.253; the paper's 1.251 is eq. (39) with its rounded
    # mu1 = 0.408, mu2 = 0.625
    mu1, mu2 = res.fit.values["mu1"], res.fit.values["mu2"]
    assert res.max_rule["eps_ratio"] == pytest.approx(res.max_rule["l1_l2_ratio"] * mu2 / mu1, rel=1e-12)
    assert round(res.max_rule["eps_ratio"], 3) == 1.253
    assert abs(0.625 / 0.408 * res.max_rule["l1_l2_ratio"] - 1.251) < 1e-3  # 1.2516, printed 1.251
    # two forces leave no degrees of freedom for their noise: said, not faked
    assert res.as_json()["noise_assumed"] == ["forces_N"]


def test_paper_sign_convention_is_accepted(tmp_path):
    write_measurements(tmp_path, dataclasses.replace(RIG, phi_convention="paper"),
                       forces=[(0.0, 12.50), (90.0, 16.50)], angles=[(39.2, 11.5)])
    assert 'phi_convention = "paper"' in (tmp_path / "rig.toml").read_text()
    res = identify(load_data(tmp_path), validate=False)
    assert round(res.max_rule["l1_l2_ratio"], 3) == 0.817


def test_noise_free_fmu_data_recovered_to_1e_6(fmu_data):
    data = MeasurementSet(Path("fmu"), RIG, fmu_data["forces"], fmu_data["angles"], fmu_data["ramp"])
    res = identify(data, validate=False)
    for name, truth in TV.items():
        assert res.fit.values[name] == pytest.approx(truth, rel=1e-6), name
    assert res.eq40["l1_l2_ratio"] == pytest.approx(cf.mat_ratio(1.251, 0.408, 0.625), rel=1e-6)


def test_eq41_is_not_the_least_squares_solution(fmu_data):
    data = MeasurementSet(Path("fmu"), RIG, None, fmu_data["angles"], None)
    e = eq40_fit(data)
    r = cf.mat_ratio(1.251, 0.408, 0.625)
    assert e["r2"] == pytest.approx(r * r, rel=1e-6)
    assert e["objective"] < 1e-20
    assert abs(e["eq41"]["r2"] - r * r) > 0.2  # model notes: ~0.99 against 0.667
    assert e["eq41"]["objective"] > 1e6 * max(e["objective"], 1e-30)


def test_fmu_validation_of_noise_free_fit(fmu_data):
    rig = RigSetup(mass_kg=1.875, f_int_N=5.0, mode="quasistatic", step_s=1e-3, travel_m=0.2)
    data = MeasurementSet(Path("fmu"), rig, fmu_data["forces"], fmu_data["angles"], fmu_data["ramp"])
    v = identify(data, validate=True, workers=2).validation
    assert v["forces_N"]["rms"] < 1e-9
    assert v["angles_deg"]["rms"] < 1e-7
    assert v["ramp_N"]["rms"] < 1e-3  # linear interpolation of the simulation across the kink


def test_absolute_stiffness_without_ramp_is_declared_not_identifiable(fmu_data):
    data = MeasurementSet(Path("fmu"), RIG, fmu_data["forces"], fmu_data["angles"], None)
    j = identify(data, validate=False).as_json()
    for name in ("eps1", "eps2"):
        assert j[name]["identifiable"] is False and "ramp" in j[name]["reason"]
        assert "value" not in j[name]
    assert j["eps_ratio"]["value"] == pytest.approx(1.251, rel=1e-6)


def test_angles_without_forces_give_only_the_eigenvalue_ratio(fmu_data):
    data = MeasurementSet(Path("fmu"), RIG, None, fmu_data["angles"], None)
    j = identify(data, validate=False).as_json()
    assert j["mu1"]["identifiable"] is False and j["eps_ratio"]["identifiable"] is False
    assert "forces" in j["eps_ratio"]["reason"]
    assert j["l1_l2_ratio"]["value"] == pytest.approx(cf.mat_ratio(1.251, 0.408, 0.625), rel=1e-6)


def test_associated_rule_cannot_give_the_stiffness_ratio(tmp_path):
    rig = RigSetup(mass_kg=1.875, f_int_N=5.0, rule="associated")
    m = simulate_measurements(TRUTH, rig, FA, [20, 40], workers=1)
    j = identify(MeasurementSet(Path("a"), rig, m["forces"], m["angles"], None), validate=False).as_json()
    assert j["eps_ratio"]["identifiable"] is False
    assert j["mu2"]["value"] == pytest.approx(0.625, rel=1e-6)


def test_cli_identify_on_the_bundled_example(tmp_path, capsys):
    out = tmp_path / "id"
    assert main(["identify", str(EXAMPLE), "--out", str(out), "--workers", "2"]) == 0
    j = json.loads((out / "identified.json").read_text())
    for name, truth in TV.items():
        e = j[name]
        assert set(e) == {"value", "stderr", "ci95", "dof"}
        assert e["dof"] == "inf" or e["dof"] >= 3  # each parameter its own degrees of freedom
        assert abs(e["value"] - truth) < 4 * e["stderr"], name  # fixed seed: deterministic
    assert j["max_rule"]["l1_l2_ratio"] > 0 and j["eq41"]["note"]
    assert j["validation_fmu"]["angles_deg"]["rms"] < 1.0
    assert (out / "fit.png").stat().st_size > 0 and "| eps2 |" in (out / "identified.md").read_text()


def test_identified_json_names_every_file_read_with_its_sha256(tmp_path):
    """data.files: each file the identification read, its SHA-256 as
    sha256sum prints it; data.sha256: sha256sum's listing of them, hashed
    (as docs/reference/file-formats.md says to recompute it); both from the shell, not the package."""
    data = tmp_path / "data"
    shutil.copytree(EXAMPLE, data)
    (data / "notes.txt").write_text("a file identify does not read")
    out = tmp_path / "id"
    assert main(["identify", str(data), "--out", str(out), "--no-validate"]) == 0
    d = json.loads((out / "identified.json").read_text())["data"]
    names = ["angles.csv", "forces.csv", "ramp.csv", "rig.toml"]
    listing = subprocess.run(["sha256sum", *names], cwd=data, capture_output=True, text=True,
                             check=True).stdout
    assert d["files"] == {ln.split()[1]: ln.split()[0] for ln in listing.splitlines()}
    assert list(d["files"]) == names    # sorted: the order the digest lists them in
    digest = subprocess.run("sha256sum " + " ".join(names) + " | sha256sum", shell=True, cwd=data,
                            capture_output=True, text=True, check=True).stdout.split()[0]
    assert d["sha256"] == digest


BAD_DATA = [
    ("missing column", "forces.csv", "alpha_deg,force\n0,12.5\n90,16.5\n", "force_N"),
    ("not a number", "forces.csv", "alpha_deg,force_N\n0,12.5\n90,sixteen\n", "line 3"),
    ("too few points", "forces.csv", "alpha_deg,force_N\n0,12.5\n", "at least 2"),
    ("angle out of range", "angles.csv", "alpha_deg,phi_deg\n400,3\n", "line 2"),
    ("phi out of range", "angles.csv", "alpha_deg,phi_deg\n30,95\n", "phi_deg"),
    ("one orientation only", "forces.csv", "alpha_deg,force_N\n0,12.5\n0,12.6\n", "two or more"),
    ("bad rig key", "rig.toml", "mass_kg = 1.875\nmass = 2\n", "mass"),
    ("rig missing mass", "rig.toml", "f_int_N = 5.0\n", "mass_kg"),
]


@pytest.mark.parametrize("what,name,content,needle", BAD_DATA, ids=[b[0] for b in BAD_DATA])
def test_bad_data_one_line_exit_2_nothing_written(tmp_path, capsys, what, name, content, needle):
    d = tmp_path / "data"
    write_measurements(d, RIG, forces=[(0.0, 12.5), (90.0, 16.5)])
    (d / name).write_text(content)
    out = tmp_path / "out"
    assert main(["identify", str(d), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert name in err[0] and needle in err[0] and "expected" in err[0]
    assert not out.exists()


def test_missing_folder_and_no_data(tmp_path, capsys):
    assert main(["identify", str(tmp_path / "nope"), "--out", str(tmp_path / "o")]) == 2
    d = tmp_path / "d"
    d.mkdir()
    (d / "rig.toml").write_text("mass_kg = 1.875\n")
    assert main(["identify", str(d), "--out", str(tmp_path / "o")]) == 2
    assert "at least one of" in capsys.readouterr().err
