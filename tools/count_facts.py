#!/usr/bin/env python3
"""Counts where facts of the code are typed by hand ("each fact once"):
every place that spells out the law's six parameters together, maps
the sliding rules to their numbers, lists the models, lists a model's
sources, names the closed forms a scenario can name together (a list or a
dispatch), or types an FMI function's name as a string in the glues.
CONTRIBUTING.md quotes its figures; tests/contracts/test_facts.py holds the
quote to the count and the counter to the rules below.

    python3 tools/count_facts.py            the table of counts
    python3 tools/count_facts.py --places   and where each place is

Comments and docstrings are left out (they change nothing when a fact
does).  The six parameters are counted in the order mu1, mu2, eps1, eps2,
alpha, beta, each at most GAP lines after the one before, as names with any
prefix or suffix of other characters than letters and digits (p.mu1,
OC_VR_mu1, "mu1", alpha_deg).  A place is counted ("code") unless it is in
one of the categories set aside: the variable tables (their one home:
fmu_src/models/<model>/table.h and the law's rows in fmu_src/law/), the closed forms (formulas of the physics,
closed_forms.paper.of_law the one place that spreads a law over their
arguments), tests, the independent references (benchmarks/peer/,
tools/rig_reference.py and tools/make_recordings.py, which import nothing of
the package: the test checks), data (scenario files) and source generated
from the tables (python/orthocontact/fmu/generated.py: tools/make_generated.py
writes it, tests/fmu/test_generated.py holds it to the tables).  The closed forms'
names are counted as quoted strings ("eq11", "mat", ...): two or more, each
within GAP_FORMS lines of the one before, make a place."""
from __future__ import annotations

import io
import re
import subprocess
import sys
import tokenize
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SIX = ("mu1", "mu2", "eps1", "eps2", "alpha", "beta")
GAP = 3  # lines between two consecutive names of one place
CODE = re.compile(r"\.(py|c|h|inc|sh|toml|cmake)$|(^|/)(CMakeLists\.txt|Makefile)$")
ASIDE = (  # (category, path pattern), first match wins; the rest is "code"
    ("table", r"^fmu_src/models/\w+/table\.h$|^fmu_src/law/law_table\.h$"),
    ("closed forms", r"^python/orthocontact/closed_forms/"),
    ("tests", r"^tests/"),
    ("independent references", r"^benchmarks/peer/|^tools/(rig_reference|make_recordings)\.py$"),
    ("data", r"^scenarios/"),
    ("generated", r"^python/orthocontact/fmu/generated\.py$"),   # tools/make_generated.py writes it
    ("this counter", r"^tools/count_facts\.py$"),
)


def category(path: str) -> str:
    for name, pattern in ASIDE:
        if re.search(pattern, path):
            return name
    return "code"


def _python_code(text: str) -> str:
    """The source with comments and docstrings blanked (lines kept)."""
    lines = text.splitlines(keepends=True)
    out = [list(line) for line in lines]
    try:
        tokens = list(tokenize.generate_tokens(io.StringIO(text).readline))
    except (tokenize.TokenError, SyntaxError):
        return text
    prev = tokenize.NEWLINE
    for tok in tokens:
        docstring = tok.type == tokenize.STRING and prev in (tokenize.NEWLINE, tokenize.INDENT,
                                                             tokenize.DEDENT, tokenize.NL)
        if tok.type == tokenize.COMMENT or docstring:
            (r0, c0), (r1, c1) = tok.start, tok.end
            for r in range(r0, r1 + 1):
                row = out[r - 1]
                a = c0 if r == r0 else 0
                b = c1 if r == r1 else len(row)
                for k in range(a, min(b, len(row))):
                    if row[k] != "\n":
                        row[k] = " "
        if tok.type not in (tokenize.COMMENT, tokenize.NL):
            prev = tok.type
    return "".join("".join(row) for row in out)


def _c_code(text: str) -> str:
    """C with comments blanked, lines kept (string literals left alone)."""
    def blank(m):
        return re.sub(r"[^\n]", " ", m.group(0))
    return re.sub(r'"(?:\\.|[^"\\\n])*"|/\*.*?\*/|//[^\n]*',
                  lambda m: m.group(0) if m.group(0).startswith('"') else blank(m), text, flags=re.S)


def _hash_code(text: str) -> str:
    """Shell, CMake, TOML: '#' comments blanked."""
    return "\n".join(re.sub(r"(^|\s)#.*$", "", line) for line in text.splitlines())


def code_of(path: str, text: str) -> str:
    if path.endswith(".py"):
        return _python_code(text)
    if path.endswith((".c", ".h", ".inc")):
        return _c_code(text)
    return _hash_code(text)


def tracked_files() -> list[str]:
    out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                         cwd=ROOT, capture_output=True, text=True, check=True).stdout
    return sorted(f for f in out.split() if CODE.search(f) and (ROOT / f).is_file())


