"""The subcommands (orthocontact.cli.commands) end to end: run writes its
summary, tables and figures; reproduce matches every number of the paper."""
import json
import math

import pytest

from orthocontact.cli.commands import load_scenario, packaged_scenarios
from orthocontact.cli.main import main
from paths import SCENARIOS

# -- the CLI ------------------------------------------------------------------------

def test_cli_run_writes_summary_tables_and_figures(tmp_path, capsys):
    sc = (SCENARIOS / "case5.toml").read_text().replace("step_deg = 1.0", "step_deg = 5.0")
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


def test_reproduce_on_coarse_grids_matches_every_number(tmp_path, capsys):
    """The main job's code path: every packaged scenario on a 10-degree grid
    (the extremum search refines it), the report and its table."""
    folder = tmp_path / "scen"
    folder.mkdir()
    for f in SCENARIOS.glob("*.toml"):
        text = f.read_text().replace("step_deg = 1.0", "step_deg = 10.0")
        text = text.replace("steps_s = [2.0e-3, 1.0e-3, 5.0e-4, 2.0e-4, 1.0e-4]",
                            "steps_s = [1.0e-3, 5.0e-4]")
        # the towed block
        text = text.replace("angles_deg = [15.0, 39.2, 60.0, 75.0]", "angles_deg = [39.2]")
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
    ratio = -t + math.sqrt(t * t + 1)  # eq. (29) with the paper's phi_max = +11.5 deg: 0.817
    chain = {c["step"]: c["value"] for c in rep["calibration_chain"]}
    assert chain["ε1/ε2 by eq. (39)"] == pytest.approx(ratio * mu2 / mu1, rel=1e-9)
    assert chain["ε1/ε2 by eq. (39), paper"] == pytest.approx(ratio * 0.625 / 0.408, rel=1e-9)
    assert "1.2528" in report
    # the rig's assumptions: the strip's sensitivity, in the report and its JSON
    assert rep["sensitivity"]["scenario"] == "mat_aged" and "## The rig's assumptions" in report
    assert (out / "sensitivity" / "sensitivity_strip.png").stat().st_size > 0
    for name in ("case1", "case5", "mat_aged", "step_study"):
        assert (out / name / "summary.json").exists()
    # the contact patch: a section of its own, not rows of the paper (tests/reproduction/test_patch_report.py)
    assert report.index("## The contact patch") < report.index("## Scenarios")
    assert all(rep["contact_patch"][n]["checks"]["ok"] for n in ("twist", "towed_block"))
    assert (out / "twist" / "twist_cells.png").stat().st_size > 0
    assert {r["scenario"] for r in rows} >= {"case1", "case2", "case3", "case4", "case5", "mat_aged",
                                            "mat_new", "calibration"}


def test_the_packaged_scenarios_are_the_repositorys(capsys):
    folder = packaged_scenarios()
    assert sorted(p.name for p in folder.glob("*.toml")) == sorted(p.name for p in SCENARIOS.glob("*.toml"))
    for f in SCENARIOS.glob("*.toml"):
        assert (folder / f.name).read_text() == f.read_text()
    sc = load_scenario(SCENARIOS / "case5.toml", yes=False)    # size checked, within the limits
    assert sc.name == "case5" and capsys.readouterr().err == ""
