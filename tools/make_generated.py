#!/usr/bin/env python3
"""Generates the two files through which the variable tables reach the
package's Python, from the manifests the build generates from the tables
(models.json and variables/<model>.json, installed with the package):

  python/orthocontact/fmu/tables.json   every model's manifest and CMake's list
      of models, as orthocontact.fmu.variables reads them;
  python/orthocontact/fmu/generated.py  the facts the code needs, as source a
      reader, mypy and pyright can see:

  LAW, RULES, ContactParams   the law's parameters (the contact's "law" rows:
      unit, range, start, description), the sliding rules' numbers and the
      typed parameter object: a field per row (those up to the first angle
      required, an angle 0 by default, a later parameter its start), the
      angles' <name>_deg properties, from_degrees with <name>_deg keywords,
      a docstring with units and ranges; its checks are
      fmu/param_checks.py's LawParameters, which read LAW;
  PATCH_*                     the ContactPatch FMU's model identifier, inputs,
      outputs (Float64 and Int32) and geometry (its parameters the contact
      has not: length, width, n1, n2 with their ranges);
  PAD_*                       the ContactPad FMU's, its foundation (its
      parameters the patch has not: kn, dn).

    make generated                                   (re)write them, and every other
                                                     generated file
    .venv/bin/python tools/make_generated.py         these two, without the set-up
    .venv/bin/python tools/make_generated.py --check exit 1 if either differs

A table the generated code could not serve is refused with its reason,
nothing written: a law parameter that is not Float64 or not a Python name,
a patch input that is not Float64, an output of another type than Float64 or
Int32, a sliding rule's start that is no item of its enumeration."""
from __future__ import annotations

import argparse
import json
import keyword
import math
import re
import sys
import textwrap
from pathlib import Path

from generated_files import differs, write

ROOT = Path(__file__).resolve().parents[1]
TARGET = Path("python/orthocontact/fmu/generated.py")
TABLES = Path("python/orthocontact/fmu/tables.json")
REFRESH = "make generated (or .venv/bin/python tools/make_generated.py)"
RULE_VARIABLE = "slidingRule"   # the contact's parameter that chooses the sliding rule
WIDTH = 108                     # of the lines written (the project's limit is 110)
DOC_WIDTH = 100                 # of the docstring's lines


# -- Python literals ----------------------------------------------------------------

def number(x) -> str:
    """A manifest's number as a Python literal that reads back to it (ints stay ints)."""
    return "None" if x is None else repr(x)


def text(s: str) -> str:
    return json.dumps(s, ensure_ascii=False)   # a double-quoted literal Python reads back


def text_lines(s: str, first: str, indent: str, end: str) -> list[str]:
    """`first` + the literal of `s` + `end`, split into adjacent literals at
    spaces where a line would be longer than WIDTH."""
    width = WIDTH - len(indent) - 2
    if len(first) + len(text(s)) + len(end) <= WIDTH:
        return [first + text(s) + end]
    words = textwrap.wrap(s, width, drop_whitespace=False, break_long_words=False)
    parts = [text(w) for w in words]
    return [first + parts[0], *(indent + p for p in parts[1:-1]), indent + parts[-1] + end]


def signature(head: str, args: list[str], tail: str, indent: int) -> list[str]:
    """`head(arg, arg, ...)tail` wrapped under its opening parenthesis."""
    lines, line = [], head + "("
    pad = " " * (indent + len(head) + 1)
    for k, arg in enumerate(args):
        piece = arg + ("," if k < len(args) - 1 else ")" + tail)
        if len(line) + len(piece) + 1 > WIDTH - indent and line.strip() not in ("", head + "("):
            lines.append(line.rstrip())
            line = pad[indent:]
        line += piece + " "
    lines.append(line.rstrip())
    return [" " * indent + lines[0], *(" " * indent + x for x in lines[1:])]


