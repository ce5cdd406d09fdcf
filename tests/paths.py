"""Where the tests find the repository: its root and the folders several
tests read, each named once here (the tests import them: `from paths import
ROOT, SCENARIOS`).  The C fixtures are the programs the FMU tests build and
run an FMU's binary with: tests/c/fmu_run.c (a native or a cross-compiled
host) and tests/c/fmi_script_host.c (the win64 host, under wine)."""
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TESTS = ROOT / "tests"
SCENARIOS = ROOT / "scenarios"            # the paper's scenarios and the example data
PKG = ROOT / "python" / "orthocontact"    # the package's source
DOCS = ROOT / "docs"
TOOLS = ROOT / "tools"
C_FIXTURES = TESTS / "c"
