#!/usr/bin/env python3
"""Generates the reference pages, and the blocks of hand-written pages,
that must not be typed by hand:

  docs/reference/variables.md  every variable of every model, from the
      manifests the build generates from the variable tables
      (orthocontact.fmu.variables), with what only the model descriptions
      carry (descriptions, display units, enumeration items, the outputs'
      dependencies) read by fmpy from the installed FMI 2.0 and 3.0 FMUs;
  docs/reference/cli.md        every command, argument and option with its
      help text and default, and the exit status, from the parser
      (orthocontact.cli.parser.build_parser);
  docs/reference/fmus.md, its block "models"  the models of OC_MODELS
      (models.json, in its order) and the FMUs' count, each model's role,
      description, variables by causality, derivatives, FMU state and what
      FMI 3.0 adds, from the manifests and the model descriptions: a model
      added to OC_MODELS appears with nothing edited by hand.

    make generated                                   (re)write every page and block, and
                                                     every other generated file
    .venv/bin/python tools/make_reference.py         the pages, without the set-up
    .venv/bin/python tools/make_reference.py --check exit 1 naming each page that differs

A fact the sources contradict is refused with its reason, nothing written:
a manifest and the model description of the same model that disagree (a
stale install), FMI 2.0 and 3.0 outputs with different dependencies, a help
text whose stated default is not the option's, an epilog without the exit
status.  Units are the tables' (variables) and the help texts' (options)."""
from __future__ import annotations

import argparse
import json
import re
import sys
from dataclasses import dataclass
from pathlib import Path

from generated_files import differs, write

ROOT = Path(__file__).resolve().parents[1]
PAGES = {"variables": Path("docs/reference/variables.md"), "cli": Path("docs/reference/cli.md")}
REFRESH = "make generated (or .venv/bin/python tools/make_reference.py)"
NONE = "—"


# -- Markdown ------------------------------------------------------------------

_SPECIAL = re.compile(r"[*<>|\\]|(?<![A-Za-z0-9])_|_(?![A-Za-z0-9])")
_ESCAPED = {"<": "&lt;", ">": "&gt;"}


def md_text(text: str) -> str:
    """`text` as literal Markdown in a table cell: emphasis marks, HTML's
    angle brackets and the cell separator escaped; `code spans` kept (their
    `|` escaped, which GitHub's tables need inside spans too); one line."""
    parts = re.split(r"(`[^`]*`)", " ".join(text.split()))
    return "".join(p.replace("|", "\\|") if p.startswith("`") and p.endswith("`") and len(p) > 1
                   else _SPECIAL.sub(lambda m: _ESCAPED.get(m.group(), "\\" + m.group()), p)
                   for p in parts)


def table(header: tuple[str, ...], rows: list[tuple[str, ...]]) -> list[str]:
    """A Markdown table; cells already in Markdown."""
    return ["| " + " | ".join(header) + " |", "|" + "---|" * len(header),
            *("| " + " | ".join(r) + " |" for r in rows)]


def number(x) -> str:
    """A value as the manifest holds it: the shortest text that reads back to it."""
    return NONE if x is None else repr(x) if isinstance(x, float) else str(x)


# -- the variables ----------------------------------------------------------------

@dataclass(frozen=True)
class ModelSources:
    """One model's generated facts: its manifest (orthocontact.fmu.variables),
    the path of its variable table, and fmpy's reading of its FMI 2.0 and 3.0
    model descriptions."""
    manifest: object
    table: str
    fmi2: object
    fmi3: object
    ranges: dict = None   # {2 or 3: {name: (min, max)}} from the XML (ranges_of)
    role: str = ""        # models.json's: contact, rig, patch
    cosim: dict = None    # {2 or 3: the CoSimulation element's attributes} (cosim_of)


FMI_VERSIONS = (2, 3)   # the package ships every model for each, in its fmi2 and fmi3 folders


def installed_models() -> list[ModelSources]:
    """Every model of models.json (CMake's OC_MODELS, in its order) as installed with the package."""
    from orthocontact.fmu.files import find_fmu, installed_file, model_description
    from orthocontact.fmu.variables import manifest, models
    tables = {m["modelIdentifier"]: m["table"]
              for m in json.loads(installed_file("models.json").read_text())["models"]}
    return [ModelSources(manifest(model), tables[model],
                         model_description(find_fmu(fmi_version=2, model=model)),
                         model_description(find_fmu(fmi_version=3, model=model)),
                         {v: ranges_of(find_fmu(fmi_version=v, model=model)) for v in FMI_VERSIONS},
                         role, {v: cosim_of(find_fmu(fmi_version=v, model=model)) for v in FMI_VERSIONS})
            for role, model in models().items()]


