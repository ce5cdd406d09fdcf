"""The C of fmu_src/ in pieces a reader takes in at once: no function of
more than MAX_FUNCTION_LINES lines outside the model-description generator
(glue/gen_model_description*, a writer of text whose functions follow the
files they write), no file of more than MAX_FILE_LINES lines, no model's
folder including from another model's (what two models share has a folder
of its own, fmu_src/cells/), and include-templates named *.inc, each
included at file scope (a header, *.h, has its include guard).

The code is clang-formatted (tests/contracts/test_c_format.py), which the
parser rests on: a function's definition starts at column 0 and its body
ends with the first `}` at column 0 after it."""
import re
from pathlib import Path

from paths import ROOT

FMU_SRC = ROOT / "fmu_src"
MAX_FUNCTION_LINES = 70
MAX_FILE_LINES = 700
GENERATOR = "gen_model_description"   # the files' prefix: exempt from the function length


def c_files() -> list[Path]:
    """Every C source, header and include-template of fmu_src/."""
    return sorted(p for p in FMU_SRC.rglob("*") if p.suffix in (".c", ".h", ".inc"))


def functions(text: str) -> list[tuple[str, int, int]]:
    """(name, first line, last line), 1-based, of every function defined in
    clang-formatted C: a definition begins at column 0 with a declarator
    whose parameter list is followed by `{` (after continuation lines) and
    ends at the next `}` at column 0, or on its own line."""
    lines, found, i, in_comment = text.splitlines(), [], 0, False
    while i < len(lines):
        line = lines[i]
        if in_comment or line.lstrip().startswith("/*"):
            in_comment = "*/" not in line
            i += 1
            continue
        if not re.match(r"[A-Za-z_]", line) or re.match(r"(typedef|struct|enum|union|extern)\b", line):
            i += 1
            continue
        j = i   # the declarator's last line: the first that ends with {, ; or }, or
        #         the last before a line that does not continue it (indented)
        while (j + 1 < len(lines) and not re.search(r"[{;}]\s*(/\*.*\*/)?\s*$", lines[j])
               and re.match(r"\s+\S", lines[j + 1])):
            j += 1
        head = re.sub(r"/\*.*?\*/", "", " ".join(s.strip() for s in lines[i:j + 1])).strip()
        m = re.match(r"[^=;{]*?\b(\w+)\s*\([^{;]*\)\s*\{", head)
        one_line = head.endswith("}") and head.count("{") == head.count("}")
        if not m or not (head.endswith("{") or one_line):
            i = j + 1
            continue
        if one_line:
            end = j
        else:
            end = next((k for k in range(j + 1, len(lines)) if lines[k].startswith("}")), None)
            assert end is not None, f"no closing brace at column 0 after line {i + 1}: {head[:60]}"
        found.append((m.group(1), i + 1, end + 1))
        i = end + 1
    return found


def all_functions() -> list[tuple[Path, str, int, int]]:
    return [(p, name, a, b) for p in c_files() for name, a, b in functions(p.read_text())]


def test_the_parser_finds_the_functions_it_should():
    """It cannot pass for finding nothing: it finds the functions it should,
    with their lengths, in a sample and in fmu_src/."""
    sample = ("/* a comment\n"
              "int not_this(void) {\n"
              "*/\n"
              "static const int TABLE[] = {1,\n"
              "                            2};\n"
              "typedef struct {\n"
              "    int x;\n"
              "} pair;\n"
              "MACRO(ITEMS)\n"
              "#define ROW(a, b) {a, b},\n"
              "MACRO(a, b)\n"
              "\n"
              "int f(int x) { return x + 1; }\n"
              "int g(int x);\n"
              "static OC_HOT double h(const double *a,\n"
              "                       int n) {\n"
              "    if (n) {\n"
              "        return a[0];\n"
              "    }\n"
              "    return 0;\n"
              "}\n")
    assert functions(sample) == [("f", 13, 13), ("h", 15, 21)]
    found = {(p.relative_to(FMU_SRC).as_posix(), name) for p, name, _, _ in all_functions()}
    for known in [("cells/cells.c", "cells_step"), ("glue/fmu_start_values.c", "fmu_load_start_values"),
                  ("glue/set_batch.inc", "SET_NAME"), ("law/contact_law.c", "oc_law_step"),
                  ("glue/fmu_values.c", "fmu_model_size"), ("glue/gen_model_description.c", "main"),
                  ("models/ContactPad/model.c", "fmu_model_do_step"), ("rig/rig_core.h", "rig_advance_on")]:
        assert known in found, known
    assert len(found) > 300


