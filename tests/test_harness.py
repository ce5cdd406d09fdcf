"""The rig harness and scenarios against the paper's closed forms and
published numbers, and the CLI's input contract."""
import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from orthocontact import closed_forms as cf
from orthocontact.cli.main import main
from orthocontact.experiment.scenario import load
from orthocontact.fmu.params import ContactParams
from orthocontact.rig.harness import Rig, run
from orthocontact.runs.sweep import closed_form_phi_deg, run_sweep

SCEN = Path(__file__).resolve().parents[1] / "scenarios"
QS = Rig(mode="quasistatic", step_s=1e-3, travel_m=0.2)


def _coarse(name, **sweep):
    sc = load(SCEN / f"{name}.toml")
    sc.sweep = dict(sc.sweep, **sweep)
    return sc


@pytest.mark.parametrize("name,eq", [("case1", "eq11"), ("case2", "eq31"), ("case3", "eq33"),
                                     ("case4", "eq25"), ("case5", "eq25")])
def test_harness_steady_angles_match_the_paper_equations(name, eq):
    sc = _coarse(name, step_deg=7.5, refine_extremum=False, trajectory_angles_deg=[0.0])
    assert sc.closed_form == eq
    res = run_sweep(sc, workers=1, progress=False)
    # the named equation and the general tensor form agree ...
    general = [cf.steady_phi_deg(*(lambda p: (p.mu1, p.mu2, p.eps1, p.eps2, p.alpha, p.beta, p.rule))(sc.params_at(a)))
               for a in res.angles_deg]
    np.testing.assert_allclose(res.phi_closed_deg, general, atol=1e-9)
    # ... and the rig reproduces them
    assert res.max_deviation_deg < 1e-6


@pytest.mark.parametrize("name,angle,phi", [("case1", 78.69, 67.38), ("case2", 11.31, -67.38),
                                            ("case3", 78.69, 67.38), ("case5", 26.56, -36.87)])
def test_extrema_match_published_values(name, angle, phi):
    sc = _coarse(name, trajectory_angles_deg=[0.0])
    e = run_sweep(sc, workers=2, progress=False).extremum
    assert e["angle_deg"] == pytest.approx(angle, abs=0.01)
    assert e["phi_deg"] == pytest.approx(phi, abs=0.005)  # the paper's 2 decimals


def test_mat_extremum_is_the_calibration_point():
    """With eps1/eps2 = 1.251 the aged mat peaks at |phi| = 11.5 deg (model notes)."""
    sc = _coarse("mat_aged", start_deg=30.0, stop_deg=50.0, step_deg=2.0, trajectory_angles_deg=[0.0])
    sc.rig = replace(sc.rig, mode="quasistatic", step_s=1e-3, travel_m=0.2)
    e = run_sweep(sc, workers=1, progress=False).extremum
    r = cf.mat_ratio(1.251, 0.408, 0.625)
    th, ph = cf.mat_extremum(r)
    assert e["angle_deg"] == pytest.approx(math.degrees(th), abs=0.01)
    assert e["phi_deg"] == pytest.approx(math.degrees(ph), abs=1e-6)
    assert abs(e["phi_deg"]) == pytest.approx(11.5, abs=0.05)


@pytest.mark.parametrize("case,angle,travel", [("case5", 26.565, 0.5), ("mat_aged", 39.2, 0.5),
                                               ("case2", 11.31, 6.0)])
def test_dynamic_and_quasistatic_modes_agree(case, angle, travel):
    """Same steady angle.  At case 2's extremum the block must build up a
    lateral speed 2.4 times the push, so its inertia needs metres, not the
    rig's 0.5 m, to settle: fit over the last 20%."""
    sc = load(SCEN / f"{case}.toml")
    p = sc.params_at(angle)
    dyn = run(p, Rig(mode="dynamic", step_s=5e-4, travel_m=travel, fit_from=0.8), record_every=1000)
    qs = run(p, Rig(mode="quasistatic", step_s=1e-3, travel_m=0.5))
    assert qs.phi_deg == pytest.approx(closed_form_phi_deg(sc, angle), abs=1e-8)
    assert dyn.phi_deg == pytest.approx(qs.phi_deg, abs=0.02)
    assert dyn.drive_mean_N == pytest.approx(qs.drive_mean_N, abs=0.01)


