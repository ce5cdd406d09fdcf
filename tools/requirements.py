#!/usr/bin/env python3
"""Prints requirements declared in pyproject.toml, one a line, for the
set-up scripts to install (tools/bootstrap.sh, tools/run_tests.sh): each list
is declared there only.

    requirements.py build            [build-system] requires
    requirements.py test             the `test` extra (any extra by its name)
    requirements.py test --missing   only those this Python does not satisfy
                                     (every one where `packaging` is not
                                     importable: pip then decides)
    requirements.py test --install   installs those into this Python (pip); a
                                     list pip refuses is retried one by one,
                                     so that the rest still installs; exit 1
                                     naming each that is not installed
"""
import argparse
import os
import subprocess
import sys
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:   # Python < 3.11: the package's own dependency
    import tomli as tomllib

PYPROJECT = Path(__file__).resolve().parents[1] / "pyproject.toml"


def declared(which: str) -> list:
    data = tomllib.loads(PYPROJECT.read_text())
    if which == "build":
        return list(data["build-system"]["requires"])
    extras = data["project"]["optional-dependencies"]
    if which not in extras:
        raise SystemExit(f"requirements.py: pyproject.toml has no extra {which!r} (has {sorted(extras)})")
    return list(extras[which])


def missing(requirements: list) -> list:
    """The requirements that apply here (their markers) and that no installed
    distribution satisfies."""
    try:
        from importlib.metadata import PackageNotFoundError, version

        from packaging.requirements import Requirement
    except ImportError:
        return requirements
    out = []
    for line in requirements:
        req = Requirement(line)
        if req.marker is not None and not req.marker.evaluate():
            continue
        try:
            have = version(req.name)
        except PackageNotFoundError:
            out.append(line)
            continue
        if not req.specifier.contains(have, prereleases=True):
            out.append(line)
    return out


def install(which: str, requirements: list) -> list:
    """Installs `requirements` into this Python with pip, all at once or,
    if pip refuses that, one by one; those not installed, each said on
    stderr."""
    if not requirements:
        return []
    print(f"requirements.py: {which} requirements into {os.path.relpath(sys.prefix)} "
          f"({', '.join(requirements)})", flush=True)

    def pip(reqs):
        return subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--disable-pip-version-check",
                               *reqs]).returncode == 0

    if pip(requirements):
        return []
    failed = [req for req in requirements if not pip([req])]
    for req in failed:
        print(f"requirements.py: {req} not installed", file=sys.stderr)
    return failed


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("which", help="build, or the name of an extra (test)")
    ap.add_argument("--missing", action="store_true", help="only those not satisfied here")
    ap.add_argument("--install", action="store_true",
                    help="install those not satisfied here (pip); exit 1 if any is not installed")
    a = ap.parse_args(argv)
    reqs = declared(a.which)
    if a.install:
        return 1 if install(a.which, missing(reqs)) else 0
    for line in missing(reqs) if a.missing else reqs:
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