def test_no_function_outside_the_generator_is_longer_than_70_lines():
    long = [f"{p.relative_to(ROOT)}:{a}: {name}, {b - a + 1} lines"
            for p, name, a, b in all_functions()
            if b - a + 1 > MAX_FUNCTION_LINES and not p.name.startswith(GENERATOR)]
    assert long == [], "split these into named steps:\n" + "\n".join(long)


def test_no_file_of_fmu_src_is_longer_than_700_lines():
    files = [p for p in FMU_SRC.rglob("*") if p.is_file()]
    assert len(files) > 40
    long = [f"{p.relative_to(ROOT)}: {n} lines" for p in files
            if (n := len(p.read_text(errors="replace").splitlines())) > MAX_FILE_LINES]
    assert long == []


def includes(text: str) -> list[tuple[int, str]]:
    """(line, path) of every #include "path"."""
    return [(i + 1, m.group(1)) for i, line in enumerate(text.splitlines())
            if (m := re.match(r'\s*#\s*include\s+"([^"]+)"', line))]


def test_no_model_includes_from_another_models_folder():
    models = sorted(d.name for d in (FMU_SRC / "models").iterdir() if d.is_dir())
    assert {"OrthotropicContact", "ContactPatch", "ContactPad", "CarriageBlock"} <= set(models)
    crossing = [f"{p.relative_to(ROOT)}:{line}: {path}"
                for model in models for p in sorted((FMU_SRC / "models" / model).iterdir())
                if p.suffix in (".c", ".h", ".inc")
                for line, path in includes(p.read_text())
                if path.startswith("models/") and not path.startswith(f"models/{model}/")]
    assert crossing == []


def test_include_templates_are_named_inc_and_included_at_file_scope():
    """A header has its include guard; a file included more than once,
    without one, is a template, *.inc, and no file is included inside a
    function's body."""
    unguarded = [p.relative_to(ROOT).as_posix() for p in c_files() if p.suffix == ".h"
                 and not re.search(r"^#ifndef (\w+)\n#define \1\b", p.read_text(), re.M)]
    assert unguarded == []
    inside = [f"{p.relative_to(ROOT)}:{line}: {path}" for p in c_files()
              for spans in [functions(p.read_text())]
              for line, path in includes(p.read_text())
              if any(a < line < b for _, a, b in spans)]
    assert inside == []
    templates = {p.relative_to(FMU_SRC).as_posix() for p in c_files() if p.suffix == ".inc"}
    assert {"glue/set_batch.inc", "glue/fmi_both.inc", "cells/cells_model.inc"} <= templates
    used = {path for p in c_files() for _, path in includes(p.read_text())}
    assert templates <= used, templates - used


def test_the_checks_see_a_long_function_an_include_inside_one_and_a_crossing():
    body = "int f(void) {\n" + "    x();\n" * 70 + '#include "glue/set_batch.inc"\n}\n'
    spans = functions(body)
    assert spans == [("f", 1, 73)] and spans[0][2] - spans[0][1] + 1 > MAX_FUNCTION_LINES
    assert any(a < line < b for line, _ in includes(body) for _, a, b in spans)
    assert includes('#include "models/ContactPatch/cells.h"\n') == [(1, "models/ContactPatch/cells.h")]
