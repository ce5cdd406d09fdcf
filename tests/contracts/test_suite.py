"""The test suite's own contracts: a test skips only for a missing optional
part (tests/optional_parts.py), which the session's summary reports and which
fails the session where it is required (CI, `make test`); and no test,
benchmark or tool speaks of the tracker's issues instead of what it tests."""
import os
import re
import subprocess
import sys
from pathlib import Path

from paths import ROOT, TESTS

# -- the optional parts' summary, on a tiny generated suite --------------------------

CONFTEST = f"""
import sys
sys.path.insert(0, {str(TESTS)!r})
from optional_parts import (PARTS, Part, pytest_addoption, pytest_configure, pytest_runtest_setup,
                            pytest_sessionfinish, pytest_terminal_summary, pytest_testnodedown)
PARTS.clear()
PARTS["here"] = Part("here", "a part that is installed", lambda: None)
PARTS["gone"] = Part("gone", "a part that is missing", lambda: "no module named gone")
PARTS["unused"] = Part("unused", "a part no test needs", lambda: "not looked for")
PARTS["platform"] = Part("platform", "a platform's condition", lambda: "not root", required=False)
"""

TESTS_PY = """
import pytest

@pytest.mark.needs("here")
def test_with_here():
    assert True

@pytest.mark.needs("gone")
def test_with_gone():
    raise AssertionError("never runs")

@pytest.mark.needs("platform")
def test_on_the_platform():
    raise AssertionError("never runs")

def test_plain():
    assert True
"""


def session(tmp_path, *args, ci=None, body=TESTS_PY):
    """pytest on the tiny suite in a child process: (exit status, output)."""
    (tmp_path / "pytest.ini").write_text("[pytest]\n")
    (tmp_path / "conftest.py").write_text(CONFTEST)
    (tmp_path / "test_tiny.py").write_text(body)
    env = {k: v for k, v in os.environ.items() if k != "CI"}
    if ci is not None:
        env["CI"] = ci
    # (hypothesis's plugin, where installed, takes a second to load)
    p = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-p", "no:hypothesispytest",
                        "-q", *args],
                       cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    return p.returncode, p.stdout


def summary(out):
    """The lines of the "optional parts" section (up to the next section or
    the counts' line)."""
    lines = out.splitlines()
    start = next(i for i, line in enumerate(lines) if "optional parts" in line and line.startswith("="))
    rest = lines[start + 1:]
    end = next((i for i, line in enumerate(rest)
                if line.startswith("=") or re.match(r"\d+ (passed|failed|skipped)", line)), len(rest))
    return rest[:end]


def test_a_missing_part_is_reported_not_run_and_the_session_passes_where_not_required(tmp_path):
    status, out = session(tmp_path)
    assert status == 0, out
    assert summary(out) == [
        "here (a part that is installed): ran",
        "gone (a part that is missing): NOT RUN: no module named gone",
        "unused (a part no test needs): not needed by the tests selected",
        "platform (a platform's condition): NOT RUN: not root (never required)",
    ]
    assert "2 passed, 2 skipped" in out


def test_a_missing_required_part_fails_the_session_in_ci_and_with_require_parts(tmp_path):
    for args, ci in (((), "true"), (("--require-parts",), None), (("--require-parts",), "false")):
        status, out = session(tmp_path, *args, ci=ci)
        assert status == 1, (args, ci, out)
        assert summary(out)[-1].startswith("FAILED: required here but not run: gone (installed by "), out
        assert "platform" not in summary(out)[-1]   # a platform's condition is never required


def test_in_worker_processes_the_summary_is_the_workers_and_a_required_part_still_fails(tmp_path):
    """make check's pytest-xdist workers: each records its parts, the
    controller's summary and verdict are those of a session in one process."""
    status, out = session(tmp_path, "-n", "2")
    assert status == 0 and "2 passed, 2 skipped" in out, out
    assert summary(out) == [
        "here (a part that is installed): ran",
        "gone (a part that is missing): NOT RUN: no module named gone",
        "unused (a part no test needs): not needed by the tests selected",
        "platform (a platform's condition): NOT RUN: not root (never required)",
    ]
    status, out = session(tmp_path, "-n", "2", ci="true")
    assert status == 1 and summary(out)[-1].startswith("FAILED: required here but not run: gone"), out


def test_a_required_part_the_selected_tests_do_not_need_fails_nothing(tmp_path):
    status, out = session(tmp_path, "-k", "not gone", ci="true")
    assert status == 0, out
    assert "gone (a part that is missing): not needed by the tests selected" in summary(out)


def test_a_failing_test_with_its_part_installed_is_a_failure_not_a_skip(tmp_path):
    body = TESTS_PY.replace("def test_with_here():\n    assert True",
                            "def test_with_here():\n    assert False, 'our code broke'")
    status, out = session(tmp_path, body=body)
    assert status == 1 and "1 failed" in out and "our code broke" in out, out
    assert "here (a part that is installed): ran" in summary(out)


def test_a_module_that_needs_a_missing_part_is_skipped_whole_and_reported(tmp_path):
    body = "from optional_parts import need\nneed('gone', module_level=True)\n\ndef test_x():\n    pass\n"
    (tmp_path / "test_other.py").write_text("def test_y():\n    pass\n")
    status, out = session(tmp_path, body=body)
    assert status == 0 and "1 passed, 1 skipped" in out, out
    assert "gone (a part that is missing): NOT RUN: no module named gone" in summary(out)
    status, out = session(tmp_path, body=body, ci="true")
    assert status == 1, out


# -- what installs them: pyproject's test extra, read by the set-up -----------------

