"""Figures and report rows a reader gets at once: overlapping curves stay
distinguishable, legends say what the angle is and sit outside the data, no
doubled parentheses, rules mapped by colour, no extremum for a flat curve."""
import json
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from orthocontact.output import figures  # noqa: E402
from orthocontact.reproduction import paper_report  # noqa: E402
from orthocontact.experiment.scenario import load

ROOT = Path(__file__).resolve().parents[1]


def test_overlapping_curves_get_distinct_markers_dashes_and_staggered_marks():
    styles = [figures.curve_style(i, 400, 7) for i in range(7)]
    assert len({(s["marker"], s["linestyle"], s["color"]) for s in styles}) == 7
    assert len({s["markevery"][0] for s in styles}) == 7  # marks do not stack


def test_legend_names_the_swept_angle():
    assert figures.swept_label(load(ROOT / "scenarios/mat_aged.toml")) == \
        "swept angle a: α = a +90°, β = a"
    assert figures.swept_label(load(ROOT / "scenarios/case5.toml")) == \
        "swept angle a: α = a, β = a +90°"


def test_legend_outside_the_axes(tmp_path):
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], label="x")
    seen = {}
    orig = plt.close

    def keep(f):
        fig.canvas.draw()
        seen["legend"] = ax.get_legend().get_window_extent()
        seen["axes"] = ax.get_window_extent()
        orig(f)
    plt.close = keep
    try:
        figures.finish(fig, ax, tmp_path / "f.png", "t", "legend", outside=True)
    finally:
        plt.close = orig
    assert seen["legend"].x0 >= seen["axes"].x1  # right of the data, not over it


def test_flat_sweep_has_no_extremum_and_titles_have_no_doubled_parentheses(tmp_path):
    sc = tmp_path / "flat.toml"
    sc.write_text((ROOT / "scenarios/mat_new.toml").read_text()
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
    step = load(ROOT / "scenarios/step_study.toml")
    assert ") (" not in step.title + " " and "((" not in step.title
