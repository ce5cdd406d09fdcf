"""The table of scenario kinds (orthocontact.experiment.kinds): each kind's
row has every piece once the modules that write them are imported, the
schema and the commands ask the row, and no module compares a kind's name."""
import re

import pytest

from cli_run import scenario_variant
from orthocontact.errors import InputError
from orthocontact.experiment.kinds import KINDS, PARTS, fmu_for, kind_of, register, require_mat_angles
from orthocontact.experiment.scenario import COMMON, SCHEMA, ScenarioError, load
from orthocontact.fmu.files import find_fmu
from paths import PKG, SCENARIOS


def test_every_kind_has_every_piece_once_the_commands_modules_are_imported():
    import orthocontact.reproduction.kinds  # noqa: F401  (what the commands import)
    import orthocontact.runs.size  # noqa: F401
    for k in KINDS.values():
        assert set(k.parts) == set(PARTS), k.name
    with pytest.raises(ValueError, match="registered twice"):
        register("twist", "run", lambda *a: {})


def test_the_schema_takes_each_kinds_tables_and_its_name():
    assert SCHEMA[""]["kind"][0].options == tuple(KINDS)
    for k in KINDS.values():
        for table, spec in k.tables.items():
            assert SCHEMA[table] is spec and table not in COMMON
    assert KINDS["twist"].tables["patch"] is KINDS["towed_block"].tables["patch"]   # one patch table


def test_a_command_that_needs_a_sweep_over_mat_angles_asks_the_kind():
    twist = load(SCENARIOS / "twist.toml")
    with pytest.raises(InputError, match=r"twist.toml: kind: expected a sweep scenario for uq, got 'twist'"):
        require_mat_angles(twist, "uq")
    require_mat_angles(load(SCENARIOS / "mat_aged.toml"), "uq")
    assert kind_of(twist) is KINDS["twist"] and not KINDS["step_study"].mat_angles


def test_the_fmu_is_the_scenarios_own_or_the_installed_one_of_its_kinds_model(tmp_path):
    twist, case1 = load(SCENARIOS / "twist.toml"), load(SCENARIOS / "case1.toml")
    assert fmu_for(twist, 3) == str(find_fmu(fmi_version=3, model="ContactPatch"))
    assert fmu_for(case1, 2) == str(find_fmu(fmi_version=2))
    own = scenario_variant(SCENARIOS / "case1.toml", 'kind = "sweep"',
                           f'kind = "sweep"\nfmu = "{find_fmu(fmi_version=3)}"', tmp_path / "own.toml")
    assert fmu_for(load(own), 2) == str(find_fmu(fmi_version=3))


def test_a_scenarios_fmu_of_another_model_than_its_kinds_is_refused(tmp_path):
    """A sweep naming the ContactPatch FMU (a patch kind naming the point
    FMU was refused before; every kind is now)."""
    patch = find_fmu(fmi_version=2, model="ContactPatch")
    bad = scenario_variant(SCENARIOS / "case1.toml", 'kind = "sweep"', f'kind = "sweep"\nfmu = "{patch}"',
                           tmp_path / "s.toml")
    with pytest.raises(ScenarioError, match="fmu: expected an OrthotropicContact FMU for a scenario of kind "
                                            "'sweep', got .*: ContactPatch"):
        load(bad)


def test_no_module_compares_a_scenario_kinds_name():
    """Which kind does what is the kind's row: `sc.kind == "sweep"` and
    the like are nowhere in the package."""
    found = [f"{p.relative_to(PKG)}:{n}" for p in PKG.rglob("*.py")
             for n, line in enumerate(p.read_text().splitlines(), 1)
             if re.search(r"\.kind\s*(==|!=|\bin\b|\bnot in\b)|kind not in PATCH|PATCH_KINDS", line)
             and "r.kind" not in line and "run.kind" not in line]   # a recording run's kind is no scenario's
    assert found == []
