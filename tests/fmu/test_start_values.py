"""A copy of the FMUs with new start values (orthocontact.fmu.start_values):
the FMU itself runs with them when the importer sets nothing, the model
description states them, the FMI schemas accept it, nothing else changes,
and a value the FMU would refuse is refused before anything is written."""
import zipfile

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from fmu_values import schema_errors, values_with_nothing_set
from orthocontact.fmu.files import MODEL_IDENTIFIER, RIG_MODEL_IDENTIFIER, find_fmu
from orthocontact.fmu.start_values import StartValueError, start_values_of, write_with_start_values

NEW = {"mu1": 0.3711, "mu2": 0.5873, "eps1": 13377.25, "eps2": 9123.5, "alpha": -0.4,
       "beta": 0.1, "slidingRule": 1}
NEW_RIG = {"mass": 2.5, "velocity": 0.1, "muStrip": 0.2, "cStrip": 3.0}


@pytest.mark.parametrize("model,new", [(MODEL_IDENTIFIER, NEW), (RIG_MODEL_IDENTIFIER, NEW_RIG)])
@pytest.mark.parametrize("fmi_version", [2, 3])
def test_the_copy_runs_with_its_new_start_values_when_nothing_is_set(tmp_path, fmi_version, model, new):
    src = find_fmu(fmi_version=fmi_version, model=model)
    before = values_with_nothing_set(src, new)
    assert all(before[n] != v for n, v in new.items())   # the change is visible
    dst = write_with_start_values(src, tmp_path / f"{model}.fmu", new,
                                  documentation={"calibration.md": "# calibrated\n"},
                                  description_note="Calibrated for the test.")
    assert values_with_nothing_set(dst, new) == new      # exactly: hex floats in the resources
    stated = start_values_of(dst)
    assert {n: stated[n] for n in new} == new
    assert validate_fmu(str(dst)) == [] and schema_errors(dst) == []
    md = read_model_description(str(dst))
    assert md.description.endswith("Calibrated for the test.")
    old, copy = zipfile.ZipFile(src), zipfile.ZipFile(dst)
    changed = {"modelDescription.xml", "resources/start_values.txt", "documentation/calibration.md"}
    assert set(copy.namelist()) - set(old.namelist()) <= changed
    for name in old.namelist():                          # binaries, sources, licenses as they were
        if name not in changed:
            assert copy.read(name) == old.read(name), name
    assert copy.read("documentation/calibration.md") == b"# calibrated\n"
    # the other parameters keep theirs, in the description and in the binary
    others = {n: v for n, v in start_values_of(src).items() if n not in new}
    assert {n: stated[n] for n in others} == others
    assert values_with_nothing_set(dst, others) == others


def test_a_second_rewrite_keeps_the_first_values(tmp_path):
    src = find_fmu(fmi_version=2)
    once = write_with_start_values(src, tmp_path / "once.fmu", {"mu1": 0.3})
    twice = write_with_start_values(once, tmp_path / "twice.fmu", {"mu2": 0.7})
    assert values_with_nothing_set(twice, ["mu1", "mu2"]) == {"mu1": 0.3, "mu2": 0.7}


@pytest.mark.parametrize("values,says", [
    ({"mu1": -0.1}, "mu1 = -0.1 is outside [1e-150, 1e+150]"),
    ({"alpha": 20.0}, "alpha = 20.0 is outside [-12.5664, 12.5664]"),
    ({"slidingRule": 4}, "slidingRule = 4 is outside [1, 3]"),
    ({"slidingRule": 1.5}, "slidingRule = 1.5: expected an integer"),
    ({"eps1": float("nan")}, "eps1 = nan: expected a finite number"),
    ({"u1": 1.0}, "u1 is not a parameter"),
    ({"nope": 1.0}, "nope is not a parameter"),
])
@pytest.mark.parametrize("fmi_version", [2, 3])
def test_a_value_the_fmu_would_refuse_is_refused_and_nothing_written(tmp_path, fmi_version, values, says):
    dst = tmp_path / "x.fmu"
    with pytest.raises(StartValueError, match=None) as e:
        write_with_start_values(find_fmu(fmi_version=fmi_version), dst, {"mu2": 0.5, **values})
    assert says in str(e.value) and "\n" not in str(e.value)
    assert "OrthotropicContact.fmu" in str(e.value)
    assert list(tmp_path.iterdir()) == []
