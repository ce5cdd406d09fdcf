"""What `orthocontact design` writes (identification.design_output): the
plan in a lab's order, design.json's fields, the figure and design.md,
for a design with a strip, ramp samples and carriage runs."""
import csv
import json

import pytest

from orthocontact.identification import design, design_inputs, design_output


@pytest.fixture(scope="module")
def strip_design():
    prior = design_inputs.paper_prior(True, design_inputs.Noise())
    space = design.Space(design.angles_of(prior, 10.0), design.velocities_of(prior, 0.05, 0.5, 0.45), 6,
                         ramp_samples=5, carriage_runs=2)
    return design.plan(prior, space, "D")


def test_every_file_is_written_and_the_plan_is_in_a_labs_order(tmp_path, strip_design):
    design_output.write_outputs(strip_design, tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == \
        ["design.json", "design.md", "design.png", "plan.csv"]
    with open(tmp_path / "plan.csv") as fh:
        rows = list(csv.DictReader(fh))
    kinds = [r["kind"] for r in rows]
    assert kinds == ["carriage"] * 2 + ["slide"] * 6 + ["ramp"]
    slides = [(float(r["mat_angle_deg"]), float(r["velocity_m_s"])) for r in rows if r["kind"] == "slide"]
    assert slides == sorted(slides)
    assert rows[-1] == {"kind": "ramp", "mat_angle_deg": "0", "velocity_m_s": "0.002"}


def test_design_json_holds_the_prediction_the_baseline_and_the_check(tmp_path, strip_design):
    design_output.write_outputs(strip_design, tmp_path)
    d = json.loads((tmp_path / "design.json").read_text())
    assert list(d["predicted_sd"]) == ["mu1", "mu2", "eps_ratio", "eps2", "c_strip"]
    assert list(d["nuisance_sd"]) == ["f_int"]
    assert d["baseline"]["predicted_sd"].keys() == d["predicted_sd"].keys()
    assert len(d["ramp_samples_x1_m"]) == 5 and len(d["baseline"]["ramp_samples_x1_m"]) == 5
    assert "0.125 and at 0.244 m/s" in d["baseline"]["description"]
    assert d["efficiency"] > 1 and "s = 5 designed parameters" in d["efficiency_definition"]
    assert d["equivalence_theorem"]["holds"] and 0 < d["approximate"]["plan_efficiency"] <= 1 + 1e-9
    assert sum(s["weight"] for s in d["approximate"]["support"] if s["kind"] == "slide") == \
        pytest.approx(1.0, abs=0.01)
    assert d["prior"]["rig"]["c_strip"] is None and d["prior"]["values"]["c_strip"] == 10.0
    assert d["space"]["velocities_m_s"] == [0.05, 0.5] and d["space"]["carriage_runs"] == 2


def test_the_figure_has_the_ramp_below_the_slides_and_the_text_says_the_figures(tmp_path, strip_design):
    from PIL import Image
    design_output.write_outputs(strip_design, tmp_path)
    assert Image.open(tmp_path / "design.png").size[1] > 700     # two axes: 6.5 in at 120 dpi
    text = design_output.summary_text(strip_design)
    assert "D-optimal for mu1, mu2, eps_ratio, eps2, c_strip" in text and "f_int" in text
    assert "ramp samples at x1:" in text and "equivalence theorem" in text
    md = (tmp_path / "design.md").read_text()
    assert md.startswith("# Experiment design") and "| carriage | 0 | 0.244 | 2 |" in md
    assert "--fixed" in md and "design.png" in md


def test_the_a_criterion_says_what_it_sums():
    prior = design_inputs.paper_prior(False, design_inputs.Noise())
    d = design.plan(prior, design.Space(design.angles_of(prior, 10.0), (0.244,), 4), "A")
    j = design_output.design_json(d)
    assert j["criterion_text"].startswith("A-optimal: the smallest sum of the relative variances")
    assert j["efficiency_definition"].startswith("tr C_baseline / tr C")
    assert j["efficiency"] == pytest.approx(
        sum((s / prior.values[n]) ** 2 for n, s in d.sd(d.baseline.M).items())
        / sum((s / prior.values[n]) ** 2 for n, s in d.sd(d.M).items()))
