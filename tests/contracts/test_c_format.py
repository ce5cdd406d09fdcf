"""The C sources' form: they follow the repository's .clang-format
(`clang-format --dry-run --Werror` over fmu_src/ (its include-templates,
*.inc, too), master_src/, benchmarks/
(its own files, not the peer's), tests/c/ and tests/fuzz/ finds nothing to
change; `clang-format -i FILE` formats one, in the style the code was
written in: 4-space indent, 100 columns), and no macro of fmu_src/ is
longer than MACRO_LINES lines (a table groups its rows a few to a macro, a
template is a file included twice, a long text a string)."""
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from paths import ROOT

MACRO_LINES = 15
C_SOURCES = ("fmu_src/**/*.[ch]", "fmu_src/**/*.inc", "master_src/*.[ch]", "benchmarks/*.[ch]",
             "tests/c/**/*.[ch]", "tests/fuzz/*.c")   # what .clang-format's comment names


def c_sources() -> list[Path]:
    """Every C file of C_SOURCES, in the repository."""
    files = sorted({p for pattern in C_SOURCES for p in ROOT.glob(pattern)})
    assert len(files) > 40, files   # the folders are where they were
    return files


def dry_run(files: list[Path], cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([shutil.which("clang-format"), "--dry-run", "--Werror", *map(str, files)],
                          cwd=cwd, capture_output=True, text=True, timeout=300)


@pytest.mark.needs("clang-format")
def test_every_c_source_is_formatted():
    p = dry_run(c_sources(), ROOT)
    findings = [line for line in p.stderr.splitlines() if ": error: " in line]
    assert p.returncode == 0, "clang-format -i to fix:\n" + "\n".join(findings[:20])


@pytest.mark.needs("clang-format")
def test_the_check_sees_a_file_out_of_style(tmp_path):
    shutil.copy(ROOT / ".clang-format", tmp_path / ".clang-format")
    (tmp_path / "good.c").write_text("int f(int x) { return x + 1; }\n")
    (tmp_path / "bad.c").write_text("int  f( int x ){\n  return x+1;}\n")
    assert dry_run([tmp_path / "good.c"], tmp_path).returncode == 0
    p = dry_run([tmp_path / "bad.c"], tmp_path)
    assert p.returncode != 0 and "bad.c" in p.stderr


def long_macros(text: str, limit: int = MACRO_LINES) -> list[tuple[int, str, int]]:
    """(line, name, lines) of each #define whose body, continued by
    backslashes, spans more than `limit` lines."""
    lines, found, i = text.splitlines(), [], 0
    while i < len(lines):
        m = re.match(r"\s*#\s*define\s+(\w+)", lines[i])
        if not m:
            i += 1
            continue
        j = i
        while j < len(lines) and lines[j].rstrip().endswith("\\"):
            j += 1
        if j - i + 1 > limit:
            found.append((i + 1, m.group(1), j - i + 1))
        i = j + 1
    return found


def test_no_macro_of_fmu_src_is_longer_than_15_lines():
    found = [f"{p.relative_to(ROOT)}:{line}: {name}, {n} lines"
             for p in sorted({*(ROOT / "fmu_src").rglob("*.[ch]"), *(ROOT / "fmu_src").rglob("*.inc")})
             for line, name, n in long_macros(p.read_text())]
    assert found == []


def test_the_macro_check_counts_continued_lines():
    def macro(n: int) -> str:
        """A #define of n lines."""
        return "#define M(a) \\\n" + "".join(f"    x{k}; \\\n" for k in range(n - 2)) + "    y;\n"
    assert long_macros(macro(MACRO_LINES)) == []
    assert long_macros("int a;\n" + macro(MACRO_LINES + 1)) == [(2, "M", MACRO_LINES + 1)]
