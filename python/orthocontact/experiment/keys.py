"""One validator for the experiment's files: the keys of a scenario's tables
and of a lab's rig.toml are checked here, each against its type and range,
then against the plausible range of its unit (orthocontact.plausibility), with
one message style: '<file>: <key>: expected <what>, got <value>'.

The rig's keys (RIG_KEYS) are the fields of rig.harness.Rig, with what
each takes and its default from there; both files read them (rig_spec), a
file overriding a default where it must (rig.toml: the mass is required).
Angles are in degrees at this boundary, as the files write them
(experiment.geometry turns them into the law's radians).

A table's reader names every problem of the table, not only the first
(errors.Problems): one line each."""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields

from .. import plausibility
from ..errors import Problems
from ..rig import Rig

REQUIRED = object()  # a spec's default for a key that must be given


@dataclass(frozen=True)
class Number:
    """A checker for a finite number in [lo, hi] ((lo, hi] with lo_open; None
    unbounded); its range is readable (the property tests draw from it)."""
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False

    def __call__(self, v):
        return plausibility.number_problem(v, self.lo, self.hi, self.lo_open)


def number(lo=None, hi=None, lo_open=False) -> Number:
    """A checker for a finite number in [lo, hi] ((lo, hi] with lo_open)."""
    return Number(lo, hi, lo_open)


@dataclass(frozen=True)
class Choice:
    """A checker for one of `options`."""
    options: tuple

    def __call__(self, v):
        return None if v in self.options else "one of " + ", ".join(repr(o) for o in self.options)


def choice(options) -> Choice:
    return Choice(tuple(options))


@dataclass(frozen=True)
class AnyOf:
    """A checker for a value any of `checks` takes, `what` in words."""
    checks: tuple
    what: str

    def __call__(self, v):
        return None if any(c(v) is None for c in self.checks) else self.what


def text(v):
    return None if isinstance(v, str) else "a string"


def file_name(v):
    """A plain file name: what is written as <out>/<name>/ stays inside <out>."""
    if not isinstance(v, str):
        return "a string"
    bad = set('/\\:*?"<>|') | {chr(c) for c in range(32)}
    if not v.strip() or v in (".", "..") or v != v.strip() or any(c in bad for c in v):
        return ("a plain file name (letters, digits, - _ . and spaces inside; no path separator, "
                "no '..', none of : * ? \" < > |)")
    return None


def boolean(v):
    return None if isinstance(v, bool) else "true or false"


@dataclass(frozen=True)
class ListOf:
    """A checker for a list of at least min_len items each `item` takes;
    unique: no item twice (a list of runs whose outputs are keyed by the
    item: a repeat would run again and be lost in them)."""
    item: Callable
    min_len: int = 1
    unique: bool = False

    def __call__(self, v):
        if not isinstance(v, list) or len(v) < self.min_len:
            return f"a list of at least {self.min_len} item(s)"
        for x in v:
            why = self.item(x)
            if why:
                return f"a list whose items are {why}"
        if self.unique and len(set(v)) < len(v):
            return "a list without repeated items (each is run once)"
        return None


def list_of(item_check, min_len=1, unique=False) -> ListOf:
    return ListOf(item_check, min_len, unique)


POSITIVE = number(0, lo_open=True)
NON_NEGATIVE = number(0)
ANGLE_DEG = number(-360, 360)


def rig_key(f) -> Callable:
    """The checker of Rig's field `f` (a dataclasses.Field): what it takes."""
    options = f.metadata["options"]
    return choice(options) if options is not None else number(*f.metadata["range"])


# The rig's keys and their checkers: Rig's fields (mass [kg], g [m/s^2],
# F_int [N], velocity [m/s], travel [m], the strip's friction [-], the mode,
# the communication step [s], the fit's start [-] and the strip's viscosity
# [N s/m]).
RIG_KEYS = {f.name: rig_key(f) for f in fields(Rig)}


def rig_spec(omit=(), **defaults) -> dict:
    """{key: (checker, default)} of the rig's keys but those in `omit`, each
    with Rig's default unless `defaults` gives the file's own (REQUIRED for
    a key the file must give)."""
    return {f.name: (RIG_KEYS[f.name], defaults.get(f.name, f.default)) for f in fields(Rig)
            if f.name not in omit}


def read_table(path, where: str, data: dict, spec: dict, error, problems: Problems | None = None
               ) -> tuple[dict, list[str]]:
    """The table's values (defaults filled in) and its warnings.  Every
    problem is one line '<path>: <where><key>: ...' (`where` the table's
    prefix, 'rig.' or ''): an unknown key, a missing required one, a value
    of the wrong type or range, or one that cannot be right for its unit.
    They are added to `problems` where given (the values then lack the keys
    in question: a check across keys needs them all), else raised together
    as one error(lines)."""
    own = problems is None
    if own:
        problems = Problems(error)
    for key in data:
        if key not in spec:
            problems.add(f"{path}: {where}{key}: expected one of the known keys {', '.join(sorted(spec))}")
    out, warnings = {}, []
    for key, (check, default) in spec.items():
        if key not in data:
            if default is REQUIRED:
                problems.add(f"{path}: {where}{key}: expected a value (the key is required)")
            else:
                out[key] = default
            continue
        v = data[key]
        why = check(v)
        if why:
            problems.add(f"{path}: {where}{key}: expected {why}, got {v!r}")
            continue
        found = plausible(key, v)
        if found is not None:
            level, message = found
            if level == "error":
                problems.add(f"{path}: {where}{message}")
                continue
            warnings.append(f"{path}: {where}{message}")
        out[key] = v
    if own:
        problems.raise_any()
    return out, warnings


def plausible(key: str, v) -> tuple[str, str] | None:
    """The plausibility gate's finding for a key's value (a number, or a
    list of numbers: each item as the key's quantity, an angle list as a
    whole too), None if plausible or not a quantity with a unit."""
    numbers = [x for x in (v if isinstance(v, list) else [v])
               if isinstance(x, (int, float)) and not isinstance(x, bool)]
    angles = key.endswith("_deg") and key != "step_deg"
    if isinstance(v, list):
        found = next((f for i, x in enumerate(numbers)
                      if (f := plausibility.check(key, x, f"{key}[{i}]")) is not None), None)
        return found or (plausibility.check_angles_deg(key, numbers) if angles and numbers else None)
    if not numbers:
        return None
    found = plausibility.check(key, v)
    return found or (plausibility.check_angle_deg(key, v) if angles else None)
