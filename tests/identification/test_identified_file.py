"""identified.json (orthocontact.identification.identified_file): one writer
and one reader of a typed file with a schema version; identify's outputs hold
to identified.schema.json (validated by jsonschema, the reference
validator); what is not identify's output is one InputError naming the file
and the field."""
import hashlib
import json
import re
import shutil
from pathlib import Path

import jsonschema
import pytest

from cli_run import run_cli
from orthocontact.errors import InputError
from orthocontact.identification.identified import (
    SCHEMA_VERSION,
    DataRecord,
    Estimate,
    IdentifiedFile,
    NotIdentified,
)
from orthocontact.identification.identified_file import SCHEMA, check_data, read_identified, write_identified
from paths import ROOT, SCENARIOS


def schema_errors(d: dict) -> list:
    schema = json.loads(SCHEMA.read_text())
    jsonschema.Draft202012Validator.check_schema(schema)
    return [e.message for e in jsonschema.Draft202012Validator(schema).iter_errors(d)]


def test_the_schema_is_installed_with_the_package():
    import orthocontact
    assert SCHEMA.parent == Path(orthocontact.__file__).parent / "identification"
    assert json.loads(SCHEMA.read_text())["properties"]["schema_version"] == {
        "const": SCHEMA_VERSION, "description": "The version of this schema; a reader refuses another."}


def test_identifys_output_holds_to_the_schema_and_reads_back_as_written(identified):
    d = json.loads(identified.read_text())
    assert d["schema_version"] == SCHEMA_VERSION and schema_errors(d) == []
    f = read_identified(identified)
    assert isinstance(f, IdentifiedFile) and f.as_json() == d            # one writer, one reader
    assert isinstance(f.estimates["mu1"], Estimate) and f.value("mu1") == d["mu1"]["value"]
    assert f.covariance.parameters == ("mu1", "mu2", "eps_ratio", "eps2")
    assert f.provenance.folder.resolve() == (SCENARIOS / "example_identification").resolve()
    copy = identified.parent.parent / "rewritten.json"
    write_identified(copy, f)
    assert json.loads(copy.read_text()) == d


def test_raw_recordings_validated_and_with_the_fmu_hold_to_the_schema_too(tmp_path):
    """The optional parts: the reduction, F_int and the strip estimated, the
    joint covariance, the FMU's validation."""
    p = run_cli(["identify", SCENARIOS / "example_recordings", "--out", tmp_path / "id"], cwd=ROOT)
    assert p.returncode == 0, p.stderr
    d = json.loads((tmp_path / "id/identified.json").read_text())
    assert {"reduction", "covariance_joint", "c_strip", "f_int"} <= set(d) and d["validation_fmu"]
    assert schema_errors(d) == []
    f = read_identified(tmp_path / "id/identified.json")
    assert f.as_json() == d and f.reduction.scenario == "rig_scenario.toml"
    assert f.assumptions.c_strip_N_s_m == "estimated" and f.value("c_strip") == d["c_strip"]["value"]
    # what the schema refuses, the reader refuses: a hand-made reason-less estimate
    d["eps2"] = {"identifiable": False}
    assert schema_errors(d)
    (tmp_path / "bad.json").write_text(json.dumps(d))
    says = f"{tmp_path / 'bad.json'}: eps2.reason: expected a string"
    with pytest.raises(InputError, match=re.escape(says)):
        read_identified(tmp_path / "bad.json")


@pytest.mark.parametrize("version", [None, 0, 1, 3, "2", True])
def test_a_file_of_another_schema_version_is_one_line(identified, tmp_path, version):
    d = json.loads(identified.read_text())
    if version is None:
        d.pop("schema_version")
    else:
        d["schema_version"] = version
    path = tmp_path / "identified.json"
    path.write_text(json.dumps(d))
    with pytest.raises(InputError) as e:
        read_identified(path)
    assert str(e.value) == (f"{path}: schema_version: expected {SCHEMA_VERSION}, got {version!r} (a file of "
                            "another version of orthocontact: run `orthocontact identify` again)")


@pytest.mark.parametrize("content,says", [
    (None, "not found"),
    ("{'mu1': 1}", "expected JSON written by `orthocontact identify`"),
    ("[1, 2]", "expected a JSON object written by `orthocontact identify`"),
    ("", "expected JSON"),
])
def test_what_is_not_identifys_output_names_the_file(tmp_path, content, says):
    path = tmp_path / "identified.json"
    if content is not None:
        path.write_text(content)
    with pytest.raises(InputError) as e:
        read_identified(path)
    assert str(e.value).startswith(f"{path}: ") and says in str(e.value)
    assert "\n" not in str(e.value)


