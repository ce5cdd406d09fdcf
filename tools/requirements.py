#!/usr/bin/env python3
"""Prints requirements declared in pyproject.toml, one a line, for the
set-up scripts to install (tools/bootstrap.sh, tools/run_tests.sh): each list
is declared there only.

    requirements.py build            [build-system] requires
    requirements.py test             the `test` extra (any extra by its name)
    requirements.py test --missing   only those this Python does not satisfy
                                     (every one where `packaging` is not
                                     importable: pip then decides)
"""
import argparse
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


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("which", help="build, or the name of an extra (test)")
    ap.add_argument("--missing", action="store_true", help="only those not satisfied here")
    a = ap.parse_args(argv)
    reqs = declared(a.which)
    for line in missing(reqs) if a.missing else reqs:
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
