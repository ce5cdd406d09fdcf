"""The carriage runs' force logs against the slide runs' (orthocontact.
identification.force_units), on synthetic recordings (tests/
recording_sets.py): F_int measured again by the ramp runs' start and the
sensor's noise at rest name a unit slip; the slides' mu decide whose."""
import math
import re

import pytest

import recording_sets as rs
from orthocontact import plausibility
from orthocontact.identification.force_units import (
    agreed_slip,
    evidence,
    force_slip,
    force_unit_finding,
    rest_noise,
)


@pytest.fixture(scope="module")
def physics():
    return rs.physics()


def finding(physics, convert=None, no_ramp=False):
    runs = rs.made(physics, convert=convert)
    if no_ramp:
        runs = {k: v for k, v in runs.items() if v[0] != "ramp"}
    rec = rs.recordings(runs)
    warnings = []
    return force_unit_finding(rec, rs.reduced(rec), warnings), warnings


def test_the_honest_set_passes_and_its_evidence_says_one_unit(physics):
    assert finding(physics) == (None, [])
    rec = rs.recordings(rs.made(physics))
    runs = rs.reduced(rec)
    ratios = [ratio for ratio, _, _ in evidence(rec, runs, 5.0)]
    assert len(ratios) == 2 and all(0.8 < r < 1.25 for r in ratios)
    assert rest_noise(rec.runs[0]) == pytest.approx(0.05, rel=0.3)    # make_recordings' sensor


@pytest.mark.parametrize("factor, unit", [(1e-3, "kN"), (0.1, "daN"), (1e3, "mN")])
def test_carriage_runs_in_another_unit_are_named(physics, factor, unit):
    line, _ = finding(physics, rs.scaled(1, factor, ("carriage",), "forces"))
    assert line.startswith("set/forces/carriage_01.csv: force_N: the 2 carriage runs (F_int = ")
    says = rf"the carriage runs' force_N in {unit}\? \(the column is in N; (4\.9|5\.0)\d* N gives"
    assert re.search(says, line)


def test_slide_and_ramp_runs_in_kn_against_the_carriage_in_n_name_the_slides(physics):
    line, _ = finding(physics, rs.scaled(1, 1e-3, ("slide", "ramp"), "forces"))
    assert line.startswith("set/forces/a000_v244_01.csv: force_N:")
    assert "the slide and ramp runs' force_N in kN?" in line


def test_the_sensors_noise_alone_refuses_kn_and_only_warns_of_dan(physics):
    """Without ramp runs only the noise tells: 1000 times quieter logs of
    one sensor cannot be, 10 times can (a filter, a rate)."""
    line, _ = finding(physics, rs.scaled(1, 1e-3, ("carriage",), "forces"), no_ramp=True)
    assert "force_N in kN?" in line and "ramp" not in line
    line, warnings = finding(physics, rs.scaled(1, 0.1, ("carriage",), "forces"), no_ramp=True)
    assert line is None and len(warnings) == 1 and "force_N in daN? (the column is in N)" in warnings[0]


def test_f_int_above_every_slide_force_without_evidence_names_the_carriage_runs(physics):
    """A noise-free carriage log 4 times too large: no unit's factor, but it
    cannot be right."""
    def convert(kind, traj, forces):
        if kind == "carriage":
            forces[:, 1] = 4 * 5.0 * (forces[:, 1] > 2.5)
        return traj, forces
    line, _ = finding(physics, convert)
    assert line.startswith("set/forces/carriage_01.csv: force_N: the 2 carriage runs (F_int = 20 N): "
                           "F_int is above every slide run's force")


def test_the_unit_tables_and_disagreeing_evidence():
    assert force_slip(1000.0) == (1e3, "kN") and force_slip(9.0) == (10.0, "daN")
    assert force_slip(1 / 102) == (9.80665e-3, "gram-force") and force_slip(3.0) is None
    assert plausibility.slip(120.0, plausibility.LENGTH_SLIPS) == (100.0, "cm")
    assert plausibility.slip(0.001, plausibility.TIME_SLIPS) is None
    kn, one, dan = (1000.0, "", True), (1.1, "", True), (10.0, "", True)
    assert agreed_slip([kn, kn])[:2] == (1e3, "kN")
    assert agreed_slip([kn, one]) is None and agreed_slip([kn, dan]) is None
    assert agreed_slip([kn, (math.inf, "", True)])[:2] == (1e3, "kN")   # a quiet log tells nothing