def description_xml(fmu):
    """The root element of the FMU's modelDescription.xml."""
    import xml.etree.ElementTree as ET
    import zipfile
    with zipfile.ZipFile(fmu) as z:
        return ET.fromstring(z.read("modelDescription.xml"))


def cosim_of(fmu) -> dict:
    """The attributes of the model description's CoSimulation element, as
    written (FMI 2.0 and 3.0 spell the capabilities differently)."""
    return dict(description_xml(fmu).find("CoSimulation").attrib)


def ranges_of(fmu) -> dict:
    """{name: (min, max)} (texts or None) as the FMU's model description
    writes them: fmpy 0.3.32 reads no min/max of an FMI 3.0 UInt type."""
    root = description_xml(fmu)
    out = {}
    for v in root.find("ModelVariables"):
        typed = v[0] if v.tag == "ScalarVariable" else v   # FMI 2.0 keeps them on the type element
        out[v.get("name")] = (typed.get("min"), typed.get("max"))
    return out


def _same_number(a, b) -> bool:
    return (a is None) == (b is None) and (a is None or float(a) == float(b))


def check_sources(src: ModelSources) -> None:
    """Refuses (ValueError, one line) a manifest its model descriptions
    contradict, and outputs whose dependencies differ between FMI 2.0 and 3.0."""
    m = src.manifest
    stale = ": reinstall the package (pip install .) so that both come from the same table"
    for md in (src.fmi2, src.fmi3):
        where = f"{m.model_identifier}: the installed FMI {md.fmiVersion} model description and " \
                f"variables/{m.model_identifier}.json"
        version = 3 if md is src.fmi3 else 2
        arrays = m.arrays if version == 3 else ()   # FMI 3.0's arrays follow the table's variables
        names = [v.name for v in md.modelVariables]
        if names != [v.name for v in m.variables] + [a.name for a in arrays]:
            raise ValueError(f"{where} list different variables ({', '.join(names)}){stale}")
        for a, theirs in zip(arrays, md.modelVariables[len(m.variables):]):
            dims = [d.variable.name if d.variable else d.start for d in theirs.dimensions]
            if (a.value_reference, a.type, a.unit, list(a.dimensions)) != \
                    (theirs.valueReference, theirs.type, theirs.unit or "", dims):
                raise ValueError(f"{where} disagree on the array {a.name}{stale}")
        for ours, theirs in zip(m.variables, md.modelVariables):
            lo, hi = src.ranges[version][ours.name] if src.ranges else (theirs.min, theirs.max)
            fields = [("valueReference", ours.value_reference, theirs.valueReference, int.__eq__),
                      ("causality", m.causality(ours, version), theirs.causality, str.__eq__),
                      ("variability", ours.variability, theirs.variability, str.__eq__),
                      ("unit", ours.unit, theirs.unit or "", str.__eq__),
                      ("start", ours.start, theirs.start, _same_number),
                      ("min", ours.min, lo, _same_number),
                      ("max", ours.max, hi, _same_number)]
            fields.append(("type", m.type(ours, version), theirs.type, str.__eq__))
            for field, a, b, same in fields:
                if not same(a, b):
                    raise ValueError(f"{where} disagree on {ours.name}'s {field} ({a!r} and {b!r}){stale}")
        outputs = [v.name for v in m.variables if v.causality == "output"] + [a.name for a in arrays]
        if [u.variable.name for u in md.outputs] != outputs:
            raise ValueError(f"{m.model_identifier}: the FMI {md.fmiVersion} model structure lists the "
                             f"outputs {[u.variable.name for u in md.outputs]}, the table {outputs}")
    deps3 = dependencies(src.fmi3)
    scalars3 = {o: d for o, d in deps3.items() if o not in {a.name for a in m.arrays}}
    if dependencies(src.fmi2) != scalars3:
        raise ValueError(f"{m.model_identifier}: the outputs' dependencies differ between FMI 2.0 "
                         f"{dependencies(src.fmi2)} and FMI 3.0 {scalars3}")
    for a in m.arrays:
        if deps3[a.name] != deps3[a.dependencies_of]:
            raise ValueError(f"{m.model_identifier}: the FMI 3.0 array {a.name} does not depend on "
                             f"what {a.dependencies_of} depends on")


def dependencies(md) -> dict[str, tuple[tuple[str, str], ...] | None]:
    """output -> (variable, kind) of each variable it depends on directly
    (kind "" when not stated; None: no dependencies stated, so on every one)."""
    return {u.variable.name: None if u.dependencies is None else
            tuple(zip((d.name for d in u.dependencies), u.dependenciesKind or [""] * len(u.dependencies)))
            for u in md.outputs}


def depends_cell(deps: tuple[tuple[str, str], ...] | None) -> str:
    if deps is None:
        return "every variable (not stated)"
    if not deps:
        return "nothing: no direct feedthrough"
    kinds = {kind for _, kind in deps}
    if len(kinds) == 1:     # one kind for all: said once
        kind = kinds.pop()
        return ", ".join(f"`{n}`" for n, _ in deps) + \
            (f" ({'all ' if len(deps) > 1 else ''}{kind})" if kind else "")
    return ", ".join(f"`{n}`" + (f" ({kind})" if kind else "") for n, kind in deps)


def display(md, unit: str, display_unit: str, x) -> str:
    """` (x in the display unit)`, or "" without one."""
    if not display_unit or x is None:
        return ""
    for u in md.unitDefinitions:
        for d in (u.displayUnits if u.name == unit else ()):
            if d.name == display_unit:
                return f" ({float(d.factor) * float(x) + float(d.offset or 0):.6g} {display_unit})"
    raise ValueError(f"{md.modelName}: display unit {display_unit!r} of {unit!r} is not defined")


def model_section(src: ModelSources) -> list[str]:
    """The Markdown section of one model."""
    check_sources(src)
    m, md = src.manifest, src.fmi3
    md2 = {v.name: v for v in src.fmi2.modelVariables}
    md3 = {v.name: v for v in md.modelVariables}
    items = {t.name: t.items for t in md.typeDefinitions if t.items}
    out = [f"## {m.model_identifier}", "", md_text(md.description or ""), "",
           f"Table: `{src.table}`. Value references are the same in FMI 2.0 and 3.0."]
    if m.structural:
        out.append(f"In FMI 3.0 {', '.join(f'`{n}`' for n in m.structural)} are structural parameters "
                   f"of type {m.structural_type} (settable also in configuration mode, with "
                   f"fmi3Set{m.structural_type}; Integer parameters in FMI 2.0) and the arrays "
                   + ", ".join(f"`{a.name}`" for a in m.arrays) + " are outputs of that shape "
                   "(row-major, read with nValues their size); FMI 2.0 has no arrays.")
    law = m.group("law")
    if law:
        out.append("The law's parameters, in the table's order: " + ", ".join(f"`{n}`" for n in law) + ".")
    rows = []
    for v in m.variables:
        d3 = md3[v.name]
        du = d3.displayUnit or ""
        kind = f"{v.type} ({v.declared_type})" if v.declared_type else m.type(v, 3)
        start = number(v.start) + display(md, v.unit, du, v.start) if v.start is not None else \
            "calculated" if d3.initial == "calculated" else NONE
        if v.declared_type and v.start is not None:
            start += "".join(f" ({i.name})" for i in items[v.declared_type] if int(i.value) == v.start)
        rng = NONE if v.min is None and v.max is None else \
            f"[{number(v.min)}, {number(v.max)}]" + (
                f" ({display(md, v.unit, du, v.min)[2:-1]} to {display(md, v.unit, du, v.max)[2:-1]})"
                if du and v.min is not None and v.max is not None else "")
        unit = (v.unit + (f" (shown in {du})" if du else "")) or NONE
        rows.append((f"`{v.name}`", str(v.value_reference), d3.causality, v.variability,
                     f"{kind} / {md2[v.name].type}", md_text(unit), md_text(start), md_text(rng),
                     md_text(d3.description or "")))
    for a in m.arrays:
        d3 = md3[a.name]
        rows.append((f"`{a.name}`", str(a.value_reference), d3.causality, d3.variability,
                     f"{a.type}[{', '.join(a.dimensions)}] / {NONE}", md_text(a.unit or NONE),
                     "calculated", NONE, md_text(d3.description or "")))
    out += ["", "### Variables", "",
            *table(("name", "value reference", "causality", "variability", "type (FMI 3.0 / 2.0)",
                    "unit", "start", "range", "description"), rows)]
    if items:
        out += ["", "### Enumerations"]
        for name, its in items.items():
            users = [v.name for v in m.variables if v.declared_type == name]
            fmi2 = " or ".join(sorted({md2[u].type for u in users}))
            out += ["", f"`{name}`, the type of {', '.join(f'`{u}`' for u in users)} "
                        f"(in FMI 2.0 {fmi2}, of the same values):", "",
                    *table(("value", "item", "description"),
                           [(str(i.value), f"`{i.name}`", md_text(i.description or "")) for i in its])]
    deps = dependencies(md)
    out += ["", "### Outputs and the inputs they depend on", "",
            "What an output depends on directly, within the same step (direct feedthrough), "
            "as the model structure of both model descriptions states it, with FMI's kind of the "
            "dependency in parentheses (constant: linearly, with a constant factor; dependent: "
            "in any other way):", "",
            *table(("output", "depends on"), [(f"`{o}`", depends_cell(d)) for o, d in deps.items()])]
    return out + state_section(m.model_identifier, src.table)


def state_section(model: str, table_path: str) -> list[str]:
    """The layout of the model's serialized state, from the manifest's
    "state" (gen_model_description writes it from the model's field list)."""
    from orthocontact.fmu.files import installed_file
    state = json.loads(installed_file(f"variables/{model}.json").read_text())["state"]
    parts = [f"the header ({state['headerBytes']} bytes): {md_text(state['header'])}, "
             f"the tag being `{state['tag']}`"]
    for part in state["parts"]:
        runs: list[tuple[str, list[str]]] = []   # consecutive fields of one type
        for f in part["fields"]:
            if runs and runs[-1][0] == f["type"]:
                runs[-1][1].append(f["name"])
            else:
                runs.append((f["type"], [f["name"]]))
        fields = ", ".join(", ".join(f"`{n}`" for n in names) + f" ({kind})" for kind, names in runs)
        times = f", {part['count']} times" if part["count"] > 1 else ""
        parts.append(f"{md_text(part['part'])}{times}: {fields}")
    folder = table_path.rsplit("/", 1)[0]
    return ["", "### Serialized state", "",
            f"{state['bytes']} bytes, format {state['format']}, little-endian, field by field with "
            "no padding (equal states give equal bytes on every platform): " + "; ".join(parts) + ". "
            f"From the model's field list (`FMU_STATE_FIELDS` in `{folder}/model.h`), as the FMU "
            "writes and reads it."]


def variables_page(sources: list[ModelSources]) -> str:
    """docs/reference/variables.md of the given models."""
    out = ["# The FMUs' variables", "",
           "<!-- Generated by tools/make_reference.py (make generated) from the variable tables: "
           "edit the tables, not this file. -->", "",
           "Every variable of every model, in its table's order, from the manifest the build "
           "generates from the model's variable table (`variables/<model>.json`, installed with the "
           "package) and the FMUs' model descriptions. Units are the tables' (a display unit in "
           f"parentheses); a range is [min, max], both included, {NONE} for no bound; a start of "
           "calculated is the FMU's to compute. Regenerate with `make generated`.", ""]
    out += [f"- [{s.manifest.model_identifier}](#{s.manifest.model_identifier.lower()})" for s in sources]
    for s in sources:
        out += ["", *model_section(s)]
    return "\n".join(out) + "\n"


# -- the command line ---------------------------------------------------------------

# argparse has no public way to list a parser's arguments: its _actions (and
# a subparsers action's _choices_actions, the commands' one-line help) are
# read here, and nowhere else.

def actions(parser: argparse.ArgumentParser) -> list[argparse.Action]:
    """The parser's arguments, in the order they were added, without --help."""
    return [a for a in parser._actions if a.dest != "help" and a.help != argparse.SUPPRESS]


def subcommands(parser: argparse.ArgumentParser) -> list[tuple[str, str, argparse.ArgumentParser]]:
    """(name, one-line help, parser) of every command, in the order they were added."""
    for a in parser._actions:
        if isinstance(a.choices, dict) and all(isinstance(p, argparse.ArgumentParser)
                                               for p in a.choices.values()):
            return [(c.dest, c.help or "", a.choices[c.dest]) for c in a._choices_actions]
    return []


