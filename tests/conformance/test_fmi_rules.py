"""The FMI conformance suite over every model: each model CMake's OC_MODELS
lists (orthocontact.fmu.variables.models()), FMI 2.0 and 3.0, keeps every
static rule of tests/conformance/fmi_rules.py (the standards' rules an XSD
cannot hold); and each rule, given a copy of a real description broken
where that rule looks, refuses it (and no rule but the ones the break
touches).  Nothing here names a model: a new one gets all of it by being
listed."""
from __future__ import annotations

import copy
import xml.etree.ElementTree as ET
import zipfile
from dataclasses import dataclass
from functools import cache
from typing import Callable

import pytest

from conformance.fmi_rules import RULES, violations
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.variables import models

VERSIONS = (2, 3)


@cache
def _xml(model: str, version: int) -> bytes:
    with zipfile.ZipFile(find_fmu(fmi_version=version, model=model)) as z:
        return z.read("modelDescription.xml")


def description(model: str, version: int) -> ET.Element:
    """A fresh copy of the installed FMU's model description, to break."""
    return ET.fromstring(_xml(model, version))


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("model", list(models().values()))
def test_every_model_description_keeps_every_rule(model, version):
    assert [str(v) for v in violations(description(model, version))] == []


# -- breaking a real description -------------------------------------------------------------------

def variables(root):
    return list(root.find("ModelVariables"))


def is_fmi3(root) -> bool:
    return root.get("fmiVersion").startswith("3")


def typed(root, el):
    """The element that holds start, min, max, unit (FMI 2.0: the type child)."""
    return el if is_fmi3(root) else el[0]


def ref(root, el) -> str:
    """How ModelStructure names el: its index (FMI 2.0), its value reference (FMI 3.0)."""
    return el.get("valueReference") if is_fmi3(root) else str(variables(root).index(el) + 1)


def structure(root, fmi2_list: str, fmi3_tag: str):
    path = f"ModelStructure/{fmi3_tag}" if is_fmi3(root) else f"ModelStructure/{fmi2_list}/Unknown"
    return root.findall(path)


def first(root, want: Callable) -> ET.Element | None:
    return next((el for el in variables(root) if want(el)), None)


def parameter(root):
    """The first parameter with a start, min and max."""
    return first(root, lambda el: el.get("causality") == "parameter" and
                 all(typed(root, el).get(k) is not None for k in ("start", "min", "max")))


def dimensioned(root):
    return first(root, lambda el: el.find("Dimension") is not None)


def _dimension_int32(root):
    """The state before the UInt64 fix: a dimension's structural parameter an Int32."""
    vr = dimensioned(root).find("Dimension").get("valueReference")
    first(root, lambda el: el.get("valueReference") == vr).tag = "Int32"


def _dimension_on_structural(root):
    first(root, lambda el: el.get("causality") == "structuralParameter").append(
        ET.Element("Dimension", start="2"))


def _parameter_continuous(root):
    parameter(root).set("variability", "continuous")


def _independent_initial(root):
    first(root, lambda el: el.get("causality") == "independent").set("initial", "exact")


def _input_initial(root):
    first(root, lambda el: el.get("causality") == "input").set("initial", "exact")


def _no_start(root):
    del typed(root, parameter(root)).attrib["start"]


def _start_above_max(root):
    t = typed(root, parameter(root))
    t.set("start", repr(float(t.get("max")) * 2 + 1) if "." in t.get("max") or "e" in t.get("max")
          else str(int(t.get("max")) + 1))


def _output_unlisted(root):
    el = structure(root, "Outputs", "Output")[0]
    (root.find("ModelStructure") if is_fmi3(root) else root.find("ModelStructure/Outputs")).remove(el)


def _initial_unknown_unlisted(root):
    el = structure(root, "InitialUnknowns", "InitialUnknown")[0]
    (root.find("ModelStructure") if is_fmi3(root) else root.find("ModelStructure/InitialUnknowns")).remove(el)


def _initial_unknowns_reordered(root):
    parent = root.find("ModelStructure/InitialUnknowns")
    a, b = list(parent)[:2]
    parent.remove(a)
    parent.insert(1, a)
    assert list(parent)[:2] == [b, a]


def _depends_on_an_output(root):
    """An output depending on an output: no known in either mode."""
    el = structure(root, "Outputs", "Output")[0]
    other = first(root, lambda v: v.get("causality") == "output")
    refs = el.get("dependencies").split() + [ref(root, other)]
    if not is_fmi3(root):
        refs.sort(key=int)   # FMI 2.0 wants them ascending: only the known is wrong here
    el.set("dependencies", " ".join(refs))
    el.set("dependenciesKind", " ".join(["dependent"] * len(refs)))


