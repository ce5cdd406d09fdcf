"""The conformance suite's drive of any model, read from its manifest
(orthocontact.fmu.variables), never typed per model: the inputs' signals,
the outputs, a set of changed parameters, the clocks importers keep; and
fmpy's run of a model with them, the reference every importer is held to.

The input rule.  The tables give inputs no range (start 0, no min or max),
so a nominal value cannot come from them.  Each input i gets, in its unit's
scale A (SCALE: what one unit of motion or load of these models is),

    x_i(t) = A (sin(w_i t) + 0.4 (1 - cos(w_i t))),   w_i = 2 pi / (0.3 s (1 + i / 2)),

0 at t = 0 (each input's start value, so an importer that sets inputs
during initialization sets what the others leave), positive 62 % of each
period, negative the rest: an input that presses (a normal force N) presses
for most of the run and lets go in between, a displacement or a turn moves
both ways.  The periods differ, so the inputs' phases mix.  A unit without a
scale is refused: a model with a new kind of input names its scale here."""
from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np

from orthocontact.fmu.slave import instantiate, integer_call
from orthocontact.fmu.variables import ArrayVariable, Variable, manifest

# the amplitude of an input of each unit: a displacement of the order of the
# contact's elastic length mu N / eps (1 mm), a turn past an edge cell's
# sticking (10 mrad), a force of the order of the rig's block's weight (20 N),
# a speed that carries a surface about a cell (12.5 mm at the defaults) a step
SCALE = {"m": 1e-3, "rad": 1e-2, "N": 20.0, "m/s": 10.0}
BIAS = 0.4
STEP = 1e-3      # s
STEPS = 1000


def inputs(model: str) -> tuple[Variable, ...]:
    """The model's inputs, in the table's order."""
    return tuple(v for v in manifest(model).variables if v.causality == "input")


def outputs(model: str) -> tuple[Variable, ...]:
    """The model's scalar outputs, in the table's order."""
    return tuple(v for v in manifest(model).variables if v.causality == "output")


def signal(v: Variable, i: int, t: np.ndarray) -> np.ndarray:
    """Input v (the model's i-th) at times t [s], in v's unit."""
    if v.unit not in SCALE:
        raise KeyError(f"the conformance drive has no scale for {v.name}'s unit {v.unit!r}: "
                       "add it to SCALE in tests/conformance/drive.py")
    w = 2 * math.pi / (0.3 * (1 + i / 2))
    return SCALE[v.unit] * (np.sin(w * t) + BIAS * (1 - np.cos(w * t)))


def input_rows(model: str, n: int = STEPS, h: float = STEP) -> np.ndarray:
    """(n, inputs) values: row k is set before the k-th step, at k h."""
    t = np.arange(n) * h
    return np.column_stack([signal(v, i, t) for i, v in enumerate(inputs(model))])


# -- the importers' clocks ----------------------------------------------------------------------
#
# An importer passes the FMU the communication point t_k and the step h_k
# (the FMU's time then is t_k + h_k), each rounded its own way; a model
# whose outputs depend on time or step (the rig's x1 = velocity t, its
# integration) differs in the last bits between clocks.  Measured on the
# importers here: libcosim counts integer nanoseconds ("grid"), Ecos adds
# the step ("sum"), the FMU container's embedded FMU sees k h ("product").

def clock(kind: str, n: int = STEPS, h: float = STEP) -> tuple[np.ndarray, np.ndarray]:
    """(t_k, h_k), k < n [s], as an importer of that kind passes them:
    grid: t_k the double nearest k h (k h in integer ns / 1e9), h_k = t_{k+1} - t_k;
    sum: t_{k+1} = t_k + h, h_k = h;  product: t_k = k h, h_k = h."""
    if kind == "grid":
        t = np.arange(n + 1) * round(h * 1e9) / 1e9
        return t[:-1], np.diff(t)
    if kind == "sum":
        return np.array(list(itertools.accumulate([0.0] + [h] * (n - 1)))), np.full(n, h)
    if kind == "product":
        return np.arange(n) * h, np.full(n, h)
    raise ValueError(f"no clock {kind!r}")


def changed_parameters(model: str) -> dict:
    """Every parameter with a range moved off its start, inside its range:
    a Float64 with a nonzero start by a quarter, an integer (not an
    enumeration: its items are not ordered) up by one.  A state restored
    into a fresh instance (at the starts) must carry them."""
    out = {}
    for v in manifest(model).variables:
        if v.causality != "parameter" or v.start is None or v.declared_type is not None:
            continue
        new = v.start * 1.25 if v.type == "Float64" else v.start + 1
        if v.start != 0 and (v.min is None or new >= v.min) and (v.max is None or new <= v.max):
            out[v.name] = new
    return out


