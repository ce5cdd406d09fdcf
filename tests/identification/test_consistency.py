"""A recording set checked as a whole (orthocontact.identification.
consistency): synthetic recordings (tools/make_recordings.py) with one
column converted as a lab might have logged it, through the real
`orthocontact identify`: one line naming the file, the column and the
likely unit, exit 2, no identified.json; the honest set still identifies;
and the raw streams' checks on their own."""
import numpy as np
import pytest

import make_recordings as mr
import recording_sets as rs
from cli_run import one_error_line, run_cli
from orthocontact.errors import InputError
from orthocontact.identification.consistency import check_streams, one_line, pull_force

# the paper's geometry turned by 45 deg: there the law allows the flipped
# angles for no eps1/eps2 (test_angle_signs.py has where it does)
TURNED = mr.Truth(c_strip=0.0, alpha_offset_deg=45.0)


@pytest.fixture(scope="module")
def physics():
    return rs.physics()


def identify(tmp_path, folder):
    return run_cli(["identify", folder, "--out", tmp_path / "out", "--no-validate"], tmp_path)


def refused(tmp_path, p, *says):
    one_error_line(p, *says)
    assert "Traceback" not in p.stderr
    assert not (tmp_path / "out" / "identified.json").exists()


CASES = {   # convert, then what the one line names: file, column, unit
    "x2 in mm": (rs.scaled(2, 1e3), ("trajectories/a030_v244_01.csv", "x2_m", "x2_m in mm?")),
    "x2 in cm": (rs.scaled(2, 1e2), ("trajectories/a030_v244_01.csv", "x2_m", "x2_m in cm?")),
    "carriage in kN": (rs.scaled(1, 1e-3, ("carriage",), "forces"),
                       ("forces/carriage_01.csv", "force_N", "carriage runs' force_N in kN?")),
    "carriage in daN": (rs.scaled(1, 0.1, ("carriage",), "forces"),
                        ("forces/carriage_01.csv", "force_N", "carriage runs' force_N in daN?")),
    "force t_s in ms": (rs.scaled(0, 1e3, series="forces"),
                        ("forces/a000_v244_01.csv", "t_s spans", "t_s in ms?")),
    "trajectory t_s in ms": (rs.scaled(0, 1e3), ("trajectories/a000_v244_01.csv", "t_s:", "t_s in ms?")),
    "force sign flipped": (rs.scaled(1, -1.0, series="forces"),
                           ("forces/a000_v244_01.csv", "force_N", "force_N sign flipped?")),
}


@pytest.mark.parametrize("case", list(CASES))
def test_a_column_in_another_unit_is_refused_naming_file_column_and_unit(tmp_path, physics, case):
    convert, says = CASES[case]
    folder = rs.folder(tmp_path / "rec", rs.made(physics, convert=convert))
    refused(tmp_path, identify(tmp_path, folder), *says)


def test_x2_flipped_is_refused_where_the_law_allows_no_such_angles(tmp_path):
    runs = rs.made(rs.physics(TURNED), truth=TURNED, convert=rs.scaled(2, -1.0))
    p = identify(tmp_path, rs.folder(tmp_path / "rec", runs, TURNED))
    refused(tmp_path, p, "trajectories/a000_v244_01.csv", "x2_m", "x2_m sign flipped, or phi_convention?")


def test_x2_flipped_in_the_papers_geometry_ends_in_a_result_or_one_line(tmp_path, physics):
    """Cases 4 and 5 allow either sign (test_angle_signs.py): the reduction
    cannot tell a flipped x2 there; the command still ends as the CLI
    promises, never in a traceback."""
    p = identify(tmp_path, rs.folder(tmp_path / "rec", rs.made(physics, convert=rs.scaled(2, -1.0))))
    assert "Traceback" not in p.stderr
    if p.returncode != 0:
        one_error_line(p)


def test_the_honest_small_set_identifies(tmp_path):
    design = mr.Design(angles_deg=[0, 30, 60, 90], velocities={0.244: 5}, carriage_runs=3, ramp_runs=2)
    runs = rs.made(rs.physics(rs.TRUTH, design), design=design)
    p = identify(tmp_path, rs.folder(tmp_path / "rec", runs))
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "out" / "identified.json").is_file()


def test_the_honest_runs_pass_the_stream_checks_and_pull_positive(physics):
    rec = rs.recordings(rs.made(physics))
    check_streams(rec)
    pulls = {run.kind: pull_force(run)[0] for run in rec.runs}
    # a slide at 90 deg: F_int + mu2 m g; a carriage run: F_int; a ramp: its sliding level
    assert pulls["slide"] == pytest.approx(5.0 + 0.625 * 1.875 * 9.806, rel=0.02)
    assert pulls["carriage"] == pytest.approx(5.0, abs=0.3)
    assert pulls["ramp"] > 5.0


def test_only_some_logs_flipped_are_named_with_how_many(physics):
    runs = rs.made(physics)
    for name in ("a060_v244_02", "ramp_01"):
        kind, a, v, traj, forces = runs[name]
        runs[name] = (kind, a, v, traj, forces * np.array([1.0, -1.0]))
    with pytest.raises(InputError, match=r"^set/forces/a060_v244_02\.csv: run a060_v244_02: force_N is "
                                         r"-\d.* force_N sign flipped\? .* \(1 more files alike\)$"):
        check_streams(rs.recordings(runs))


def test_one_line_says_how_many_more():
    assert one_line(["a"]) == "a"
    assert one_line(["a", "b", "c"]) == "a (2 more files alike)"