def test_experiment_driving_forces():
    sc = load(SCEN / "mat_aged.toml")
    f0 = run(sc.params_at(0.0), sc.rig).drive_mean_N
    f90 = run(sc.params_at(90.0), sc.rig).drive_mean_N
    assert f0 == pytest.approx(12.50, abs=0.05)
    assert f90 == pytest.approx(16.50, abs=0.05)
    # and eq. (1) turns them back into the friction coefficients
    assert cf.eq1_mu(f0, 5.0, 1.875) == pytest.approx(0.408, abs=5e-4)
    assert cf.eq1_mu(f90, 5.0, 1.875) == pytest.approx(0.625, abs=5e-4)


def test_new_mat_moves_straight_although_friction_is_orthotropic():
    sc = _coarse("mat_new", step_deg=15.0, trajectory_angles_deg=[0.0])
    sc.rig = replace(sc.rig, mode="quasistatic", step_s=1e-3, travel_m=0.2)
    res = run_sweep(sc, workers=1, progress=False)
    assert np.max(np.abs(res.phi_deg)) < 1e-8
    assert sc.law.eps1 / sc.law.eps2 == pytest.approx(0.625 / 0.408)


@pytest.mark.parametrize("mode", ["quasistatic", "dynamic"])
@pytest.mark.parametrize("mu_strip", [0.1, 0.3, 0.8])
def test_teflon_strip_friction_against_its_closed_form(mode, mu_strip):
    a = math.radians(40)
    p = ContactParams(0.1, 0.5, 1e4, 1e3, a, a + math.pi / 2)
    rig = Rig(mode=mode, mu_strip=mu_strip, step_s=1e-3 if mode == "quasistatic" else 2e-4, travel_m=0.4)
    expected = math.degrees(math.atan(cf.steady_tan_phi_with_strip(
        p.mu1, p.mu2, p.eps1, p.eps2, p.alpha, p.beta, p.rule, mu_strip)))
    assert run(p, rig).phi_deg == pytest.approx(expected, abs=1e-6 if mode == "quasistatic" else 0.02)


def test_sweep_does_not_depend_on_the_number_of_workers():
    sc = _coarse("case5", step_deg=10.0, refine_extremum=False, trajectory_angles_deg=[0.0])
    sc.rig = replace(sc.rig, mode="dynamic", step_s=5e-4)
    one = run_sweep(sc, workers=1, progress=False)
    two = run_sweep(sc, workers=2, progress=False)
    assert np.array_equal(one.phi_deg, two.phi_deg)
    assert np.array_equal(one.drive_mean_N, two.drive_mean_N)


def test_energy_balance_of_a_rig_run():
    """Work of the push minus the kinetic energy left in the block equals the
    dissipated energy plus what is stored in the interface (quasistatic: no
    kinetic energy) -- to the backward-Euler algorithmic term, small here."""
    sc = load(SCEN / "case5.toml")
    p = sc.params_at(30.0)
    r = run(p, Rig(mode="quasistatic", step_s=1e-4, travel_m=0.1))
    work = np.sum(-r.T1[1:] * np.diff(r.x1)) + np.sum(-r.T2[1:] * np.diff(r.x2))
    B = cf.adhesion_tensor(p.eps1, p.eps2, p.alpha)
    e = np.array([r.x1[-1] - r.s1[-1], r.x2[-1] - r.s2[-1]])
    stored = 0.5 * e @ B @ e
    assert r.energy[-1] > 0
    assert work == pytest.approx(r.energy[-1] + stored, rel=2e-3)


# -- the CLI ------------------------------------------------------------------------