def docstring_safe(s: str, where: str) -> str:
    if '"""' in s or "\\" in s:
        raise ValueError(f"{where}: a description with \\ or \"\"\" cannot stand in a docstring")
    return s


# -- the rows ---------------------------------------------------------------------

def row_lines(v, indent: str = "    ") -> list[str]:
    """A Row(...) of the manifest's variable v; an angle's range on a line of
    its own, with its multiples of pi as a comment."""
    kind = f"{indent}Row({text(v.name)}, type={text(v.type)}, unit={text(v.unit)},"
    limits = f"min={number(v.min)}, max={number(v.max)},"
    if v.unit == "rad" and v.min is not None and v.max is not None:
        head = [f"{kind} start={number(v.start)},",
                f"{indent}    {limits}   # [{pi_text(v.min)}, {pi_text(v.max)}] rad"]
    elif len(f"{kind} {limits} start={number(v.start)},") <= WIDTH:
        head = [f"{kind} {limits} start={number(v.start)},"]
    else:
        head = [f"{kind} start={number(v.start)},", f"{indent}    {limits}"]
    return [*head, *text_lines(v.description, f"{indent}    description=", f"{indent}                ", "),")]


def rule_line(title: str) -> str:
    """A section's heading comment, ruled out to a fixed width."""
    return f"# -- {title} ".ljust(DOC_WIDTH - 8, "-")


def pi_text(x: float) -> str:
    turns = x / math.pi
    return f"{round(turns):d} pi" if abs(turns - round(turns)) < 1e-12 else repr(x)


def range_text(v) -> str:
    if v.unit == "rad" and v.min is not None and v.max is not None:
        return f"[{pi_text(v.min)}, {pi_text(v.max)}]"
    return f"[{number(v.min)}, {number(v.max)}]"


# -- the contact's law: LAW, RULES, ContactParams -----------------------------------

KEEP = "\x00"   # a space the docstring's lines do not break at


def doc_item(item: str) -> list[str]:
    """An item of a docstring's list, its name in a column of its own."""
    return [line.replace(KEEP, " ") for line in textwrap.wrap(item, DOC_WIDTH, initial_indent=" " * 8,
                                                              subsequent_indent=" " * 15)]


def law_rows(contact) -> list:
    rows = [contact.variable(name) for name in contact.group("law")]
    if not rows:
        raise ValueError(f"{contact.model_identifier}: the table has no law parameter (no L rows)")
    for v in rows:
        if v.type != "Float64":
            raise ValueError(f"{contact.model_identifier}: law parameter {v.name} is {v.type}; "
                             "ContactParams holds floats (Float64)")
        if not v.name.isidentifier() or keyword.iskeyword(v.name) or v.name == "rule" or \
                v.name.endswith("_deg"):
            raise ValueError(f"{contact.model_identifier}: law parameter {v.name!r} cannot be a field "
                             "of ContactParams (a Python name, not rule, not ending in _deg)")
        docstring_safe(v.description, f"{contact.model_identifier}.{v.name}")
    return rows


def rules_of(contact) -> tuple[dict[str, int], str]:
    """The sliding rules' names and numbers, and the name of the table's start (the default)."""
    v = contact.variable(RULE_VARIABLE)
    rules = dict(contact.enumerations[v.declared_type])
    default = [name for name, n in rules.items() if n == v.start]
    if len(default) != 1:
        raise ValueError(f"{contact.model_identifier}: {RULE_VARIABLE}'s start {v.start!r} is no item of "
                         f"{v.declared_type} {rules}")
    return rules, default[0]


def fields(rows) -> list[tuple]:
    """(row, default literal or None) per law parameter: required up to the
    first angle, then an angle 0 (its axis along X1), another its start."""
    out, defaulted = [], False
    for v in rows:
        defaulted = defaulted or v.unit == "rad"
        out.append((v, None if not defaulted else "0.0" if v.unit == "rad" else repr(float(v.start))))
    return out


