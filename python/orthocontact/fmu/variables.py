"""The models and their variables as the build generated them from the
variable tables (fmu_src/models/*/table.h): models.json (CMake's list of
models, OC_MODELS) and variables/<model>.json (gen_model_description
manifest), installed with the package.  The package reads names, value
references, units, ranges, starts, the enumerations and the law's
parameters from here instead of typing them.

Units as the tables give them ("" for none); angles in rad."""
from __future__ import annotations

import json
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from .files import installed_file


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


def _read(rel: str) -> dict:
    path = installed_file(rel)
    if path is None:
        raise FileNotFoundError(f"{rel} (generated from the variable tables) is not installed with "
                                "the package; run `pip install .` from the repository")
    return json.loads(Path(path).read_text())


@cache
def models() -> dict[str, str]:
    """role ("contact", "rig") -> model identifier, in CMake's order."""
    return {m["role"]: m["modelIdentifier"] for m in _read("models.json")["models"]}


@cache
def manifest(model: str) -> Manifest:
    """The manifest of `model` (a model identifier of models())."""
    d = _read(f"variables/{model}.json")
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
