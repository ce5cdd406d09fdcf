"""Results that check themselves (orthocontact.rig.checks), through the real
command in a subprocess: a rig that never settled, a run off the steady
closed form, --strict, the default rig of a new scenario, and the
identification's validation with its strip terms."""
import json
import math
import subprocess

import pytest

from cli_run import CMD
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.params import ContactParams
from orthocontact.rig.checks import SETTLE_TOL_DEG, check_runs
from orthocontact.rig.compiled import CMaster
from orthocontact.rig.harness import Rig
from paths import DOCS, SCENARIOS

CASE2_LAW = """
[law]
rule = "coupled"
mu1 = 0.1
mu2 = 0.5
eps1 = 1.0e4
eps2 = 1.0e4
[geometry]
closed_form = "eq31"
[sweep]
start_deg = 0.0
stop_deg = 90.0
step_deg = 1.0
"""


def scenario(tmp_path, name, body):
    path = tmp_path / f"{name}.toml"
    path.write_text(f'name = "{name}"\nkind = "sweep"\n' + body)
    return path


def run(args, cwd):
    return subprocess.run(CMD + args, cwd=cwd, capture_output=True, text=True, timeout=300)


def warnings_of(p):
    return [line for line in p.stderr.splitlines() if line.startswith("orthocontact: warning:")]


def test_a_dynamic_rig_that_never_settled_is_flagged_everywhere(tmp_path):
    """Case 2's law in the dynamic rig over the default 0.5 m: a reported
    -59.13 deg at 23.6 deg where the steady state is -67.38 deg at 11.31."""
    sc = scenario(tmp_path, "c2dyn", CASE2_LAW + '[rig]\nmode = "dynamic"\n')
    p = run(["run", str(sc), "--out", "o"], tmp_path)
    assert p.returncode == 0, p.stderr
    lines = warnings_of(p)
    assert len(lines) == 1, p.stderr
    line = lines[0]
    assert "c2dyn:" in line and "not steady sliding" in line and "1-31 deg" in line
    assert "departs from the steady closed form by up to 36.2 deg" in line
    assert 'rig.mode = "quasistatic"' in line and "rig.travel_m >=" in line
    # the rig's guide shows this very line
    guide = DOCS / "guides" / "scenarios-and-rig.md"
    assert line in guide.read_text()
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    checks = summary["checks"]
    assert checks["ok"] is False and checks["warning"] == line.split("warning: ", 1)[1]
    assert checks["unsettled_angles_deg"] == [float(a) for a in range(1, 32)]
    assert 23.0 in checks["off_steady_angles_deg"] and 0.0 not in checks["off_steady_angles_deg"]
    rows = (tmp_path / "o" / "sweep.csv").read_text().splitlines()
    header = rows[0].split(",")
    assert header[-4:] == ["phi_head_deg", "phi_tail_deg", "phi_steady_deg", "check"]
    by_angle = {r.split(",")[0]: r for r in rows[1:]}
    assert by_angle["0"].endswith(",ok") and by_angle["11"].endswith('"unsettled, off-steady"')
    assert by_angle["40"].endswith(",ok")
    # the extremum the sweep found lies among them: it says so
    assert summary["extremum"]["steady_sliding"] is False
    # --strict: the same warnings, exit 1, the results written all the same
    p = run(["run", str(sc), "--out", "o2", "--strict"], tmp_path)
    assert p.returncode == 1 and len(warnings_of(p)) == 1 and "--strict" in p.stderr
    assert (tmp_path / "o2" / "summary.json").is_file()


def test_a_new_scenario_gets_a_rig_that_settles(tmp_path):
    """No [rig] table: the quasi-static rig, whose extremum is the paper's."""
    sc = scenario(tmp_path, "c2", CASE2_LAW)
    p = run(["run", str(sc), "--out", "o", "--strict"], tmp_path)
    assert p.returncode == 0 and warnings_of(p) == [], p.stderr
    s = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert s["mode"] == "quasistatic" and s["checks"]["ok"] is True
    assert s["extremum"]["steady_sliding"] is True
    assert s["extremum"]["phi_deg"] == pytest.approx(-67.380135, abs=1e-4)
    assert s["extremum"]["angle_deg"] == pytest.approx(math.degrees(math.atan(0.2)), abs=1e-3)


def test_a_default_travel_the_law_cannot_settle_in_is_refused(tmp_path):
    soft = "[law]\nmu1 = 0.4\nmu2 = 0.6\neps1 = 100.0\neps2 = 100.0\n[sweep]\nstep_deg = 10.0\n"
    p = run(["run", str(scenario(tmp_path, "soft", soft)), "--out", "o"], tmp_path)
    assert p.returncode == 2 and not (tmp_path / "o").exists()
    line = p.stderr.strip()
    assert len(line.splitlines()) == 1 and "soft.toml: rig.travel_m" in line and "elastic length" in line
    assert "set rig.travel_m >= 2.21" in line
    # the travel it names settles
    p = run(["run", str(scenario(tmp_path, "soft2", soft + "[rig]\ntravel_m = 2.21\n")), "--out", "o",
             "--strict"], tmp_path)
    assert p.returncode == 0, p.stderr


