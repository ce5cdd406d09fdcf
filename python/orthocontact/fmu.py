"""Access to the OrthotropicContact FMU (FMI 2.0 Co-Simulation) through fmpy.

Units: displacements u, slip s in m; forces N, T in N; stiffness eps in N/m;
angles alpha, beta in rad; energy in J.
"""
from __future__ import annotations

import ctypes
import os
import dataclasses
from dataclasses import dataclass
from pathlib import Path

from fmpy import extract, read_model_description
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)

MODEL_IDENTIFIER = "OrthotropicContact"
FMU_ENV = "ORTHOCONTACT_FMU"

RULES = {"associated": 1, "coupled": 2, "eq20": 3}


class FMUError(RuntimeError):
    """An FMI call returned an error; the message carries what the FMU logged."""


def find_fmu(path: str | os.PathLike | None = None) -> Path:
    """The FMU to use: `path`, else $ORTHOCONTACT_FMU, else the one installed
    with the package."""
    for given, where in ((path, "given path"), (os.environ.get(FMU_ENV), f"${FMU_ENV}")):
        if given:
            if not Path(given).is_file():
                raise FileNotFoundError(f"FMU not found: {given} ({where})")
            return Path(given)
    packaged = Path(__file__).with_name(MODEL_IDENTIFIER + ".fmu")
    if packaged.is_file():
        return packaged
    raise FileNotFoundError(
        f"{MODEL_IDENTIFIER}.fmu is not installed with the package; run `pip install .` "
        f"from the repository or set {FMU_ENV}")


@dataclass(frozen=True)
class ContactParams:
    """Parameters of the law.

    mu1, mu2   friction coefficients along the friction axes [-]
    eps1, eps2 tangential stiffnesses along the adhesion axes [N/m]
    alpha      angle of adhesion axis 1 from X1, counterclockwise [rad]
    beta       angle of friction axis 1 from X1, counterclockwise [rad]
    rule       "associated", "coupled" or "eq20"
    """
    mu1: float
    mu2: float
    eps1: float
    eps2: float
    alpha: float = 0.0
    beta: float = 0.0
    rule: str = "coupled"

    def replace(self, **kw) -> "ContactParams":
        return dataclasses.replace(self, **kw)


_extracted: dict[Path, str] = {}


def _unzipped(path: Path) -> str:
    """One extraction per FMU file and process (instances share it)."""
    key = path.resolve()
    if key not in _extracted:
        _extracted[key] = extract(str(key))
    return _extracted[key]


