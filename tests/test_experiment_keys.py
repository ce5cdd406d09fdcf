"""The one validator of the experiment's files (experiment.keys) and the one
angle convention at their boundary (experiment.geometry): a scenario's [rig]
table and a lab's rig.toml check the same keys the same way."""
import math
from pathlib import Path

import numpy as np
import pytest

from orthocontact.errors import InputError
from orthocontact.experiment.geometry import AxisGeometry
from orthocontact.experiment.keys import RIG_KEYS, read_table, rig_spec
from orthocontact.experiment.rig_setup import RIG_TOML, load_rig_toml
from orthocontact.experiment.scenario import SCHEMA, ScenarioError, load
from orthocontact.fmu import ContactParams

MAT = '''name = "m"
kind = "sweep"
[law]
mu1 = 0.408
mu2 = 0.625
eps2 = 1.0e4
eps_ratio = 1.251
[sweep]
step_deg = 45.0
'''


def test_both_files_check_the_rigs_keys_with_the_same_checkers():
    for key, check in RIG_KEYS.items():
        assert SCHEMA["rig"][key][0] is check and RIG_TOML[key][0] is check, key


@pytest.mark.parametrize("key,value,says", [
    ("velocity_m_s", -1.0, "velocity_m_s: expected a number > 0, got -1.0"),
    ("mode", "fast", "mode: expected one of 'dynamic', 'quasistatic', got 'fast'"),
    ("step_s", 0.5, "step_s: expected a number <= 0.1, got 0.5"),
    ("travel_m", 500.0, "travel_m = 500 m: a lab rig's travel is 0.005-10 m; mm?"),
])
def test_a_bad_rig_value_reads_the_same_in_both_files(tmp_path, key, value, says):
    text = f'"{value}"' if isinstance(value, str) else repr(value)
    (tmp_path / "s.toml").write_text(MAT + f"[rig]\n{key} = {text}\n")
    with pytest.raises(ScenarioError) as scen:
        load(tmp_path / "s.toml")
    (tmp_path / "rig.toml").write_text(f"mass_kg = 1.875\n{key} = {text}\n")
    with pytest.raises(InputError) as lab:
        load_rig_toml(tmp_path / "rig.toml")
    assert str(scen.value) == f"{tmp_path / 's.toml'}: rig.{says}"
    assert str(lab.value) == f"{tmp_path / 'rig.toml'}: {says}"


def test_read_table_fills_defaults_and_refuses_unknown_and_missing_keys():
    spec = rig_spec(mass_kg=1.0, g=9.806)
    values, warnings = read_table(Path("f"), "", {"g": 9.81}, spec, InputError)
    assert values == {"mass_kg": 1.0, "g": 9.81} and warnings == []
    with pytest.raises(InputError, match="f: colour: expected one of the known keys g, mass_kg"):
        read_table(Path("f"), "", {"colour": 1}, spec, InputError)
    from orthocontact.experiment.keys import REQUIRED
    with pytest.raises(InputError, match="f: rig.mass_kg: expected a value"):
        read_table(Path("f"), "rig.", {}, rig_spec(mass_kg=REQUIRED), InputError)
    _, warnings = read_table(Path("f"), "", {"g": 9.7}, spec, InputError)
    assert warnings == ["f: g = 9.7 m/s^2: gravity on Earth is 9.76-9.84 m/s^2"]


def test_one_angle_convention_degrees_in_the_files_radians_in_the_law():
    g = AxisGeometry(90.0, 0.0)
    alpha, beta = g.axes(39.0)
    assert alpha == math.radians(129.0) and beta == math.radians(39.0)
    arr = g.axes(np.array([0.0, 39.0]))
    assert arr[0].tolist() == [math.radians(90.0), math.radians(129.0)]
    law = ContactParams(0.408, 0.625, 12510.0, 1e4)
    assert g.params_at(law, 39.0, "associated") == law.replace(alpha=alpha, beta=beta, rule="associated")
    assert g.beta_minus_alpha_deg == -90.0


def test_a_scenario_and_a_rig_toml_with_the_same_geometry_give_the_same_law(tmp_path):
    (tmp_path / "s.toml").write_text(MAT + "[geometry]\nalpha_offset_deg = 90.0\n")
    (tmp_path / "rig.toml").write_text("mass_kg = 1.875\nalpha_offset_deg = 90.0\n")
    sc, rig = load(tmp_path / "s.toml"), load_rig_toml(tmp_path / "rig.toml")
    for a in (0.0, 12.5, 39.2, 90.0):
        assert sc.params_at(a) == rig.params_at(sc.law, a)
