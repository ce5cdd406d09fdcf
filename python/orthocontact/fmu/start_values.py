"""A copy of an FMU (FMI 2.0 or 3.0) whose parameters have new start values,
in both places an importer can find them: the `start` attributes of
modelDescription.xml (for importers that set every start value) and
resources/start_values.txt, which the shared C glue reads at instantiation
(for importers that set nothing: fmu_src/glue/fmu_instance.h gives its format).
Everything else of the FMU (binaries of every platform, sources, licenses,
the rest of the XML byte for byte) is kept; documentation pages can be
added and a sentence appended to the model description's description."""
from __future__ import annotations

import math
import re
import zipfile
from pathlib import Path

from ..errors import InputError

DESCRIPTION = "modelDescription.xml"
START_VALUES = "resources/start_values.txt"

_FLOAT_TYPES = {"Real", "Float32", "Float64"}
_INTEGER_TYPES = {"Integer", "Enumeration", "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32",
                  "Int64", "UInt64"}


class StartValueError(InputError, ValueError):
    """A start value the FMU would refuse, or an FMU this module cannot rewrite:
    one line naming the FMU and the parameter (an InputError: the values come
    from the user's files)."""


def _number(text):
    return None if text is None else float(text)


def parameters(xml: bytes) -> dict:
    """name -> (type, min, max, start) of each parameter of a model
    description; min/max from the variable or its declared type (None: no
    limit), start as written."""
    from xml.etree import ElementTree  # here: a command's start does without it
    root = ElementTree.fromstring(xml)
    fmi2 = root.get("fmiVersion", "").startswith("2")
    declared = {}
    for types in root.iter("TypeDefinitions"):
        for t in types:   # FMI 2.0: SimpleType with the type element inside
            declared[t.get("name")] = next(iter(t), t) if t.tag == "SimpleType" else t
    variables = root.find("ModelVariables")
    out = {}
    for v in (variables.iter("ScalarVariable") if fmi2 else variables) if variables is not None else ():
        if v.get("causality") != "parameter":
            continue
        spec = next((c for c in v if c.tag in _FLOAT_TYPES | _INTEGER_TYPES | {"Boolean", "String"}),
                    None) if fmi2 else v
        if spec is None:
            continue
        kind = spec.tag
        base = declared.get(spec.get("declaredType"))
        lo = spec.get("min", base.get("min") if base is not None else None)
        hi = spec.get("max", base.get("max") if base is not None else None)
        out[v.get("name")] = (kind, _number(lo), _number(hi), spec.get("start"))
    return out


def _checked(fmu_name: str, params: dict, values: dict) -> dict:
    """The values as the XML and the resource file write them (float or int),
    or StartValueError for the first one the FMU would refuse."""
    out = {}
    for name, value in values.items():
        if name not in params:
            raise StartValueError(f"{fmu_name}: {name} is not a parameter of this FMU")
        kind, lo, hi, _ = params[name]
        if kind in _FLOAT_TYPES:
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                raise StartValueError(f"{fmu_name}: {name} = {value!r}: expected a finite number")
            value = float(value)
        elif kind in _INTEGER_TYPES:
            if isinstance(value, bool) or not isinstance(value, int):
                raise StartValueError(f"{fmu_name}: {name} = {value!r}: expected an integer ({kind})")
        else:
            raise StartValueError(f"{fmu_name}: {name} is a {kind}: only numbers can be rewritten")
        if (lo is not None and value < lo) or (hi is not None and value > hi):
            raise StartValueError(f"{fmu_name}: {name} = {value!r} is outside [{_bound(lo, '-inf')}, "
                                  f"{_bound(hi, 'inf')}], the FMU's range")
        out[name] = value
    return out


def _bound(b, none: str) -> str:
    """A range's end as the message shows it: `none` where it is open."""
    return none if b is None else f"{b:g}"


def _xml_number(value) -> str:
    return repr(value) if isinstance(value, float) else str(int(value))