class ContactFMU:
    """One instance of the contact element.

    The FMU's step semantics: after `set_inputs`, `outputs()` / `force()`
    return the return-mapped result for those inputs from the committed
    state, without committing; `do_step` commits it.  So a master can iterate
    (Newton with `tangent()`) before committing.
    """

    OUT_NAMES = ("T1", "T2", "s1", "s2", "dissipatedEnergy")

    def __init__(self, fmu_path=None, instance_name: str = "contact", logging_on: bool = False):
        path = find_fmu(fmu_path)
        self.path = path
        self.model_description = read_model_description(str(path))
        self.vr = {v.name: v.valueReference for v in self.model_description.modelVariables}
        self.messages: list[tuple[int, str, str]] = []
        self._callbacks = self._make_callbacks()
        self._slave = FMU2Slave(guid=self.model_description.guid, unzipDirectory=_unzipped(path),
                                modelIdentifier=MODEL_IDENTIFIER, instanceName=instance_name)
        self._slave.instantiate(callbacks=self._callbacks, loggingOn=logging_on)
        self._c = self._slave.component
        self.time = 0.0
        self.initialized = False
        # Preallocated ctypes arrays for the hot path (one FMI call each).
        vr = self.vr
        self._in_vr = (ctypes.c_uint * 3)(vr["u1"], vr["u2"], vr["N"])
        self._in_val = (ctypes.c_double * 3)()
        self._T_vr = (ctypes.c_uint * 2)(vr["T1"], vr["T2"])
        self._T_val = (ctypes.c_double * 2)()
        self._out_vr = (ctypes.c_uint * 5)(*(vr[n] for n in self.OUT_NAMES))
        self._out_val = (ctypes.c_double * 5)()
        self._state_vr = (ctypes.c_uint * 1)(vr["contactState"])
        self._state_val = (ctypes.c_int * 1)()
        self._dT_val = (ctypes.c_double * 2)()
        self._known_vr = [(ctypes.c_uint * 1)(vr[n]) for n in ("u1", "u2", "N")]
        self._one = (ctypes.c_double * 1)(1.0)
        f = self._slave._functions  # raw ctypes functions: no status exceptions, no per-call allocation
        self._fSetReal = f["fmi2SetReal"]
        self._fGetReal = f["fmi2GetReal"]
        self._fGetInteger = f["fmi2GetInteger"]
        self._fDoStep = f["fmi2DoStep"]
        self._fDirDer = f["fmi2GetDirectionalDerivative"]

    # -- logging -----------------------------------------------------------
    def _make_callbacks(self):
        def log(env, instance, status, category, message):
            self.messages.append((status, category.decode(), message.decode(errors="replace")))

        from fmpy.fmi2 import calloc, free
        from fmpy.logging import addLoggerProxy
        cb = fmi2CallbackFunctions()
        cb.logger = fmi2CallbackLoggerTYPE(log)
        cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        addLoggerProxy(ctypes.byref(cb))  # formats the printf-style message in C
        self._log_fn = log
        return cb

    def _check(self, status: int, what: str):
        if status > 1:
            last = self.messages[-1][2] if self.messages else "(no message logged)"
            raise FMUError(f"{what} failed (status {status}): {last}")

    @property
    def slave(self) -> FMU2Slave:
        """The underlying fmpy FMU2Slave, for calls not wrapped here."""
        return self._slave

    # -- set-up --------------------------------------------------------------
    def initialize(self, params: ContactParams, start_time: float = 0.0):
        """Sets the parameters and enters step mode (parameters are fixed)."""
        if params.rule not in RULES:
            raise ValueError(f"rule must be one of {sorted(RULES)}, got {params.rule!r}")
        names = ["mu1", "mu2", "eps1", "eps2", "alpha", "beta"]
        vr = (ctypes.c_uint * 6)(*(self.vr[n] for n in names))
        val = (ctypes.c_double * 6)(*(float(getattr(params, n)) for n in names))
        self._check(self._fSetReal(self._c, vr, 6, val), "setting parameters")
        self._check(self._slave.fmi2SetInteger(self._c, (ctypes.c_uint * 1)(self.vr["slidingRule"]), 1,
                                               (ctypes.c_int * 1)(RULES[params.rule])), "setting slidingRule")
        self._slave.setupExperiment(startTime=start_time)
        self._slave.enterInitializationMode()
        self._slave.exitInitializationMode()
        self.time = start_time
        self.initialized = True

    def reset(self, params: ContactParams | None = None):
        """Back to the unloaded initial state; with params, re-initialized."""
        self._slave.reset()
        self.initialized = False
        self.time = 0.0
        if params is not None:
            self.initialize(params)

    # -- the hot path -----------------------------------------------------------
    def set_inputs(self, u1: float, u2: float, N: float):
        """Displacement of the body [m] and normal force [N]."""
        v = self._in_val
        v[0] = u1
        v[1] = u2
        v[2] = N
        st = self._fSetReal(self._c, self._in_vr, 3, v)
        if st > 1:
            self._check(st, f"fmi2SetReal(u1={u1}, u2={u2}, N={N})")

    def force(self) -> tuple[float, float]:
        """(T1, T2) [N]: force of the surface on the body for the current inputs."""
        st = self._fGetReal(self._c, self._T_vr, 2, self._T_val)
        if st > 1:
            self._check(st, "fmi2GetReal(T1, T2)")
        return self._T_val[0], self._T_val[1]

    def outputs(self) -> dict:
        """All outputs: T1, T2 [N], s1, s2 [m], dissipatedEnergy [J], contactState."""
        self._check(self._fGetReal(self._c, self._out_vr, 5, self._out_val), "fmi2GetReal")
        self._check(self._fGetInteger(self._c, self._state_vr, 1, self._state_val), "fmi2GetInteger")
        d = dict(zip(self.OUT_NAMES, self._out_val))
        d["contactState"] = self._state_val[0]
        return d

    def do_step(self, h: float):
        """Commits the pending step; h [s] is the communication step size."""
        st = self._fDoStep(self._c, self.time, h, 1)
        if st > 1:
            self._check(st, f"fmi2DoStep(t={self.time}, h={h})")
        self.time += h

    def tangent_column(self, known: str) -> tuple[float, float]:
        """d(T1, T2)/d(known) for known in u1 [N/m], u2 [N/m], N [-]."""
        k = ("u1", "u2", "N").index(known)
        st = self._fDirDer(self._c, self._T_vr, 2, self._known_vr[k], 1, self._one, self._dT_val)
        if st > 1:
            self._check(st, "fmi2GetDirectionalDerivative")
        return self._dT_val[0], self._dT_val[1]

    def tangent(self):
        """2x3 Jacobian d(T1, T2)/d(u1, u2, N) as nested lists."""
        cols = [self.tangent_column(k) for k in ("u1", "u2", "N")]
        return [[cols[j][i] for j in range(3)] for i in range(2)]

    # -- state -------------------------------------------------------------------
    def get_state(self):
        return self._slave.getFMUstate()

    def set_state(self, state):
        self._slave.setFMUstate(state)

    def free_state(self, state):
        self._slave.freeFMUstate(state)

    def serialize(self, state) -> bytes:
        return bytes(self._slave.serializeFMUstate(state))

    def deserialize(self, data: bytes):
        return self._slave.deSerializeFMUstate(data)

    def close(self):
        if self._slave is not None:
            if self.initialized:
                try:
                    self._slave.terminate()
                except Exception:  # already terminated or in error: freeing is what matters
                    pass
            self._slave.freeInstance()
            self._slave = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass
