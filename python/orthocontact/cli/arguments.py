"""The command line's arguments checked as they are read, each bad one a
line and exit 2 before any work (number, positive_int, positive_float,
count, angle_deg, seed, out_path, workers; Parser's one-line errors), and
--version (VersionAction: the package's and every installed FMU's)."""
from __future__ import annotations

import argparse
from pathlib import Path


def number(convert, expected, in_range, expected_in_range=None):
    """An argparse type: `convert` (int or float) the text, then `in_range`
    its value; either failing is one line, `expected ..., got ...` (a float
    out of range as typed: 1e400, not inf; a whole number as read)."""
    def parse(text):
        try:
            x = convert(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}") from None
        if not in_range(x):
            shown = x if convert is int else text
            raise argparse.ArgumentTypeError(f"expected {expected_in_range or expected}, got {shown}")
        return x
    return parse


def positive_int(what):
    return number(int, f"a whole number of {what} >= 1", lambda n: n >= 1)


positive_float = number(float, "a number > 0", lambda x: 0 < x < float("inf"), "a finite number > 0")
count = number(int, "a whole number >= 0", lambda n: n >= 0)
# nan and inf fail the range too
angle_deg = number(float, "an angle in degrees", lambda x: -360.0 <= x <= 360.0,
                   "a finite angle in [-360, 360] degrees")
# numpy's generators take no negative seed
seed = number(int, "a whole number >= 0", lambda n: n >= 0)


def out_path(text):
    # Path("") is the current folder: an unset shell variable ($OUT) would
    # scatter the results into wherever the command was started.
    if not text.strip():
        raise argparse.ArgumentTypeError("expected a path, got an empty one (an unset shell variable?); "
                                         "write . for the current folder")
    return Path(text)


def workers(text):
    # Checked here, before any work, for every command that takes --workers:
    # above the machine's bound a run would fork until memory runs out.
    from ..runtime import check_workers
    n = positive_int("worker processes")(text)
    try:
        return check_workers(n)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def version_text() -> str:
    """The package's version and every installed FMU with the `version` its
    model description states; an FMU of another version is named as such (a
    stale install), not passed over."""
    from ..fmu import find_fmu, model_description, models
    from ..version import __version__
    lines = [f"orthocontact {__version__}"]
    for model in models().values():
        for v in (2, 3):
            try:
                path = find_fmu(fmi_version=v, model=model)
                md = model_description(path)
                note = "" if md.version == __version__ else \
                    f" -- differs from the package's {__version__}: reinstall (pip install .)"
                lines.append(f"  FMI {md.fmiVersion} FMU: {model} {md.version} ({path}){note}")
            except FileNotFoundError as e:
                lines.append(f"  FMI {v}.0 FMU: {model} not found ({e})")
            except Exception as e:  # fmpy raises plain Exception for a broken FMU
                lines.append(f"  FMI {v}.0 FMU: {model} unreadable ({e})")
    return "\n".join(lines)


class VersionAction(argparse.Action):
    def __init__(self, option_strings, dest, **kw):
        super().__init__(option_strings, dest, nargs=0, help=kw.get("help"))

    def __call__(self, parser, namespace, values, option_string=None):
        print(version_text())
        parser.exit(0)


class Parser(argparse.ArgumentParser):
    """Bad arguments are one line, as every other input error (exit 2); the
    usage is one --help away."""

    def error(self, message):
        self.exit(2, f"orthocontact: error: {self.prog}: {message} (see {self.prog} --help)\n")
