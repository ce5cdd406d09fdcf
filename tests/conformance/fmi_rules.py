"""The static rules of FMI 2.0 and FMI 3.0 that the standards' XML schemas
cannot hold, written from the standards' text, as an independent reference
for the tests: it shares no code with the FMUs' generator
(fmu_src/glue/gen_model_description.c) nor with fmpy, and reads the model
description with xml.etree itself, so that it sees what fmpy's reader drops
(fmpy 0.3.32 keeps no min/max of an FMI 3.0 UInt64, and its validate_fmu
checks no Dimension, no start against min/max, no dependency against the
knowns).

Sources, by rule (RULES): FMI 2.0.5, section 2.2 (modelica/fmi-standard,
docs/2_2_common_schema.adoc: ModelVariables 2.2.7, ModelStructure 2.2.8);
FMI 3.0.2, section 2.4 (docs/2_4_common_schema.adoc: 2.4.7 Model Variables
with its tables of allowed causality x variability and of initial,
2.4.8 Model Structure).  Cross-read with VDMCheck (INTO-CPS's VDM-SL model
of the rules: fmi2/rule-model/Rules/ModelVariables.adoc, FmiModelDescription.adoc)
and fmpy.validation.validate_model_description.

    violations(xml) -> [Violation(rule, where, why)]   every one found, none: []
    violations_of_fmu(path)                               the same, of an FMU file

Only Co-Simulation's and Model Exchange's common rules; no clocks, no
terminals, no build description."""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
import zipfile
from dataclasses import dataclass, field

RULES = {
    "dimension": "FMI 3.0 2.4.7.2: a Dimension has start or valueReference, not both; the variable "
                 "it references is a UInt64 constant or structural parameter; every initial size > 0",
    "structural-parameter": "FMI 3.0 2.4.7.3: a structural parameter is fixed or tunable, initial exact, "
                            "has a start, has no Dimension",
    "causality-variability": "FMI 2.0 2.2.7 / FMI 3.0 2.4.7.4: the allowed combinations of causality "
                             "and variability; continuous only for Real / Float; one Real / Float "
                             "independent variable",
    "initial": "FMI 2.0 2.2.7 / FMI 3.0 2.4.7.5: the values of initial each causality x variability "
               "allows (FMI 2.0: none for input and independent)",
    "start": "FMI 2.0 2.2.7 / FMI 3.0 2.4.7.5: a start for initial exact or approx, for inputs and "
             "parameters (FMI 3.0: and constants, structural parameters); none for calculated or "
             "independent",
    "start-range": "FMI 2.0 / 3.0 schemas' annotations: min <= start <= max, min <= max, each within "
                   "its type",
    "outputs": "FMI 2.0 2.2.8 / FMI 3.0 2.4.8: ModelStructure lists every output once in Outputs "
               "(Output) and nothing else",
    "initial-unknowns": "FMI 2.0 2.2.8 / FMI 3.0 2.4.8: InitialUnknowns are exactly the outputs with "
                        "initial approx or calculated, the calculated parameters and the states and "
                        "state derivatives with initial approx or calculated, once each (FMI 2.0: "
                        "ordered by index)",
    "dependencies": "FMI 2.0 2.2.8 / FMI 3.0 2.4.8: dependencies name only knowns of the mode "
                    "(step: inputs, states, the independent variable; FMI 3.0 also parameters; "
                    "initialization: inputs, initial exact, the independent variable), each once "
                    "(FMI 2.0: ascending)",
    "dependencies-kind": "FMI 2.0 2.2.8 / FMI 3.0 2.4.8: dependenciesKind only with dependencies of "
                         "the same length; constant only for a Real / Float unknown, fixed, tunable "
                         "and discrete only for one outside initialization",
    "units": "FMI 2.0 2.2.2 / FMI 3.0 2.4.3: a unit a variable (or type) uses is a UnitDefinitions "
             "Unit; a displayUnit needs a unit and is one of its DisplayUnits",
    "unique-names": "FMI 2.0 2.2.7 / FMI 3.0 2.4.7: every variable's name (FMI 3.0: and alias's) is "
                    "unique",
    "value-references": "FMI 3.0 2.4.7: valueReference unique over all variables; FMI 2.0 2.2.7: "
                        "unique within a base type but for alias variables",
    "aliases": "FMI 2.0 2.2.7: an alias set (same base type and valueReference) has at most one "
               "settable variable and none with the independent one, at most one non-constant "
               "start, constants only among constants with one start, one unit",
    "derivatives": "FMI 2.0 2.2.7-8 / FMI 3.0 2.4.7-8: derivative names another existing Real / Float "
                   "variable; each state derivative of ModelStructure has the attribute",
}