def contact_params(contact, table: str) -> list[str]:
    rows = law_rows(contact)
    rules, default = rules_of(contact)
    spec = fields(rows)
    angles = [v for v in rows if v.unit == "rad"]
    doc = [f'    """Parameters of the law (the contact\'s variable table, {table}):', ""]
    for v in rows:
        item = f"{v.name:<6} {v.description} [{v.unit or '-'}], in {range_text(v).replace(' ', KEEP)}"
        doc += doc_item(item)
    doc += [*doc_item(f"{'rule':<6} sliding rule: {', '.join(map(repr, rules))} (by default {default!r}, "
                      "the table's start)"), "",
            "    The angles are in radians, as the FMU takes them; ContactParams.from_degrees",
            "    takes degrees (`<name>_deg`), as scenario files do.  Invalid values raise ValueError",
            '    (LawParameters checks each field against its row of LAW)."""']
    out = ["@dataclasses.dataclass(frozen=True)", "class ContactParams(LawParameters):", *doc]
    for v, default_literal in spec:
        out.append(f"    {v.name}: float" + (f" = {default_literal}" if default_literal else ""))
    out += [f"    rule: str = {text(default)}   # the table's start of {RULE_VARIABLE} "
            f"({rules[default]})", "",
            "    TABLE: ClassVar[tuple[Row, ...]] = LAW",
            "    RULE_NUMBERS: ClassVar[Mapping[str, int]] = RULES",
            f"    RULE_VARIABLE: ClassVar[str] = {text(RULE_VARIABLE)}"]
    for v in angles:
        out += ["", "    @property", f"    def {v.name}_deg(self) -> float:",
                f'        """{v.name} in degrees."""', f"        return math.degrees(self.{v.name})"]
    args = ["cls"]
    for v, default_literal in spec:
        name = f"{v.name}_deg" if v.unit == "rad" else v.name
        args.append(f"{name}: float" + (f" = {default_literal}" if default_literal else ""))
    args += [f"rule: str = {text(default)}", "**misnamed: NoReturn"]
    call = ", ".join(f"radians({v.name}_deg)" if v.unit == "rad" else v.name for v in rows)
    out += ["", "    @classmethod", *signature("def from_degrees", args, " -> ContactParams:", 4),
            '        """The same parameters with the axis angles in degrees (as scenario files give',
            "        them), counterclockwise from X1: positionally in the table's order, or by keyword",
            "        with the angles named `<name>_deg`.  A misnamed keyword (`alpha` for `alpha_deg`)",
            '        is refused: TypeError here, an error of a type checker before."""',
            "        refuse_misnamed(cls, misnamed)",
            *signature("return cls", [*call.split(", "), "rule"], "", 8)]
    return out


def law_section(contact, table: str) -> list[str]:
    rows = law_rows(contact)
    rules, _ = rules_of(contact)
    rule_type = contact.variable(RULE_VARIABLE).declared_type
    out = [rule_line(f"{contact.model_identifier}: the law's parameters (its table's L rows, in order)"),
           "", "LAW: tuple[Row, ...] = ("]
    for v in rows:
        out += row_lines(v)
    out += [")", "",
            f"# The sliding rules' names and the numbers the FMU's {RULE_VARIABLE} takes (enumeration "
            f"{rule_type}).",
            "RULES: dict[str, int] = {" + ", ".join(f"{text(k)}: {n}" for k, n in rules.items()) + "}",
            "", ""]
    return out + contact_params(contact, table)


# -- the models on the cells: PATCH_*, PAD_* ------------------------------------------

