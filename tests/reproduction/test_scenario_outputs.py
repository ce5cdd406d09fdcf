"""A scenario's results (orthocontact.reproduction.scenario_outputs): figures
that misled a reader (a flat curve autoscaled so that rounding looked like
a curve, a closed-form line hidden under another) and a flat sweep's
summary.  Each figure is drawn in-process and inspected just before it is
closed (the last_figure fixture, conftest.py)."""
import json
import subprocess
import sys

import matplotlib

from paths import SCENARIOS

matplotlib.use("Agg")

from orthocontact.experiment.scenario import load  # noqa: E402
from orthocontact.reproduction import paper_report  # noqa: E402


def test_a_flat_sweep_is_drawn_on_a_degree_scale(tmp_path, last_figure):
    from orthocontact.reproduction.scenario_outputs import figure_phi
    from orthocontact.runs.sweep import run_sweep
    sc = tmp_path / "flat.toml"
    sc.write_text((SCENARIOS / "mat_new.toml").read_text().replace("step_deg = 1.0", "step_deg = 15.0"))
    sc = load(sc)
    res = run_sweep(sc, workers=1, progress=False)
    assert max(abs(res.phi_deg)) < 1e-6  # rounding, not a curve
    figure_phi(sc, res, tmp_path / "phi.png", flat=True)
    (_, (lo, hi), _, _, _), = last_figure[-1]
    assert hi - lo >= 2.0


def test_rules_that_share_a_closed_form_share_its_line(tmp_path, last_figure):
    from orthocontact.reproduction.scenario_outputs import figure_step_study
    from orthocontact.runs.sweep import run_step_study
    sc = tmp_path / "study.toml"
    sc.write_text((SCENARIOS / "step_study.toml").read_text()
                  .replace("steps_s = [2.0e-3, 1.0e-3, 5.0e-4, 2.0e-4, 1.0e-4]", "steps_s = [2.0e-3, 1.0e-3]")
                  .replace("travel_m = 1.0", "travel_m = 0.2"))
    res = run_step_study(load(sc), workers=1, progress=False)
    figure_step_study(load(sc), res, tmp_path / "s.png")
    (_, _, _, _, labels), = last_figure[-1]
    closed = [t for t in labels if "closed form" in t]
    assert closed == ["associated: closed form", "coupled+eq20: closed form"], labels


def test_flat_sweep_has_no_extremum_and_titles_have_no_doubled_parentheses(tmp_path):
    sc = tmp_path / "flat.toml"
    sc.write_text((SCENARIOS / "mat_new.toml").read_text()
                  .replace("step_deg = 1.0", "step_deg = 30.0").replace("travel_m = 0.5", "travel_m = 0.05"))
    out = tmp_path / "out"
    p = subprocess.run([sys.executable, "-m", "orthocontact", "run", str(sc), "--out", str(out),
                        "--workers", "1"], capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    s = json.loads((out / "summary.json").read_text())
    assert s["flat"] is True and s["extremum"] is None
    assert s["max_abs_phi_deg"] < 0.5  # 5 cm of travel has not settled; still no "extremum"
    text = paper_report.reproduction_report(tmp_path, [(load(sc), s)], [], 1.0)
    assert "flat: |φ|" in text and "extremum φ" not in text
    step = load(SCENARIOS / "step_study.toml")
    assert ") (" not in step.title + " " and "((" not in step.title


def test_a_step_study_without_an_angle_at_any_step_is_drawn_and_said(tmp_path):
    """One step of 1 s over the rig's 1 m at 1 m/s: no angle can be fitted
    (phi is nan), and the figure's log axis had no point to scale
    (ValueError, a traceback).  The run says why and draws its figure."""
    from cli_run import run_cli
    (tmp_path / "s.toml").write_text(
        'name = "s"\nkind = "step_study"\n[law]\nmu1 = 0.408\nmu2 = 0.625\neps1 = 1.251e4\neps2 = 1.0e4\n'
        "[rig]\nvelocity_m_s = 1.0\ntravel_m = 1.0\n"
        '[study]\nangle_deg = 30.0\nrules = ["coupled"]\nsteps_s = [1.0]\n')
    p = run_cli(["run", "s.toml", "--out", "o"], tmp_path)
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr
    assert "too few steps in a half of the fitted path to fit an angle" in p.stderr
    assert (tmp_path / "o/step_study.png").stat().st_size > 10_000