def test_every_required_python_part_is_in_the_test_extra_the_test_command_installs():
    from optional_parts import PARTS
    from requirements import declared
    extra = {re.split(r"[<>=!~;\s]", r, maxsplit=1)[0].lower().replace("_", "-") for r in declared("test")}
    wanted = {p.distribution for p in PARTS.values() if p.required and p.distribution}
    assert wanted == {"libcosimpy", "ecospy", "fmu-manipulation-toolbox", "hypothesis"}
    # besides the optional parts: the runner and its workers for make check,
    # what tests import outright (jsonschema validates identified.json
    # against its schema), the linter make check runs first (ruff) and the
    # identification benchmark's peer (scipy: benchmarks/bench_fit.py)
    assert wanted | {"pytest", "pytest-xdist", "jsonschema", "ruff", "scipy"} == extra


def test_the_set_up_scripts_declare_no_requirement_of_their_own():
    """Every Python requirement is pyproject's, read by tools/requirements.py;
    bootstrap names tomli only to be able to read pyproject before 3.11."""
    for script, own in (("tools/bootstrap.sh", ["tomli>=1.1"]), ("tools/run_tests.sh", []), ("Makefile", [])):
        text = (ROOT / script).read_text()
        assert re.findall(r'"([A-Za-z0-9_.-]+ *(?:>=|==|~=|<=)[^"]*)"', text) == own, script


def test_only_the_requirements_not_satisfied_here_are_missing():
    from requirements import missing
    assert missing(["pytest>=1", "pytest>=999", "surely-not-installed-anywhere>=1",
                    "surely-not-installed-anywhere>=1; python_version<'3'"]) == \
        ["pytest>=999", "surely-not-installed-anywhere>=1"]


def test_a_requirement_pip_cannot_install_is_named_and_the_rest_still_installs(monkeypatch, capfd):
    """tools/requirements.py --install, what both set-up scripts call: the
    list pip refuses is retried one by one (offline: no index, so only the
    requirement already satisfied installs)."""
    from requirements import install
    monkeypatch.setenv("PIP_NO_INDEX", "1")
    assert install("test", ["pytest>=1", "surely-not-installed-anywhere>=1"]) == \
        ["surely-not-installed-anywhere>=1"]
    err = capfd.readouterr().err
    assert "requirements.py: surely-not-installed-anywhere>=1 not installed" in err
    assert "pytest>=1 not installed" not in err
    assert install("test", []) == []


# -- no skip but for a missing part --------------------------------------------------

SKIPPING = re.compile(r"pytest\.skip\(|importorskip|skipif|xfail|SkipTest|unittest\.skip")
# file -> the skips it may hold, each with why it is not our own failure
ALLOWED_SKIPS = {
    # after asserting an importer's own refusal of an FMI version (libcosim's of 3.0)
    "conformance/test_importers.py": 1,
}


def skips_in(tests: Path) -> dict:
    found = {}
    for f in sorted(tests.rglob("*.py")):
        rel = f.relative_to(tests).as_posix()
        if rel in ("optional_parts.py", "contracts/test_suite.py"):
            continue
        n = len(SKIPPING.findall(f.read_text()))
        if n:
            found[rel] = n
    return found


def test_no_test_skips_but_through_an_optional_part():
    assert skips_in(TESTS) == ALLOWED_SKIPS


def test_the_skip_scan_sees_every_way_to_skip(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "test_a.py").write_text(
        "import pytest\npytest.importorskip('x')\n@pytest.mark.skipif(True, reason='')\ndef test_a():\n"
        "    pytest.skip('crashed')\n@pytest.mark.xfail\ndef test_b():\n    pass\n")
    (tmp_path / "test_b.py").write_text("import pytest\n@pytest.mark.needs('libcosimpy')\ndef test_c():\n"
                                        "    pass\n")
    assert skips_in(tmp_path) == {"sub/test_a.py": 4}


# -- names say what they test ----------------------------------------------------------

# "issue 14", "issue #3", "the issue's ...", test_the_issues_..., issue14
ISSUE = re.compile(r"\bissues?\s+#?\d|\bthe\s+issue'?s\b|the_issues?_|\bissue_?\d", re.I)


def issue_mentions(root: Path) -> list:
    found = []
    for top in ("tests", "benchmarks", "tools"):
        for f in sorted((root / top).rglob("*")):
            if not f.is_file() or "__pycache__" in f.parts:
                continue
            rel = f.relative_to(root).as_posix()
            if rel == "tests/contracts/test_suite.py":   # its own examples
                continue
            if ISSUE.search(rel):
                found.append(rel)
            try:
                text = f.read_text()
            except (UnicodeDecodeError, OSError):
                continue
            found += [f"{rel}:{n}" for n, line in enumerate(text.splitlines(), 1) if ISSUE.search(line)]
    return found


def test_no_test_benchmark_or_tool_speaks_of_an_issue():
    assert issue_mentions(ROOT) == []


def test_the_issue_scan_sees_numbers_possessives_names_and_files(tmp_path):
    for top in ("tests", "benchmarks", "tools"):
        (tmp_path / top).mkdir()
    (tmp_path / "tests" / "test_x.py").write_text(
        "# fixed in issue 14\n# see Issue #3\n# the issue's case\ndef test_the_issues_figures():\n"
        "    pass\n# no documentation names an issue a reader cannot see\n")
    (tmp_path / "benchmarks" / "issue19.py").write_text("")
    (tmp_path / "tools" / "x.c").write_text("/* ---- issue 19: edges */\n")
    assert issue_mentions(tmp_path) == ["tests/test_x.py:1", "tests/test_x.py:2", "tests/test_x.py:3",
                                        "tests/test_x.py:4", "benchmarks/issue19.py", "tools/x.c:1"]