FLOATS = {"Real", "Float32", "Float64"}
# FMI 3.0's integer types and their ranges (section 2.4.1); FMI 2.0's Integer is 32 bits
INT_RANGES = {"Int8": (-2**7, 2**7 - 1), "UInt8": (0, 2**8 - 1), "Int16": (-2**15, 2**15 - 1),
              "UInt16": (0, 2**16 - 1), "Int32": (-2**31, 2**31 - 1), "UInt32": (0, 2**32 - 1),
              "Int64": (-2**63, 2**63 - 1), "UInt64": (0, 2**64 - 1), "Integer": (-2**31, 2**31 - 1)}
BASE_TYPE = {"Real": "Real", "Integer": "Integer", "Enumeration": "Integer", "Boolean": "Boolean",
             "String": "String"}   # FMI 2.0: Integer and Enumeration share fmi2Integer
ALLOWED = {   # causality x variability (both standards; structuralParameter FMI 3.0 only)
    "constant": {"output", "local"},
    "fixed": {"parameter", "calculatedParameter", "local", "structuralParameter"},
    "tunable": {"parameter", "calculatedParameter", "local", "structuralParameter"},
    "discrete": {"input", "output", "local"},
    "continuous": {"input", "output", "local", "independent"},
}
KINDS = {"dependent", "constant", "fixed", "tunable", "discrete"}


@dataclass(frozen=True)
class Violation:
    rule: str    # a key of RULES
    where: str   # the variable or element
    why: str

    def __str__(self):
        return f"{self.rule}: {self.where}: {self.why}"


@dataclass
class Var:
    """A variable as its XML states it, with the standard's defaults filled in."""
    index: int              # 1-based, in the order of ModelVariables (FMI 2.0's ScalarVariable index)
    name: str
    vr: int
    type: str               # Real, Integer, ..., Float64, UInt64, ...
    causality: str
    variability: str
    initial: str | None     # as written, None if absent
    effective_initial: str | None
    start: str | None
    min: str | None
    max: str | None
    unit: str | None
    display_unit: str | None
    derivative: str | None
    clocked: bool           # a Clock, or a variable with the clocks attribute (FMI 3.0)
    dimensions: list = field(default_factory=list)   # the Dimension elements' attributes
    aliases: list = field(default_factory=list)      # FMI 3.0 Alias elements' attributes


def default_initial(causality: str, variability: str, fmi3: bool) -> str | None:
    """The tables' default of initial (FMI 2.0 2.2.7, FMI 3.0 2.4.7.5)."""
    if causality in ("independent",) or (causality == "input" and not fmi3):
        return None
    if variability == "constant":
        return "exact" if causality in ("output", "local") else None
    if causality in ("parameter", "structuralParameter"):
        return "exact"
    if causality == "input":
        return "exact"
    return "calculated"


def allowed_initials(causality: str, variability: str, fmi3: bool) -> set:
    """The values initial may take (empty: it must be absent)."""
    if causality == "independent" or (causality == "input" and not fmi3):
        return set()
    if variability == "constant":
        return {"exact"} if causality in ("output", "local") else set()
    if causality in ("parameter", "structuralParameter"):
        return {"exact"}
    if causality == "calculatedParameter" or (causality == "local" and variability in ("fixed", "tunable")):
        return {"calculated", "approx"}
    if causality == "input":
        return {"exact"}
    return {"calculated", "exact", "approx"}


def _number(text, integer: bool):
    try:
        return int(text) if integer else float(text)
    except (TypeError, ValueError):
        return None


