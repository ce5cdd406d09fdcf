"""The models and their variables as generated from the variable tables
(fmu_src/models/*/table.h): fmu/tables.json, which tools/make_generated.py
writes beside fmu/generated.py from the manifests the build generates
(models.json: CMake's list of models, OC_MODELS; variables/<model>.json:
gen_model_description manifest).  The one way the tables reach Python:
the installed manifests are only held to it (tests/fmu/test_variables.py),
so a source checkout reads the same facts with or without an install.  The
package reads names, value references, units, ranges, starts, the
enumerations and the law's parameters from here instead of typing them.

Units as the tables give them ("" for none); angles in rad."""
from __future__ import annotations

import json
from dataclasses import dataclass
from functools import cache
from pathlib import Path

# tools/make_generated.py writes it: {"models": models.json's list, "variables": {model: manifest}}
TABLES = Path(__file__).with_name("tables.json")


@dataclass(frozen=True)
class Variable:
    """One row of a model's variable table."""
    name: str
    value_reference: int
    type: str                 # Float64, Int32 or Enumeration (the table's: Manifest.type gives each FMI's)
    declared_type: str | None  # the enumeration's type, e.g. SlidingRule
    causality: str
    variability: str
    unit: str
    start: float | int | None  # None: calculated or independent
    min: float | int | None    # None: unbounded
    max: float | int | None
    group: str                # "law" for the law's parameters, else ""
    description: str = ""     # the table's description (the model description's)


@dataclass(frozen=True)
class ArrayVariable:
    """An FMI 3.0 array output (FMI 2.0 has none), after the table's variables:
    its shape is the current values of `dimensions` (structural parameters),
    its elements depend on what the output `dependencies_of` depends on."""
    name: str
    value_reference: int
    type: str                 # Float64 or Int32
    unit: str
    dimensions: tuple[str, ...]
    dependencies_of: str
    description: str


@dataclass(frozen=True)
class Manifest:
    """A model's variables (in the table's order) and enumerations; in FMI
    3.0 also its structural parameters (parameters in FMI 2.0) and arrays."""
    model_identifier: str
    variables: tuple[Variable, ...]
    enumerations: dict[str, dict[str, int]]
    structural: tuple[str, ...] = ()
    arrays: tuple[ArrayVariable, ...] = ()
    structural_type: str = ""   # FMI 3.0's type of the structural parameters (UInt64)

    def causality(self, v: Variable, fmi_version: int) -> str:
        """v's causality in that FMI version's model description."""
        return "structuralParameter" if fmi_version == 3 and v.name in self.structural else v.causality

    def type(self, v: Variable, fmi_version: int) -> str:
        """v's type in that FMI version's model description as fmpy names it
        (Real, Integer in FMI 2.0; in FMI 3.0 the table's, but a structural
        parameter, an array's dimension, is the standard's UInt64)."""
        if fmi_version == 2:
            return "Real" if v.type == "Float64" else "Integer"
        return self.structural_type if v.name in self.structural else v.type

    def group(self, name: str) -> tuple[str, ...]:
        """The names of the variables of a group, in the table's order."""
        return tuple(v.name for v in self.variables if v.group == name)

    def value_references(self) -> dict[str, int]:
        return {v.name: v.value_reference for v in self.variables}

    def variable(self, name: str) -> Variable:
        for v in self.variables:
            if v.name == name:
                return v
        raise KeyError(f"{self.model_identifier} has no variable {name!r}")


@cache
def tables() -> dict:
    """fmu/tables.json: {"models": [{"role", "modelIdentifier", "table"}, ...]
    in CMake's order, "variables": {model identifier: its manifest}}."""
    return json.loads(TABLES.read_text())


@cache
def models() -> dict[str, str]:
    """role ("contact", "rig") -> model identifier, in CMake's order."""
    return {m["role"]: m["modelIdentifier"] for m in tables()["models"]}


@cache
def manifest(model: str) -> Manifest:
    """The manifest of `model` (a model identifier of models())."""
    found = tables()["variables"].get(model)
    if found is None:
        raise KeyError(f"no model {model!r} in the variable tables (models: {', '.join(models().values())})")
    return manifest_from(found)


def manifest_from(d: dict) -> Manifest:
    """A Manifest from a manifest's JSON (variables/<model>.json as the build writes it)."""
    rows = tuple(Variable(v["name"], v["valueReference"], v["type"], v["declaredType"], v["causality"],
                          v["variability"], v["unit"], v["start"], v["min"], v["max"], v["group"],
                          v.get("description", ""))
                 for v in d["variables"])
    fmi3 = d.get("fmi3", {})
    arrays = tuple(ArrayVariable(a["name"], a["valueReference"], a["type"], a["unit"],
                                 tuple(a["dimensions"]), a["dependenciesOf"], a["description"])
                   for a in fmi3.get("arrays", ()))
    return Manifest(d["modelIdentifier"], rows, d["enumerations"],
                    tuple(fmi3.get("structuralParameters", ())), arrays, fmi3.get("structuralType", ""))


def contact() -> Manifest:
    """The contact model's manifest."""
    return manifest(models()["contact"])


def law_parameters() -> tuple[str, ...]:
    """The law's parameters in the table's order (mu1, mu2, ... as ContactParams names them)."""
    return contact().group("law")
