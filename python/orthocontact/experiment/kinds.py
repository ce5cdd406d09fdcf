"""The scenario kinds: one table, KINDS, a row (Kind) per kind, as
closed_forms.FORMS is for the closed forms.  No command, size check or
report compares a kind's name: each asks the scenario's row (kind_of).

A kind is written in pieces across the layers, and each piece joins the
kind's row where it is written:

- here (experiment): the kind's own tables of the scenario file with their
  keys, its checks across those keys, the FMU model it runs, whether it
  runs on the carriage rig and whether it sweeps mat angles there (what
  uq, an SSP, an export and the sensitivity study take);
- runs.size: its work estimate ("work"), every rig run `run` makes, with
  the keys that set it;
- reproduction: its runner ("run"), which runs it and writes its outputs
  into a folder, and its part of the reproduction report ("report").

Imports go down only, so this module knows none of the higher pieces: the
layer that writes one registers it into the row (`part`), and whoever asks
for it (Kind.part) has imported the module that registers it.  runs.size
asks for the estimates it registers itself; the commands and the report
import reproduction.kinds, which imports every module registering a
kind's reproduction pieces, and a test checks that every kind has every
piece (PARTS).  A new kind is a `kind(...)` row here and its pieces, each
registered where it is written; no other module names it."""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from ..errors import InputError, Problems
from ..fmu import (
    GEOMETRY,
    MODEL_IDENTIFIER,
    PAD_MODEL,
    PATCH_MODEL,
    RULES,
    cells_problem,
    find_fmu,
    foundation_problem,
    geometry_problem,
    geometry_range,
)
from ..rig import fit_steps_problem
from .keys import ANGLE_DEG, NON_NEGATIVE, POSITIVE, REQUIRED, boolean, choice, list_of, number

# The pieces of a kind written above this layer: what registers each, and
# what it is.
PARTS = {
    "work": "runs.size: a WorkEstimate, every rig run `orthocontact run` makes and the keys that set it",
    "run": "reproduction: run(sc, out, fmu_path, how: RunOptions) -> summary, its outputs written into out",
    "report": "reproduction.paper_report: a ReportPart, its section of report.md and report.json",
}


@dataclass
class Kind:
    """One scenario kind.  tables: its own tables of the scenario file,
    {table: {key: (checker, default)}} (experiment.keys); check(path,
    values, problems): its checks across keys, given its tables' values
    (a key whose own check failed is absent: a check that needs it is left
    out) and adding a line per problem; model: the FMU model it runs
    (fmu.files.find_fmu's model, and what a scenario's `fmu` key must name);
    carriage: its runs are the carriage rig's (rig.harness: rig.travel_m and
    rig.fit_from set them, so the default travel must settle for the law);
    mat_angles: it sweeps mat angles on the carriage rig (sc.sweep_angles()),
    which uq, an SSP, an export and the sensitivity study take.  parts: the
    pieces of the higher layers (PARTS)."""
    name: str
    tables: dict
    model: str
    carriage: bool
    mat_angles: bool = False
    check: Callable | None = None
    parts: dict = field(default_factory=dict)

    def part(self, what: str):
        """The piece `what` (PARTS) of this kind; LookupError if no module
        registered one (a bug: the asker did not import its module)."""
        try:
            return self.parts[what]
        except KeyError:
            raise LookupError(f"scenario kind {self.name!r} has no {what!r} piece: {PARTS[what]}; the "
                              "module that writes it is not imported") from None


KINDS: dict[str, Kind] = {}


def kind(name: str, **facts) -> Kind:
    """Puts the kind `name` with its facts (Kind's fields) into KINDS; a name
    given twice is an error."""
    if name in KINDS:
        raise ValueError(f"scenario kind {name!r} is written twice")
    KINDS[name] = Kind(name, **facts)
    return KINDS[name]


def register(name: str, what: str, piece) -> None:
    """Puts `piece` into the kind's row as its `what` (PARTS); twice is an error."""
    row = KINDS[name]
    if what not in PARTS or what in row.parts:
        raise ValueError(f"scenario kind {name!r}: {what!r} is not a piece (PARTS) or is registered twice")
    row.parts[what] = piece


def part(name: str, what: str):
    """Decorator: registers the function as the kind's piece `what`."""
    def put(f):
        register(name, what, f)
        return f
    return put


