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


def test_a_rolling_pad_shows_each_runs_deviation_where_the_brush_holds_and_its_lateral_force():
    sc = load(SCENARIOS / "rolling_wheel.toml")
    worst = {f"{r} {a:g} {d}": 1e-3 for r in ("coupled", "associated") for a in (0.0, 90.0)
             for d in ("longitudinal", "lateral")}
    lateral = {f"{r} {a:g}": 0.0 if a in (0.0, 90.0) else 0.05 for r in ("coupled", "associated")
               for a in sc.roll["angles_deg"]}
    s = {"kind": "rolling", "pad": sc.pad, "roll": sc.roll, "lateral_from_longitudinal_max_over_Fn": lateral,
         "checks": {"ok": True, "warning": None, "tolerance_over_mu_Fn": 1 / 32, "worst_over_mu_Fn": worst}}
    text = "\n".join(pad_report.rolling_lines(sc, s))
    assert "| coupled | 0 | 1.00e-03 | 1.00e-03 | 0.0000 |" in text
    assert "| coupled | 45 | no closed form | no closed form | 0.0500 |" in text
    assert "Check: ok." in text and "rolling_wheel/zones.png" in text
    assert pad_report.rolling_json(sc, s)["checks"]["ok"]