class Description:
    """A model description read for the rules."""

    def __init__(self, root: ET.Element):
        self.root = root
        self.fmi3 = root.get("fmiVersion", "").startswith("3")
        self.units = {u.get("name"): {d.get("name") for d in u.findall("DisplayUnit")}
                      for u in root.findall("UnitDefinitions/Unit")}
        self.types = {}   # declared type name -> its defaults (unit, displayUnit, min, max)
        for t in root.findall("TypeDefinitions/*"):
            el = t[0] if not self.fmi3 and len(t) else t   # FMI 2.0: SimpleType/<Real ...>
            self.types[t.get("name")] = {k: el.get(k) for k in ("unit", "displayUnit", "min", "max")}
        variables = root.find("ModelVariables")
        self.vars = [self._var(i + 1, el) for i, el in enumerate(variables if variables is not None else [])]
        self.by_vr = {}
        for v in self.vars:
            self.by_vr.setdefault(v.vr, v)

    def _var(self, index: int, el: ET.Element) -> Var:
        if self.fmi3:
            typed, kind = el, el.tag
        else:
            typed = el[0] if len(el) else ET.Element("missing")
            kind = typed.tag
        causality = el.get("causality", "local")
        if self.fmi3:
            parameters = ("parameter", "structuralParameter", "calculatedParameter")
            default_var = "fixed" if causality in parameters else "continuous" if kind in FLOATS \
                else "discrete"
        else:
            default_var = "continuous"
        variability = el.get("variability", default_var)
        declared = self.types.get(typed.get("declaredType"), {})

        def attr(k):
            return typed.get(k, declared.get(k))
        initial = el.get("initial")
        start = typed.get("start")
        if start is None and typed.findall("Start"):   # FMI 3.0 String, Binary: <Start value=.../>
            start = " ".join(st.get("value", "") for st in typed.findall("Start"))
        return Var(index, el.get("name", ""), _number(el.get("valueReference"), True), kind, causality,
                   variability, initial,
                   initial or default_initial(causality, variability, self.fmi3),
                   start, attr("min"), attr("max"), attr("unit"), attr("displayUnit"),
                   typed.get("derivative"), kind == "Clock" or el.get("clocks") is not None,
                   [dict(d.attrib) for d in el.findall("Dimension")],
                   [dict(a.attrib) for a in el.findall("Alias")])

    def ref(self, text) -> Var | None:
        """The variable an index (FMI 2.0) or value reference (FMI 3.0) names."""
        k = _number(text, True)
        if k is None:
            return None
        if self.fmi3:
            return self.by_vr.get(k)
        return self.vars[k - 1] if 1 <= k <= len(self.vars) else None

    def structure(self, fmi2_list: str, fmi3_tag: str) -> list:
        """The elements of a ModelStructure list."""
        if self.fmi3:
            return self.root.findall(f"ModelStructure/{fmi3_tag}")
        return self.root.findall(f"ModelStructure/{fmi2_list}/Unknown")

    def unknown(self, el: ET.Element) -> Var | None:
        return self.ref(el.get("valueReference" if self.fmi3 else "index"))

    def states(self) -> set:
        """The continuous-time states: what the derivatives of ModelStructure are derivatives of."""
        out = set()
        for el in self.structure("Derivatives", "ContinuousStateDerivative"):
            d = self.unknown(el)
            if d is not None and d.derivative is not None and self.ref(d.derivative) is not None:
                out.add(self.ref(d.derivative).name)
        return out


def violations(xml) -> list[Violation]:
    """Every violation of the rules by a model description (bytes, text or an Element)."""
    root = xml if isinstance(xml, ET.Element) else ET.fromstring(xml)
    md = Description(root)
    found: list[Violation] = []

    def bad(rule, where, why):
        found.append(Violation(rule, where, why))

    for check in CHECKS:
        check(md, bad)
    return found


def violations_of_fmu(path) -> list[Violation]:
    with zipfile.ZipFile(path) as z:
        return violations(z.read("modelDescription.xml"))


# -- the rules ------------------------------------------------------------------------------------

