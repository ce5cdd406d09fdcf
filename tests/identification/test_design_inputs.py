"""What a design starts from (identification.design_inputs): the paper's
prior, the noise and which source wins, plan files read and written in a
lab's order, and the paper's design at any number of runs."""
import json

import pytest

from orthocontact.errors import InputError
from orthocontact.identification import design_inputs as di


def test_the_paper_prior_is_the_aged_mat_on_the_paper_rig():
    prior = di.paper_prior(False, di.noise_of(None, None, 0.05))
    assert {k: prior.values[k] for k in ("mu1", "mu2", "eps_ratio", "eps2", "f_int")} == \
        {"mu1": 0.408, "mu2": 0.625, "eps_ratio": 1.251, "eps2": 1e4, "f_int": 5.0}
    r = prior.rig
    assert (r.mass_kg, r.g, r.f_int_N, r.alpha_offset_deg, r.beta_offset_deg, r.velocity_m_s) == \
        (1.875, 9.806, 5.0, 90.0, 0.0, 0.244)
    assert not prior.strip and not prior.rate_dependent and r.c_strip == 0.0
    # the paper's calibration point: |phi| peaks at 39.2 deg (model notes)
    assert prior.peak_angle_deg() == 39.2
    strip = di.paper_prior(True, di.noise_of(None, None, 0.05))
    assert strip.strip and strip.rate_dependent and strip.values["c_strip"] == 10.0


def test_the_options_set_the_noise_else_the_identification_else_the_defaults():
    assert di.noise_of(None, None, 0.05) == di.Noise(force_rel=0.01, angle_deg=1.0, ramp_N=0.05)
    estimate = {"forces_N": 0.06, "angles_deg": 0.4, "angles_deg_by_velocity": {"0.125": 0.7, "0.244": 0.3}}
    n = di.noise_of(None, None, 0.02, estimate)
    assert (n.force_rel, n.force_sd(15.0), n.angle_sd(0.125), n.angle_sd(0.244), n.angle_sd(0.3)) == \
        (None, 0.06, 0.7, 0.3, 0.4)
    n = di.noise_of(0.02, 2.0, 0.02, estimate)
    assert (n.force_sd(15.0), n.angle_sd(0.125)) == (pytest.approx(0.3), 2.0)
    json.dumps(n.as_json())


def test_the_paper_design_at_five_runs_is_its_points_and_at_others_their_proportions():
    def angles(n, velocities=(0.244,)):
        return sorted(r.mat_angle_deg for r in di.baseline_runs(n, 39.2, velocities))
    assert angles(5) == [0, 0, 39.2, 90, 90]
    assert angles(10) == [0] * 4 + [39.2] * 2 + [90] * 4
    assert angles(3) == [0, 39.2, 90]
    assert angles(6) == [0, 0, 0, 39.2, 90, 90]   # 2.4, 1.2, 2.4: the tie of 0 and 90 to 0
    both = di.baseline_runs(10, 39.2, (0.125, 0.244))
    assert sorted(r.mat_angle_deg for r in both if r.velocity_m_s == 0.125) == [0, 0, 39.2, 90, 90]


def test_a_plan_is_written_in_a_labs_order_and_read_back(tmp_path):
    runs = [di.Run("slide", 90.0, 0.244), di.Run("ramp", 0.0, 0.002), di.Run("slide", 29.0, 0.5),
            di.Run("carriage", 0.0, 0.244), di.Run("slide", 29.0, 0.05)]
    rows = di.plan_rows(runs)
    assert [r[:2] for r in rows] == [("carriage", 0.0), ("slide", 29.0), ("slide", 29.0), ("slide", 90.0),
                                     ("ramp", 0.0)]
    path = tmp_path / "plan.csv"
    path.write_text("run,kind,mat_angle_deg,velocity_m_s\n" + "".join(f"r{i},{k},{a},{v}\n"
                                                                      for i, (k, a, v) in enumerate(rows)))
    assert di.read_plan(path) == di.lab_order(runs)   # a runs.csv reads too: its run column ignored
    assert di.grouped(runs + [di.Run("slide", 90.0, 0.244)])[-2] == (di.Run("slide", 90.0, 0.244), 2)


@pytest.mark.parametrize("text, says", [
    ("kind,mat_angle_deg\nslide,3\n", "expected column 'velocity_m_s'"),
    ("kind,mat_angle_deg,velocity_m_s\nslid,3,0.2\n", "line 2: kind: expected one of carriage, slide, ramp"),
    ("kind,mat_angle_deg,velocity_m_s\nslide,x,0.2\n", "line 2: mat_angle_deg: expected a number"),
    ("kind,mat_angle_deg,velocity_m_s\nslide,400,0.2\n", "mat_angle_deg: expected an angle in [-180, 180]"),
    ("kind,mat_angle_deg,velocity_m_s\nslide,30,-0.2\n", "line 2: velocity_m_s"),
    ("kind,mat_angle_deg,velocity_m_s\n", "expected at least one run"),
])
def test_a_bad_plan_is_one_line_naming_the_file_and_the_line(tmp_path, text, says):
    path = tmp_path / "plan.csv"
    path.write_text(text)
    with pytest.raises(InputError) as e:
        di.read_plan(path)
    assert str(path) in str(e.value) and says in str(e.value) and "\n" not in str(e.value)