def help_text(action: argparse.Action, prog: str) -> str:
    """The action's help as --help prints it (argparse's %(default)s and the like filled in)."""
    text = action.help or ""
    return text % {**vars(action), "prog": prog} if "%(" in text else text


def check_stated_default(action: argparse.Action, prog: str) -> None:
    """Refuses (ValueError, one line) a help text that states another default
    than the option has: "(default 45)", "default: 0.5", or "X (default" where
    X is one of the option's choices."""
    if action.default is None or isinstance(action.default, bool):
        return
    text, name = help_text(action, prog), "/".join(action.option_strings) or action.dest
    stated = [m.group(1) for m in re.finditer(r"\bdefault:? (-?\d[\d.eE+-]*\d|-?\d)\b", text)]
    if action.choices is not None:
        stated += [m.group(1) for m in re.finditer(r"(\S+) \(default\b", text)
                   if m.group(1) in {str(c) for c in action.choices}]
    for s in stated:
        same = str(action.default) == s
        if not same and isinstance(action.default, (int, float)):
            same = float(s) == float(action.default)
        if not same:
            raise ValueError(f"{prog} {name}: the help says the default is {s}, the option's default "
                             f"is {action.default!r}: correct one of them in cli/parser.py")


def option_cell(action: argparse.Action) -> str:
    """`--fmi {2,3}`, `--out DIR`, `SCENARIO`: the argument as the usage writes it."""
    if not action.option_strings:
        return f"`{action.metavar or action.dest}`"
    if action.nargs == 0:
        return "`" + ", ".join(action.option_strings) + "`"
    value = action.metavar or ("{" + ",".join(map(str, action.choices)) + "}" if action.choices
                               else action.dest.upper())
    return "`" + ", ".join(f"{o} {value}" for o in action.option_strings) + "`"


def usage(prog: str, parser: argparse.ArgumentParser) -> str:
    """The command's synopsis (argparse's, without its line wrapping)."""
    words = []
    for a in actions(parser):
        cell = option_cell(a).strip("`").split(", ")[-1]
        words.append(cell if a.required or not a.option_strings else f"[{cell}]")
    return " ".join([prog, *words])


def default_cell(action: argparse.Action) -> str:
    if action.required or not action.option_strings:
        return "required"
    if action.nargs == 0:   # a flag: store_true's default is False
        return "off" if action.default is False else NONE if action.default is None else \
            md_text(f"`{action.default}`")
    return NONE if action.default is None else md_text(f"`{action.default}`")


def exit_status(epilog: str) -> tuple[list[tuple[int, str]], str]:
    """The epilog's "Exit status: 0 ..., 2 ...; notes." as [(status, meaning)]
    and the text that follows (its notes); ValueError without one."""
    start = epilog.find("Exit status: ")
    if start < 0:
        raise ValueError("the parser's epilog states no exit status (\"Exit status: 0 success, "
                         "2 bad input, ...\"): add it to build_parser()")
    text, depth, cuts, end = epilog[start + len("Exit status: "):], 0, [], None
    for i, c in enumerate(text):
        depth += {"(": 1, ")": -1}.get(c, 0)
        if depth == 0 and c == "," and re.match(r",\s*\d+\s", text[i:]):
            cuts.append(i)
        elif depth == 0 and c in ";." and (c == ";" or i + 1 == len(text) or text[i + 1].isspace()):
            end = i
            break
    end = len(text) if end is None else end
    pieces = [text[a:b].lstrip(", ").strip() for a, b in zip([0, *cuts], [*cuts, end])]
    codes = []
    for p in pieces:
        m = re.fullmatch(r"(\d+)\s+(.+)", p, re.S)
        if m is None:
            raise ValueError(f"the parser's epilog: {p!r} is not '<status> <meaning>'")
        codes.append((int(m.group(1)), " ".join(m.group(2).split())))
    notes = " ".join((epilog[:start] + text[end + 1:]).split())
    return codes, notes[:1].upper() + notes[1:]


def arguments_table(parser: argparse.ArgumentParser, options_only: bool = False) -> list[str]:
    """The table of the parser's arguments (with options_only, of its options)."""
    rows = []
    for a in actions(parser):
        if a.option_strings or not options_only:
            check_stated_default(a, parser.prog)
            rows.append((option_cell(a), default_cell(a), md_text(help_text(a, parser.prog))))
    return table(("argument", "default", "description"), rows)