def check_dimensions(md: Description, bad):
    if not md.fmi3:
        return
    for v in md.vars:
        for d in v.dimensions:
            if ("start" in d) == ("valueReference" in d):
                bad("dimension", v.name, "a Dimension needs exactly one of start and valueReference")
            elif "start" in d:
                if not (_number(d["start"], True) or 0) > 0:
                    bad("dimension", v.name, f"Dimension start={d['start']!r} is not a size > 0")
            else:
                r = md.ref(d["valueReference"])
                if r is None:
                    bad("dimension", v.name,
                        f"Dimension valueReference={d['valueReference']} names no variable")
                    continue
                if r.type != "UInt64":
                    bad("dimension", v.name, f"its dimension {r.name} is {r.type}, not UInt64")
                if not (r.variability == "constant" or r.causality == "structuralParameter"):
                    bad("dimension", v.name, f"its dimension {r.name} is neither a constant nor a "
                                             "structural parameter")
                if not (_number(r.start, True) or 0) > 0:
                    bad("dimension", v.name, f"its dimension {r.name} has start={r.start!r}, not > 0")


def check_structural_parameters(md: Description, bad):
    for v in md.vars:
        if v.causality != "structuralParameter":
            continue
        if not md.fmi3:
            bad("structural-parameter", v.name, "FMI 2.0 has no structural parameters")
            continue
        if v.variability not in ("fixed", "tunable"):
            bad("structural-parameter", v.name, f"variability {v.variability}, not fixed or tunable")
        if v.effective_initial != "exact":
            bad("structural-parameter", v.name, f"initial {v.effective_initial}, not exact")
        if v.start is None:
            bad("structural-parameter", v.name, "no start")
        if v.dimensions:
            bad("structural-parameter", v.name, "a structural parameter must not have a Dimension")


def check_causality_variability(md: Description, bad):
    independents = [v for v in md.vars if v.causality == "independent"]
    if len(independents) > 1 or (md.fmi3 and not independents):
        bad("causality-variability", "ModelVariables",
            f"{len(independents)} independent variables: {'exactly' if md.fmi3 else 'at most'} one")
    for v in md.vars:
        if v.variability not in ALLOWED or v.causality not in ALLOWED[v.variability] or \
                (v.causality == "structuralParameter" and not md.fmi3):
            bad("causality-variability", v.name, f"causality {v.causality} with variability {v.variability}")
        if v.variability == "continuous" and v.type not in FLOATS:
            bad("causality-variability", v.name, f"a {v.type} cannot be continuous")
        if v.causality == "independent" and v.type not in FLOATS:
            bad("causality-variability", v.name, f"the independent variable is {v.type}, not Real / Float")


def check_initial(md: Description, bad):
    for v in md.vars:
        if v.initial is not None and v.initial not in allowed_initials(v.causality, v.variability, md.fmi3):
            bad("initial", v.name, f"initial {v.initial} with causality {v.causality}, "
                                   f"variability {v.variability}")


def check_start(md: Description, bad):
    for v in md.vars:
        needs = v.effective_initial in ("exact", "approx") or v.causality in ("input", "parameter") or \
            (md.fmi3 and (v.variability == "constant" or v.causality == "structuralParameter"))
        forbidden = v.effective_initial == "calculated" or v.causality == "independent"
        if forbidden and v.start is not None:
            bad("start", v.name, f"start={v.start!r} where initial is {v.effective_initial} "
                                 f"(causality {v.causality})")
        elif needs and not forbidden and v.start is None and v.type != "Clock":
            bad("start", v.name, f"no start (causality {v.causality}, initial {v.effective_initial})")


def check_start_range(md: Description, bad):
    for v in md.vars:
        if v.type not in FLOATS and v.type not in INT_RANGES and v.type != "Enumeration":
            continue
        integer = v.type not in FLOATS
        lo, hi = _number(v.min, integer), _number(v.max, integer)
        starts = [_number(s, integer) for s in (v.start.split() if v.start else [])]
        for name, text, x in (("min", v.min, lo), ("max", v.max, hi)):
            if text is not None and x is None:
                bad("start-range", v.name, f"{name}={text!r} is not a {v.type}")
        if v.type in INT_RANGES:
            t_lo, t_hi = INT_RANGES[v.type]
            for name, x in (("min", lo), ("max", hi), *(("start", s) for s in starts)):
                if x is not None and not t_lo <= x <= t_hi:
                    bad("start-range", v.name, f"{name} {x} outside the {v.type} range")
        if lo is not None and hi is not None and lo > hi:
            bad("start-range", v.name, f"min {lo} > max {hi}")
        for s in starts:
            if s is None or (isinstance(s, float) and math.isnan(s)):
                bad("start-range", v.name, f"start={v.start!r} is not a {v.type}")
            elif (lo is not None and s < lo) or (hi is not None and s > hi):
                bad("start-range", v.name, f"start {s} outside [{v.min}, {v.max}]")


