"""The one validator of the experiment's files (orthocontact.experiment.keys):
a scenario's [rig] table and a lab's rig.toml check the same keys the same way."""
from pathlib import Path

import pytest

from cli_run import MAT_SWEEP
from orthocontact.errors import InputError
from orthocontact.experiment.keys import RIG_KEYS, read_table, rig_spec
from orthocontact.experiment.rig_setup import RIG_TOML, load_rig_toml
from orthocontact.experiment.scenario import SCHEMA, ScenarioError, load


def test_both_files_check_the_rigs_keys_with_the_same_checkers():
    for key, check in RIG_KEYS.items():
        assert SCHEMA["rig"][key][0] is check, key
        assert key == "fit_from" or RIG_TOML[key][0] is check, key   # a lab's rig fits no path


def test_the_rigs_keys_their_defaults_and_ranges_are_the_rigs_fields():
    """Rig (rig.harness) is the one place of the rig's fields, defaults and
    checks: the scenario's [rig] table has them all with Rig's defaults,
    rig.toml its own defaults where it says so, and Rig refuses what the
    files refuse, in the same words."""
    import dataclasses

    from orthocontact.experiment.rig_setup import LAB_DEFAULTS, RigSetup
    from orthocontact.rig.harness import Rig
    fields = {f.name: f for f in dataclasses.fields(Rig)}
    assert list(SCHEMA["rig"]) == list(fields)
    assert {k: d for k, (_, d) in SCHEMA["rig"].items()} == {k: f.default for k, f in fields.items()}
    lab = RigSetup(mass_kg=1.875)
    for key, (_, default) in RIG_TOML.items():
        if key in fields and key != "mass_kg":
            assert default == LAB_DEFAULTS.get(key, fields[key].default) == getattr(lab, key), key
    for key, value in (("fit_from", 0.96), ("velocity_m_s", 0.0), ("mode", "fast"), ("c_strip", -1.0)):
        why = SCHEMA["rig"][key][0](value)
        with pytest.raises(ValueError, match=f"Rig: {key} must be {why}, got"):
            Rig(**{key: value})


@pytest.mark.parametrize("key,value,says", [
    ("velocity_m_s", -1.0, "velocity_m_s: expected a number > 0, got -1.0"),
    ("mode", "fast", "mode: expected one of 'dynamic', 'quasistatic', got 'fast'"),
    ("step_s", 0.5, "step_s = 0.5 s: a communication step of 1e-7-1e-2 s"),
    ("step_s", -1e-3, "step_s: expected a number > 0, got -0.001"),
    ("travel_m", 500.0, "travel_m = 500 m: a lab rig's travel is 0.005-10 m; mm?"),
])
def test_a_bad_rig_value_reads_the_same_in_both_files(tmp_path, key, value, says):
    text = f'"{value}"' if isinstance(value, str) else repr(value)
    (tmp_path / "s.toml").write_text(MAT_SWEEP + f"[rig]\n{key} = {text}\n")
    with pytest.raises(ScenarioError) as scen:
        load(tmp_path / "s.toml")
    (tmp_path / "rig.toml").write_text(f"mass_kg = 1.875\n{key} = {text}\n")
    with pytest.raises(InputError) as lab:
        load_rig_toml(tmp_path / "rig.toml")
    assert str(scen.value) == f"{tmp_path / 's.toml'}: rig.{says}"
    assert str(lab.value) == f"{tmp_path / 'rig.toml'}: {says}"


def test_read_table_fills_defaults_and_refuses_unknown_and_missing_keys():
    spec = {k: v for k, v in rig_spec(mass_kg=1.0, g=9.806).items() if k in ("mass_kg", "g")}
    values, warnings = read_table(Path("f"), "", {"g": 9.81}, spec, InputError)
    assert values == {"mass_kg": 1.0, "g": 9.81} and warnings == []
    with pytest.raises(InputError, match="f: colour: expected one of the known keys g, mass_kg"):
        read_table(Path("f"), "", {"colour": 1}, spec, InputError)
    from orthocontact.experiment.keys import REQUIRED
    with pytest.raises(InputError, match="f: rig.mass_kg: expected a value"):
        read_table(Path("f"), "rig.", {}, rig_spec(mass_kg=REQUIRED), InputError)
    _, warnings = read_table(Path("f"), "", {"g": 9.7}, spec, InputError)
    assert warnings == ["f: g = 9.7 m/s^2: gravity on Earth is 9.76-9.84 m/s^2"]


def test_read_table_names_every_problem_of_the_table_one_line_each():
    """An unknown key, a missing required one, a wrong type, a value out of
    range and one that cannot be right for its unit: five lines in one error;
    with a Problems collector given, the lines join it and the good keys'
    values come back."""
    from orthocontact.errors import Problems
    from orthocontact.experiment.keys import REQUIRED
    spec = rig_spec(mass_kg=REQUIRED)
    data = {"colour": 1, "g": "9.8", "velocity_m_s": -1.0, "travel_m": 500.0, "step_s": 1e-3}
    with pytest.raises(InputError) as e:
        read_table(Path("f"), "rig.", data, spec, InputError)
    assert e.value.lines == [
        "f: rig.colour: expected one of the known keys " + ", ".join(sorted(spec)),
        "f: rig.mass_kg: expected a value (the key is required)",
        "f: rig.g: expected a finite number, got '9.8'",
        "f: rig.velocity_m_s: expected a number > 0, got -1.0",
        "f: rig.travel_m = 500 m: a lab rig's travel is 0.005-10 m; mm?"]
    problems = Problems(InputError)
    values, _ = read_table(Path("f"), "rig.", data, spec, InputError, problems)
    assert len(problems.lines) == 5 and values["step_s"] == 1e-3 and "g" not in values
    with pytest.raises(InputError) as again:
        problems.raise_any()
    assert again.value.lines == e.value.lines


def test_rig_toml_names_every_problem_in_one_error(tmp_path):
    (tmp_path / "rig.toml").write_text('g = -9.8\nmode = "fast"\nrule = "sticky"\n')
    with pytest.raises(InputError) as e:
        load_rig_toml(tmp_path / "rig.toml")
    assert [line.split(": ")[1] for line in e.value.lines] == ["mass_kg", "g", "mode", "rule"]


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
    assert isinstance(SCHEMA["patch"]["n1"][0], Number) and SCHEMA["patch"]["n1"][0].hi == 64
    assert plausible("pin_m", 0.015) is None
    assert plausible("pin_m", [0.015, 15.0]) == ("error", "pin_m[1] = 15 m: a tow's pin is 1 mm-1 m ahead of "
                                                          "the block's centre; mm?")
    assert plausible("angles_deg", [0.0, 30.0]) is None and plausible("rules", ["coupled"]) is None
    assert plausible("angles_deg", [0.1, 0.2])[1].startswith("angles_deg = [0.1, 0.2]: all within +-pi/2")
