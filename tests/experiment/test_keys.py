"""The one validator of the experiment's files (orthocontact.experiment.keys):
a scenario's [rig] table and a lab's rig.toml check the same keys the same way."""
from pathlib import Path
import pytest

from orthocontact.errors import InputError
from orthocontact.experiment.keys import RIG_KEYS, read_table, rig_spec
from orthocontact.experiment.rig_setup import RIG_TOML, load_rig_toml
from orthocontact.experiment.scenario import SCHEMA, ScenarioError, load

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


def test_a_checkers_range_options_and_items_are_readable_and_a_list_is_gated_item_by_item():
    """The schema's checkers say what they take (the property tests of
    test_scenario.py draw from them); a list's numbers pass the plausibility
    gate as their key's quantity, named by their index."""
    from orthocontact.experiment.keys import ANGLE_DEG, Choice, ListOf, Number, plausible
    assert (ANGLE_DEG.lo, ANGLE_DEG.hi, ANGLE_DEG.lo_open) == (-360, 360, False)
    rules = SCHEMA["twist"]["rules"][0]
    assert isinstance(rules, ListOf) and isinstance(rules.item, Choice) and rules.unique
    assert rules.item.options == ("associated", "coupled")
    assert rules(["coupled", "associated"]) is None
    assert rules(["coupled", "coupled"]) == "a list without repeated items (each is run once)"
    assert isinstance(SCHEMA["patch"]["n1"][0], Number) and SCHEMA["patch"]["n1"][0].hi == 32
    assert plausible("pin_m", 0.015) is None
    assert plausible("pin_m", [0.015, 15.0]) == ("error", "pin_m[1] = 15 m: a tow's pin is 1 mm-1 m ahead of "
                                                          "the block's centre; mm?")
    assert plausible("angles_deg", [0.0, 30.0]) is None and plausible("rules", ["coupled"]) is None
    assert plausible("angles_deg", [0.1, 0.2])[1].startswith("angles_deg = [0.1, 0.2]: all within +-pi/2")