def check_outputs(md: Description, bad):
    listed = [md.unknown(el) for el in md.structure("Outputs", "Output")]
    if None in listed:
        bad("outputs", "ModelStructure", "an Output names no variable")
    names = [v.name for v in listed if v is not None]
    for v in listed:
        if v is not None and v.causality != "output":
            bad("outputs", v.name, f"listed as an Output with causality {v.causality}")
    for name in sorted({n for n in names if names.count(n) > 1}):
        bad("outputs", name, "listed more than once")
    for v in md.vars:
        if v.causality == "output" and v.name not in names:
            bad("outputs", v.name, "an output missing from the ModelStructure's Outputs")


def check_initial_unknowns(md: Description, bad):
    states = md.states()
    derivatives = {md.unknown(el).name for el in md.structure("Derivatives", "ContinuousStateDerivative")
                   if md.unknown(el) is not None}
    required = {v.name for v in md.vars
                if (v.causality == "output" and v.effective_initial in ("approx", "calculated")
                    and not v.clocked)
                or v.causality == "calculatedParameter"
                or ((v.name in states or v.name in derivatives)
                    and v.effective_initial in ("approx", "calculated"))}
    listed = [md.unknown(el) for el in md.structure("InitialUnknowns", "InitialUnknown")]
    if None in listed:
        bad("initial-unknowns", "ModelStructure", "an InitialUnknown names no variable")
    listed = [v for v in listed if v is not None]
    names = [v.name for v in listed]
    for name in sorted(required - set(names)):
        bad("initial-unknowns", name, "required in InitialUnknowns, missing")
    clocked = {v.name for v in md.vars if v.clocked}   # FMI 3.0: those it wishes to initialize
    for name in sorted(set(names) - required - clocked):
        bad("initial-unknowns", name, "in InitialUnknowns, not an unknown of initialization")
    for name in sorted({n for n in names if names.count(n) > 1}):
        bad("initial-unknowns", name, "listed more than once")
    if not md.fmi3 and [v.index for v in listed] != sorted(v.index for v in listed):
        bad("initial-unknowns", "ModelStructure", "InitialUnknowns not ordered by index")


def _known(md: Description, v: Var, init: bool, states: set) -> bool:
    if v.causality in ("input", "independent"):
        return True
    if init:
        return v.effective_initial == "exact"
    return v.name in states or (md.fmi3 and v.causality == "parameter")


def check_dependencies(md: Description, bad):
    states = md.states()
    lists = [("Outputs", "Output", False), ("Derivatives", "ContinuousStateDerivative", False),
             ("InitialUnknowns", "InitialUnknown", True)]
    for fmi2_list, fmi3_tag, init in lists:
        for el in md.structure(fmi2_list, fmi3_tag):
            unknown = md.unknown(el)
            where = f"{fmi3_tag if md.fmi3 else fmi2_list} {unknown.name if unknown else '?'}"
            deps, kinds = el.get("dependencies"), el.get("dependenciesKind")
            if kinds is not None:
                kind_list = kinds.split()
                if deps is None or len(deps.split()) != len(kind_list):
                    bad("dependencies-kind", where,
                        "dependenciesKind without dependencies of the same length")
                for k in kind_list:
                    if k not in KINDS:
                        bad("dependencies-kind", where, f"kind {k!r} unknown")
                    elif k != "dependent" and (unknown is None or unknown.type not in FLOATS):
                        bad("dependencies-kind", where, f"kind {k} for a non-Real / Float unknown")
                    elif k in ("fixed", "tunable", "discrete") and init:
                        bad("dependencies-kind", where, f"kind {k} in initialization")
            if deps is None:
                continue
            refs = deps.split()
            named = [md.ref(r) for r in refs]
            for r, v in zip(refs, named):
                if v is None:
                    bad("dependencies", where, f"dependency {r} names no variable")
                elif not _known(md, v, init, states):
                    mode = "of initialization" if init else "at a communication point"
                    bad("dependencies", where, f"depends on {v.name} (causality {v.causality}, initial "
                                               f"{v.effective_initial}), not a known {mode}")
            if len(set(refs)) != len(refs):
                bad("dependencies", where, "a dependency listed twice")
            indices = [int(r) for r in refs if r.isdigit()]
            if not md.fmi3 and indices != sorted(indices):
                bad("dependencies", where, "dependencies not in ascending order")