def _with_start(xml: str, fmi2: bool, name: str, value) -> str:
    """The XML with the start attribute of parameter `name` rewritten in
    place (added if absent): the rest of the text is untouched."""
    variables = xml.find("<ModelVariables")   # not a unit or type of the same name
    if fmi2:
        head = re.compile(rf'<ScalarVariable[^>]*?\sname="{re.escape(name)}"[^>]*>').search(
            xml, variables)
        if not head:
            raise StartValueError(f"{name}: no ScalarVariable in the model description")
        tag = re.compile(r"<(Real|Integer|Enumeration)\b[^>]*?/?>").search(xml, head.end())
    else:
        tag = re.compile(rf'<(\w+)[^>]*?\sname="{re.escape(name)}"[^>]*?/?>').search(
            xml, variables)
    if not tag:
        raise StartValueError(f"{name}: its type element was not found in the model description")
    element = tag.group(0)
    new_start = f'start="{_xml_number(value)}"'
    if re.search(r'\sstart="[^"]*"', element):
        element = re.sub(r'(\s)start="[^"]*"', lambda m: m.group(1) + new_start, element, count=1)
    else:
        end = -2 if element.endswith("/>") else -1
        element = element[:end].rstrip() + " " + new_start + element[end:]
    return xml[:tag.start()] + element + xml[tag.end():]


def _with_description(xml: str, note: str) -> str:
    from xml.sax.saxutils import escape, quoteattr  # here, not at the start: it imports urllib.request
    head = re.search(r"<fmiModelDescription\b[^>]*>", xml)
    element = head.group(0)
    m = re.search(r'\sdescription="([^"]*)"', element)
    if m:
        base = m.group(1).rstrip()
        element = (element[:m.start(1)] + base + ("" if base.endswith(".") else ".") + " "
                   + escape(note, {'"': "&quot;"})
                   + element[m.end(1):])
    else:
        element = element[:-1].rstrip() + f" description={quoteattr(note)}>"
    return xml[:head.start()] + element + xml[head.end():]


def start_values_text(values: dict) -> str:
    """resources/start_values.txt: floats as hexadecimal floats (read back
    exactly, independently of the locale), integers in decimal."""
    lines = ["# Start values of the parameters (read by the FMU at instantiation;",
             "# the same as the start attributes of modelDescription.xml)."]
    for name, v in values.items():
        lines.append(f"{name} = {v.hex() if isinstance(v, float) else int(v)}")
    return "\n".join(lines) + "\n"


def _read_start_values(text: str, params: dict) -> dict:
    """The assignments of an existing start_values.txt (written by this
    module or by hand in the same format)."""
    out = {}
    for line in text.splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        name, _, value = (s.strip() for s in line.partition("="))
        kind = params.get(name, ("Real",))[0]
        out[name] = (float.fromhex(value) if "x" in value.lower() else float(int(value))) \
            if kind in _FLOAT_TYPES else int(value)
    return out


def write_with_start_values(src, dst, values: dict, documentation: dict | None = None,
                            description_note: str | None = None) -> Path:
    """Writes to `dst` a copy of the FMU `src` whose parameters `values`
    (name -> number) are its start values: in the model description and in
    resources/start_values.txt (merged with one already there).
    documentation: file name -> text, written under documentation/;
    description_note: a sentence appended to the model's description.
    A value outside the variable's [min, max], of the wrong type or for a
    name that is not a parameter raises StartValueError, and nothing is
    written."""
    src, dst = Path(src), Path(dst)
    with zipfile.ZipFile(src) as z:
        entries = [(info, z.read(info)) for info in z.infolist()]
    files = {info.filename: data for info, data in entries}
    if DESCRIPTION not in files:
        raise StartValueError(f"{src.name}: no {DESCRIPTION} in it: not an FMU")
    params = parameters(files[DESCRIPTION])
    checked = _checked(src.name, params, values)
    xml = files[DESCRIPTION].decode("utf-8")
    fmi2 = re.search(r'fmiVersion="2', xml) is not None
    for name, value in checked.items():
        xml = _with_start(xml, fmi2, name, value)
    if description_note:
        xml = _with_description(xml, description_note)
    merged = {}
    if START_VALUES in files:
        merged = _read_start_values(files[START_VALUES].decode("utf-8"), params)
    merged.update(checked)
    replaced = {DESCRIPTION: xml.encode("utf-8"), START_VALUES: start_values_text(merged).encode()}
    for name, text in (documentation or {}).items():
        replaced[f"documentation/{name}"] = text.encode("utf-8") if isinstance(text, str) else text
    tmp = dst.with_name(f".{dst.name}.partial")
    dst.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        for info, data in entries:
            z.writestr(info, replaced.pop(info.filename, data))
        for name, data in replaced.items():
            z.writestr(name, data)
    tmp.replace(dst)
    return dst


def start_values_of(path) -> dict:
    """name -> start value (float or int) of each parameter of the FMU at
    `path` as its model description states it."""
    with zipfile.ZipFile(path) as z:
        params = parameters(z.read(DESCRIPTION))
    return {name: (float(start) if kind in _FLOAT_TYPES else int(start))
            for name, (kind, _, _, start) in params.items() if start is not None}
