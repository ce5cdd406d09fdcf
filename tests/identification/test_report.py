"""What identification writes for people (orthocontact.identification.report):
the fit figure's legends sit below the data; identified.md's runs section."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from orthocontact.identification.report import reduction_markdown  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def test_the_fits_legends_do_not_cover_the_data(tmp_path, last_figure):
    from orthocontact.identification.job import load_data, run
    data = load_data(ROOT / "scenarios" / "example_identification")
    run(data, tmp_path, validate=False, workers=1)
    panels = last_figure[-1]
    assert len(panels) == 3
    for _, _, axes_box, legend_box, _ in panels:
        assert legend_box.y1 <= axes_box.y0  # below the panel


def test_the_runs_section_of_identified_md_by_hand():
    j = {"noise_model": {"angles": {"between_runs": {"0.125": 0.2, "0.244": 0.05}, "within_run_rms": 0.011},
                         "forces": {"between_runs": 0.04, "within_run_rms": 0.0}},
         "reduction": {"runs": {"slide": 20, "carriage": 3, "ramp": 2}, "left_out": ["s07"],
                       "flagged": {"s03": ["dropout", "outlier"]}, "figures": ["paths_30.png"]}}
    assert reduction_markdown(j).splitlines() == [
        "## Runs", "",
        "- run-to-run scatter (between runs) / within-run error (rms): angles 0.2 at 0.125 m/s, "
        "0.05 at 0.244 m/s / 0.011; forces 0.04 / 0",
        "- runs: 20 slide, 3 carriage, 2 ramp; left out: s07; flagged: s03 (dropout outlier)",
        "- the reduction per run: reduction.csv; the paths per mat angle: ![paths_30.png](paths_30.png)"]
