"""No comment or docstring names a file or folder that does not exist.

Every path-like token in the comments and docstrings of the code (python/,
tools/, tests/, benchmarks/, fmu_src/, master_src/, CMakeLists.txt,
Makefile) resolves: against the repository's root, the file's folder or one
of its parents, or the package (python/orthocontact/); a bare file name
(no slash) as the name of some file of the repository.  A name the code
itself uses outside its comments (a file a command writes, a generated
header) is not a stale reference either; what is left is in NOT_IN_THE_TREE."""
import io
import re
import subprocess
import tokenize
from pathlib import Path

import pytest

from paths import PKG, ROOT

SCOPE = ("python/", "tools/", "tests/", "benchmarks/", "fmu_src/", "master_src/")
TOP = ("CMakeLists.txt", "Makefile")

# Names that are neither in the tree nor in its code: system headers, the
# build tree and the placeholders of examples.
NOT_IN_THE_TREE = {
    "sysexits.h", "linux/prctl.h", "linux/fs.h",       # system headers
    "build/python/orthocontact/",                      # CMake's staging of the package
    "INPUT.csv", "s.toml", "file.py", "out/", "folder/forces/",  # an example's placeholders
}

# A file name with one of these extensions, or a folder path ending in a
# slash; not part of a longer token or of a placeholder (<run>/x.csv,
# {name}/x, *.csv).
EXT = r"(?:py|c|h|inc|md|toml|json|csv|sh|txt|xml|html|cmake)"
FILE = re.compile(r"(?<![\w./<>{}*$-])((?:[\w.-]+/)*[\w-][\w.-]*\." + EXT + r")(?![\w/])")
FOLDER = re.compile(r"(?<![\w./<>{}*$-])((?:[\w.-]*[A-Za-z][\w.-]*/)+)(?=[\s)\]`'\",;:]|\.\s|\.$|$)")


def files() -> list[str]:
    out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                         cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    return [f for f in out if (ROOT / f).is_file()]


def split(path: str, text: str) -> tuple[str, list[tuple[int, str]]]:
    """(the code without its comments and docstrings, [(line, comment or docstring)])."""
    if path.endswith(".py"):
        notes, code, prev = [], [], tokenize.NEWLINE
        for tok in tokenize.generate_tokens(io.StringIO(text).readline):
            doc = tok.type == tokenize.STRING and prev in (tokenize.NEWLINE, tokenize.INDENT,
                                                           tokenize.DEDENT, tokenize.NL)
            (notes if tok.type == tokenize.COMMENT or doc else code).append((tok.start[0], tok.string))
            if tok.type not in (tokenize.COMMENT, tokenize.NL):
                prev = tok.type
        return " ".join(s for _, s in code), notes
    if path.endswith((".c", ".h", ".inc")):
        pattern = r'"(?:\\.|[^"\\\n])*"|/\*.*?\*/|//[^\n]*'
    else:   # shell, CMake, Make, TOML
        pattern = r'"(?:\\.|[^"\\\n])*"|(?:(?<=\s)|^)#[^\n]*'
    notes, code, at = [], [], 0
    for m in re.finditer(pattern, text, re.S | re.M):
        if m.group(0).startswith('"'):
            continue
        code.append(text[at:m.start()])
        notes.append((text.count("\n", 0, m.start()) + 1, m.group(0)))
        at = m.end()
    return "".join(code) + text[at:], notes


def named_paths(comment: str) -> list[str]:
    """The path-like tokens of a comment (a trailing full stop dropped)."""
    return [m.group(1) for m in FILE.finditer(comment)] + [m.group(1) for m in FOLDER.finditer(comment)]


def scanned(tree: list[str]) -> dict[str, str]:
    """{path: text} of the files whose comments are checked."""
    return {f: (ROOT / f).read_text(errors="replace") for f in tree
            if (f.startswith(SCOPE) and f.endswith((".py", ".c", ".h", ".inc", ".sh", ".cmake", ".toml")))
            or f in TOP}


def unresolved(texts: dict[str, str], tree: list[str]) -> list[str]:
    """path:line: token of every path named in the comments of `texts` that
    does not resolve in the repository whose files are `tree`."""
    names = {Path(f).name for f in tree} | {Path(d).name for f in tree for d in Path(f).parents}
    parts = {f: split(f, text) for f, text in texts.items()}
    code = "\n".join(c for c, _ in parts.values())
    bad = []
    for f, (_, notes) in parts.items():
        bases = [ROOT, *(ROOT / f).parents, PKG]
        for line, note in notes:
            for token in named_paths(note):
                bare = token.strip("/")
                if "/" not in bare and bare in names or token in NOT_IN_THE_TREE:
                    continue
                if any((b / bare).exists() for b in bases):
                    continue
                if re.search(r"(?<![\w.-])" + re.escape(bare) + r"(?![\w-])", code):
                    continue   # a name the code uses: a file it writes or generates
                bad.append(f"{f}:{line}: {token}")
    return bad


def test_no_comment_or_docstring_names_a_file_that_does_not_exist():
    tree = files()
    assert unresolved(scanned(tree), tree) == []


@pytest.mark.parametrize("comment,found", [
    ("see docs/model-notes.md, erratum 1", ["docs/model-notes.md"]),
    ("# the order rig.py writes it; cmaster.py and fmu_src/ too.", ["rig.py", "cmaster.py", "fmu_src/"]),
    ("eq. (37): l = eps1 mu1/(eps2 mu2), 1/2 of it, <run>/x.csv, *.csv, .py files", []),
])
def test_the_scan_finds_the_paths_of_a_comment(comment, found):
    assert named_paths(comment) == found


def test_the_scan_reports_a_stale_name_and_passes_a_real_one():
    fake = "python/orthocontact/fake.py"
    text = ('"""Names fmu_src/law/contact_law.h, closed_forms/paper.py, conftest.py and\n'
            'nowhere/cmaster.py."""\n'
            'NAME = "written.json"  # the file it writes, written.json; not docs/gone/\n')
    assert unresolved({fake: text}, files()) == [f"{fake}:1: nowhere/cmaster.py", f"{fake}:3: docs/gone/"]