def kind_of(sc) -> Kind:
    """The row of the scenario's kind."""
    return KINDS[sc.kind]


def with_kinds(test: Callable[[Kind], bool]) -> str:
    """The names of the kinds with the property `test`, in words ('sweep',
    'sweep or twist')."""
    return " or ".join(k.name for k in KINDS.values() if test(k))


def require_mat_angles(sc, what: str, path=None) -> None:
    """InputError unless the scenario's kind sweeps mat angles on the
    carriage rig: what `what` (uq, an SSP) takes; `path` names the file
    (default: the scenario's)."""
    if not kind_of(sc).mat_angles:
        raise InputError(f"{path or sc.path}: kind: expected a {with_kinds(lambda k: k.mat_angles)} "
                         f"scenario for {what}, got {sc.kind!r}")


def fmu_for(sc, fmi_version: int) -> str:
    """The path of the FMU a command runs the scenario on: its own (`fmu`)
    if it names one, else the installed FMU of its kind's model and
    `fmi_version`.  A command resolves it once and passes the path down."""
    return sc.fmu or str(find_fmu(fmi_version=fmi_version, model=kind_of(sc).model))


@dataclass(frozen=True)
class RunOptions:
    """How a command runs a scenario (a runner's `how`): worker processes
    (None: the default), the rig's master ("auto", "c", "fmpy"), progress
    lines, the figure drawer (None: drawn here) and the Dask cluster (None:
    local processes)."""
    workers: int | None = None
    master: str = "auto"
    progress: bool = True
    draw: Callable | None = None
    dask: object = None


@dataclass(frozen=True)
class Section:
    """A section of the reproduction report (report.md) holding the
    scenarios of some kinds: its heading, the lines that open it, its key in
    report.json (None: none) and whether it is written without a scenario
    of its kinds."""
    title: str
    intro: tuple = ()
    json_key: str | None = None
    always: bool = False


@dataclass(frozen=True)
class ReportPart:
    """A kind's part of the reproduction report (its piece "report"): its
    Section; lines(sc, summary) its lines there; json(sc, summary) its entry
    under the section's json_key; rows(sc, summary) the paper's numbers it
    compares with (None: none)."""
    section: Section
    lines: Callable
    json: Callable | None = None
    rows: Callable | None = None


# -- the kinds -----------------------------------------------------------------------

RUN_RULES = ("associated", "coupled")   # the implicit rules a body on the patch runs under


def sweep_order(path, values: dict, problems: Problems) -> None:
    """A sweep's stop at or after its start."""
    sw = values["sweep"]
    if "start_deg" in sw and "stop_deg" in sw and sw["stop_deg"] < sw["start_deg"]:
        problems.add(f"{path}: sweep.stop_deg: expected a value >= sweep.start_deg = {sw['start_deg']}, "
                     f"got {sw['stop_deg']!r}")


kind("sweep", model=MODEL_IDENTIFIER, carriage=True, mat_angles=True, check=sweep_order, tables={"sweep": {
    "start_deg": (ANGLE_DEG, 0.0), "stop_deg": (ANGLE_DEG, 90.0), "step_deg": (POSITIVE, 1.0),
    "refine_extremum": (boolean, True),
    "trajectory_angles_deg": (list_of(ANGLE_DEG), [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0])}})

kind("step_study", model=MODEL_IDENTIFIER, carriage=True, tables={"study": {
    "angle_deg": (ANGLE_DEG, REQUIRED), "rules": (list_of(choice(tuple(RULES)), unique=True), REQUIRED),
    "steps_s": (list_of(POSITIVE, unique=True), REQUIRED)}})

# The contact rectangle under a body on the ContactPatch FMU (rig.planar).
PATCH = {"length_m": (POSITIVE, REQUIRED), "width_m": (POSITIVE, REQUIRED),
         "n1": (number(*geometry_range("n1")), 8), "n2": (number(*geometry_range("n2")), 8)}


def rectangle_problems(path, table: str, given: dict, problems: Problems) -> None:
    """A [patch] or [pad] table's sides and cells against the FMU's own
    ranges, and its cells in all (fmu.cells_problem)."""
    for name, key in zip(GEOMETRY, ("length_m", "width_m", "n1", "n2")):
        problem = geometry_problem(name, given[key]) if key in given else None
        if problem is not None:
            problems.add(f"{path}: {table}.{key}: {problem}")
    problem = cells_problem(given["n1"], given["n2"]) if "n1" in given and "n2" in given else None
    if problem is not None:
        problems.add(f"{path}: {table}.n1, {table}.n2: {problem}")