def command_section(parser: argparse.ArgumentParser) -> list[str]:
    return [f"## {parser.prog}", "", md_text(parser.description or ""), "",
            f"Usage: `{usage(parser.prog, parser)}`", "", *arguments_table(parser)]


def cli_page(parser: argparse.ArgumentParser) -> str:
    """docs/reference/cli.md of `parser` (orthocontact's: build_parser())."""
    codes, notes = exit_status(parser.epilog or "")
    commands = subcommands(parser)
    out = ["# The command line", "",
           "<!-- Generated by tools/make_reference.py (make generated) from the parser "
           "(python/orthocontact/cli/parser.py): edit the parser, not this file. -->", "",
           md_text(parser.description or ""), "",
           f"Usage: `{parser.prog} COMMAND ARGUMENTS`; `{parser.prog} COMMAND --help` prints "
           "a command's arguments as below. Units are in each help text ([deg], [N/m], ...). "
           "Regenerate this page with `make generated`.", "",
           *arguments_table(parser, options_only=True),
           "", "## Commands", "",
           *table(("command", "what it does"),
                  [(f"[`{n}`](#{p.prog.replace(' ', '-')})", md_text(h)) for n, h, p in commands]),
           "", "## Exit status", "",
           *table(("status", "meaning"), [(str(c), md_text(m)) for c, m in codes])]
    if notes:
        out += ["", md_text(notes)]
    for _, _, p in commands:
        out += ["", *command_section(p)]
    return "\n".join(out) + "\n"


# -- the models, in blocks of hand-written pages -------------------------------------

# A hand-written page holds a generated block between a BEGIN and an END line
# naming it; make generated rewrites what lies between them and leaves the rest.
BLOCK_PAGES = {Path("docs/reference/fmus.md"): ("models",)}
BEGIN = "<!-- generated by tools/make_reference.py (make generated) from OC_MODELS and the tables: {} -->"
END = "<!-- end of the generated block {} -->"
_WORDS = "no one two three four five six seven eight nine ten eleven twelve".split()


def count(n: int, noun: str) -> str:
    """'three models', 'one model': a count in words up to twelve."""
    return f"{_WORDS[n] if n < len(_WORDS) else n} {noun}{'' if n == 1 else 's'}"


def names(xs) -> str:
    return ", ".join(f"`{x}`" for x in xs) or NONE


def capabilities(src: ModelSources) -> tuple[str, str, tuple[bool, bool]]:
    """(its derivatives, what FMI 3.0 adds, (get and set, serialize) its FMU
    state) as the model descriptions declare them; ValueError where FMI 2.0
    and 3.0 disagree."""
    c2, c3 = src.cosim[2], src.cosim[3]
    yes = "true".__eq__
    directional = {yes(c2.get("providesDirectionalDerivative")),
                   yes(c3.get("providesDirectionalDerivatives"))}
    state = {(yes(c2.get("canGetAndSetFMUstate")), yes(c2.get("canSerializeFMUstate"))),
             (yes(c3.get("canGetAndSetFMUState")), yes(c3.get("canSerializeFMUState")))}
    if len(directional) > 1 or len(state) > 1:
        raise ValueError(f"{src.manifest.model_identifier}: the FMI 2.0 and 3.0 model descriptions declare "
                         f"different capabilities ({c2} and {c3})")
    adjoint = yes(c3.get("providesAdjointDerivatives"))
    derivatives = ("directional" if directional.pop() else "") + (", adjoint (FMI 3.0)" if adjoint else "")
    m, fmi3 = src.manifest, []
    if m.structural:
        fmi3.append(f"structural parameters {names(m.structural)} ({m.structural_type})")
    for shape in dict.fromkeys(a.dimensions for a in m.arrays):
        fmi3.append("arrays " + ", ".join(f"`{a.name}`" + (f" [{a.unit}]" if a.unit else "")
                                          for a in m.arrays if a.dimensions == shape)
                    + " of shape (" + ", ".join(f"`{d}`" for d in shape) + ")")
    return derivatives.lstrip(", ") or "none", "; ".join(fmi3) or NONE, state.pop()


