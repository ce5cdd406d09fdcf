"""The report's section on the contact pad (orthocontact.reproduction.pad_report):
a push's lines show every run's regime against the closed form's, the
thresholds and the figures; a run off its closed form is marked, and the
section's entry in report.json carries the checks and the runs."""
from orthocontact.experiment.scenario import load
from orthocontact.reproduction import pad_report
from paths import SCENARIOS


def summary(regime="lift-off", closed="lift-off", ok=True):
    run = {"height_m": 0.05, "angle_deg": 30.0, "length_m": 0.09, "regime": regime, "regime_closed": closed,
           "mu": 0.44, "e_m": 0.022, "tipped_at_m": 2e-4 if regime == "tips" else None,
           "contact_fraction": 0.765, "contact_fraction_closed": 0.765, "phi_deg": -10.88,
           "phi_closed_deg": -10.88}
    return {"kind": "pushed_block", "weight_N": 18.39,
            "pad": {"length_m": 0.09, "width_m": 0.09, "n1": 8, "n2": 8, "kn_N_m3": 1e8},
            "runs": [run], "thresholds": {"30": {"lift_off_height_m": 0.034, "tipping_height_m": 0.102}},
            "checks": {"ok": ok, "warning": None if ok else "pushed_block: off", "phi_unchecked": 0}}


def test_a_push_shows_each_run_against_its_closed_forms_and_the_thresholds():
    sc = load(SCENARIOS / "pushed_block.toml")
    text = "\n".join(pad_report.pushed_lines(sc, summary()))
    assert "| 50 | 30 | 0.2444 | lift-off | 0.2444 | 0.7650 (0.7650) | -10.8800 | -10.8800 |" in text
    assert "a = 30°: lift-off from h = 34 mm, tipping from 102 mm" in text
    assert "Check: ok." in text and "pushed_block/pressure_cells.png" in text
    entry = pad_report.pushed_json(sc, summary())
    assert entry["runs"][0]["regime"] == "lift-off" and entry["checks"]["ok"]


def test_a_run_off_its_regime_is_marked_and_a_tipped_one_says_where():
    sc = load(SCENARIOS / "pushed_block.toml")
    text = "\n".join(pad_report.pushed_lines(sc, summary("tips", "lift-off", ok=False)))
    assert "tips (**lift-off**) at 0.2 mm of travel | — |" in text
    assert "Check: **warning**: pushed_block: off" in text