def test_checks_separate_settled_from_unsettled_runs_on_the_rig_itself():
    """The checks' verdicts against independent evidence: the same law run
    much further settles onto the closed form; the short run did not."""
    law = ContactParams.from_degrees(0.1, 0.5, 1e4, 1e4, 11.31, 11.31)
    short = Rig(mode="dynamic", travel_m=0.5)
    long = Rig(mode="dynamic", travel_m=8.0, step_s=1e-3, fit_from=0.75)
    cm = CMaster(find_fmu())
    try:
        res = cm.run([(law, short), (law, long)])
    finally:
        cm.close()
    checks = check_runs([(law, short), (law, long)], res)
    assert checks.status() == ["unsettled, off-steady", "ok"]
    assert abs(checks.halves_deg[1]) <= SETTLE_TOL_DEG
    assert res[1].phi_deg == pytest.approx(-67.38, abs=0.01)
    # the settling length the message names: the model notes' 0.40 m
    L = checks.settling_length_m[0]
    assert L == pytest.approx(0.40, abs=0.01)


def test_eq20_runs_are_marked_but_not_warned_about(tmp_path):
    """The step study shows the literal rule's step dependence on purpose."""
    p = run(["run", str(SCENARIOS / "step_study.toml"), "--out", "o", "--strict"], tmp_path)
    assert p.returncode == 0 and warnings_of(p) == [], p.stderr
    rows = (tmp_path / "o" / "step_study.csv").read_text().splitlines()
    eq20 = [r for r in rows[1:] if r.startswith("eq20")]
    assert eq20 and any("unsettled" in r for r in eq20)
    assert all(r.endswith(",ok") for r in rows[1:] if not r.startswith("eq20"))


def test_the_identifications_validation_runs_the_fitted_strip(tmp_path):
    """Noise-free data from the rig with a viscous strip at two velocities:
    the validation simulates the estimated c_strip (it took c_strip = 0 and
    reported 3.1 deg and -0.19 N of residuals for a perfect fit)."""
    from orthocontact.experiment.rig_setup import RigSetup
    from orthocontact.identification.measurements import write_measurements
    truth = ContactParams(0.408, 0.625, 12510.0, 1e4)
    rig = RigSetup(mass_kg=1.875, f_int_N=5.0, mu_strip=0.05)
    tasks, meta = [], []
    for v in (0.125, 0.244):
        h = rig.harness(step_s=1e-3, travel_m=0.2, velocity_m_s=v, c_strip=20.0)
        for a in range(5, 90, 10):
            tasks.append((rig.params_at(truth, a), h))
            meta.append(("angle", a, v))
    h = rig.harness(step_s=1e-3, travel_m=0.2, c_strip=20.0)
    for a in (0, 30, 60, 90):
        tasks.append((rig.params_at(truth, a), h))
        meta.append(("force", a, rig.velocity_m_s))
    cm = CMaster(find_fmu())
    try:
        res = cm.run(tasks)
    finally:
        cm.close()
    angles = [[a, r.phi_deg] for (k, a, _), r in zip(meta, res) if k == "angle"]
    vel = [v for k, _, v in meta if k == "angle"]
    forces = [[a, r.drive_mean_N] for (k, a, _), r in zip(meta, res) if k == "force"]
    write_measurements(tmp_path / "d", rig, forces=forces, angles=angles, angle_velocities=vel)
    p = run(["identify", str(tmp_path / "d"), "--out", "o", "--strict"], tmp_path)
    assert p.returncode == 0, p.stderr
    j = json.loads((tmp_path / "o" / "identified.json").read_text())
    v = j["validation_fmu"]
    assert v["c_strip_used_N_s_m"] == pytest.approx(20.0, rel=1e-5)
    assert v["checks"]["ok"] is True
    assert v["angles_deg"]["max_abs"] < 1e-5 and v["forces_N"]["max_abs"] < 1e-5