def check_units(md: Description, bad):
    for name, t in md.types.items():
        if t["unit"] is not None and t["unit"] not in md.units:
            bad("units", f"type {name}", f"unit {t['unit']!r} is not in UnitDefinitions")
    for v in md.vars:
        if v.unit is not None and v.unit not in md.units:
            bad("units", v.name, f"unit {v.unit!r} is not in UnitDefinitions")
        for who, du in [(v.name, v.display_unit)] + [(f"alias {a.get('name')}", a.get("displayUnit"))
                                                     for a in v.aliases]:
            if du is None:
                continue
            if v.unit is None:
                bad("units", who, f"displayUnit {du!r} without a unit")
            elif du not in md.units.get(v.unit, set()):
                bad("units", who, f"displayUnit {du!r} is not a DisplayUnit of {v.unit!r}")


def check_unique_names(md: Description, bad):
    names = [v.name for v in md.vars] + [a.get("name") for v in md.vars for a in v.aliases]
    for name in sorted({n for n in names if names.count(n) > 1}):
        bad("unique-names", name, f"the name is used {names.count(name)} times")
    for v in md.vars:
        if not v.name:
            bad("unique-names", f"variable {v.index}", "an empty name")


def check_value_references(md: Description, bad):
    for v in md.vars:
        if v.vr is None:
            bad("value-references", v.name, "no valueReference")
    if md.fmi3:
        seen = {}
        for v in md.vars:
            if v.vr is not None and v.vr in seen:
                bad("value-references", v.name, f"valueReference {v.vr} is also {seen[v.vr]}'s")
            seen.setdefault(v.vr, v.name)


def check_aliases(md: Description, bad):
    if md.fmi3:
        return
    sets = {}
    for v in md.vars:
        sets.setdefault((BASE_TYPE.get(v.type, v.type), v.vr), []).append(v)
    for (base, vr), group in sets.items():
        if len(group) < 2:
            continue
        where = f"{base} valueReference {vr} ({', '.join(v.name for v in group)})"
        settable = [v for v in group if v.variability != "constant" and
                    (v.causality in ("input", "parameter") or v.effective_initial in ("exact", "approx"))]
        if len(settable) > 1:
            bad("aliases", where, f"{len(settable)} settable variables alias each other")
        if settable and any(v.causality == "independent" for v in group):
            bad("aliases", where, "a settable variable aliases the independent variable")
        if sum(v.start is not None for v in group if v.variability != "constant") > 1:
            bad("aliases", where, "more than one non-constant alias has a start")
        constants = [v for v in group if v.variability == "constant"]
        if constants and len(constants) != len(group):
            bad("aliases", where, "a constant aliases a non-constant")
        if len({v.start for v in constants}) > 1:
            bad("aliases", where, "constant aliases with different starts")
        if base == "Real" and len({v.unit for v in group}) > 1:
            bad("aliases", where, "aliases with different units")


def check_derivatives(md: Description, bad):
    for v in md.vars:
        if v.derivative is None:
            continue
        target = md.ref(v.derivative)
        if v.type not in FLOATS:
            bad("derivatives", v.name, f"a {v.type} with a derivative attribute")
        if target is None:
            bad("derivatives", v.name, f"derivative={v.derivative} names no variable")
        elif target is v:
            bad("derivatives", v.name, "the derivative of itself")
        elif target.type not in FLOATS:
            bad("derivatives", v.name, f"the derivative of {target.name}, a {target.type}")
    for el in md.structure("Derivatives", "ContinuousStateDerivative"):
        d = md.unknown(el)
        if d is None or d.derivative is None:
            bad("derivatives", "ModelStructure", f"a state derivative {d.name if d else '?'} without the "
                                                 "derivative attribute")


CHECKS = (check_dimensions, check_structural_parameters, check_causality_variability, check_initial,
          check_start, check_start_range, check_outputs, check_initial_unknowns, check_dependencies,
          check_units, check_unique_names, check_value_references, check_aliases, check_derivatives)
