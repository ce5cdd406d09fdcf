"""What identification writes for people (orthocontact.identification.report):
the fit figure's legends sit below the data."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[2]


def test_the_fits_legends_do_not_cover_the_data(tmp_path, last_figure):
    from orthocontact.identification.job import load_data, run
    data = load_data(ROOT / "scenarios" / "example_identification")
    run(data, tmp_path, validate=False, workers=1)
    panels = last_figure[-1]
    assert len(panels) == 3
    for _, _, axes_box, legend_box, _ in panels:
        assert legend_box.y1 <= axes_box.y0  # below the panel