def test_identify_no_longer_ends_in_a_traceback_on_case5_material_with_a_viscous_strip(tmp_path):
    """Case 5's material in the mat geometry with c_strip = 40 N s/m known:
    the old strip closed form took a square root of a negative number."""
    from orthocontact.experiment.rig_setup import RigSetup
    from orthocontact.identification.measurements import write_measurements
    truth = ContactParams(0.1, 0.5, 1e4, 1e3)
    rig = RigSetup(mass_kg=1.875, f_int_N=5.0, c_strip=40.0)
    h = rig.harness(step_s=1e-3, travel_m=0.2)
    angles_at, forces_at = list(range(5, 90, 5)), [0, 15, 30, 45, 60, 75, 90]
    cm = CMaster(find_fmu())
    try:
        ra = cm.run([(rig.params_at(truth, a), h) for a in angles_at])
        rf = cm.run([(rig.params_at(truth, a), h) for a in forces_at])
    finally:
        cm.close()
    write_measurements(tmp_path / "d", rig, forces=[[a, r.drive_mean_N] for a, r in zip(forces_at, rf)],
                       angles=[[a, r.phi_deg] for a, r in zip(angles_at, ra)])
    p = run(["identify", str(tmp_path / "d"), "--out", "o"], tmp_path)
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr
    j = json.loads((tmp_path / "o" / "identified.json").read_text())
    assert j["eps_ratio"]["value"] == pytest.approx(10.0, rel=1e-6)
    assert j["mu1"]["value"] == pytest.approx(0.1, rel=1e-6)


def test_a_stiffness_in_n_per_mm_is_named_as_the_cause_not_the_travel(tmp_path):
    """eps2 = 10 (N/mm typed as N/m) in the aged mat's 0.5 m dynamic rig: it
    was told "rig.travel_m >= 0.357 m", a travel it has; the cause is the
    elastic length mu N / eps = 1.15 m."""
    text = (SCENARIOS / "mat_aged.toml").read_text()
    assert "eps2 = 1.0e4" in text and 'mode = "dynamic"' in text and "travel_m = 0.5" in text
    sc = tmp_path / "aged.toml"
    sc.write_text(text.replace("eps2 = 1.0e4", "eps2 = 10.0"))
    p = run(["run", str(sc), "--out", "o"], tmp_path)
    assert p.returncode == 0, p.stderr
    lines = warnings_of(p)
    assert len(lines) == 1, p.stderr
    remedy = lines[0].split("; remedy: ", 1)[1]
    assert remedy.startswith("check eps1, eps2 = 12.51, 10 N/m (N/mm typed as N/m?")
    assert "the elastic length max(mu) N / min(eps) = 1.15 m" in remedy
    assert "0.357" not in remedy and "nan" not in lines[0]
    # the travel it would take otherwise is longer than the rig's, never one it has
    need = float(remedy.rsplit("rig.travel_m >= ", 1)[1].split(" m")[0])
    assert need > 0.5


def test_the_remedy_names_the_step_when_the_step_is_the_cause():
    """Quasi-static runs whose fitted path holds 3 steps: the step, not the
    travel (the law's elastic length is 1 mm, it settles)."""
    from orthocontact.rig.checks import MIN_FIT_STEPS, fitted_steps, remedy, run_cause
    law = ContactParams.from_degrees(0.408, 0.625, 12510.0, 1e4, 130.0, 40.0)
    rig = Rig(travel_m=0.5, step_s=0.5)
    assert fitted_steps(rig) == 3 < MIN_FIT_STEPS
    assert run_cause(law, rig, float("nan"))[0] == "step"
    text = remedy([(law, rig)], [float("nan")], "--step-s")
    assert text.startswith("--step-s <= 0.051 s (the step 0.5 s leaves 3 steps in the fitted path")
    # a rig that settles has no cause: the remedy says so instead of guessing
    fine = Rig(travel_m=0.5, step_s=1e-3)
    assert run_cause(law, fine, float("nan")) is None
    assert "neither the elastic length, the settling length nor the step" in \
        remedy([(law, fine)], [float("nan")])


def test_a_rig_that_fits_from_the_start_of_its_path_is_told_to_fit_later(tmp_path):
    """rig.fit_from = 0 (its range is [0, 0.95]) puts the fit's start at
    0 m, within any elastic length: the run's remedy and the default
    travel's refusal divided by it (ZeroDivisionError, a traceback); they
    name rig.fit_from instead."""
    law = "[law]\nmu1 = 0.408\nmu2 = 0.625\neps1 = 1.251e3\neps2 = 1.0e3\n[sweep]\nstep_deg = 45.0\n"
    p = run(["run", str(scenario(tmp_path, "f0", law + "[rig]\nfit_from = 0.0\ntravel_m = 0.2\n")), "--out",
             "o"], tmp_path)
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr
    assert len(warnings_of(p)) == 1 and "rig.fit_from > 0: the fit starts where the path does" in p.stderr
    p = run(["run", str(scenario(tmp_path, "d0", law + "[rig]\nfit_from = 0.0\n")), "--out", "o2"], tmp_path)
    assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert "d0.toml: rig.travel_m: expected a travel for this law" in p.stderr
    assert "set rig.fit_from > 0 (the fit starts where the path does)" in p.stderr