def cells_section(prefix: str, model_m, without, own_name: str, own_words: str, table: str) -> list[str]:
    """<prefix>_MODEL, _INPUTS, _FLOAT_OUTPUTS, _INTEGER_OUTPUTS and
    <prefix>_<own_name>: its parameters none of the manifests `without` has
    (own_words says what they are)."""
    model = model_m.model_identifier
    inputs = [v for v in model_m.variables if v.causality == "input"]
    outputs = [v for v in model_m.variables if v.causality == "output"]
    for v in inputs:
        if v.type != "Float64":
            raise ValueError(f"{model}: input {v.name} is {v.type}; {model}'s access sets its inputs as "
                             "Float64")
    for v in outputs:
        if v.type not in ("Float64", "Int32"):
            raise ValueError(f"{model}: output {v.name} is {v.type}; {model}'s access reads Float64 and "
                             "Int32")
    others = {v.name for m in without for v in m.variables}
    own = [v for v in model_m.variables if v.causality == "parameter" and v.name not in others]
    floats = [v for v in outputs if v.type == "Float64"]
    ints = [v for v in outputs if v.type == "Int32"]

    def names(head: str, vs) -> list[str]:
        """`head = (...)`, the names wrapped under the parenthesis."""
        items = [text(v.name) for v in vs]
        one = head + " = (" + ", ".join(items) + ("," if len(items) == 1 else "") + ")"
        return [one] if len(one) <= WIDTH else signature(head + " = ", items, "", 0)

    def units(vs) -> str:
        return ", ".join(f"{v.name} [{v.unit or '-'}]" for v in vs)

    out = [rule_line(f"{model} ({table})"), "", f"{prefix}_MODEL = {text(model)}", "",
           *textwrap.wrap(f"Its inputs in the table's order, all Float64: {units(inputs)}.", DOC_WIDTH,
                          initial_indent="# ", subsequent_indent="# "),
           *names(f"{prefix}_INPUTS", inputs), "",
           *textwrap.wrap(f"Its outputs in the table's order: Float64 {units(floats)}; Int32 "
                          f"{units(ints)}.", DOC_WIDTH, initial_indent="# ", subsequent_indent="# "),
           *names(f"{prefix}_FLOAT_OUTPUTS", floats), *names(f"{prefix}_INTEGER_OUTPUTS", ints), "",
           f"# {own_words}, with their type, unit, range and start.",
           f"{prefix}_{own_name}: tuple[Row, ...] = ("]
    for v in own:
        out += row_lines(v)
    return out + [")"]


# The cells' limit in all (n1 n2), which no table row holds: the C constant itself.
CELLS_HEADER = Path("fmu_src/cells/cell_rows.h")


def max_cells() -> int:
    """PATCH_MAX_CELLS as fmu_src/cells/cell_rows.h defines it."""
    found = re.search(r"^#define PATCH_MAX_CELLS (\d+)$", (ROOT / CELLS_HEADER).read_text(), re.M)
    if found is None:
        raise ValueError(f"{CELLS_HEADER}: no `#define PATCH_MAX_CELLS N`")
    return int(found.group(1))


def patch_section(contact, patch, table: str) -> list[str]:
    return cells_section("PATCH", patch, (contact,), "GEOMETRY",
                         "Its geometry: its parameters the point contact has not", table) + [
        "", f"# The most cells a patch or pad has in all, n1 n2 ({CELLS_HEADER}'s PATCH_MAX_CELLS).",
        f"PATCH_MAX_CELLS = {max_cells()}"]


def pad_section(contact, patch, pad, table: str) -> list[str]:
    return cells_section("PAD", pad, (contact, patch), "FOUNDATION",
                         "Its foundation: its parameters the patch has not", table)


# -- the file ------------------------------------------------------------------------

