"""The optional parts of the suite: the other FMU/SSP importers and tools
some tests need beyond the package's own dependencies.  A test names the part
it needs (`@pytest.mark.needs("libcosimpy")`, or `need("hypothesis")` at a
module's top); where the part is not usable its tests are skipped, and the
part is recorded as not run, with why.  At the end pytest prints one line per
part (ran / not run and why / not needed by the tests selected), and a
required part that did not run fails the session in CI (CI=true) and under
--require-parts (`make test`); `make check` runs without some.  Not
required: a platform's condition (root) and what the project does not
install (cffconvert, an FMI 3.0 libcosim).  Only a missing tool may skip a test here: a failure of our own
code, in a tool that is there, is a failure.

conftest.py hands pytest the hooks below (pytest_addoption, ...), the
`needs` marker's registration among them."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import pytest

INSTALLED_BY = "tools/run_tests.sh (pyproject's test extra; apt for the system parts)"


def _module(name: str) -> Callable[[], str | None]:
    """A probe importing `name` in a child process (libcosim's library and
    fmpy's loaded FMUs in one process have crashed): None if it imports,
    else the error's last line."""
    def probe() -> str | None:
        p = subprocess.run([sys.executable, "-c", f"import {name}"], capture_output=True, text=True,
                           timeout=120)
        if p.returncode == 0:
            return None
        lines = p.stderr.strip().splitlines()
        return lines[-1] if lines else f"import {name} exited {p.returncode}"
    return probe


def _qemu() -> str | None:
    if not shutil.which("qemu-aarch64"):
        return "qemu-aarch64 is not on PATH (apt: qemu-user)"
    if not Path("/usr/aarch64-linux-gnu/lib/ld-linux-aarch64.so.1").exists():
        return "no arm64 C library in /usr/aarch64-linux-gnu (apt: libc6-arm64-cross)"
    return None


def wine64() -> str | None:
    """The loader that runs a 64-bit Windows program: wine64 on PATH,
    Debian's (/usr/lib/wine/wine64, which its `wine` script calls), or a
    `wine` of the new WoW64 mode (wine >= 9, one loader for both); None if
    there is none."""
    for path in (shutil.which("wine64"), "/usr/lib/wine/wine64", shutil.which("wine")):
        if path and os.access(path, os.X_OK):
            return path
    return None


def _wine() -> str | None:
    path = wine64()
    if path is None:
        return "no wine64 (apt: wine64)"
    p = subprocess.run([path, "--version"], capture_output=True, text=True, timeout=60)
    return None if p.returncode == 0 else f"{path} --version exited {p.returncode}"


def _clang_format() -> str | None:
    """clang-format 14 or newer (the style's keys: .clang-format)."""
    path = shutil.which("clang-format")
    if path is None:
        return "clang-format is not on PATH (apt: clang-format)"
    p = subprocess.run([path, "--version"], capture_output=True, text=True, timeout=60)
    m = re.search(r"version (\d+)", p.stdout)
    return None if m and int(m.group(1)) >= 14 else f"{p.stdout.strip()!r}: 14 or newer needed"


def _root() -> str | None:
    return None if os.geteuid() == 0 else "mounting a tmpfs needs root"


@dataclass(frozen=True)
class Part:
    """One optional part: what needs it, and whether a session that must run
    everything fails without it (False: a platform condition or a tool the
    project cannot install alongside its own dependencies)."""
    name: str
    what: str
    probe: Callable[[], str | None] | None   # None: the test itself decides (record())
    required: bool = True
    distribution: str | None = None   # the Python distribution providing it (pyproject's test extra)


PARTS = {p.name: p for p in (
    Part("libcosimpy", "libcosim runs the FMUs and the SSPs", _module("libcosimpy.CosimExecution"),
         distribution="libcosimpy"),
    Part("ecospy", "Ecos runs the FMUs and the SSPs (its library needs libtbb12)", _module("ecospy"),
         distribution="ecospy"),
    Part("fmu_manipulation_toolbox", "the FMUs and the SSP in an FMU container",
         _module("fmu_manipulation_toolbox.assembly"), distribution="fmu-manipulation-toolbox"),
    Part("hypothesis", "the law's properties at every scale", _module("hypothesis"),
         distribution="hypothesis"),
    Part("qemu-aarch64", "the aarch64 Linux binary run under qemu-user", _qemu),
    Part("wine", "the win64 binaries run under wine64", _wine),
    Part("clang-format", "the C sources against .clang-format", _clang_format),
    Part("root", "a full disk, a read-only folder: tmpfs mounts", _root, required=False),
    Part("cffconvert", "CITATION.cff against the CFF schema", _module("cffconvert"), required=False),
    Part("libcosim-fmi3", "libcosim runs the FMI 3.0 FMUs like fmpy", None, required=False),
)}

# part -> None when it ran, else why not; only parts some test asked for.
STATUS: dict[str, str | None] = {}
_PROBED: dict[str, str | None] = {}


def usable(name: str) -> str | None:
    """None if the part is usable here, else why not (probed once a session)."""
    part = PARTS[name]
    if part.probe is None:
        raise ValueError(f"{name}: its test decides (record())")
    if name not in _PROBED:
        _PROBED[name] = part.probe()
    return _PROBED[name]


def record(name: str, why_not: str | None) -> None:
    """Records that the part ran (None) or did not (why); a part some test
    could not run stays not run."""
    if name not in PARTS:
        raise ValueError(f"no optional part {name!r}: add it to PARTS")
    if STATUS.get(name, None) is None:
        STATUS[name] = why_not


def need(name: str, module_level: bool = False) -> None:
    """Skips the calling test (its whole module with module_level) when the
    part is not usable, recording it as not run."""
    why = usable(name)
    record(name, why)
    if why is not None:
        pytest.skip(f"{name} not usable here: {why}", allow_module_level=module_level)


def required_here(config) -> bool:
    return bool(config.getoption("require_parts")) or \
        os.environ.get("CI", "").strip().lower() in ("true", "1", "yes")


def missing_required(config) -> list[str]:
    if not required_here(config):
        return []
    return [n for n, why in STATUS.items() if why is not None and PARTS[n].required]


def summary_lines(config) -> list[str]:
    lines = []
    for name, part in PARTS.items():
        if name not in STATUS:
            state = "not needed by the tests selected"
        elif STATUS[name] is None:
            state = "ran"
        else:
            state = f"NOT RUN: {STATUS[name]}" + ("" if part.required else " (never required)")
        lines.append(f"{name} ({part.what}): {state}")
    missing = missing_required(config)
    if missing:
        lines.append(f"FAILED: required here but not run: {', '.join(missing)} (installed by {INSTALLED_BY})")
    return lines


# -- the hooks conftest.py hands to pytest ---------------------------------------------

def pytest_addoption(parser):
    parser.addoption("--require-parts", action="store_true", dest="require_parts",
                     help="fail the session if an optional part a selected test needs is missing "
                          "(always so with CI=true)")


def pytest_configure(config):
    config.addinivalue_line("markers",
                            "needs(*parts): the optional parts the test needs (tests/optional_parts.py)")


def pytest_runtest_setup(item):
    for mark in item.iter_markers("needs"):
        for name in mark.args:
            need(name)


def pytest_sessionfinish(session, exitstatus):
    worker_output = getattr(session.config, "workeroutput", None)
    if worker_output is not None:   # a pytest-xdist worker (make check): the controller sums up
        worker_output["optional_parts"] = dict(STATUS)
        return
    if missing_required(session.config) and exitstatus in (pytest.ExitCode.OK,
                                                           pytest.ExitCode.NO_TESTS_COLLECTED):
        session.exitstatus = pytest.ExitCode.TESTS_FAILED


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    """pytest-xdist's controller: a worker's record of the parts joins the
    session's (a part not run on any worker is not run)."""
    for name, why_not in getattr(node, "workeroutput", {}).get("optional_parts", {}).items():
        record(name, why_not)


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    terminalreporter.section("optional parts")
    for line in summary_lines(config):
        terminalreporter.line(line, red=line.startswith("FAILED") or "NOT RUN" in line)