def test_cli_run_writes_summary_tables_and_figures(tmp_path, capsys):
    sc = (SCEN / "case5.toml").read_text().replace("step_deg = 1.0", "step_deg = 5.0")
    f = tmp_path / "c5.toml"
    f.write_text(sc)
    out = tmp_path / "out"
    assert main(["run", str(f), "--out", str(out), "--workers", "2"]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["extremum"]["angle_deg"] == pytest.approx(26.565, abs=0.01)
    assert s["extremum"]["phi_deg"] == pytest.approx(-36.87, abs=0.005)
    assert s["max_deviation_deg"] < 1e-6
    for name in ("sweep.csv", "trajectories.csv", "phi_vs_angle.png", "trajectories.png",
                 "force_vs_travel.png"):
        assert (out / name).stat().st_size > 0
    header = (out / "sweep.csv").read_text().splitlines()[0]
    assert header.startswith("angle_deg,alpha_deg,beta_deg,phi_deg,phi_closed_deg")
    assert "100%" in capsys.readouterr().err  # progress


BAD = [
    ("unknown key", "mu3 = 0.2\n", "[law]", "law.mu3"),
    ("wrong type", 'mu1 = "high"\n', "[law]", "law.mu1"),
    ("out of range", "mu2 = -0.5\n", "[law]", "law.mu2"),
    ("bad mode", 'mode = "fast"\n', "[rig]", "rig.mode"),
    ("missing fmu", 'fmu = "nowhere/OrthotropicContact.fmu"\n', None, "fmu"),
    ("bad evidence", 'evidence = "hearsay"\n', "[paper]", "paper.evidence"),
    ("unknown calibration input", 'calibrated_on = ["phi_deg"]\n', "[paper]", "paper.calibrated_on"),
]


@pytest.mark.parametrize("what,line,table,key", BAD, ids=[b[0] for b in BAD])
def test_bad_scenario_one_line_exit_2_nothing_written(tmp_path, capsys, what, line, table, key):
    text = (SCEN / "case1.toml").read_text()
    if table:
        # replace an existing key of the table, or add the new one to it
        k = line.split("=")[0].strip()
        lines = text.splitlines(keepends=True)
        start = lines.index(table + "\n")
        for i in range(start + 1, len(lines)):
            if lines[i].startswith(k + " ") or lines[i].startswith("["):
                if lines[i].startswith(k + " "):
                    lines[i] = line
                else:
                    lines.insert(i, line)
                break
        else:  # the table is the file's last
            lines.append(line)
        text = "".join(lines)
    else:
        text = line + text
    f = tmp_path / "bad.toml"
    f.write_text(text)
    out = tmp_path / "out"
    assert main(["run", str(f), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert str(f) in err[0] and key in err[0] and "expected" in err[0]
    assert not out.exists() or not any(out.iterdir())
    assert not list(tmp_path.glob(".out.partial-*"))


def test_toml_syntax_error_is_one_line(tmp_path, capsys):
    f = tmp_path / "broken.toml"
    f.write_text("name = \n")
    assert main(["run", str(f), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "broken.toml" in err[0] and "TOML" in err[0]


def test_failed_run_leaves_the_output_folder_untouched(tmp_path, monkeypatch):
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("earlier result")
    import orthocontact.reproduction.scenario_outputs as report

    def boom(*a, **k):
        raise RuntimeError("disk full")
    monkeypatch.setattr(report, "sweep_outputs", boom)
    sc = (SCEN / "case4.toml").read_text().replace("step_deg = 1.0", "step_deg = 45.0")
    f = tmp_path / "c4.toml"
    f.write_text(sc)
    with pytest.raises(RuntimeError):
        main(["run", str(f), "--out", str(out), "--workers", "1"])
    assert [p.name for p in out.iterdir()] == ["keep.txt"]
    assert not list(tmp_path.glob(".out.partial-*"))


def test_reproduce_on_coarse_grids_matches_every_number(tmp_path, capsys):
    """The main job's code path: every packaged scenario on a 10-degree grid
    (the extremum search refines it), the report and its table."""
    folder = tmp_path / "scen"
    folder.mkdir()
    for f in SCEN.glob("*.toml"):
        text = f.read_text().replace("step_deg = 1.0", "step_deg = 10.0")
        text = text.replace("steps_s = [2.0e-3, 1.0e-3, 5.0e-4, 2.0e-4, 1.0e-4]", "steps_s = [1.0e-3, 5.0e-4]")
        (folder / f.name).write_text(text)
    out = tmp_path / "results"
    assert main(["reproduce", "--out", str(out), "--scenarios", str(folder), "--workers", "2"]) == 0
    report = (out / "report.md").read_text()
    rows = json.loads((out / "summary.json").read_text())["rows"]
    assert len(rows) == 19 and all(r["match"] for r in rows)
    rep = json.loads((out / "report.json").read_text())
    assert [{k: r[k] for k in ("scenario", "quantity", "kind")} for r in rep["rows"]] == \
        [{k: r[k] for k in ("scenario", "quantity", "kind")} for r in rows]
    assert all(set(r) >= {"scenario", "quantity", "paper", "here", "tolerance", "match", "kind"}
               for r in rep["rows"])
    kinds = {}
    for r in rows:
        kinds.setdefault(r["kind"], []).append((r["scenario"], r["quantity"]))
    # every number the aged mat was calibrated on comes back as a round trip
    assert sorted(s for s, _ in kinds["round-trip"]) == ["mat_aged"] * 5 + ["mat_new"]
    assert {s for s, _ in kinds["closed-form"]} == {"case1", "case2", "case3", "case4", "case5",
                                                    "calibration"}
    assert "prediction" not in kinds
    assert "closed-form: 13 of 13 matched; round-trip: 6 of 6 matched; prediction: none" in report
    # the new mat's forces are not in the paper: no row claims them
    assert not [r for r in rows if r["scenario"] == "mat_new" and "force" in r["quantity"]]
    # signed, in the paper's convention, with the other rule beside
    aged = next(r for r in rows if r["scenario"] == "mat_aged" and r["quantity"].startswith("extremal"))
    assert aged["here"] == pytest.approx(11.53, abs=0.05) and aged["other_rule"]["rule"] == "associated"
    assert aged["other_rule"]["here"] < -15  # the associated rule turns the block the other way
    c2 = next(r for r in rows if r["scenario"] == "case2" and r["quantity"].startswith("extremal"))
    assert c2["paper"] < 0 and c2["here"] == pytest.approx(-67.38, abs=0.01)
    # the calibration chain from the forces, unrounded (eq. 1, 29, 39 by hand)
    mu1, mu2 = (12.5 - 5.0) / (1.875 * 9.806), (16.5 - 5.0) / (1.875 * 9.806)
    t = math.tan(math.radians(11.5))
    l = -t + math.sqrt(t * t + 1)  # eq. (29) with the paper's phi_max = +11.5 deg: 0.817
    chain = {c["step"]: c["value"] for c in rep["calibration_chain"]}
    assert chain["ε1/ε2 by eq. (39)"] == pytest.approx(l * mu2 / mu1, rel=1e-9)
    assert chain["ε1/ε2 by eq. (39), paper"] == pytest.approx(l * 0.625 / 0.408, rel=1e-9)
    assert "1.2528" in report
    # the rig's assumptions: the strip's sensitivity, in the report and its JSON
    assert rep["sensitivity"]["scenario"] == "mat_aged" and "## The rig's assumptions" in report
    assert (out / "sensitivity" / "sensitivity_strip.png").stat().st_size > 0
    for name in ("case1", "case5", "mat_aged", "step_study"):
        assert (out / name / "summary.json").exists()
    assert {r["scenario"] for r in rows} >= {"case1", "case2", "case3", "case4", "case5", "mat_aged",
                                            "mat_new", "calibration"}


def test_vectorized_closed_forms_equal_the_scalar_ones():
    """The report's 90,001-point scans use the array form: same numbers."""
    from pathlib import Path as _P

    import numpy as np

    from orthocontact.runs.sweep import closed_form_phi_deg, closed_form_phi_deg_array
    a = np.linspace(-30, 120, 301)
    for f in sorted((_P(__file__).resolve().parents[1] / "scenarios").glob("*.toml")):
        sc = load(f)
        for rule in (None, "associated", "coupled", "eq20"):
            v = closed_form_phi_deg_array(sc, a, rule)
            s = np.array([closed_form_phi_deg(sc, x, rule) for x in a])
            np.testing.assert_allclose(v, s, rtol=0, atol=1e-12)
