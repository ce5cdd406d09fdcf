"""The report's section on the contact patch (orthocontact.reproduction.
patch_report) through `orthocontact reproduce`: the bundled twist and towed
block beside a paper scenario, each check against its closed forms in the
section, its figures linked and written, the paper's rows and headline
untouched; a failed check is its warning line, not a failed reproduction."""
import json
import math
import re

from cli_run import run_cli
from orthocontact.experiment.scenario import load
from orthocontact.reproduction import patch_report
from orthocontact.reproduction.planar_outputs import YAW_TOL_DEG
from orthocontact.rig import planar
from paths import SCENARIOS


def test_reproduce_writes_the_patch_section_apart_from_the_papers_rows(tmp_path):
    folder = tmp_path / "scen"
    folder.mkdir()
    for name in ("twist", "towed_block"):
        (folder / f"{name}.toml").write_text((SCENARIOS / f"{name}.toml").read_text())
    (folder / "case4.toml").write_text((SCENARIOS / "case4.toml").read_text()
                                       .replace("step_deg = 1.0", "step_deg = 10.0"))
    # a twist stopped before its plateau: not checked, said in one line with the angle it needs
    (folder / "short.toml").write_text((SCENARIOS / "twist.toml").read_text()
                                       .replace('name = "twist"', 'name = "short"')
                                       .replace("angle_deg = 15.0", "angle_deg = 1.0"))
    out = tmp_path / "results"
    p = run_cli(["reproduce", "--scenarios", folder, "--out", out, "--workers", "2"], cwd=tmp_path)
    assert p.returncode == 0, p.stderr      # the patch is not the paper's: no failed reproduction
    warnings = [x for x in p.stderr.splitlines() if ": warning: " in x]
    assert len(warnings) == 1 and "short: the full-slip plateau was not checked under the associated, " \
        "coupled rule(s)" in warnings[0] and "turn to twist.angle_deg >= 11.2 to check it" in warnings[0]
    assert "off its closed forms" not in warnings[0]
    report = (out / "report.md").read_text()
    rep = json.loads((out / "report.json").read_text())
    # the paper's rows and headline: case 4's only
    assert {r["scenario"] for r in rep["rows"]} == {"case4", "calibration"}
    assert "closed-form: 5 of 5 matched" in report
    section = report[report.index("## The contact patch"):report.index("## Scenarios")]
    assert "not rows of the paper's table" in section
    assert "### Contact patch: the aged mat's block twisted in place" not in report.split("## Scenarios")[1]
    # the twist: both rules' slope and plateau against the closed forms, from the summary
    tw = json.loads((out / "twist/summary.json").read_text())
    for rule in ("associated", "coupled"):
        r = tw["rules"][rule]
        assert r["ok"] and r["slope_relative_error"] < 1e-6
        assert f"| {rule} | {r['slope_N_m_rad']:.6g} | {r['k_N_m_rad']:.6g} |" in section
    assert rep["contact_patch"]["twist"]["checks"] == {"ok": True, "warning": None, "not_checked": []}
    assert rep["contact_patch"]["short"]["checks"]["ok"] is False
    assert rep["contact_patch"]["short"]["checks"]["not_checked"] == ["associated", "coupled"]
    assert "| not checked: the twist stops before it (" in section
    assert f"Check: **warning**: {rep['contact_patch']['short']['checks']['warning']}" in section
    # the towed block: each mat angle's yaw against its closed form and the paper's phi
    sc = load(SCENARIOS / "towed_block.toml")
    rows = re.findall(r"^\| ([\d.]+) \| (\w+) \| ([+-][\d.]+) \| ([+-][\d.]+) \| [^|]+ \| ([+-][\d.]+) \| "
                      r"([+-][\d.]+) \|$", section, re.M)
    assert len(rows) == 8
    tows = {(f"{t['angle_deg']:g}", t["rule"]): t for t in rep["contact_patch"]["towed_block"]["tows"]}
    assert set(tows) == {(a, rule) for a, rule, *_ in rows}
    for a, rule, yaw, closed, minus_phi_turned, phi in rows:
        t = tows[(a, rule)]
        # the numbers against their closed form within the run's settling tolerance ...
        closed_deg = math.degrees(planar.steady_yaw(sc.params_at(float(a), rule)))
        assert abs(t["yaw_closed_deg"] - closed_deg) <= 1e-9
        assert abs(t["yaw_deg"] - closed_deg) <= YAW_TOL_DEG
        assert abs(t["minus_phi_turned_by_yaw_deg"] - t["yaw_deg"]) <= YAW_TOL_DEG
        # ... and the table shows them
        assert (yaw, closed, minus_phi_turned, phi) == tuple(
            f"{t[k]:+.4f}" for k in ("yaw_deg", "yaw_closed_deg", "minus_phi_turned_by_yaw_deg", "phi_deg"))
    # the coupled yaw at the paper's extremal mat angle: near minus its measured 11.5 deg
    assert 10 < float(next(r[2] for r in rows if r[:2] == ("39.2", "coupled"))) < 11.5
    # every figure and table the section links is written
    links = re.findall(r"\]\(([^)]+)\)", section)
    assert {"twist/twist.png", "twist/twist_cells.png", "towed_block/yaw_vs_angle.png",
            "towed_block/yaw_vs_time.png", "twist/twist_cells.csv"} <= set(links)
    for link in links:
        assert (out / link).stat().st_size > 0, link


def test_no_patch_scenario_no_section(tmp_path):
    """A report without a patch scenario has no patch section, and an empty
    "contact_patch" in report.json; its kinds' parts are the patch's."""
    import json

    from orthocontact.experiment.kinds import KINDS
    from orthocontact.reproduction import paper_report
    assert {KINDS[k].part("report").section for k in ("twist", "towed_block")} == {patch_report.PATCH}
    assert paper_report.section_lines(patch_report.PATCH, []) == []
    text = paper_report.reproduction_report(tmp_path, [], [], 1.0)
    assert "## The contact patch" not in text and "## Scenarios" in text
    assert json.loads((tmp_path / "report.json").read_text())["contact_patch"] == {}
