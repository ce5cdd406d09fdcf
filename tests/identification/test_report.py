"""What identification writes for people (orthocontact.identification.report):
the fit figure draws the model that was fitted, its legends sit below the
data and its title clear of the labels; identified.md's runs section."""

import matplotlib
import numpy as np

from paths import ROOT, SCENARIOS

matplotlib.use("Agg")

from orthocontact.identification.report import reduction_markdown  # noqa: E402


def test_the_fits_legends_do_not_cover_the_data(tmp_path, last_figure):
    from orthocontact.identification.job import load_data, run
    data = load_data(SCENARIOS / "example_identification")
    run(data, tmp_path, validate=False, workers=1)
    panels = last_figure[-1]
    assert len(panels) == 3
    for _, _, axes_box, legend_box, _ in panels:
        assert legend_box.y1 <= axes_box.y0  # below the panel


def _curve(ax, label_start):
    lines = [ln for ln in ax.get_lines() if ln.get_label().startswith(label_start)]
    assert len(lines) == 1, [ln.get_label() for ln in ax.get_lines()]
    return lines[0]


def test_the_recordings_fit_figure_draws_the_fitted_model_through_the_runs(tmp_path, last_figure):
    """example_recordings: the strip's viscosity fitted from two velocities.
    The figure drew the joint fit without the strip (-11.5 deg at 40 deg,
    every run at -8 to -10); each velocity's curve of the fitted model now
    passes within the runs' scatter at every mat angle (2 standard errors
    of their mean, at least 0.5 deg / 0.1 N), the maximum rule is named as
    the paper's approximation, and the title clears every axis label."""
    from orthocontact.identification.job import load_folder, run
    data, recordings = load_folder(SCENARIOS / "example_recordings")
    run(data, tmp_path, validate=False, workers=1, recordings=recordings)
    panels = last_figure[-1]
    by_label = {ax.get_ylabel().split(" [")[0]: (ax, legend) for ax, _, _, _, legend in panels}
    checked = 0
    for name, pts, vel, floor in (("trajectory angle φ", data.angles, data.velocities_of_angles(), 0.5),
                                  ("driving force", data.forces, data.velocities_of_forces(), 0.1)):
        ax, _ = by_label[name]
        speeds = np.unique(vel)
        assert len(speeds) == 2
        for u in speeds:
            line = _curve(ax, f"fitted model at {u:g} m/s")
            for a in np.unique(pts[:, 0]):
                runs = pts[(pts[:, 0] == a) & (vel == u), 1]
                stderr = runs.std(ddof=1) / np.sqrt(len(runs))
                drawn = np.interp(a, line.get_xdata(), line.get_ydata())
                assert abs(drawn - runs.mean()) <= max(2 * stderr, floor), (name, u, a, drawn, runs)
                checked += 1
    assert checked == 2 * 2 * 7
    _, legend = by_label["trajectory angle φ"]
    assert any(t.startswith("the paper's approximation (maximum rule): ε1/ε2=") for t in legend), legend
    fig = panels[0][0].figure
    fig.canvas.draw()
    title = [t for t in fig.findobj(matplotlib.text.Text) if t.get_text() == fig.get_suptitle()]
    assert len(title) == 1 and "example_recordings" in title[0].get_text()
    box = title[0].get_window_extent()
    for ax, *_ in panels:
        for label in (ax.xaxis.label, ax.yaxis.label):
            assert not box.overlaps(label.get_window_extent()), label.get_text()


def test_the_runs_section_of_identified_md_by_hand():
    from orthocontact.identification.identified import ReductionSummary
    noise_model = {"angles": {"between_runs": {"0.125": 0.2, "0.244": 0.05}, "within_run_rms": 0.011},
                   "forces": {"between_runs": 0.04, "within_run_rms": 0.0}}
    reduction = ReductionSummary(runs={"slide": 20, "carriage": 3, "ramp": 2}, left_out=("s07",),
                                 flagged={"s03": ["dropout", "outlier"]}, table="reduction.csv",
                                 figures=("paths_30.png",), scenario=None)
    assert reduction_markdown(noise_model, reduction).splitlines() == [
        "## Runs", "",
        "- run-to-run scatter (between runs) / within-run error (rms): angles 0.2 at 0.125 m/s, "
        "0.05 at 0.244 m/s / 0.011; forces 0.04 / 0",
        "- runs: 20 slide, 3 carriage, 2 ramp; left out: s07; flagged: s03 (dropout outlier)",
        "- the reduction per run: reduction.csv; the paths per mat angle: ![paths_30.png](paths_30.png)"]


def test_identify_prints_every_estimate_with_its_unit_and_positive_intervals(tmp_path):
    """Through the CLI on the bundled recordings (every estimate: μ, ε, their
    ratio, c_strip, F_int): the terminal summary and identified.md give each
    value's unit, the maximum rule's angles in degrees; identified.json's
    intervals are on the log scale, so each is above 0 and holds its value."""
    import json

    from cli_run import run_cli
    from orthocontact.identification.identified import UNITS
    from orthocontact.identification.report import unit_of
    out = tmp_path / "id"
    p = run_cli(["identify", SCENARIOS / "example_recordings", "--out", out, "--no-validate"],
                cwd=ROOT)
    assert p.returncode == 0, p.stderr
    want = {"mu1": "[-]", "mu2": "[-]", "eps_ratio": "[-]", "eps1": "[N/m]", "eps2": "[N/m]",
            "c_strip": "[N s/m]", "f_int": "[N]"}
    assert {n: unit_of(n) for n in want} == want and set(want) <= set(UNITS)
    lines = {ln.split("=")[0].strip(): ln for ln in p.stdout.splitlines() if " ± " in ln}
    assert set(lines) == set(want), p.stdout
    for n, u in want.items():
        # the value's unit and the interval's
        assert lines[n].count(f" {u}") == 2, lines[n]
    rule = [ln for ln in p.stdout.splitlines() if ln.startswith("maximum rule")]
    assert len(rule) == 1 and " deg at mat angle " in rule[0] and "the paper's approximation" in rule[0]
    md = (out / "identified.md").read_text()
    assert "| parameter | unit | value | std. error | 95% interval |" in md
    for n, u in want.items():
        assert f"| {n} | {u[1:-1]} | " in md, n
    j = json.loads((out / "identified.json").read_text())
    assert "log scale" in j["intervals"]
    for n in want:
        lo, hi = j[n]["ci95"]
        assert 0 < lo < j[n]["value"] < hi, (n, j[n])