def six_places(path: str, lines: list[str]) -> list[tuple[int, int]]:
    """(first line, last line), 1-based, of each place naming the six in order."""
    pat = re.compile(r"(?<![A-Za-z0-9])(" + "|".join(SIX) + r")(?![A-Za-z0-9])")
    toks = [(i, m.group(1)) for i, line in enumerate(lines) for m in pat.finditer(line)]
    places, last_end = [], -1
    for k, (i0, name) in enumerate(toks):
        if name != SIX[0] or i0 <= last_end:
            continue
        want, line = 1, i0
        for i, n in toks[k + 1:]:
            if i - line > GAP or want == len(SIX):
                break
            if n == SIX[want]:
                want, line = want + 1, i
        if want == len(SIX):
            places.append((i0 + 1, line + 1))
            last_end = line
    return places


def window_places(lines: list[str], patterns: list[str], span: int) -> list[tuple[int, int]]:
    """Places where every pattern matches within `span` consecutive lines."""
    places, i = [], 0
    while i < len(lines):
        window = lines[i:i + span]
        if re.search(patterns[0], lines[i]) and all(
                any(re.search(p, w) for w in window) for p in patterns[1:]):
            last = max(i + k for k, w in enumerate(window) if any(re.search(p, w) for p in patterns))
            places.append((i + 1, last + 1))
            i = last + 1
        else:
            i += 1
    return places


RULES = [r"(?i)associated", r"(?i)coupled", r"(?i)eq20", r"\b[123]\b"]
RULE_RANGE = [r"rule\s*[<>]=?\s*[13]\b|\b1, 2 or 3\b"]
MODELS = [r"OrthotropicContact", r"CarriageBlock"]
SOURCES = ([r"contact_law\.c", r"OrthotropicContact/model\.c"], [r"CarriageBlock/model\.c", r"rig_core\.c"])
FORM_NAMES = ("general", "eq11", "eq25", "eq31", "eq33", "mat")
GAP_FORMS = 4   # lines between two consecutive names of one place
FMI_LITERAL = re.compile(r'"fmi[23][A-Z][A-Za-z0-9]*')
GLUES = ("fmu_src/glue/fmi2_glue.c", "fmu_src/glue/fmi3_glue.c")


def form_places(lines: list[str]) -> list[tuple[int, int]]:
    """Places where two or more of the closed forms' names stand as quoted
    strings, each within GAP_FORMS lines of the one before (a list, a choice or
    a dispatch)."""
    pat = re.compile(r"[\"'](" + "|".join(FORM_NAMES) + r")[\"']")
    hits = [(i, m.group(1)) for i, line in enumerate(lines) for m in pat.finditer(line)]
    places, k = [], 0
    while k < len(hits):
        first, names, last, j = hits[k][0], {hits[k][1]}, hits[k][0], k + 1
        while j < len(hits) and hits[j][0] - last <= GAP_FORMS:
            names.add(hits[j][1])
            last = hits[j][0]
            j += 1
        if len(names) >= 2:
            places.append((first + 1, last + 1))
        k = j
    return places


def count() -> dict[str, list[tuple[str, int, int]]]:
    found: dict[str, list[tuple[str, int, int]]] = {k: [] for k in (
        "six", "rules", "models", "sources", "forms", "fmi")}
    for path in tracked_files():
        text = (ROOT / path).read_text(errors="replace")
        lines = code_of(path, text).splitlines()
        for a, b in six_places(path, lines):
            found["six"].append((path, a, b))
        for a, b in window_places(lines, RULES, 4) + window_places(lines, RULE_RANGE, 1):
            found["rules"].append((path, a, b))
        for a, b in window_places(lines, MODELS, 10):
            found["models"].append((path, a, b))
        for a, b in sorted(set(window_places(lines, SOURCES[0], 4) + window_places(lines, SOURCES[1], 4))):
            found["sources"].append((path, a, b))
        for a, b in form_places(lines):
            found["forms"].append((path, a, b))
        if path in GLUES:
            for i, line in enumerate(lines):
                if line.lstrip().startswith("#include"):
                    continue  # the standard's header, not a function's name
                for _ in FMI_LITERAL.finditer(line):
                    found["fmi"].append((path, i + 1, i + 1))
    return found


TITLES = {
    "six": "places spelling out mu1, mu2, eps1, eps2, alpha, beta together",
    "rules": "places mapping the sliding rules to their numbers",
    "models": "places listing the models (OrthotropicContact with CarriageBlock)",
    "sources": "places listing a model's sources (contact_law.c with the contact's model.c, "
               "the rig's model.c with rig_core.c)",
    "forms": "places naming the closed forms' names together (a list or a dispatch)",
    "fmi": "FMI function names typed as string literals in the two glues",
}


def main(argv: list[str]) -> int:
    show = "--places" in argv
    found = count()
    for key, title in TITLES.items():
        places = found[key]
        by = Counter(category(p) for p, _, _ in places)
        files = sorted({p for p, _, _ in places if category(p) == "code"})
        aside = ", ".join(f"{n} {c}" for c, n in sorted(by.items()) if c != "code")
        print(f"{by.get('code', 0):4d}  {title}" + (f"  (aside: {aside})" if aside else ""))
        print(f"      in {len(files)} files")
        if show:
            for p, a, b in places:
                print(f"        {category(p):24s} {p}:{a}" + (f"-{b}" if b != a else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
