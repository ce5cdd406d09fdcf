"""The scenario kinds twist and towed_block (orthocontact.reproduction.
planar_outputs) through `orthocontact run`: their files, their self-checks
against the closed forms (an unsettled run is said, not passed), their
figures, and a bad scenario refused in one line."""
import csv
import json
import math

import pytest

from orthocontact.experiment.scenario import load
from orthocontact.fmu.params import ContactParams
from orthocontact.reproduction import planar_outputs
from orthocontact.rig import planar
from cli_run import one_error_line, run_cli

LAW = """
[law]
rule = "coupled"
mu1 = 0.408
mu2 = 0.625
eps2 = {eps2}
eps_ratio = 1.251

[geometry]
alpha_offset_deg = 90.0
beta_offset_deg = 0.0

[rig]
mass_kg = 1.875
velocity_m_s = 0.244

[patch]
length_m = 0.1
width_m = 0.05
n1 = {n1}
n2 = {n2}
"""

TWIST = 'name = "twist"\nkind = "twist"\n' + LAW.format(eps2=1e5, n1=8, n2=4) + """
[twist]
angle_deg = 30.0
rate_deg_s = 10.0
step_s = 1.0e-3
"""

TOWED = 'name = "towed"\nkind = "towed_block"\n' + LAW.format(eps2=1e4, n1=4, n2=2) + """
[tow]
pin_m = 0.1
duration_s = {duration}
step_s = 5.0e-3
angles_deg = [20.0, 39.2, 60.0]
"""


def test_twist_run_checks_itself_against_both_closed_forms(tmp_path):
    (tmp_path / "t.toml").write_text(TWIST)
    p = run_cli(["run", tmp_path / "t.toml", "--out", tmp_path / "out"], cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert p.stderr == ""
    s = json.loads((tmp_path / "out/summary.json").read_text())
    assert s["kind"] == "twist" and s["checks"] == {"ok": True, "warning": None}
    sc = load(tmp_path / "t.toml")
    body = planar_outputs.body_of(sc)
    for rule in ("associated", "coupled"):
        r = s["rules"][rule]
        k = planar.twist_stiffness(sc.params_at(0.0, rule), body.patch)
        assert r["k_N_m_rad"] == k and r["ok"]
        assert r["slope_relative_error"] <= r["slope_tolerance"]
        assert r["plateau_max_relative_error"] <= r["plateau_tolerance"]
    rows = list(csv.DictReader(open(tmp_path / "out/twist.csv")))
    assert {r["rule"] for r in rows} == {"associated", "coupled"}
    assert (tmp_path / "out/twist.png").stat().st_size > 10_000


def test_towed_block_run_gives_the_closed_form_yaw_at_every_mat_angle(tmp_path):
    (tmp_path / "t.toml").write_text(TOWED.format(duration=20.0))
    p = run_cli(["run", tmp_path / "t.toml", "--out", tmp_path / "out", "--fmi", "3"], cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    s = json.loads((tmp_path / "out/summary.json").read_text())
    assert s["checks"]["ok"] and s["fmi_version"] == 3
    assert s["max_deviation_deg"] < 1e-7
    for rule in ("associated", "coupled"):
        for a in (20.0, 39.2, 60.0):
            law = ContactParams.from_degrees(0.408, 0.625, 1.251e4, 1e4, a + 90.0, a, rule)
            assert s["yaw_deg"][rule][f"{a:g}"] == pytest.approx(math.degrees(planar.steady_yaw(law)),
                                                                abs=1e-7)
    for name in ("towed_block.csv", "yaw_vs_time.csv", "yaw_vs_angle.png", "yaw_vs_time.png"):
        assert (tmp_path / "out" / name).is_file(), name


def test_an_unsettled_towed_block_is_said_not_passed(tmp_path):
    (tmp_path / "t.toml").write_text(TOWED.format(duration=0.5))
    p = run_cli(["run", tmp_path / "t.toml", "--out", tmp_path / "out"], cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert "has not settled; tow longer (tow.duration_s)" in p.stderr
    s = json.loads((tmp_path / "out/summary.json").read_text())
    assert not s["checks"]["ok"] and s["max_deviation_deg"] > planar_outputs.YAW_TOL_DEG


@pytest.mark.parametrize("old,new,says", [
    ("[tow]\n", "[towx]\n", "towx: expected a known table"),
    ("pin_m = 0.1", "pin_m = -0.1", "tow.pin_m: expected a number > 0"),
    ("n1 = 4", "n1 = 4.5", "patch.n1: expected an integer in 1..32"),
    ('kind = "towed_block"', 'kind = "twist"', "tow: expected no [tow] table in a scenario of kind 'twist'"),
])
def test_a_bad_patch_scenario_is_one_line(tmp_path, old, new, says):
    text = TOWED.format(duration=1.0)
    assert old in text
    (tmp_path / "t.toml").write_text(text.replace(old, new))
    p = run_cli(["run", tmp_path / "t.toml", "--out", tmp_path / "out"], cwd=tmp_path)
    one_error_line(p, says)
    assert not (tmp_path / "out").exists()


def test_a_patch_scenario_naming_the_point_fmu_is_one_line(tmp_path):
    from orthocontact.fmu.files import find_fmu
    text = 'fmu = "%s"\n' % find_fmu(fmi_version=2) + TOWED.format(duration=1.0)
    (tmp_path / "t.toml").write_text(text)
    p = run_cli(["run", tmp_path / "t.toml", "--out", tmp_path / "out"], cwd=tmp_path)
    one_error_line(p, "fmu: expected a ContactPatch FMU for a scenario of kind 'towed_block'",
                   "OrthotropicContact")


def test_the_paper_report_refuses_a_patch_scenario_in_its_folder(tmp_path):
    (tmp_path / "s").mkdir()
    (tmp_path / "s/t.toml").write_text(TOWED.format(duration=1.0))
    p = run_cli(["reproduce", "--scenarios", tmp_path / "s", "--out", tmp_path / "out"], cwd=tmp_path)
    one_error_line(p, "kind: expected a sweep or step_study scenario for the paper's report",
                   "'towed_block'")
