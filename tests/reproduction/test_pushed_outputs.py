"""The scenario kind pushed_block (orthocontact.reproduction.pushed_outputs)
through `orthocontact run`: the bundled scenario's runs in the regimes of
the closed forms at every height and mat angle (full contact, lift-off,
tipping), its files and figures, the cells from the FMI 3.0 twin of an FMI
2.0 run; an unsettled push said, not passed; a height the pad could hold
only with a large tilt, and bad keys, refused in one line each."""
import csv
import json

import pytest

from cli_run import error_lines, one_error_line, run_cli, scenario_variant
from orthocontact.closed_forms.pad import FULL_CONTACT, LIFT_OFF, TIPS
from orthocontact.experiment.scenario import load
from orthocontact.reproduction import pushed_outputs
from paths import SCENARIOS

BUNDLED = SCENARIOS / "pushed_block.toml"


def test_the_bundled_push_shows_full_contact_lift_off_and_tipping_at_the_thresholds(tmp_path):
    """FMI 2.0: every run in its closed form's regime, the trajectory angle
    the closed form's at every height, the cells taken from the same push on
    the FMI 3.0 FMU, bit for bit."""
    p = run_cli(["run", BUNDLED, "--out", tmp_path / "out"], cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    s = json.loads((tmp_path / "out/summary.json").read_text())
    assert s["checks"] == {"ok": True, "warning": None, "phi_unchecked": 0}
    regimes = {(r["height_m"], r["angle_deg"]): r["regime"] for r in s["runs"]}
    assert {r["regime"] for r in s["runs"]} == {FULL_CONTACT, LIFT_OFF, TIPS}
    for r in s["runs"]:
        assert r["regime"] == r["regime_closed"] and r["ok"]
        share = r["mu"] * r["height_m"] / r["length_m"]
        assert r["regime"] == (FULL_CONTACT if share <= 1 / 6 else LIFT_OFF if share < 0.5 else TIPS)
        if r["regime"] != TIPS:
            assert abs(r["phi_deg"] - r["phi_closed_deg"]) < 1e-9
            assert r["e_m"] == pytest.approx(r["mu"] * r["height_m"], rel=1e-7, abs=1e-12)
    assert regimes[(0.09, 90.0)] == TIPS and regimes[(0.05, 0.0)] == LIFT_OFF
    sc = load(BUNDLED)
    for a, t in s["thresholds"].items():
        mu = pushed_outputs.friction_along_x1(sc.params_at(float(a)))
        assert t["lift_off_height_m"] == pytest.approx(0.09 / (6 * mu))
    assert all("FMI 3.0 ContactPad FMU, equal to this run" in why for why in s["cells"].values()
               if why != "the block tipped")
    rows = list(csv.DictReader(open(tmp_path / "out/pressure_cells.csv")))
    assert {float(r["height_m"]) for r in rows} == {0.0, 0.02, 0.05, 0.09}
    at_90 = [r for r in rows if float(r["height_m"]) == 0.09]
    assert any(r["cell_state"] == "0" for r in at_90) and any(r["cell_state"] == "2" for r in at_90)
    for name in ("pressure_cells.png", "phi_vs_angle.png", "regimes.png"):
        assert (tmp_path / "out" / name).stat().st_size > 10_000, name


PUSH = 'heights_m = [0.0, 0.02, 0.05, 0.09]\nangles_deg = [0.0, 30.0, 60.0, 90.0]'


def test_fmi3_gives_the_cells_itself(tmp_path):
    small = scenario_variant(BUNDLED, PUSH, "heights_m = [0.05]\nangles_deg = [30.0]", tmp_path / "s.toml")
    p = run_cli(["run", small, "--out", tmp_path / "out", "--fmi", "3"], cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    s = json.loads((tmp_path / "out/summary.json").read_text())
    assert s["checks"]["ok"] and s["cells"] == {"0.05": "this run (FMI 3.0: cellFn, cellState)"}


def test_an_unsettled_push_is_said_not_passed(tmp_path):
    """A softer law (eps2 = 1e4 N/m): the most loaded cell's elastic length
    is longer than a tenth of the fitted half of the travel."""
    short = scenario_variant(BUNDLED, PUSH, "heights_m = [0.05]\nangles_deg = [60.0]", tmp_path / "s.toml")
    short.write_text(short.read_text().replace("eps2 = 1.0e6", "eps2 = 1.0e4"))
    p = run_cli(["run", short, "--out", tmp_path / "out"], cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert "the trajectory angle and the pose were not checked at 1 pushes" in p.stderr
    assert "push further (push.travel_m >= " in p.stderr
    assert not json.loads((tmp_path / "out/summary.json").read_text())["checks"]["ok"]


def test_a_height_held_only_by_a_large_tilt_is_refused_in_one_line(tmp_path):
    """mu h just below length/2: an equilibrium exists, with a tilt the pad
    does not model; the line says how far to go either way."""
    near = scenario_variant(BUNDLED, PUSH, "heights_m = [0.108]\nangles_deg = [0.0]", tmp_path / "s.toml")
    p = run_cli(["run", near, "--out", tmp_path / "out"], cwd=tmp_path)
    one_error_line(p, "push.heights_m: expected heights whose push the pad holds with small tilts",
                   "to see the block tip")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("old,new,says", [
    ("kn_N_m3 = 1.0e8", "kn_N_m3 = 1.0e200", ["pad.kn_N_m3 = 1e+200 N/m^3: a pad's foundation"]),
    ("n1 = 8", "n1 = 70", ["pad.n1: expected a number <= 64, got 70"]),
    # each side within 64, the cells in all not: refused here, not as the FMU's traceback
    ("n1 = 8\nn2 = 8", "n1 = 27\nn2 = 38",
     ["pad.n1, pad.n2: n1 x n2 = 27 x 38 = 1026 cells: at most 1024 cells in all"]),
    ("heights_m = [0.0,", "heights_m = [-0.01,", ["push.heights_m"]),
    ("[push]\n", "[pushx]\n", ["pushx: expected a known table",
                               "push: expected a [push] table for kind 'pushed_block'"]),
])
def test_a_bad_pushed_block_scenario_is_a_line_per_problem(tmp_path, old, new, says):
    bad = scenario_variant(BUNDLED, old, new, tmp_path / "s.toml")
    p = run_cli(["run", bad, "--out", tmp_path / "out"], cwd=tmp_path)
    error_lines(p, *says)


@pytest.mark.parametrize("old,new,says", [
    # one step over the whole travel left no angle to fit (NaN), marked checked and ok
    ("step_m = 2.0e-4", "step_m = 5.0e-3", ["push.step_m: the trajectory angle is fitted over the last 50% "
                                            "of the travel (0.0025 m) through at least 3 steps",
                                            "leaves 1: step_m <= 0.00125 m"]),
    # heights typed in mm ran, tipping "at 90 m"
    ("heights_m = [0.0, 0.02, 0.05, 0.09]", "heights_m = [0, 20, 50, 90]",
     ["push.heights_m[1] = 20 m: a push's height above the contact is 0-1 m; mm?"]),
    # a foundation that sinks the block by 2,270 km was blamed on the heights
    ("kn_N_m3 = 1.0e8", "kn_N_m3 = 1e-3", ["pad.kn_N_m3 = 0.001 N/m^3: a pad's foundation (a layer's "
                                           "modulus over its thickness) is 1e4-1e15 N/m^3"]),
])
def test_a_push_that_cannot_be_measured_or_right_is_refused_naming_its_key(tmp_path, old, new, says):
    bad = scenario_variant(BUNDLED, old, new, tmp_path / "s.toml")
    p = run_cli(["run", bad, "--out", tmp_path / "out"], cwd=tmp_path)
    one_error_line(p, *says)
    assert not (tmp_path / "out").exists()


def test_a_value_that_is_not_a_number_is_off_its_closed_form():
    """The check itself: NaN (a trajectory with no slope to fit) cannot
    pass, and two values equal to every digit shown say their difference."""
    assert "cannot be checked" in pushed_outputs.off_closed_form("phi", float("nan"), 11.5, 1e-3, "deg")
    assert "cannot be checked" in pushed_outputs.off_closed_form("phi", None, 11.5, 1e-3, "deg")
    assert pushed_outputs.off_closed_form("d", 1.0 + 1e-9, 1.0, 1e-6, "m") is None
    line = pushed_outputs.off_closed_form("phi2", 0.01601724, 0.01601721, 1e-8, "rad")
    assert "off by 3e-08" in line
