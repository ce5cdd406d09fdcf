"""Access to the OrthotropicContact FMU (FMI 2.0 or FMI 3.0 Co-Simulation)
through fmpy.

Units: displacements u, slip s in m; forces N, T in N; stiffness eps in N/m;
angles alpha, beta in rad; energy in J."""
from __future__ import annotations

import ctypes
from functools import partial

from .files import find_fmu, model_description
from .params import RULES, ContactParams
from .slave import FreedOnClose, instantiate
from .variables import contact, law_parameters


class FMUError(RuntimeError):
    """An FMI call returned an error; the message carries what the FMU logged."""


INITIAL_SLIP = dict(contact().enumerations["InitialSlip"])   # the FMU's parameter initialSlip


class ContactFMU(FreedOnClose):
    """One instance of the contact element, FMI 2.0 or 3.0 (read from the
    FMU's model description); both run the same calls on the hot path.

    The FMU's step semantics: after `set_inputs`, `outputs()` / `force()`
    return the return-mapped result for those inputs from the committed
    state, without committing; `do_step` commits it.  So a master can iterate
    (Newton with `tangent()`) before committing.
    """

    OUT_NAMES = ("T1", "T2", "s1", "s2", "dissipatedEnergy")

    def __init__(self, fmu_path=None, instance_name: str = "contact", logging_on: bool = False,
                 fmi_version: int | None = None):
        path = find_fmu(fmu_path, fmi_version or 2) if fmu_path is None else find_fmu(fmu_path)
        self.path = path
        self.model_description = model_description(path)
        self.fmi_version = int(self.model_description.fmiVersion.split(".")[0])
        if fmi_version is not None and fmi_version != self.fmi_version:
            raise ValueError(f"{path} is an FMI {self.fmi_version}.0 FMU, not {fmi_version}.0")
        self.vr = {v.name: v.valueReference for v in self.model_description.modelVariables}
        self.messages: list[tuple[int, str, str]] = []
        self.time = 0.0
        self.initialized = False
        vr = self.vr
        c_uint = ctypes.c_uint
        self._in_vr = (c_uint * 3)(vr["u1"], vr["u2"], vr["N"])
        self._in_val = (ctypes.c_double * 3)()
        self._T_vr = (c_uint * 2)(vr["T1"], vr["T2"])
        self._T_val = (ctypes.c_double * 2)()
        self._out_vr = (c_uint * 5)(*(vr[n] for n in self.OUT_NAMES))
        self._out_val = (ctypes.c_double * 5)()
        self._state_vr = (c_uint * 1)(vr["contactState"])
        self._state_val = (ctypes.c_int32 * 1)()
        self._dT_val = (ctypes.c_double * 2)()
        self._known_vr = [(c_uint * 1)(vr[n]) for n in ("u1", "u2", "N")]
        self._one = (ctypes.c_double * 1)(1.0)
        if self.fmi_version == 2:
            self._open_fmi2(path, instance_name, logging_on)
        else:
            self._open_fmi3(path, instance_name, logging_on)

    # -- the two standards' calls, bound once ----------------------------------
    def _log(self, status: int, category: str, message: str):
        self.messages.append((status, category, message))

    def _open_fmi2(self, path, name, logging_on):
        s, self._callbacks = instantiate(path, self.model_description, name, self._log, logging_on)
        self._slave, c, f = s, s.component, s._functions  # raw ctypes: no exceptions, no allocation
        self._c = c
        self._set_in = partial(f["fmi2SetReal"], c, self._in_vr, 3, self._in_val)
        self._get_T = partial(f["fmi2GetReal"], c, self._T_vr, 2, self._T_val)
        self._get_out = partial(f["fmi2GetReal"], c, self._out_vr, 5, self._out_val)
        self._get_state_int = partial(f["fmi2GetInteger"], c, self._state_vr, 1, self._state_val)
        self._fDoStep = partial(f["fmi2DoStep"], c)
        self._dir = [partial(f["fmi2GetDirectionalDerivative"], c, self._T_vr, 2, k, 1, self._one,
                             self._dT_val) for k in self._known_vr]
        self._set_reals = lambda vr, val, n: f["fmi2SetReal"](c, vr, n, val)
        self._set_rule = lambda vr, val: f["fmi2SetInteger"](c, vr, 1, (ctypes.c_int32 * 1)(val))
        self._get_state_fn = partial(f["fmi2GetFMUstate"], c)

    def _open_fmi3(self, path, name, logging_on):
        s, self._callbacks = instantiate(path, self.model_description, name, self._log, logging_on)
        self._slave, c, f = s, s.component, s._functions
        self._c = c
        self._set_in = partial(f["fmi3SetFloat64"], c, self._in_vr, 3, self._in_val, 3)
        self._get_T = partial(f["fmi3GetFloat64"], c, self._T_vr, 2, self._T_val, 2)
        self._get_out = partial(f["fmi3GetFloat64"], c, self._out_vr, 5, self._out_val, 5)
        self._get_state_int = partial(f["fmi3GetInt32"], c, self._state_vr, 1, self._state_val, 1)
        # the out-arguments of fmi3DoStep, referenced once rather than every step
        self._flags = [ctypes.c_bool() for _ in range(3)]
        self._last_time = ctypes.c_double()
        refs = [ctypes.byref(x) for x in self._flags] + [ctypes.byref(self._last_time)]
        do_step = f["fmi3DoStep"]
        self._fDoStep = lambda t, h, no_set: do_step(c, t, h, no_set, *refs)
        self._dir = [partial(f["fmi3GetDirectionalDerivative"], c, self._T_vr, 2, k, 1, self._one,
                             1, self._dT_val, 2) for k in self._known_vr]
        self._set_reals = lambda vr, val, n: f["fmi3SetFloat64"](c, vr, n, val, n)
        self._set_rule = lambda vr, val: f["fmi3SetInt64"](c, vr, 1, (ctypes.c_int64 * 1)(val), 1)
        self._get_state_fn = partial(f["fmi3GetFMUState"], c)

    def _check(self, status: int, what: str):
        if status > 1:
            last = self.messages[-1][2] if self.messages else "(no message logged)"
            raise FMUError(f"{what} failed (status {status}): {last}")

    @property
    def slave(self):
        """The underlying fmpy FMU2Slave or FMU3Slave, for calls not wrapped here."""
        return self._slave

    # -- set-up --------------------------------------------------------------
    def initialize(self, params: ContactParams, start_time: float = 0.0,
                   inputs: tuple[float, float, float] = (0.0, 0.0, 0.0),
                   initial_slip: str = "atInputs",
                   s_start: tuple[float, float] | None = None):
        """Sets the parameters, the initial inputs and the initial slip, and
        enters step mode (parameters are fixed), as a system simulator does.

        inputs        (u1 [m], u2 [m], N [N]) at start_time [s]: set in
                      initialization mode, where the FMU takes them.
        initial_slip  "atInputs" (the FMU's default): the contact starts
                      unloaded where the body is, s = (u1, u2); "explicit":
                      s = s_start, loaded by B (u - s_start) at once.
        s_start       (s1Start, s2Start) [m], only with "explicit" (default
                      (0, 0): the behaviour of the FMU before 0.4 and of this
                      wrapper before it took inputs).
        """
        if params.rule not in RULES:
            raise ValueError(f"rule must be one of {sorted(RULES)}, got {params.rule!r}")
        if initial_slip not in INITIAL_SLIP:
            raise ValueError(f"initial_slip must be one of {sorted(INITIAL_SLIP)}, got {initial_slip!r}")
        if s_start is not None and initial_slip != "explicit":
            # the FMU would ignore it: refuse rather than run another start than asked
            raise ValueError(f"s_start is used only with initial_slip='explicit', not {initial_slip!r}")
        if len(inputs) != 3:
            raise ValueError(f"inputs must be (u1 [m], u2 [m], N [N]), got {inputs!r}")
        names = list(law_parameters())
        values = [float(getattr(params, n)) for n in names]
        if initial_slip == "explicit":
            names += ["s1Start", "s2Start"]
            values += [float(x) for x in (s_start or (0.0, 0.0))]
        vr = (ctypes.c_uint * len(names))(*(self.vr[n] for n in names))
        val = (ctypes.c_double * len(names))(*values)
        self._check(self._set_reals(vr, val, len(names)), "setting parameters")
        self._check(self._set_rule((ctypes.c_uint * 1)(self.vr["slidingRule"]), RULES[params.rule]),
                    "setting slidingRule")
        self._check(self._set_rule((ctypes.c_uint * 1)(self.vr["initialSlip"]), INITIAL_SLIP[initial_slip]),
                    "setting initialSlip")
        if self.fmi_version == 2:
            self._slave.setupExperiment(startTime=start_time)
            self._slave.enterInitializationMode()
        else:
            self._slave.enterInitializationMode(startTime=start_time)
        self.set_inputs(*inputs)  # initialization mode: where the FMU takes the start from them
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
        st = self._set_in()
        if st > 1:
            self._check(st, f"setting inputs (u1={u1}, u2={u2}, N={N})")

    def force(self) -> tuple[float, float]:
        """(T1, T2) [N]: force of the surface on the body for the current inputs."""
        st = self._get_T()
        if st > 1:
            self._check(st, "getting T1, T2")
        return self._T_val[0], self._T_val[1]

    def outputs(self) -> dict:
        """All outputs: T1, T2 [N], s1, s2 [m], dissipatedEnergy [J], contactState."""
        self._check(self._get_out(), "getting outputs")
        self._check(self._get_state_int(), "getting contactState")
        d = dict(zip(self.OUT_NAMES, self._out_val))
        d["contactState"] = self._state_val[0]
        return d

    def do_step(self, h: float):
        """Commits the pending step; h [s] is the communication step size."""
        st = self._fDoStep(self.time, h, 1)
        if st > 1:
            self._check(st, f"doStep(t={self.time}, h={h})")
        self.time += h

    def tangent_column(self, known: str) -> tuple[float, float]:
        """d(T1, T2)/d(known) for known in u1 [N/m], u2 [N/m], N [-]."""
        st = self._dir[("u1", "u2", "N").index(known)]()
        if st > 1:
            self._check(st, "getting the directional derivative")
        return self._dT_val[0], self._dT_val[1]

    def tangent(self):
        """2x3 Jacobian d(T1, T2)/d(u1, u2, N) as nested lists."""
        cols = [self.tangent_column(k) for k in ("u1", "u2", "N")]
        return [[cols[j][i] for j in range(3)] for i in range(2)]

    # -- state -------------------------------------------------------------------
    def get_state(self):
        """A new FMU state holding the instance as it is now."""
        return self._slave.getFMUstate() if self.fmi_version == 2 else self._slave.getFMUState()

    def refresh_state(self, state):
        """Overwrites a state from get_state in place with the current one (no
        allocation: for a master that saves every step)."""
        self._check(self._get_state_fn(ctypes.byref(state)), "getting the FMU state")
        return state

    def set_state(self, state):
        if self.fmi_version == 2:
            self._slave.setFMUstate(state)
        else:
            self._slave.setFMUState(state)

    def free_state(self, state):
        if self.fmi_version == 2:
            self._slave.freeFMUstate(state)
        else:
            self._slave.freeFMUState(state)

    def serialize(self, state) -> bytes:
        if self.fmi_version == 2:
            return bytes(self._slave.serializeFMUstate(state))
        return bytes(self._slave.serializeFMUState(state))

    def deserialize(self, data: bytes):
        if self.fmi_version == 2:
            return self._slave.deSerializeFMUstate(data)
        return self._slave.deserializeFMUState(data)
