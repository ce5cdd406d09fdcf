"""The C sources follow the repository's .clang-format: `clang-format
--dry-run --Werror` over fmu_src/, master_src/, benchmarks/ (its own files,
not the peer's), tests/c/ and tests/fuzz/ finds nothing to change.  Format a
file with `clang-format -i FILE`; the style is the one the code was written
in (4-space indent, 100 columns)."""
import shutil
import subprocess
from pathlib import Path

import pytest

from paths import ROOT

C_SOURCES = ("fmu_src/**/*.[ch]", "master_src/*.[ch]", "benchmarks/*.[ch]", "tests/c/**/*.[ch]",
             "tests/fuzz/*.c")   # what .clang-format's comment names


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
