"""The command's lines on stderr besides its results: a note, which is no
warning, and warnings, which --strict counts (exit 1 for any)."""
from __future__ import annotations

import sys

_warnings: list[str] = []


def note(line: str) -> None:
    """One line on stderr that is no warning (--strict does not count it)."""
    print(f"orthocontact: {line}", file=sys.stderr, flush=True)


def warnings_said() -> int:
    """How many warnings this command has printed."""
    return len(_warnings)


def forget_warnings() -> None:
    _warnings.clear()


def warn(line: str) -> None:
    """One warning line on stderr; --strict turns any into exit status 1."""
    _warnings.append(line)
    print(f"orthocontact: warning: {line}", file=sys.stderr, flush=True)
