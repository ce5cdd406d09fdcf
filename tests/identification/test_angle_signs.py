"""The slide angles' signs against those the law can give (orthocontact.
identification.angle_signs): where the law allows both signs for some
eps1/eps2 (the paper's geometry) a flipped x2 cannot be told here; where it
allows one (the associated rule, turned axes), a flip is named."""
import math

import numpy as np
import pytest

import make_recordings as mr
import recording_sets as rs
from orthocontact.identification.angle_signs import (
    angle_sign_finding,
    law_signs,
    mu_ratio,
    signed_groups,
)


def sets(truth, flip):
    runs = rs.made(rs.physics(truth), truth=truth, convert=rs.scaled(2, -1.0) if flip else None)
    rec = rs.recordings(runs, truth)
    return rec, rs.reduced(rec)


@pytest.mark.parametrize("truth", [mr.Truth(c_strip=0.0, rule="associated"),
                                   mr.Truth(c_strip=0.0, alpha_offset_deg=45.0)],
                         ids=["associated", "axes turned by 45 deg"])
def test_a_flipped_x2_is_named_where_the_law_allows_one_sign(truth):
    assert angle_sign_finding(*sets(truth, False)) is None
    line = angle_sign_finding(*sets(truth, True))
    assert line.startswith("set/trajectories/a0") and line.endswith(
        "x2_m sign flipped, or phi_convention? (rig.toml: 'counterclockwise')")


def test_the_papers_geometry_allows_both_signs_so_a_flip_passes_here():
    """Case 5 (beta = alpha - 90 deg), coupled: every angle's sign is that
    of eps1/eps2 - mu2/mu1, either way for some eps1/eps2."""
    rec, runs = sets(rs.TRUTH, True)
    assert angle_sign_finding(rec, runs) is None
    signs = law_signs(rec, [30.0, 60.0], 0.625 / 0.408)
    patterns = {tuple(s) for s in signs.reshape(-1, 2)}
    assert {(1, 1), (-1, -1)} <= patterns


def test_the_forces_give_mu2_over_mu1_and_the_groups_their_signs():
    rec, runs = sets(rs.TRUTH, False)
    assert mu_ratio(rec, runs, 5.0) == pytest.approx(0.625 / 0.408, rel=0.03)
    groups = signed_groups(rec, runs)
    # the truth at 30 and 60 deg: -10.8 and -8.9 deg; at 0 and 90 deg only drift
    assert {a: s for (a, _), (_, s) in groups.items()} == {0.0: 0, 30.0: -1, 60.0: -1, 90.0: 0}


def test_without_two_friction_directions_mu2_over_mu1_is_unknown():
    rec, runs = sets(rs.TRUTH, False)
    one = [r for r in runs if r.kind != "slide" or r.mat_angle_deg == 30.0]
    assert mu_ratio(rec, one, 5.0) is None
    assert mu_ratio(rec, runs, 1e3) is None      # forces below F_int
    assert not math.isnan(np.sum(law_signs(rec, [30.0], None)))
