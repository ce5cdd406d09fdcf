"""The compiled master: the rig loop of orthocontact.rig in C
(master_src/rig_master.c), running a contact FMU through its FMI 2.0 functions
(dlopen of the extracted binary) for a batch of parameter sets per call.

It is the Python harness's loop operation for operation, so it gives the same
trajectory angles (tests/test_cmaster.py); it only spends no Python per step.
Units as in orthocontact.rig: kg, m/s^2, N, m/s, m, s; angles in rad."""
from __future__ import annotations

import ctypes
import math
import sys
from pathlib import Path

import numpy as np

from .fmu import (MODEL_IDENTIFIER, RULES, ContactParams, FMUError, _unzipped, fmi_version_of,
                  installed_file, model_description)
from .rig import Rig, RigResult


class _Contact(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in ("mu1", "mu2", "eps1", "eps2", "alpha", "beta")] + \
               [("rule", ctypes.c_int)]


class _Rig(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in ("mass", "g", "f_int", "velocity", "travel", "mu_strip",
                                               "step", "fit_from", "c_strip")] + \
               [("quasistatic", ctypes.c_int)]


def _library_path() -> Path:
    name = "_orthocontact_master" + (".dylib" if sys.platform == "darwin" else ".so")
    path = installed_file(name)
    if path is None:
        raise FileNotFoundError(f"the compiled master {name} is not installed with the package; "
                                "run `pip install .` from the repository, or use --master fmpy")
    return path


_lib = None


def _load():
    global _lib
    if _lib is None:
        lib = ctypes.CDLL(str(_library_path()))
        lib.rm_open.restype = ctypes.c_void_p
        lib.rm_open.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p,
                                ctypes.c_size_t]
        lib.rm_run.restype = ctypes.c_int
        lib.rm_run.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.POINTER(_Contact),
                               ctypes.POINTER(_Rig), ctypes.POINTER(ctypes.c_double),
                               ctypes.POINTER(ctypes.c_double), ctypes.c_char_p, ctypes.c_size_t]
        lib.rm_record.restype = ctypes.c_int
        lib.rm_record.argtypes = [ctypes.c_void_p, ctypes.POINTER(_Contact), ctypes.POINTER(_Rig),
                                  ctypes.c_long, ctypes.POINTER(ctypes.c_double), ctypes.c_long,
                                  ctypes.POINTER(ctypes.c_long), ctypes.POINTER(ctypes.c_double),
                                  ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_long),
                                  ctypes.c_char_p, ctypes.c_size_t]
        lib.rm_close.argtypes = [ctypes.c_void_p]
        _lib = lib
    return _lib


def _structs(p: ContactParams, r: Rig) -> tuple[_Contact, _Rig]:
    return (_Contact(p.mu1, p.mu2, p.eps1, p.eps2, p.alpha, p.beta, RULES[p.rule]),
            _Rig(r.mass_kg, r.g, r.f_int_N, r.velocity_m_s, r.travel_m, r.mu_strip, r.step_s,
                 r.fit_from, r.c_strip, 1 if r.mode == "quasistatic" else 0))


class CMaster:
    """The compiled master on one FMI 2.0 contact FMU (one loaded binary)."""

    def __init__(self, fmu_path):
        path = Path(fmu_path)
        if fmi_version_of(path) != 2:
            raise ValueError(f"{path}: the compiled master runs FMI 2.0 FMUs; use --master fmpy "
                             "for FMI 3.0")
        md = model_description(path)
        folder = Path(_unzipped(path))
        binary = folder / "binaries" / "linux64" / (MODEL_IDENTIFIER + ".so")
        if sys.platform == "darwin":
            binary = folder / "binaries" / "darwin64" / (MODEL_IDENTIFIER + ".dylib")
        self._lib = _load()
        err = ctypes.create_string_buffer(512)
        self._h = self._lib.rm_open(str(binary).encode(), md.guid.encode(),
                                    (folder / "resources").as_uri().encode(), err, 512)
        if not self._h:
            raise FMUError(err.value.decode(errors="replace"))

    def run(self, tasks: list[tuple[ContactParams, Rig]]) -> list[tuple[float, float]]:
        """(phi_deg, drive_mean_N) of each (params, rig), in order."""
        n = len(tasks)
        if n == 0:
            return []
        cs = (_Contact * n)()
        rs = (_Rig * n)()
        for i, (p, r) in enumerate(tasks):
            cs[i], rs[i] = _structs(p, r)
        phi = (ctypes.c_double * n)()
        drive = (ctypes.c_double * n)()
        err = ctypes.create_string_buffer(512)
        if self._lib.rm_run(self._h, n, cs, rs, phi, drive, err, 512) != 0:
            raise FMUError(err.value.decode(errors="replace"))
        return [(phi[i], drive[i]) for i in range(n)]

    def record(self, params: ContactParams, rig: Rig, record_every: int = 1) -> RigResult:
        """One run with its time series kept every `record_every` steps (and
        at the last): the RigResult of rig.run, from the compiled loop."""
        if isinstance(record_every, bool) or not isinstance(record_every, int) or record_every < 1:
            raise ValueError(f"record_every must be a whole number >= 1, got {record_every!r}")
        n_steps = math.ceil(rig.travel_m / (rig.velocity_m_s * rig.step_s) - 1e-9)
        capacity = n_steps // record_every + 1
        rows = np.empty((capacity, 10))
        c, r = _structs(params, rig)
        n_rows, newton = ctypes.c_long(), ctypes.c_long()
        phi, drive = ctypes.c_double(), ctypes.c_double()
        err = ctypes.create_string_buffer(512)
        if self._lib.rm_record(self._h, ctypes.byref(c), ctypes.byref(r), record_every,
                               rows.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), capacity,
                               ctypes.byref(n_rows), ctypes.byref(phi), ctypes.byref(drive),
                               ctypes.byref(newton), err, 512) != 0:
            raise FMUError(err.value.decode(errors="replace"))
        cols = rows[:n_rows.value].T.copy()
        return RigResult(*cols, phi_deg=phi.value, drive_mean_N=drive.value,
                         newton_iterations=newton.value)

    def close(self):
        if getattr(self, "_h", None):
            self._lib.rm_close(self._h)
            self._h = None

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass
