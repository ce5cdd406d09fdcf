"""Access to the ContactPatch FMU (FMI 2.0 or 3.0 Co-Simulation) through
fmpy: a rectangle length x width [m] of a rigid body on the textured surface,
n1 x n2 cells each the law with its own slip (fmu_src/models/ContactPatch/table.h).

Units: displacement u [m] of the patch centre and rotation theta [rad] of
the body relative to the surface; normal force N [N]; centre of pressure
(p1, p2) [m] in body coordinates; outputs T1, T2 [N] and Mz [N m] (the
surface's force and moment on the body at the patch centre, surface frame),
dissipatedEnergy [J].

Step semantics as the point FMU (fmu.contact): `set_inputs` computes every
cell's step from the committed state without committing it, so a master can
iterate on the pending result; `do_step` commits it."""
from __future__ import annotations

import math
from dataclasses import dataclass

from .contact import INITIAL_SLIP, FMUError
from .files import find_fmu, model_description
from .generated import (
    PATCH_FLOAT_OUTPUTS,
    PATCH_GEOMETRY,
    PATCH_INPUTS,
    PATCH_INTEGER_OUTPUTS,
    PATCH_MAX_CELLS,
    PATCH_MODEL,
)
from .param_checks import Row
from .params import ContactParams
from .slave import FreedOnClose, instantiate, integer_call

# The FMU's inputs and outputs, and the patch's geometry (its parameters the
# point contact has not), in the table's order: fmu/generated.py.
INPUTS = PATCH_INPUTS
OUTPUTS = PATCH_FLOAT_OUTPUTS          # read as reals; PATCH_INTEGER_OUTPUTS as integers
GEOMETRY = tuple(row.name for row in PATCH_GEOMETRY)


def table_row(rows: tuple[Row, ...], name: str, what: str) -> Row:
    """The row `name` of `rows` (a part of a model's table: the patch's
    geometry, the pad's foundation); KeyError `what` 'name' with the names
    there are (`what`, e.g. "ContactPatch has no geometry parameter")."""
    for row in rows:
        if row.name == name:
            return row
    raise KeyError(f"{what} {name!r} (it has {', '.join(row.name for row in rows)})")


def value_problem(row: Row, value) -> str | None:
    """What is wrong with `value` for the parameter of `row` by the FMU's
    own table: its type (a Float64 a finite number, an integer parameter an
    int) and its range [min, max] in the row's unit; None if it is right."""
    name = row.name
    count = row.type != "Float64"
    if isinstance(value, bool) or not isinstance(value, int if count else (int, float)) or \
            (not count and not math.isfinite(value)):
        return f"{name} must be {'an integer' if count else 'a finite number'}, got {value!r}"
    if (row.min is not None and value < row.min) or (row.max is not None and value > row.max):
        unit = f" {row.unit}" if row.unit else ""
        return f"{name} = {value!r}{unit} is outside [{row.min:g}, {row.max:g}]{unit}, the FMU's range"
    return None


def refuse_problems(record, rows: tuple[Row, ...]) -> None:
    """ValueError "<its class>: <problem>" for the first field of the
    dataclass `record` named by `rows` that its row refuses (value_problem):
    a frozen dataclass's __post_init__, before the FMU sees the value."""
    for row in rows:
        problem = value_problem(row, getattr(record, row.name))
        if problem is not None:
            raise ValueError(f"{type(record).__name__}: {problem}")


def geometry_row(name: str) -> Row:
    """The row of the patch's geometry parameter `name` (GEOMETRY) in the FMU's table."""
    return table_row(PATCH_GEOMETRY, name, f"{PATCH_MODEL} has no geometry parameter")


def geometry_range(name: str) -> tuple:
    """(min, max) of the patch's geometry parameter `name` in the FMU's table."""
    v = geometry_row(name)
    return v.min, v.max


def cells_start(name: str) -> int:
    """The table's start of the cell count `name` (n1, n2): PatchGeometry's default."""
    start = geometry_row(name).start
    if not isinstance(start, int):
        raise TypeError(f"{PATCH_MODEL}: {name}'s start {start!r} is no cell count")
    return start


def geometry_problem(name: str, value) -> str | None:
    """What is wrong with `value` for the patch's geometry parameter `name`
    (GEOMETRY) by the FMU's own table (value_problem: a length a finite
    number, a cell count an integer, in [min, max]); None if it is right."""
    return value_problem(geometry_row(name), value)


def cells_problem(n1, n2) -> str | None:
    """What is wrong with n1 x n2 cells in all (the FMU holds at most
    PATCH_MAX_CELLS), the sides each right; None if it is right."""
    if n1 * n2 > PATCH_MAX_CELLS:
        return f"n1 x n2 = {n1} x {n2} = {n1 * n2} cells: at most {PATCH_MAX_CELLS} cells in all"
    return None


@dataclass(frozen=True)
class PatchGeometry:
    """The patch: length along the body's axis 1, width along axis 2 [m];
    n1 x n2 cells.  A value the FMU's table refuses (geometry_problem)
    raises ValueError here, where the FMU would refuse it later with less
    context."""
    length: float
    width: float
    n1: int = cells_start("n1")   # the table's start, 8
    n2: int = cells_start("n2")

    def __post_init__(self):
        refuse_problems(self, PATCH_GEOMETRY)
        problem = cells_problem(self.n1, self.n2)
        if problem is not None:
            raise ValueError(f"PatchGeometry: {problem}")


class CellsFMU(FreedOnClose):
    """One instance of an FMU on the patch's cells, FMI 2.0 or 3.0: what the
    patch (PatchFMU) and the pad (fmu.pad.PadFMU) share.  A subclass names
    its MODEL, its INPUTS (all Float64, set together), its FLOAT_OUTPUTS and
    INTEGER_OUTPUTS, and LOAD: the outputs load() and derivative() read."""
    MODEL: str = PATCH_MODEL
    INPUTS: tuple = PATCH_INPUTS
    FLOAT_OUTPUTS: tuple = PATCH_FLOAT_OUTPUTS
    INTEGER_OUTPUTS: tuple = PATCH_INTEGER_OUTPUTS
    LOAD: tuple = ("T1", "T2", "Mz")

    def __init__(self, fmu_path=None, instance_name: str = "patch", fmi_version: int = 2):
        path = find_fmu(fmu_path, fmi_version, model=self.MODEL)
        self.path = path
        md = model_description(path)
        self.fmi_version = int(md.fmiVersion.split(".")[0])
        if self.fmi_version != fmi_version:
            raise ValueError(f"{path} is an FMI {self.fmi_version}.0 FMU, not {fmi_version}.0")
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.types = {v.name: v.type for v in md.modelVariables}
        self.messages: list[str] = []
        self.time = 0.0
        self.initialized = False
        self.shape = None   # (n1, n2), set by initialize
        self._slave, self._callbacks = instantiate(path, md, instance_name,
                                                   lambda status, category, text: self.messages.append(text))
        if self.fmi_version == 2:
            self._set_real, self._get_real = self._slave.setReal, self._slave.getReal
        else:
            self._set_real, self._get_real = self._slave.setFloat64, self._slave.getFloat64
        self._in_vr = [self.vr[n] for n in self.INPUTS]
        self._out_vr = [self.vr[n] for n in self.FLOAT_OUTPUTS]
        self._load_vr = [self.vr[n] for n in self.LOAD]

    def _call(self, what: str, fn, *args):
        """fmpy raises on an error status; the FMU's last logged line says why."""
        try:
            return fn(*args)
        except Exception as e:
            last = self.messages[-1] if self.messages else "(no message logged)"
            raise FMUError(f"{what} failed: {last}") from e

    def _set_integer(self, name: str, value: int):
        """By the function of its type: in FMI 3.0 n1, n2 are UInt64 (array
        dimensions), the enumerations Int64."""
        self._call(f"setting {name}", integer_call(self._slave, self.fmi_version, self.types[name]),
                   [self.vr[name]], [int(value)])

    def _start(self, params: ContactParams, geometry: PatchGeometry, reals: dict, inputs: tuple):
        """Sets the law's parameters, the geometry and the model's own `reals`
        {name: value}, the initial inputs (INPUTS' order) and enters step
        mode; every cell starts unloaded where the inputs put it
        (initialSlip = atInputs)."""
        law = params.fmu_values()
        rule = law.pop(params.RULE_VARIABLE)
        sizes = {row.name: float(getattr(geometry, row.name))
                 for row in PATCH_GEOMETRY if row.type == "Float64"}
        values = {**law, **sizes, **reals}
        self._call("setting parameters", self._set_real, [self.vr[n] for n in values],
                   list(values.values()))
        self._set_integer(params.RULE_VARIABLE, int(rule))
        self._set_integer("initialSlip", INITIAL_SLIP["atInputs"])
        for row in PATCH_GEOMETRY:
            if row.type != "Float64":
                self._set_integer(row.name, getattr(geometry, row.name))
        self.shape = (geometry.n1, geometry.n2)
        if self.fmi_version == 2:
            self._call("setupExperiment", self._slave.setupExperiment)
        self._call("enterInitializationMode", self._slave.enterInitializationMode)
        self._set_inputs(inputs)
        self._call("exitInitializationMode", self._slave.exitInitializationMode)
        self.initialized = True

    def _set_inputs(self, values, also: dict | None = None):
        """All INPUTS in one call (their order), with the Float64 inputs
        `also` names ({name: value}): the pending step, not committed."""
        names, refs = self.INPUTS, self._in_vr
        values = [float(v) for v in values]
        if also:
            names, refs = (*names, *also), [*refs, *(self.vr[n] for n in also)]
            values += [float(v) for v in also.values()]
        pairs = ", ".join(f"{n}={v}" for n, v in zip(names, values))
        self._call(f"setting inputs ({pairs})", self._set_real, refs, values)

    def outputs(self) -> dict:
        """FLOAT_OUTPUTS (T1, T2 [N], Mz [N m], dissipatedEnergy [J],
        slipFraction [-], ...) and contactState (0 open, 1 all stick, 2
        partly slipping, 3 all slipping) of the pending step."""
        out = dict(zip(self.FLOAT_OUTPUTS, self._call("getting outputs", self._get_real, self._out_vr)))
        get_int = self._slave.getInteger if self.fmi_version == 2 else self._slave.getInt32
        for name in self.INTEGER_OUTPUTS:
            out[name] = self._call(f"getting {name}", get_int, [self.vr[name]])[0]
        return out

    def _cells(self, name: str, get) -> list[list]:
        """The FMI 3.0 array `name` of the pending step, [i][j] the i-th cell
        along length, the j-th along width; FMI 2.0 has no arrays: ValueError."""
        if self.fmi_version != 3:
            raise ValueError(f"{self.path}: the cells' values are FMI 3.0 arrays ({name}); "
                             "FMI 2.0 has no arrays")
        if self.shape is None:
            raise ValueError(f"{name}: the FMU is not initialized yet (initialize sets n1, n2)")
        n1, n2 = self.shape
        flat = self._call(f"getting {name}", get, [self.vr[name]], n1 * n2)
        return [list(flat[i * n2:(i + 1) * n2]) for i in range(n1)]

    def cell_states(self) -> list[list[int]]:
        """Each cell's state in the pending step (0 open, 1 stick, 2 slip),
        [i][j] the i-th cell along length, the j-th along width: the FMI 3.0
        array cellState.  FMI 2.0 has no arrays: ValueError there."""
        return self._cells("cellState", getattr(self._slave, "getInt32", None))

    def load(self) -> tuple:
        """LOAD of the pending step ((T1, T2, Mz) [N, N, N m] for the patch)."""
        return tuple(self._call(f"getting {', '.join(self.LOAD)}", self._get_real, self._load_vr))

    def derivative(self, known: str) -> tuple:
        """d(LOAD)/d(known) of the pending step, known one of INPUTS (the
        FMU's consistent tangent)."""
        return tuple(self._call(f"getting d({', '.join(self.LOAD)})/d{known}",
                                self._slave.getDirectionalDerivative, self._load_vr, [self.vr[known]],
                                [1.0]))

    def do_step(self, h: float):
        """Commits the pending step; h [s] is the communication step size."""
        self._call(f"doStep(t={self.time}, h={h})", self._slave.doStep, self.time, h)
        self.time += h


class PatchFMU(CellsFMU):
    """One instance of the ContactPatch FMU, FMI 2.0 or 3.0."""

    def initialize(self, params: ContactParams, geometry: PatchGeometry,
                   inputs: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0),
                   centre_of_pressure: tuple[float, float] = (0.0, 0.0)):
        """Sets the law's parameters and the patch's, the initial inputs
        (u1 [m], u2 [m], theta [rad], N [N]) and enters step mode; every cell
        starts unloaded where the inputs put it (initialSlip = atInputs)."""
        if len(inputs) != 4:
            raise ValueError(f"inputs must be (u1 [m], u2 [m], theta [rad], N [N]), got {inputs!r}")
        self._start(params, geometry, {}, (*inputs, *centre_of_pressure))

    def set_inputs(self, u1: float, u2: float, theta: float, N: float, p1: float = 0.0,
                   p2: float = 0.0):
        """Displacement of the patch centre [m], rotation [rad], normal force
        [N], centre of pressure [m]: the pending step, not committed.  All six
        in one call: with N > 0, p must lie in the kern and be 0 along a side
        of one cell (else FMUError with the FMU's reason, nothing changed);
        with N <= 0 the contact is open and p is not looked at."""
        self._set_inputs((u1, u2, theta, N, p1, p2))