@pytest.mark.parametrize("edit,says", [
    (lambda d: d.pop("mu2"), "mu2: expected an object written by `orthocontact identify`, got None"),
    (lambda d: d["eps1"].update(value="12.6e3"), "eps1.value: expected a finite number > 0, got '12.6e3'"),
    (lambda d: d["eps1"].update(ci95=[2, 1]), "eps1.ci95: expected [low, high], low <= high, got [2, 1]"),
    (lambda d: d["assumptions"].update(mass_kg=0),
     "assumptions.mass_kg: expected a finite number > 0, got 0"),
    (lambda d: d["assumptions"].pop("rule"), "assumptions.rule: expected one of associated, coupled, eq20"),
    (lambda d: d["assumptions"].update(f_int_N="fitted"),
     "assumptions.f_int_N: expected a number >= 0 or \"estimated\", got 'fitted'"),
    (lambda d: d["assumptions"].update(c_strip_N_s_m="estimated"),
     "c_strip: expected its estimate (assumptions.c_strip_N_s_m is \"estimated\"), got None"),
    (lambda d: d["points"].update(angle_velocities=[0.244]),
     "points.angle_velocities: expected one velocity [m/s] per angle (34), got 1"),
    (lambda d: d["noise_estimate"].update(angles_deg=-0.1),
     "noise_estimate.angles_deg: expected a number >= 0"),
    (lambda d: d["covariance"]["values"].__setitem__(0, 0.0), "covariance.values: expected estimates > 0"),
    (lambda d: d["data"].update(forces="21"), "data.forces: expected an integer >= 0, got '21'"),
    (lambda d: d.update(validation_fmu=[]), "validation_fmu: expected an object or null, got []"),
])
def test_each_field_is_checked_with_one_line_naming_the_file_and_field(identified, tmp_path, edit, says):
    d = json.loads(identified.read_text())
    d["data"]["folder"] = str(SCENARIOS / "example_identification")
    edit(d)
    path = tmp_path / "identified.json"
    path.write_text(json.dumps(d))
    with pytest.raises(InputError) as e:
        read_identified(path)
    assert str(e.value) == f"{path}: {says}" or str(e.value).startswith(f"{path}: {says}"), str(e.value)
    assert "\n" not in str(e.value)


def test_the_data_are_checked_file_by_file(tmp_path):
    from orthocontact.identification.measurements import data_digest
    data = tmp_path / "id" / "data"
    data.mkdir(parents=True)
    (data / "rig.toml").write_text("mass_kg = 1.875\n")
    (data / "forces.csv").write_text("mat_angle_deg,force_N\n0,12.5\n")
    files = {n: hashlib.sha256((data / n).read_bytes()).hexdigest() for n in ("forces.csv", "rig.toml")}
    record = DataRecord(folder="data", absolute_folder="", forces=1, angles=0, ramp=0, files=files,
                        sha256=data_digest(files))
    path = tmp_path / "id" / "identified.json"
    got = check_data(path, record)         # data.folder found relative to the file's folder too
    assert got.folder == path.parent / "data" and got.files == files
    (data / "forces.csv").unlink()
    with pytest.raises(InputError) as e:
        check_data(path, record)
    assert str(e.value).startswith(f"{path}: data.files: 1 of the 2 files the identification read")
    assert "forces.csv (missing)" in str(e.value)


def test_a_value_that_cannot_be_right_is_refused_by_the_one_reader(identified, tmp_path):
    """Every reader of identified.json (export, uq) gets the plausibility
    gate: a hand-edited eps1 above the hard limit is refused, naming the
    override the caller gives; forced, it is read as it is."""
    d = json.loads(identified.read_text())
    d["data"]["folder"] = str(SCENARIOS / "example_identification")
    d["eps1"]["value"] = 1e13
    path = tmp_path / "identified.json"
    path.write_text(json.dumps(d))
    with pytest.raises(InputError) as e:
        read_identified(path, override="--force writes it anyway")
    assert str(e.value) == (f"{path}: eps1 = 1e+13 N/m: a contact's tangential stiffness is 10-1e9 N/m; "
                            "none above 1e+12 N/m can be right; refused (--force writes it anyway)")
    assert read_identified(path, force=True).value("eps1") == 1e13
    # what uq draws around (covariance.values) and the assumptions are judged too
    for edit, says in ((("covariance", "values"), "covariance.values: eps2 = 1e+13 N/m"),
                       (("assumptions", "mass_kg"), "assumptions.mass_kg = 1.875e+06 kg")):
        bad = json.loads(json.dumps(d))
        bad["eps1"]["value"] = 1.25e4
        if edit[0] == "covariance":
            bad["covariance"]["values"][3] = 1e13
        else:
            bad["assumptions"]["mass_kg"] = 1.875e6
        path.write_text(json.dumps(bad))
        with pytest.raises(InputError, match=re.escape(says)):
            read_identified(path)


def test_a_parameter_not_identified_is_typed_with_its_reason(identified, tmp_path):
    d = json.loads(identified.read_text())
    d["eps2"] = {"identifiable": False, "reason": "no ramp.csv"}
    folder = tmp_path / "id"
    shutil.copytree(SCENARIOS / "example_identification", folder / "data")
    d["data"].update(folder="data", absolute_folder="")
    (folder / "identified.json").write_text(json.dumps(d))
    f = read_identified(folder / "identified.json")
    assert f.estimates["eps2"] == NotIdentified("no ramp.csv") and f.value("eps2") is None
    assert f.provenance.folder == folder / "data" and f.as_json() == d