class Instance:
    """One instance of a model's FMU through fmpy, by its manifest: values
    set and read by name, each in its type's call."""

    def __init__(self, model: str, version: int, path, name: str = "conformance"):
        from fmpy import read_model_description
        self.model, self.version, self.path = model, version, Path(path)
        self.md = read_model_description(str(path))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.types = {v.name: v.type for v in self.md.modelVariables}
        self.messages = []
        self.slave, self._keep = instantiate(self.path, self.md, name,
                                             lambda s, c, m: self.messages.append((s, m)))
        self.structural = set(manifest(model).structural) if version == 3 else set()
        self.arrays = manifest(model).arrays if version == 3 else ()
        self.initialized = False

    def set(self, values: dict) -> None:
        """Sets values by name; FMI 3.0's structural parameters in configuration mode."""
        structural = {k: x for k, x in values.items() if k in self.structural}
        if structural:
            self.slave.enterConfigurationMode()
            self._set(structural)
            self.slave.exitConfigurationMode()
        self._set({k: x for k, x in values.items() if k not in self.structural})

    def _set(self, values: dict) -> None:
        for name, x in values.items():
            if self.types[name] in ("Real", "Float64"):
                (self.slave.setReal if self.version == 2 else self.slave.setFloat64)([self.vr[name]], [x])
            else:
                integer_call(self.slave, self.version, self.types[name])([self.vr[name]], [int(x)])

    def get(self, names) -> list:
        out = []
        for name in names:
            if self.types[name] in ("Real", "Float64"):
                out += (self.slave.getReal if self.version == 2 else self.slave.getFloat64)([self.vr[name]])
            else:
                out += integer_call(self.slave, self.version, self.types[name], get=True)([self.vr[name]])
        return out

    def get_array(self, a: ArrayVariable) -> list:
        """FMI 3.0 array output a, its size the product of its dimensions' current values."""
        size = math.prod(self.get(a.dimensions))
        get = self.slave.getFloat64 if a.type == "Float64" else getattr(self.slave, "get" + a.type)
        return list(get([a.value_reference], nValues=size))

    def snapshot(self) -> list:
        """Every output as a float: the scalars, then (FMI 3.0) the arrays' elements."""
        out = self.get(v.name for v in outputs(self.model))
        for a in self.arrays:
            out += self.get_array(a)
        return [float(x) for x in out]

    def start(self, t0: float = 0.0) -> None:
        """Initialization with nothing set in it, into step mode at t0."""
        if self.version == 2:
            self.slave.setupExperiment(startTime=t0)
            self.slave.enterInitializationMode()
        else:
            self.slave.enterInitializationMode(startTime=t0)
        self.slave.exitInitializationMode()
        self.initialized = True

    def step(self, row, t: float, h: float) -> None:
        """Sets the inputs to row, then steps from t by h."""
        self._set(dict(zip((v.name for v in inputs(self.model)), row)))
        self.slave.doStep(float(t), float(h))

    # the FMU state, as each FMI version spells its calls
    def get_state(self):
        return (self.slave.getFMUstate if self.version == 2 else self.slave.getFMUState)()

    def set_state(self, state) -> None:
        (self.slave.setFMUstate if self.version == 2 else self.slave.setFMUState)(state)
        self.initialized = True

    def free_state(self, state) -> None:
        (self.slave.freeFMUstate if self.version == 2 else self.slave.freeFMUState)(state)

    def serialize(self, state) -> bytes:
        serialize = self.slave.serializeFMUstate if self.version == 2 else self.slave.serializeFMUState
        return bytes(serialize(state))

    def deserialize(self, data: bytes):
        return (self.slave.deSerializeFMUstate if self.version == 2 else self.slave.deserializeFMUState)(data)

    def free(self) -> None:
        if self.initialized:
            self.slave.terminate()
        self.slave.freeInstance()


def run_fmpy(model: str, version: int, path, rows: np.ndarray, kind: str = "grid",
             parameters: dict | None = None, h: float = STEP) -> np.ndarray:
    """fmpy's run of the model: parameters set, initialized at t = 0, then
    for each row k its inputs set and a step (t_k, h_k) of the clock `kind`;
    (rows, scalar outputs) after each step, as floats."""
    f = Instance(model, version, path)
    try:
        f.set(parameters or {})
        f.start()
        names = [v.name for v in outputs(model)]
        got = []
        for row, t, hk in zip(rows, *clock(kind, len(rows), h)):
            f.step(row, t, hk)
            got.append(f.get(names))
        return np.array(got, dtype=float)
    finally:
        f.free()
