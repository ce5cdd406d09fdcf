"""Inputs checked for their units (orthocontact.plausibility), through the
real command: an error where a value cannot be right, a warning where it is
merely unusual, each naming the likely unit slip."""
import math
import shutil
import subprocess

import numpy as np
import pytest

from cli_run import AGED_LAW, CMD
from orthocontact import plausibility
from orthocontact.experiment.rig_setup import RigSetup
from orthocontact.identification.measurements import write_measurements
from paths import DOCS, SCENARIOS

EXAMPLE = SCENARIOS / "example_identification"

MAT = 'name = "mat"\nkind = "sweep"\n' + AGED_LAW + """[geometry]
alpha_offset_deg = 90.0
closed_form = "mat"
[sweep]
start_deg = 35.0
stop_deg = 40.0
step_deg = 5.0
"""


def run(args, cwd):
    return subprocess.run(CMD + args, cwd=cwd, capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("table,line,says", [
    ("rig", "velocity_m_s = 24.4",
     "rig.velocity_m_s = 24.4 m/s: a lab rig's carriage moves at 0.001-2 m/s; cm/s?"),
    ("rig", "travel_m = 500", "rig.travel_m = 500 m: a lab rig's travel is 0.005-10 m; mm?"),
    ("rig", "mass_kg = 1875", "rig.mass_kg = 1875 kg: a block on a lab rig weighs 0.01-100 kg; g?"),
    ("rig", "g = 981", "rig.g = 981 m/s^2: gravity on Earth is 9.76-9.84 m/s^2; cm/s^2?"),
    ("law", "mu1 = 40.8", "law.mu1 = 40.8: friction coefficients are 0.01-3"),
])
def test_a_value_that_cannot_be_right_is_one_line_and_exit_2(tmp_path, table, line, says):
    text = MAT.replace("mu1 = 0.408\n", "") if line.startswith("mu1") else MAT
    body = text + f"[{table}]\n{line}\n" if table == "rig" else text.replace("[law]\n", f"[law]\n{line}\n")
    (tmp_path / "s.toml").write_text(body)
    p = run(["run", "s.toml", "--out", "o"], tmp_path)
    assert p.returncode == 2 and p.stdout == ""
    assert p.stderr.strip() == f"orthocontact: error: s.toml: {says}"
    assert not (tmp_path / "o").exists()


def test_an_angle_in_radians_in_a_degree_key_is_a_warning(tmp_path):
    # the general closed form: the mat's holds only at the mat's axes (a refusal that names the
    # warning, tests/experiment/test_scenario.py)
    (tmp_path / "s.toml").write_text(MAT.replace("alpha_offset_deg = 90.0", "alpha_offset_deg = 1.5708")
                                     .replace('closed_form = "mat"', 'closed_form = "general"'))
    p = run(["run", "s.toml", "--out", "o"], tmp_path)
    assert p.returncode == 0, p.stderr
    w = [x for x in p.stderr.splitlines() if x.startswith("orthocontact: warning:")]
    assert w == ["orthocontact: warning: s.toml: geometry.alpha_offset_deg = 1.5708: looks like pi/2 in "
                 "radians; this key is in degrees (90.0002 deg if it was meant in rad)"]
    assert run(["run", "s.toml", "--out", "o2", "--strict"], tmp_path).returncode == 1


def test_an_unusual_velocity_is_a_warning_naming_the_slip(tmp_path):
    (tmp_path / "s.toml").write_text(MAT + '[rig]\nvelocity_m_s = 5.0\nmode = "quasistatic"\n')
    p = run(["run", "s.toml", "--out", "o"], tmp_path)
    assert p.returncode == 0
    assert "orthocontact: warning: s.toml: rig.velocity_m_s = 5 m/s: a lab rig's carriage moves at " \
           "0.001-2 m/s; cm/s?" in p.stderr


def measurement_set(tmp_path, rig=None, angles=None, forces=None):
    rig = rig or RigSetup(mass_kg=1.875, f_int_N=5.0)
    angles = [[a, p] for a, p in np.loadtxt(EXAMPLE / "angles.csv", delimiter=",", skiprows=1,
                                            usecols=(0, 1))] if angles is None else angles
    forces = [[a, f] for a, f in np.loadtxt(EXAMPLE / "forces.csv", delimiter=",", skiprows=1)] \
        if forces is None else forces
    write_measurements(tmp_path / "d", rig, forces=forces, angles=angles)
    return tmp_path / "d"


def test_angles_csv_written_in_radians_is_refused(tmp_path):
    """It gave eps1/eps2 = 1.447 with a tight interval (truth 1.251)."""
    good = np.loadtxt(EXAMPLE / "angles.csv", delimiter=",", skiprows=1, usecols=(0, 1))
    d = measurement_set(tmp_path, angles=[[math.radians(a), math.radians(p)] for a, p in good])
    p = run(["identify", str(d), "--out", "o"], tmp_path)
    assert p.returncode == 2 and not (tmp_path / "o").exists()
    line = p.stderr.strip()
    assert len(line.splitlines()) == 1
    assert "angles.csv: mat_angle_deg: all mat angles lie within +-pi/2" in line and "radians?" in line


def test_trajectory_angles_that_all_look_like_radians_are_a_warning(tmp_path):
    good = np.loadtxt(EXAMPLE / "angles.csv", delimiter=",", skiprows=1, usecols=(0, 1))
    d = measurement_set(tmp_path, angles=[[a, math.radians(p)] for a, p in good])
    p = run(["identify", str(d), "--out", "o", "--no-validate"], tmp_path)
    assert "angles.csv: phi_deg: all trajectory angles lie within +-0.25 deg: radians?" in p.stderr


@pytest.mark.parametrize("force,says", [
    (4.0, "force_N = 4: below f_int_N = 5 N"),
    (200.0, "mu = (F - F_int)/(m g) = 10.6, outside (0, 5)"),
])
def test_forces_that_cannot_be_right_are_refused(tmp_path, force, says):
    d = measurement_set(tmp_path, forces=[[0.0, 12.5], [90.0, force]])
    p = run(["identify", str(d), "--out", "o"], tmp_path)
    assert p.returncode == 2 and says in p.stderr and "forces.csv: row 2 (mat_angle_deg = 90)" in p.stderr


def test_rig_toml_velocity_in_cm_s_is_refused(tmp_path):
    d = measurement_set(tmp_path)
    (d / "rig.toml").write_text((d / "rig.toml").read_text().replace("velocity_m_s = 0.244",
                                                                     "velocity_m_s = 24.4"))
    p = run(["identify", str(d), "--out", "o"], tmp_path)
    assert p.returncode == 2 and "rig.toml: velocity_m_s = 24.4 m/s" in p.stderr and "cm/s?" in p.stderr


def test_the_plausibility_table_itself():
    assert plausibility.check("velocity_m_s", 0.244) is None
    assert plausibility.check("f_int_N", 0.0) is None and plausibility.check("mu_strip", 0.0) is None
    assert plausibility.check("velocity_m_s", 0.0)[0] == "error"
    assert plausibility.radian_slip(90.0) is None and plausibility.radian_slip(3.14159) == "pi"
    assert plausibility.radian_slip(-0.5236) == "-pi/6" and plausibility.radian_slip(2.0) is None
    # every quantity's usual range lies inside its hard range
    for key, q in plausibility.QUANTITIES.items():
        assert q.hard[0] <= q.usual[0] <= q.usual[1] <= q.hard[1], key


def test_the_docs_list_every_range_as_the_code_has_it():
    readme = (DOCS / "reference" / "plausible-inputs.md").read_text()

    def fmt(x):
        return f"{x:g}"
    for key, q in plausibility.QUANTITIES.items():
        lo, hi = q.hard
        hard = f"[{fmt(lo)}, {fmt(hi)}]" if (q.zero_allowed or lo != 0) else f"({fmt(lo)}, {fmt(hi)}]"
        row = (f"| `{key}` | {q.unit} | {hard} | [{fmt(q.usual[0])}, {fmt(q.usual[1])}] | "
               f"{', '.join(u for _, u in q.slips) or '–'} |")
        assert row in readme, row


# --- the one gate (plausibility.gate) and the cross-checks --------------------

def test_the_gate_refuses_the_first_value_outside_its_hard_range_with_its_limit():
    from orthocontact.errors import InputError
    assert plausibility.gate({"eps1": 1.25e4, "mu1": 0.4}, "f: ") == []
    with pytest.raises(InputError) as e:
        plausibility.gate({"mu1": 0.4, "eps1": 1e13}, "f: ", refused="refused (--force)")
    assert str(e.value) == ("f: eps1 = 1e+13 N/m: a contact's tangential stiffness is 10-1e9 N/m; none "
                            "above 1e+12 N/m can be right; refused (--force)")
    with pytest.raises(InputError, match=r"f: mu2 = nan: expected a finite number \[-\]"):
        plausibility.gate({"mu2": float("nan")}, "f: ")
    with pytest.raises(InputError, match="it cannot be 0"):
        plausibility.gate({"eps2": 0.0})
    # unusual: a warning line, named slip included
    assert plausibility.gate({"eps2": 5.0}, "f: ") == [
        "f: eps2 = 5 N/m: a contact's tangential stiffness is 10-1e9 N/m; N/mm?"]
    # a value the table does not know is a programming error, not a silent pass
    with pytest.raises(KeyError):
        plausibility.gate({"eps3": 1.0})


def test_the_elastic_length_bounds_the_stiffness_by_the_travel():
    """mu N / eps against the rig's travel, with N = m g of the example rig."""
    N = 1.875 * 9.806
    short, long = plausibility.elastic_lengths(0.408, 0.625, 12.51, 10.0, N)
    assert short == pytest.approx(0.408 * N / 12.51) and long == pytest.approx(0.625 * N / 10.0)
    # eps in N/mm typed as N/m: even the shortest (0.60 m) exceeds 0.5 m of travel
    f = plausibility.elastic_length_check(0.408, 0.625, 12.51, 10.0, N, 0.5, "d: ")
    assert f.level == "error" and "would stick over the whole travel" in f.line
    assert f.line.endswith("; eps1, eps2 in N/mm?") and "0.6 .. 1.15 m" in f.line
    # soft but possible: the rig's fit would start within 10 elastic lengths
    f = plausibility.elastic_length_check(0.408, 0.625, 125.1, 100.0, N, 0.5)
    assert f.level == "warning" and "would not settle" in f.line
    assert plausibility.elastic_length_check(0.408, 0.625, 12510.0, 1e4, N, 0.5) is None


def test_a_ramp_beyond_the_travel_names_the_length_unit():
    f = plausibility.ramp_extent_check(1.965, 0.5, "ramp.csv: ")
    assert f.level == "error" and f.line == ("ramp.csv: x1_m reaches 1.965 m, beyond the rig's travel "
                                             "0.5 m: x1_m in mm? the column is in m")
    assert plausibility.ramp_extent_check(0.002, 0.5) is None
    assert "in mm?" not in plausibility.ramp_extent_check(900.0, 0.5).line   # no unit explains it


def test_a_force_is_judged_against_f_int_and_m_g():
    N = 1.875 * 9.806
    assert plausibility.force_check(12.5, 5.0, N) is None
    assert plausibility.force_check(4.0, 5.0, N).line == ("force_N = 4: below f_int_N = 5 N (the sensor "
                                                          "reads F_int plus the push)")
    assert "mu = (F - F_int)/(m g) = 10.6, outside (0, 5)" in plausibility.force_check(200.0, 5.0, N).line
    # too large a force names a smaller unit that fits (it said "kN, or lbf?", which give smaller numbers)
    assert plausibility.force_check(12500.0, 5.0, N).line.endswith("; force_N in mN? (the column is in N)")
    assert plausibility.force_check(1275.0, 5.0, N).line.endswith("; force_N in gram-force? (the column is "
                                                                   "in N)")
    assert plausibility.force_check(1e9, 5.0, N).line.endswith("; force_N in N? (the column is in N)")


def test_identify_refuses_a_stiffness_that_cannot_be_right_and_writes_nothing(tmp_path):
    """A ramp whose x1_m is 1e-9 of the example's: eps ~ 1e13 N/m, above the
    hard limit; the identified value is refused before identified.json."""
    from cli_run import one_error_line
    d = tmp_path / "d"
    shutil.copytree(EXAMPLE, d)
    rows = np.loadtxt(EXAMPLE / "ramp.csv", delimiter=",", skiprows=1)
    np.savetxt(d / "ramp.csv", np.column_stack([rows[:, 0] * 1e-9, rows[:, 1]]), delimiter=",",
               header="x1_m,force_N", comments="")
    p = run(["identify", str(d), "--out", "o", "--no-validate"], tmp_path)
    one_error_line(p, "identified eps", "none above 1e+12 N/m can be right",
                   "refused: identified.json not written")
    assert not (tmp_path / "o").exists()


def test_forces_all_in_kn_are_named_by_their_size_against_m_g():
    """The bundled recordings with every force in kN: each ratio is sane,
    but every (F - F_int)/(m g) is 1000 times too small (measured 0.00041 ..
    0.00063 over the slides, F_int 0.00498 N)."""
    N = 1.875 * 9.806
    f = plausibility.force_unit_check([0.00041, 0.00063], 0.00498, "d: ", "mu1, mu2")
    assert f.level == "warning" and f.line == (
        "d: mu1, mu2 = 0.00041 .. 0.00063 (F_int = 0.00498 N): all below the usual 0.01-3 of a friction "
        "coefficient, and 1000 times each within it; forces in kN? (force_N is in N)")
    assert "(m g = 18.39 N, F_int" in plausibility.force_unit_check([0.0004], 0.005, normal_force=N).line
    assert plausibility.force_unit_check([0.41, 0.63], 4.98) is None              # in N
    assert plausibility.force_unit_check([0.0004, 0.41], 0.005) is None           # not every force
    assert plausibility.force_unit_check([0.00041, 0.0045], 0.005) is None        # 4.5: no factor 1000 fits
    assert plausibility.force_unit_check([0.00041], 5.0) is None                  # F_int 5 kN: no
    # a force in kN against F_int in N is below F_int: the refusal names kN where 1000 F fits
    assert plausibility.force_check(0.0125, 5.0, N).line.endswith("; force_N in kN?")
    assert "kN" not in plausibility.force_check(4.0, 5.0, N).line


def test_the_last_gate_refuses_a_warning_too_unless_forced():
    """export's gate: what gate() only warns about is refused; a cross-check
    (which names the cause) is the line said, before a single value."""
    from orthocontact.errors import InputError
    assert plausibility.gate({"eps2": 5.0}, "f: ") != []          # identify: a warning
    kn = plausibility.force_unit_check([0.0004], 0.005, "f: ")
    with pytest.raises(InputError) as e:
        plausibility.last_gate({"mu1": 0.0004, "eps2": 5.0}, "f: ", [None, kn], override="--force")
    assert str(e.value) == kn.line + "; refused (--force)"
    found = plausibility.last_gate({"mu1": 0.0004, "eps1": 1e13}, "f: ", [kn], force=True)
    assert [f.level for f in found] == ["error", "warning", "warning"] and found[1] == kn
    assert plausibility.last_gate({"mu1": 0.4}, "f: ", [None]) == []
    assert [f.line for f in plausibility.angle_findings({"--angle": 0.7854, "a": 45.0, "b": float("nan")})] \
        == ["--angle = 0.7854: looks like pi/4 in radians; this key is in degrees (45.0001 deg if it was "
            "meant in rad)"]


def test_a_list_of_angles_typed_in_radians_is_named_as_a_list_or_by_its_item():
    assert plausibility.check_angles_deg("a_deg", [0.0, 15.0, 90.0]) is None
    assert plausibility.check_angles_deg("a_deg", [0.0]) is None    # one value: no spread to judge
    level, line = plausibility.check_angles_deg("a_deg", [0.5, 1.0])
    assert level == "warning"
    assert line == ("a_deg = [0.5, 1]: all within +-pi/2, they look like radians; "
                    "this key is in degrees ([28.65, 57.3] deg if they were meant in rad)")
    item = plausibility.check_angles_deg("a_deg", [45.0, 1.5708])[1]
    assert item.startswith("a_deg[1] = 1.5708: looks like pi/2 in radians")
    # the patch's lengths: mm typed as m is an error naming mm
    assert plausibility.check("length_m", 50.0) == ("error", "length_m = 50 m: a block's contact patch is "
                                                             "1 mm-1 m long; mm?")
    assert plausibility.check("length_m", 0.05) is None