def patch_geometry(path, values: dict, problems: Problems) -> None:
    """The patch's sides and cells against the FMU's own ranges."""
    rectangle_problems(path, "patch", values["patch"], problems)


kind("twist", model=PATCH_MODEL, carriage=False, check=patch_geometry, tables={"patch": PATCH, "twist": {
    "angle_deg": (number(0, 360, lo_open=True), REQUIRED), "rate_deg_s": (POSITIVE, 10.0),
    "step_s": (number(0, 0.1, lo_open=True), 1e-3),
    "rules": (list_of(choice(RUN_RULES), unique=True), list(RUN_RULES))}})

kind("towed_block", model=PATCH_MODEL, carriage=False, check=patch_geometry, tables={"patch": PATCH, "tow": {
    "pin_m": (POSITIVE, REQUIRED), "duration_s": (POSITIVE, 20.0),
    "step_s": (number(0, 0.1, lo_open=True), 5e-3),
    "angles_deg": (list_of(ANGLE_DEG, unique=True), [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0]),
    "rules": (list_of(choice(RUN_RULES), unique=True), list(RUN_RULES))}})

# The pad under a body on the ContactPad FMU (rig.pushed): the patch's
# rectangle on a Winkler foundation of stiffness kn [N/m^3].
PAD = {**PATCH, "kn_N_m3": (POSITIVE, REQUIRED)}


def pad_geometry(path, values: dict, problems: Problems) -> None:
    """The pad's sides, cells and foundation against the FMU's own ranges."""
    pad = values["pad"]
    rectangle_problems(path, "pad", pad, problems)
    problem = foundation_problem("kn", pad["kn_N_m3"]) if "kn_N_m3" in pad else None
    if problem is not None:
        problems.add(f"{path}: pad.kn_N_m3: {problem}")


def pushed_block_problems(path, values: dict, problems: Problems) -> None:
    """The pad's (pad_geometry) and the push's: a step that leaves the
    trajectory angle something to measure (rig.pushed.fit_steps_problem)."""
    pad_geometry(path, values, problems)
    push = values["push"]
    if "travel_m" in push and "step_m" in push:
        problem = fit_steps_problem(push["travel_m"], push["step_m"])
        if problem is not None:
            problems.add(f"{path}: push.step_m: {problem}")


PUSH = {"heights_m": (list_of(NON_NEGATIVE, unique=True), REQUIRED),
        "angles_deg": (list_of(ANGLE_DEG, unique=True), [0.0, 30.0, 60.0, 90.0]),
        "travel_m": (POSITIVE, REQUIRED), "step_m": (POSITIVE, 1e-4)}

kind("pushed_block", model=PAD_MODEL, carriage=False, check=pushed_block_problems,
     tables={"pad": PAD, "push": PUSH})

# The pad rolling (reproduction.rolling_outputs): a wheel's or a belt roller's
# contact on the pad, pressed by load_N [N], its surface passing through at
# vr_m_s [m/s] along the pad's axis 1, the body creeping at each creepage
# (longitudinal and lateral) for rolled_lengths pad lengths at the Courant
# number courant (the material's passage per step in cells).
ROLL = {"load_N": (POSITIVE, REQUIRED), "vr_m_s": (POSITIVE, 1.0),
        "creepages": (list_of(number(0.0, 1.0), unique=True), REQUIRED),
        "angles_deg": (list_of(ANGLE_DEG, unique=True), [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0]),
        "rules": (list_of(choice(RUN_RULES), unique=True), list(RUN_RULES)),
        "courant": (number(0.0, 1.0, lo_open=True), 1.0), "rolled_lengths": (number(1.0, 100.0), 2.0)}

kind("rolling", model=PAD_MODEL, carriage=False, check=pad_geometry, tables={"pad": PAD, "roll": ROLL})


def roll_steps(roll: dict, n1: int) -> int:
    """The steps a rolling scenario holds each creepage for: its
    rolled_lengths pad lengths of n1 cells at courant cells a step."""
    return math.ceil(roll["rolled_lengths"] * n1 / roll["courant"] - 1e-9)
