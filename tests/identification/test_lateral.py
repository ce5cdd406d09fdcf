"""The lateral tracker column against the longitudinal one (orthocontact.
identification.lateral), on synthetic recordings (tests/recording_sets.py):
angles near +-90 deg are x2 in another unit, named by the factor that
brings them back and by the tracker's noise on both columns."""
import math

import pytest

import recording_sets as rs
from orthocontact.identification.lateral import (
    PLAUSIBLE_PHI_DEG,
    STEEPEST_PHI_DEG,
    lateral_finding,
    noise_ratio,
    slide_groups,
)


@pytest.fixture(scope="module")
def physics():
    return rs.physics()


def lateral(physics, factor):
    rec = rs.recordings(rs.made(physics, convert=rs.scaled(2, factor)))
    runs = rs.reduced(rec)
    return rec, runs


def test_the_honest_set_passes_and_its_columns_share_the_trackers_noise(physics):
    rec, runs = lateral(physics, 1.0)
    assert lateral_finding(rec, runs) is None
    slides = [r for rs_ in slide_groups(runs).values() for r in rs_]
    assert 0.5 < noise_ratio(rec, slides) < 2


@pytest.mark.parametrize("factor, unit", [(1e3, "mm"), (1e2, "cm")])
def test_x2_in_mm_or_cm_is_named_with_the_angle_it_would_give(physics, factor, unit):
    rec, runs = lateral(physics, factor)
    line = lateral_finding(rec, runs)
    assert line.startswith("set/trajectories/a030_v244_01.csv: x2_m: the slide runs at 30 deg, 0.244 m/s")
    assert f"x2_m in {unit}? (x2 / {factor:g} would give -10." in line     # the truth: -10.8 deg at 30 deg
    slides = [r for rs_ in slide_groups(runs).values() for r in rs_]
    assert 0.5 * factor < noise_ratio(rec, slides) < 2 * factor


def test_x2_in_no_length_unit_is_still_refused():
    """tan(phi) 1e5 times too large: no length unit brings it within
    PLAUSIBLE_PHI_DEG, and the set is refused all the same."""
    rec, runs = lateral(rs.physics(), 1e5)
    assert lateral_finding(rec, runs).endswith("x2_m in another unit than x1_m? both columns are in m")


def test_the_thresholds_leave_room_between_a_mat_and_a_unit_slip():
    # a 5 deg path in cm, a 0.5 deg one in mm: beyond STEEPEST_PHI_DEG
    assert math.degrees(math.atan(100 * math.tan(math.radians(5)))) > STEEPEST_PHI_DEG
    assert math.degrees(math.atan(1000 * math.tan(math.radians(0.5)))) > STEEPEST_PHI_DEG
    assert PLAUSIBLE_PHI_DEG < STEEPEST_PHI_DEG