def _kinds_short(root):
    el = structure(root, "Outputs", "Output")[0]
    el.set("dependenciesKind", " ".join(el.get("dependenciesKind").split()[1:]))


def _unknown_unit(root):
    typed(root, first(root, lambda el: typed(root, el).get("unit") is not None)).set("unit", "furlong")


def _name_twice(root):
    a, b = variables(root)[:2]
    b.set("name", a.get("name"))


def _copy_of_a_parameter(root):
    """A second variable at a parameter's value reference, appended (indices keep)."""
    el = copy.deepcopy(parameter(root))
    el.set("name", el.get("name") + "Copy")
    root.find("ModelVariables").append(el)


def _no_value_reference(root):
    del parameter(root).attrib["valueReference"]


def _derivative_of_nothing(root):
    out = first(root, lambda el: el.get("causality") == "output" and
                (el.tag == "Float64" or (not is_fmi3(root) and el[0].tag == "Real")))
    typed(root, out).set("derivative", "9999")


def found(pick: Callable) -> Callable:
    """A break's `needs` from a picker of a variable (an Element is false when it has no children)."""
    return lambda root: pick(root) is not None


@dataclass(frozen=True)
class Break:
    rule: str                 # the rule that must refuse it
    versions: tuple
    change: Callable          # breaks a description in place
    needs: Callable = lambda root: True   # what a description must have to be broken so
    also: frozenset = frozenset()         # other rules the same change breaks, by the standard

    def __str__(self):
        return f"{self.rule}-{self.change.__name__.strip('_')}"


BREAKS = [
    Break("dimension", (3,), _dimension_int32, found(dimensioned)),
    Break("structural-parameter", (3,), _dimension_on_structural,
          found(lambda root: first(root, lambda el: el.get("causality") == "structuralParameter"))),
    Break("causality-variability", VERSIONS, _parameter_continuous, found(parameter)),
    Break("initial", VERSIONS, _independent_initial),
    Break("initial", (2,), _input_initial),
    Break("start", VERSIONS, _no_start, found(parameter)),
    Break("start-range", VERSIONS, _start_above_max, found(parameter)),
    Break("outputs", VERSIONS, _output_unlisted, lambda root: structure(root, "Outputs", "Output")),
    Break("initial-unknowns", VERSIONS, _initial_unknown_unlisted,
          lambda root: len(structure(root, "InitialUnknowns", "InitialUnknown")) > 0),
    Break("initial-unknowns", (2,), _initial_unknowns_reordered,
          lambda root: len(structure(root, "InitialUnknowns", "InitialUnknown")) > 1),
    Break("dependencies", VERSIONS, _depends_on_an_output,
          lambda root: len(structure(root, "Outputs", "Output")) > 0 and
          structure(root, "Outputs", "Output")[0].get("dependencies") is not None),
    Break("dependencies-kind", VERSIONS, _kinds_short,
          lambda root: len(structure(root, "Outputs", "Output")) > 0 and
          len((structure(root, "Outputs", "Output")[0].get("dependenciesKind") or "").split()) > 1),
    Break("units", VERSIONS, _unknown_unit),
    Break("unique-names", VERSIONS, _name_twice),
    Break("value-references", (3,), _copy_of_a_parameter, found(parameter)),
    Break("value-references", (2,), _no_value_reference, found(parameter)),
    Break("aliases", (2,), _copy_of_a_parameter, found(parameter)),
    Break("derivatives", VERSIONS, _derivative_of_nothing),
]


def breakable(b: Break, version: int) -> ET.Element:
    """A copy of the first model's description (in OC_MODELS' order) that
    has what the break needs."""
    for model in models().values():
        root = description(model, version)
        if b.needs(root):
            return root
    raise AssertionError(f"no model's FMI {version}.0 description has what {b} needs")


@pytest.mark.parametrize("b,version", [(b, v) for b in BREAKS for v in b.versions],
                         ids=lambda x: str(x))
def test_each_rule_refuses_a_description_broken_where_it_looks(b, version):
    root = breakable(b, version)
    assert violations(root) == []
    b.change(root)
    found = violations(ET.fromstring(ET.tostring(root)))   # as a file would hold it
    assert b.rule in {v.rule for v in found}, [str(v) for v in found]
    assert {v.rule for v in found} <= {b.rule} | b.also, [str(v) for v in found]


def test_every_rule_has_a_break():
    assert {b.rule for b in BREAKS} == set(RULES)
