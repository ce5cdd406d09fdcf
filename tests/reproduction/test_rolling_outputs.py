"""The scenario kind rolling (orthocontact.reproduction.rolling_outputs)
through `orthocontact run`: the bundled wheel meets the brush's closed
forms where the texture's axes are the pad's, and a pure longitudinal
creepage pushes sideways only where they are not; FMI 3.0 gives the same
rows and cells (an FMI 2.0 run takes them from its FMI 3.0 twin); bad keys
refused in one line each."""
import csv
import json

import pytest

from cli_run import one_error_line, run_cli, scenario_variant
from orthocontact.closed_forms import brush
from orthocontact.experiment.scenario import load
from orthocontact.reproduction import rolling_outputs
from paths import SCENARIOS

BUNDLED = SCENARIOS / "rolling_wheel.toml"
ANGLES = "angles_deg = [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0]"


def rows_of(out) -> list[dict]:
    return json.loads((out / "summary.json").read_text())["rows"]


def test_the_bundled_wheel_meets_the_brush_on_the_axes_and_pushes_sideways_off_them(tmp_path):
    p = run_cli(["run", BUNDLED, "--out", tmp_path / "out"], cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    s = json.loads((tmp_path / "out/summary.json").read_text())
    assert s["checks"]["ok"], s["checks"]
    sc = load(BUNDLED)
    for r in s["rows"]:
        assert r["Fn_N"] == pytest.approx(50.0, rel=1e-12)       # flat: the load, exactly
        if r["angle_deg"] in (0.0, 90.0):
            # the closed form, independently: the mat's eps and mu along the creepage's axis
            a = r["angle_deg"]
            along_x1 = r["direction"] == "longitudinal"
            eps = sc.law.eps2 if (a == 0.0) == along_x1 else sc.law.eps1
            mu = sc.law.mu1 if (a == 0.0) == along_x1 else sc.law.mu2
            want = brush.steady_force(eps, mu, 50.0, 0.1, r["creepage"])
            got = r["T1_over_Fn"] if along_x1 else r["T2_over_Fn"]
            assert abs(got * 50.0 - want) <= s["checks"]["tolerance_over_mu_Fn"] * mu * 50.0, r
            if along_x1:
                assert abs(r["T2_over_Fn"]) < 1e-12
        elif r["direction"] == "longitudinal" and r["creepage"] >= 4e-4:
            assert abs(r["T2_over_Fn"]) > 1e-3, r     # no isotropic brush has it
    for name in ("force_creepage.png", "lateral_force.png", "zones.png", "rolling.csv"):
        assert (tmp_path / "out" / name).stat().st_size > 1000, name


def test_fmi3_gives_the_same_rows_and_the_cells(tmp_path):
    small = scenario_variant(BUNDLED, ANGLES, "angles_deg = [30.0]", tmp_path / "s.toml")
    for fmi in ("2", "3"):
        p = run_cli(["run", small, "--out", tmp_path / fmi, "--fmi", fmi], cwd=tmp_path)
        assert p.returncode == 0, p.stderr
    for name in ("rolling.csv", "rolling_cells.csv"):    # FMI 2.0's cells: its FMI 3.0 twin's
        assert (tmp_path / "2" / name).read_bytes() == (tmp_path / "3" / name).read_bytes(), name
    said = json.loads((tmp_path / "2/summary.json").read_text())["cells"]
    assert said == {"coupled 30": "the same rolls on the installed FMI 3.0 ContactPad FMU, equal to this run "
                                  "at the end of every creepage (FMI 2.0 has no arrays)"}
    cells = list(csv.DictReader(open(tmp_path / "3/rolling_cells.csv")))
    assert len(cells) == 8 * 32 * 4                        # the first rule: creepages x cells
    states = {c["state"] for c in cells}
    assert states == {"1", "2"}, states                    # adhesion and slip, never open (flat)


def test_the_closed_form_tolerance_is_first_order_in_the_cells():
    """The grid's brush against the continuum's: what the check allows is
    1/n1 of mu Fn, capped."""
    sc = load(BUNDLED)
    assert rolling_outputs.closed_form_tol(rolling_outputs.pad_of(sc)) == pytest.approx(1 / 32)


@pytest.mark.parametrize("old, new, says", [
    ("courant = 1.0", "courant = 0.0", "roll.courant: expected a number > 0"),
    ("load_N = 50.0", "load_N = -5.0", "roll.load_N: expected a number > 0"),
    ("creepages = [0.0, 1.0e-4, 2.0e-4, 4.0e-4, 8.0e-4, 1.6e-3, 3.2e-3, 6.4e-3]", "creepages = [-0.1]",
     "roll.creepages"),
    ("vr_m_s = 1.0", "vr_m_s = 1000.0", "roll.vr_m_s = 1000 m/s: a wheel or belt rolls at 0.001-100 m/s; "
     "cm/s?"),
])
def test_a_bad_rolling_scenario_is_one_line_naming_its_key(tmp_path, old, new, says):
    bad = scenario_variant(BUNDLED, old, new, tmp_path / "s.toml")
    p = run_cli(["run", bad, "--out", tmp_path / "out"], cwd=tmp_path)
    one_error_line(p, says)
    assert not (tmp_path / "out").exists()


def test_a_load_typed_in_kn_is_said_and_strict_refuses_it(tmp_path):
    """Unusual, not impossible: a warning naming the slip; --strict exits 1
    (the results written all the same, as --help says)."""
    one = scenario_variant(BUNDLED, ANGLES, "angles_deg = [0.0]", tmp_path / "one.toml")
    light = scenario_variant(one, "load_N = 50.0", "load_N = 0.05", tmp_path / "s.toml")
    p = run_cli(["run", light, "--out", tmp_path / "out", "--strict"], cwd=tmp_path)
    assert p.returncode == 1, p.stderr
    assert "roll.load_N = 0.05 N: a wheel's load is 0.1-1e5 N; kN?" in p.stderr


def test_a_force_that_is_not_a_number_fails_the_check():
    """No NaN passes as ok: a deviation that is not a number is off."""
    sc = load(BUNDLED)
    pad = rolling_outputs.pad_of(sc)
    law = rolling_outputs.axis_law(sc.params_at(0.0, "coupled"), 0)
    row = rolling_outputs.creepage_row("coupled", 0.0, "longitudinal", law, pad,
                                       (1e-3, float("nan"), 0.0, 0.0, 50.0, 1.0))
    worst = {("coupled", 0.0, "longitudinal"): row["off_closed_form_over_mu_Fn"]}
    s = rolling_outputs.rolling_summary(sc, pad, [row], worst, {})
    assert not s["checks"]["ok"] and "mat angle 0 deg" in s["checks"]["warning"]


def test_a_normal_force_off_the_load_fails_the_check():
    """Flat and in full contact the pad carries its load exactly: a row whose
    Fn is not the load (a foundation misapplied) is a warning."""
    sc = load(BUNDLED)
    pad = rolling_outputs.pad_of(sc)
    law = rolling_outputs.axis_law(sc.params_at(0.0, "coupled"), 0)
    one = [rolling_outputs.creepage_row("coupled", 0.0, "longitudinal", law, pad,
                                        (0.0, 0.0, 0.0, 0.0, fn, 0.0)) for fn in (50.0, 50.5)]
    s = rolling_outputs.rolling_summary(sc, pad, one, {}, {})
    assert not s["checks"]["ok"] and s["checks"]["Fn_off_load"] == pytest.approx(0.01)
    assert "roll.load_N = 50 N" in s["checks"]["warning"]
