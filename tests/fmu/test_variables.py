"""The generated manifests (orthocontact.fmu.variables) against the FMUs'
own model descriptions, read by fmpy (ranges from the XML itself: fmpy
0.3.32 reads no min/max of an FMI 3.0 UInt64): the package's facts are the
tables'.  The package reads them from fmu/tables.json alone; the manifests
the build installs are held to it here."""
import dataclasses
import json
import xml.etree.ElementTree as ET
import zipfile

import pytest
from fmpy import read_model_description

from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.params import RULES, ContactParams
from orthocontact.fmu.variables import contact, law_parameters, manifest, models, tables


def _number(text):
    return None if text is None else float(text)


def _ranges(path):
    """{name: (min, max)} as the model description's XML writes them (text or None)."""
    with zipfile.ZipFile(path) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    out = {}
    for v in root.find("ModelVariables"):
        typed = v[0] if v.tag == "ScalarVariable" else v   # FMI 2.0 keeps them on the type element
        out[v.get("name")] = (typed.get("min"), typed.get("max"))
    return out


@pytest.mark.parametrize("fmi_version", [2, 3])
@pytest.mark.parametrize("role", list(models()))
def test_manifest_is_the_model_description(role, fmi_version):
    model = models()[role]
    md = read_model_description(str(find_fmu(fmi_version=fmi_version, model=model)))
    ranges = _ranges(find_fmu(fmi_version=fmi_version, model=model))
    assert md.coSimulation.modelIdentifier == model
    m = manifest(model)
    arrays = m.arrays if fmi_version == 3 else ()   # FMI 2.0 has no arrays
    assert [v.name for v in m.variables] + [a.name for a in arrays] == [v.name for v in md.modelVariables]
    for a, theirs in zip(arrays, md.modelVariables[len(m.variables):]):
        assert (a.value_reference, a.type, a.unit) == (theirs.valueReference, theirs.type, theirs.unit or "")
        assert [d.variable.name for d in theirs.dimensions] == list(a.dimensions) != []
        assert set(a.dimensions) <= set(m.structural)
    for ours, theirs in zip(m.variables, md.modelVariables):
        assert ours.value_reference == theirs.valueReference, ours.name
        assert m.causality(ours, fmi_version) == theirs.causality, ours.name
        assert ours.variability == theirs.variability, ours.name
        assert ours.unit == (theirs.unit or ""), ours.name
        if ours.start is not None or theirs.start is not None:
            assert float(ours.start) == float(theirs.start), ours.name
        assert (_number(ours.min), _number(ours.max)) == tuple(map(_number, ranges[ours.name])), ours.name
        assert m.type(ours, fmi_version) == theirs.type, ours.name   # FMI 3.0: n1, n2 UInt64
        if fmi_version == 3:
            assert ours.declared_type == (theirs.declaredType.name if theirs.declaredType else None)


def test_enumerations_are_the_fmi3_type_definitions():
    md = read_model_description(str(find_fmu(fmi_version=3)))
    theirs = {t.name: {i.name: int(i.value) for i in t.items} for t in md.typeDefinitions}
    assert contact().enumerations == theirs
    assert RULES == theirs["SlidingRule"] == {"associated": 1, "coupled": 2, "eq20": 3}


def test_the_typed_parameters_follow_the_tables_law_group():
    assert law_parameters() == ("mu1", "mu2", "eps1", "eps2", "alpha", "beta")
    fields = [f.name for f in dataclasses.fields(ContactParams)]
    assert fields == [*law_parameters(), "rule"]


def test_the_installed_manifests_are_the_generated_tables():
    """One channel: what the build installed (models.json, variables/<model>.json)
    is tables.json, value for value; a table changed without `make generated`
    fails here (and in tests/fmu/test_generated.py, naming the command)."""
    from orthocontact.fmu.files import installed_file
    listed = json.loads(installed_file("models.json").read_text())["models"]
    assert listed == tables()["models"]
    for m in listed:
        model = m["modelIdentifier"]
        installed = json.loads(installed_file(f"variables/{model}.json").read_text())
        assert installed == tables()["variables"][model], model


def test_an_unknown_model_is_one_clear_error_naming_the_models_there_are():
    with pytest.raises(KeyError, match=r"no model .Nope. in the variable tables \(models: Orthotropic"):
        manifest("Nope")
