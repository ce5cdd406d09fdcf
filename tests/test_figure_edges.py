"""Figures that misled a reader (issue 18): a flat curve autoscaled so that
rounding looked like a curve, a closed-form line hidden under another, a
legend over the data.  Each figure is drawn in-process and inspected just
before it is closed."""
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from orthocontact.experiment.scenario import load  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def last_figure(monkeypatch):
    """The axes of every figure, as they were when it was closed."""
    seen = []
    orig = plt.close

    def keep(fig=None):
        if fig is not None and hasattr(fig, "canvas"):
            fig.canvas.draw()
            seen.append([(ax, ax.get_ylim(), ax.get_window_extent(),
                          ax.get_legend().get_window_extent() if ax.get_legend() else None,
                          [t.get_text() for t in ax.get_legend().get_texts()] if ax.get_legend() else [])
                         for ax in fig.axes])
        orig(fig)
    monkeypatch.setattr(plt, "close", keep)
    return seen


def test_a_flat_sweep_is_drawn_on_a_degree_scale(tmp_path, last_figure):
    from orthocontact.reproduction.scenario_outputs import _figure_phi
    from orthocontact.runs.sweep import run_sweep
    sc = tmp_path / "flat.toml"
    sc.write_text((ROOT / "scenarios/mat_new.toml").read_text().replace("step_deg = 1.0", "step_deg = 15.0"))
    sc = load(sc)
    res = run_sweep(sc, workers=1, progress=False)
    assert max(abs(res.phi_deg)) < 1e-6  # rounding, not a curve
    _figure_phi(sc, res, tmp_path / "phi.png", flat=True)
    (_, (lo, hi), _, _, _), = last_figure[-1]
    assert hi - lo >= 2.0


def test_rules_that_share_a_closed_form_share_its_line(tmp_path, last_figure):
    from orthocontact.reproduction.scenario_outputs import _figure_step_study
    from orthocontact.runs.sweep import run_step_study
    sc = tmp_path / "study.toml"
    sc.write_text((ROOT / "scenarios/step_study.toml").read_text()
                  .replace("steps_s = [2.0e-3, 1.0e-3, 5.0e-4, 2.0e-4, 1.0e-4]", "steps_s = [2.0e-3, 1.0e-3]")
                  .replace("travel_m = 1.0", "travel_m = 0.2"))
    res = run_step_study(load(sc), workers=1, progress=False)
    _figure_step_study(load(sc), res, tmp_path / "s.png")
    (_, _, _, _, labels), = last_figure[-1]
    closed = [t for t in labels if "closed form" in t]
    assert closed == ["associated: closed form", "coupled+eq20: closed form"], labels


def test_the_fits_legends_do_not_cover_the_data(tmp_path, last_figure):
    from orthocontact.identification.job import load_data, run
    data = load_data(ROOT / "scenarios" / "example_identification")
    run(data, tmp_path, validate=False, workers=1)
    panels = last_figure[-1]
    assert len(panels) == 3
    for _, _, axes_box, legend_box, _ in panels:
        assert legend_box.y1 <= axes_box.y0  # below the panel