def models_block(sources: list[ModelSources]) -> list[str]:
    """The models' table: what each is, its variables by causality, its capabilities."""
    rows, states = [], {}
    for s in sources:
        m = s.manifest
        by = {c: [v.name for v in m.variables if v.causality == c] for c in ("parameter", "input", "output")}
        derivatives, fmi3, state = capabilities(s)
        states.setdefault(state, []).append(m.model_identifier)
        rows.append((f"[`{m.model_identifier}`](variables.md#{m.model_identifier.lower()})", s.role,
                     md_text(s.fmi3.description or ""), str(len(by["parameter"])),
                     names(by["input"]), names(by["output"]), derivatives, fmi3))
    n = len(sources)
    said = {(True, True): "gets, sets and serializes its FMU state", (True, False): "gets and sets its FMU "
            "state, without serializing it", (False, False): "has no FMU state to get or set"}
    state = " ".join(("Every model " if len(states) == 1 else names(who) + ": ") + said[st] + "."
                     for st, who in states.items())
    return [f"The package ships {count(n * len(FMI_VERSIONS), 'Co-Simulation FMU')}: "
            f"{'the' if n > 1 else 'its'} {count(n, 'model')} of `OC_MODELS` (`CMakeLists.txt`), each for "
            + " and ".join(f"FMI {v}.0" for v in FMI_VERSIONS) + ", in that list's order below. "
            "Installed, `orthocontact.fmu.find_fmu(fmi_version, model)` finds each; `make fmus` "
            "writes them to " + " and ".join(f"`dist/fmi{v}/<model>.fmu`" for v in FMI_VERSIONS) + ". "
            "Each model is a folder `fmu_src/models/<model>/` over the shared FMI glue, with one "
            "variable table (`table.h`) from which its model descriptions, its documentation and "
            "the package's manifest are generated; every variable with its unit, range and start: "
            "[variables](variables.md).", "",
            *table(("model", "role", "what it is", "parameters", "inputs", "outputs", "derivatives",
                    "FMI 3.0 only"), rows), "", state]


BLOCKS = {"models": models_block}


def fill_blocks(text: str, rel: Path, sources: list[ModelSources]) -> str:
    """`text` (the page `rel`) with each of its generated blocks rewritten;
    ValueError for a block it lacks or one left open."""
    for name in BLOCK_PAGES[rel]:
        begin, end = BEGIN.format(name), END.format(name)
        if text.count(begin) != 1 or text.count(end) != 1 or text.index(begin) > text.index(end):
            raise ValueError(f"{rel}: the generated block {name!r} needs one line {begin!r} and after it "
                             f"one line {end!r}")
        head, rest = text.split(begin + "\n", 1)
        _, tail = rest.split(end, 1)
        text = head + begin + "\n" + "\n".join(BLOCKS[name](sources)) + "\n" + end + tail
    return text


# -- the pages ------------------------------------------------------------------------

def pages(root: Path = ROOT) -> dict[Path, str]:
    """Every generated page (its path under the repository) and its text: the
    generated pages whole, the hand-written ones under `root` with their
    generated blocks rewritten."""
    from orthocontact.cli.parser import build_parser
    models = installed_models()
    out = {PAGES["variables"]: variables_page(models), PAGES["cli"]: cli_page(build_parser())}
    for rel in BLOCK_PAGES:
        if not (root / rel).is_file():
            raise FileNotFoundError(f"{rel}, which holds generated blocks, is not in {root}")
        out[rel] = fill_blocks((root / rel).read_text(), rel, models)
    return out


def stale(root: Path = ROOT) -> list[tuple[Path, str]]:
    """(page, a short diff) of each page under `root` that differs from what it generates."""
    diffs = [(rel, differs(root, rel, text, 24)) for rel, text in pages(root).items()]
    return [(rel, diff) for rel, diff in diffs if diff]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="make_reference", description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true", help="write nothing; exit 1 if a page differs")
    args = ap.parse_args(argv)
    try:
        generated = stale() if args.check else pages()
    except (ValueError, FileNotFoundError) as e:
        print(f"make_reference: error: {e}", file=sys.stderr)
        return 2
    if args.check:
        for rel, diff in generated:
            print(f"{rel} is out of date: run {REFRESH}\n{diff}", file=sys.stderr)
        return 1 if generated else 0
    for rel, text in generated.items():
        write(ROOT, rel, text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
