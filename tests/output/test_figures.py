"""The common look of every figure (orthocontact.output.figures): overlapping
curves stay distinguishable, legends say what the angle is and sit outside
the data."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from orthocontact.output import figures  # noqa: E402
from orthocontact.experiment.scenario import load

ROOT = Path(__file__).resolve().parents[2]


def test_overlapping_curves_get_distinct_markers_dashes_and_staggered_marks():
    styles = [figures.curve_style(i, 400, 7) for i in range(7)]
    assert len({(s["marker"], s["linestyle"], s["color"]) for s in styles}) == 7
    assert len({s["markevery"][0] for s in styles}) == 7  # marks do not stack


def test_legend_names_the_mat_angle():
    assert figures.swept_label(load(ROOT / "scenarios/mat_aged.toml")) == \
        "mat angle a: α = a +90°, β = a"
    assert figures.swept_label(load(ROOT / "scenarios/case5.toml")) == \
        "mat angle a: α = a, β = a +90°"


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