def source(contact, patch, tables: dict[str, str], pad=None) -> str:
    """generated.py's text from the contact's, the patch's (and the pad's)
    manifests and {model identifier: its table's path}."""
    ct, pt = tables[contact.model_identifier], tables[patch.model_identifier]
    names = f"{ct}\n# ({contact.model_identifier}), {pt} ({patch.model_identifier})"
    if pad is not None:
        names += f"\n# and {tables[pad.model_identifier]} ({pad.model_identifier}),"
    else:
        names = names.replace(", " + pt, " and " + pt) + ","
    lines = [f"# Generated by tools/make_generated.py from the variable tables {names}",
             "# through the manifests the build writes from them (variables/<model>.json): do not edit.",
             "# Regenerate: make generated.",
             "# tests/fmu/test_generated.py fails while this file is not what the tables give.",
             '"""The facts of the variable tables the package\'s Python code needs, as source:',
             "the law's parameters (LAW: a Row each, with unit, range and start), the sliding",
             "rules' numbers (RULES), ContactParams (the typed parameter object; its checks",
             "are param_checks.LawParameters', which read LAW), the ContactPatch FMU's",
             "inputs, outputs and geometry (PATCH_*) and the ContactPad FMU's inputs,",
             "outputs and foundation (PAD_*).",
             "",
             'Units as the tables give them ("" for none); angles in rad."""',
             "from __future__ import annotations", "", "import dataclasses", "import math",
             "from collections.abc import Mapping", "from typing import ClassVar, NoReturn", "",
             "from .param_checks import LawParameters, Row, radians, refuse_misnamed", "",
             *law_section(contact, ct), "", "", *patch_section(contact, patch, pt)]
    if pad is not None:
        lines += ["", "", *pad_section(contact, patch, pad, tables[pad.model_identifier])]
    return "\n".join(lines) + "\n"


def installed_tables() -> dict:
    """The manifests as the build installed them with the package: {"models": models.json's
    list, "variables": {model identifier: variables/<model>.json}} (tables.json's content)."""
    def read(rel: str) -> dict:
        # as orthocontact.fmu.files.installed_file finds them, without importing the package:
        # its import reads tables.json, which this writes
        for entry in sys.path:
            found = Path(entry or ".") / "orthocontact" / rel
            if found.is_file():
                return json.loads(found.read_text())
        raise FileNotFoundError(f"{rel} is not installed with the package; run `make setup`")
    listed = read("models.json")["models"]
    models = [m["modelIdentifier"] for m in listed]
    return {"models": listed, "variables": {model: read(f"variables/{model}.json") for model in models}}


def tables_text(tables: dict) -> str:
    return json.dumps(tables, indent=1, ensure_ascii=False) + "\n"


def installed(tables: dict) -> tuple:
    """The contact's and the patch's manifests, their tables' paths and the pad's manifest."""
    from orthocontact.fmu.variables import manifest_from
    paths = {m["modelIdentifier"]: m["table"] for m in tables["models"]}
    roles = {m["role"]: m["modelIdentifier"] for m in tables["models"]}
    return (*(manifest_from(tables["variables"][roles[r]]) for r in ("contact", "patch")), paths,
            manifest_from(tables["variables"][roles["pad"]]))


def generated() -> dict[Path, str]:
    """{file: its text}: generated.py and tables.json."""
    tables = installed_tables()
    return {TARGET: source(*installed(tables)), TABLES: tables_text(tables)}


def stale(root: Path = ROOT, texts: dict[Path, str] | None = None) -> str:
    """A short diff for each file under `root` that is not what the tables give, else ""."""
    new = generated() if texts is None else texts
    out = []
    for rel, text_now in new.items():
        diff = differs(root, rel, text_now, 30)
        if diff:
            out.append(f"{rel} is not what the variable tables give: run {REFRESH}\n{diff}")
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="make_generated", description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true", help="write nothing; exit 1 if either file differs")
    args = ap.parse_args(argv)
    try:
        new = generated()
    except (ValueError, FileNotFoundError, KeyError) as e:
        print(f"make_generated: error: {e}", file=sys.stderr)
        return 2
    if args.check:
        problem = stale(ROOT, new)
        if problem:
            print(problem, file=sys.stderr)
        return 1 if problem else 0
    for rel, text_now in new.items():
        write(ROOT, rel, text_now)
    return 0


if __name__ == "__main__":
    sys.exit(main())
