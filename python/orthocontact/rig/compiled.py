"""The compiled master: the rig in C (fmu_src/rig/rig_core.c, the CarriageBlock
FMU's rig too) run by master_src/rig_master.c over a contact FMU's FMI 2.0
functions (dlopen of the extracted binary) for a batch of parameter sets per
call.

The C rig is pinned to the Python harness (orthocontact.rig, the reference)
bit for bit by tests/rig/test_compiled.py; it only spends no Python per step.
The structs passed to it are built from the library's own description of
their layout (rm_layout, master_src/rig_master.h), so there is one
declaration of them, in C.  Units as in orthocontact.rig: kg, m/s^2, N, m/s,
m, s; angles in rad."""
from __future__ import annotations

import ctypes
import sys
from pathlib import Path

import numpy as np

from ..fmu import (
    MODEL_IDENTIFIER,
    RULES,
    ContactParams,
    FMUError,
    fmi_version_of,
    installed_file,
    law_parameters,
    model_description,
)
from ..runtime import unzipped
from .harness import Rig, RigResult, RunFigures

_CTYPES = {"double": ctypes.c_double, "int": ctypes.c_int, "long": ctypes.c_long}


def structs_from_layout(text: str) -> dict[str, type]:
    """ctypes structures from rm_layout's description ("struct <name> <size>",
    then "<field> <offset> <type>" lines), each checked field by field against
    the offsets and size the C compiler gave them."""
    layout: dict[str, tuple[int, list[tuple[str, int, str]]]] = {}
    current = None
    for line in text.splitlines():
        words = line.split()
        if len(words) == 3 and words[0] == "struct":
            current = words[1]
            layout[current] = (int(words[2]), [])
        elif len(words) == 3 and current is not None and words[2] in _CTYPES:
            layout[current][1].append((words[0], int(words[1]), words[2]))
        else:
            raise FMUError(f"the compiled master describes its structs in a form this package "
                           f"does not read: {line!r}")
    structs = {}
    for name, (size, fields) in layout.items():
        cls = type(name, (ctypes.Structure,), {"_fields_": [(f, _CTYPES[t]) for f, _, t in fields]})
        got = [(f, getattr(cls, f).offset) for f, _, _ in fields]
        if got != [(f, o) for f, o, _ in fields] or ctypes.sizeof(cls) != size:
            raise FMUError(f"struct {name}: ctypes lays it out as {got} ({ctypes.sizeof(cls)} "
                           f"bytes), the compiled master as {fields} ({size} bytes)")
        structs[name] = cls
    return structs


def _library_path() -> Path:
    name = "_orthocontact_master" + (".dylib" if sys.platform == "darwin" else ".so")
    path = installed_file(name)
    if path is None:
        raise FileNotFoundError(f"the compiled master {name} is not installed with the package; "
                                "run `pip install .` from the repository, or use --master fmpy")
    return path


_lib = None


_Contact = _Rig = _Figures = None


def _layout_of(lib) -> str:
    """rm_layout's text: its length asked first, then the text, which must be that long."""
    lib.rm_layout.restype = ctypes.c_int
    lib.rm_layout.argtypes = [ctypes.c_char_p, ctypes.c_size_t]
    size = lib.rm_layout(None, 0)
    buf = ctypes.create_string_buffer(size + 1)
    wrote = lib.rm_layout(buf, size + 1)
    if wrote != size or len(buf.value) != size:
        raise FMUError(f"the compiled master's rm_layout said {size} characters, then wrote {wrote} "
                       f"({len(buf.value)} before its end)")
    return buf.value.decode()


def layout_text() -> str:
    """The installed compiled master's description of the structs it takes
    (rm_layout, master_src/rig_master.h), which structs_from_layout reads."""
    return _layout_of(_load())


def _load():
    global _lib, _Contact, _Rig, _Figures
    if _lib is None:
        lib = ctypes.CDLL(str(_library_path()))
        structs = structs_from_layout(_layout_of(lib))
        missing = {"rm_contact", "rig_setup", "rig_figures"} - structs.keys()
        if missing:
            raise FMUError(f"the compiled master does not describe {sorted(missing)}")
        contact, rig, figures = structs["rm_contact"], structs["rig_setup"], structs["rig_figures"]
        lib.rm_open.restype = ctypes.c_void_p
        lib.rm_open.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p,
                                ctypes.c_size_t]
        lib.rm_run.restype = ctypes.c_int
        lib.rm_run.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.POINTER(contact),
                               ctypes.POINTER(rig), ctypes.POINTER(figures), ctypes.c_char_p,
                               ctypes.c_size_t]
        lib.rm_record.restype = ctypes.c_int
        lib.rm_record.argtypes = [ctypes.c_void_p, ctypes.POINTER(contact), ctypes.POINTER(rig),
                                  ctypes.c_long, ctypes.POINTER(ctypes.c_double), ctypes.c_long,
                                  ctypes.POINTER(ctypes.c_long), ctypes.POINTER(figures),
                                  ctypes.c_char_p, ctypes.c_size_t]
        lib.rm_close.argtypes = [ctypes.c_void_p]
        lib.rig_step_count.restype = ctypes.c_long
        lib.rig_step_count.argtypes = [ctypes.c_double] * 3
        _Contact, _Rig, _Figures = contact, rig, figures
        _lib = lib
    return _lib


def filled(cls, **values):
    """cls with every field given, by name: ctypes would leave a field the
    caller does not name at 0 and keep a name it does not know as a Python
    attribute, both silently."""
    fields = [f for f, _ in cls._fields_]
    if sorted(values) != sorted(fields):
        raise FMUError(f"struct {cls.__name__} of the compiled master has the fields {fields}, "
                       f"this package fills {sorted(values)}")
    return cls(**values)


def _structs(p: ContactParams, r: Rig):
    law = {name: getattr(p, name) for name in law_parameters()}
    return (filled(_Contact, **law, rule=RULES[p.rule]),
            filled(_Rig, mass=r.mass_kg, g=r.g, f_int=r.f_int_N, velocity=r.velocity_m_s,
                    travel=r.travel_m, mu_strip=r.mu_strip, step=r.step_s, fit_from=r.fit_from,
                    c_strip=r.c_strip, quasistatic=1 if r.mode == "quasistatic" else 0))


def _figures(f) -> RunFigures:
    return RunFigures(f.phi_deg, f.drive_mean_N, f.phi_head_deg, f.phi_tail_deg)


# rm_record's columns (master_src/rig_master.h), RigResult's names.
_RECORD_COLUMNS = ("t", "x1", "x2", "T1", "T2", "s1", "s2", "state", "energy", "drive")


class CMaster:
    """The compiled master on one FMI 2.0 contact FMU (one loaded binary)."""

    def __init__(self, fmu_path):
        path = Path(fmu_path)
        if fmi_version_of(path) != 2:
            raise ValueError(f"{path}: the compiled master runs FMI 2.0 FMUs; use --master fmpy "
                             "for FMI 3.0")
        md = model_description(path)
        folder = Path(unzipped(path))
        binary = folder / "binaries" / "linux64" / (MODEL_IDENTIFIER + ".so")
        if sys.platform == "darwin":
            binary = folder / "binaries" / "darwin64" / (MODEL_IDENTIFIER + ".dylib")
        self._lib = _load()
        err = ctypes.create_string_buffer(512)
        self._h = self._lib.rm_open(str(binary).encode(), md.guid.encode(),
                                    (folder / "resources").as_uri().encode(), err, 512)
        if not self._h:
            raise FMUError(err.value.decode(errors="replace"))

    def run(self, tasks: list[tuple[ContactParams, Rig]]) -> list[RunFigures]:
        """The RunFigures of each (params, rig), in order."""
        n = len(tasks)
        if n == 0:
            return []
        cs = (_Contact * n)()
        rs = (_Rig * n)()
        for i, (p, r) in enumerate(tasks):
            cs[i], rs[i] = _structs(p, r)
        out = (_Figures * n)()
        err = ctypes.create_string_buffer(512)
        if self._lib.rm_run(self._h, n, cs, rs, out, err, 512) != 0:
            raise FMUError(err.value.decode(errors="replace"))
        return [_figures(f) for f in out]

    def run_grid(self, laws: list[ContactParams], axes: list[tuple[float, float]],
                 rig: Rig) -> np.ndarray:
        """Every law at every (alpha, beta) [rad] of `axes`, law after law, on
        one rig: run()'s figures as an array [len(laws) x len(axes) x 4]
        (RunFigures' fields), the same numbers bit for bit.  The structs are
        filled by numpy (record arrays with the library's own layout) rather
        than one Python object per run: for `orthocontact uq`'s 10^6 runs
        those cost as much as the runs.  The laws' angles are ignored; each
        (alpha, beta) is checked by the caller (ContactParams)."""
        nl, na = len(laws), len(axes)
        out_fields = RunFigures._fields
        if nl * na == 0:
            return np.empty((nl, na, len(out_fields)))
        n = nl * na
        cdt, rdt, fdt = np.dtype(_Contact), np.dtype(_Rig), np.dtype(_Figures)
        # every law parameter law after law, but the axes' angles, which take turns
        columns = {name: np.repeat(np.array([getattr(p, name) for p in laws], dtype=float), na)
                   for name in law_parameters()}
        columns["alpha"] = np.tile(np.array([a for a, _ in axes], dtype=float), nl)
        columns["beta"] = np.tile(np.array([b for _, b in axes], dtype=float), nl)
        columns["rule"] = np.repeat(np.array([RULES[p.rule] for p in laws]), na)
        if sorted(columns) != sorted(cdt.names):  # as filled(): no field left at 0
            raise FMUError(f"struct {_Contact.__name__} of the compiled master has the fields "
                           f"{list(cdt.names)}, this package fills {sorted(columns)}")
        cs = np.zeros(n, dtype=cdt)
        for name, col in columns.items():
            cs[name] = col
        rs = np.frombuffer(bytes(_structs(laws[0], rig)[1]), dtype=rdt).repeat(n)
        out = np.zeros(n, dtype=fdt)
        err = ctypes.create_string_buffer(512)
        if self._lib.rm_run(self._h, n, cs.ctypes.data_as(ctypes.POINTER(_Contact)),
                            rs.ctypes.data_as(ctypes.POINTER(_Rig)),
                            out.ctypes.data_as(ctypes.POINTER(_Figures)), err, 512) != 0:
            raise FMUError(err.value.decode(errors="replace"))
        return np.stack([out[f] for f in out_fields], axis=-1).reshape(nl, na, len(out_fields))

    def record(self, params: ContactParams, rig: Rig, record_every: int = 1) -> RigResult:
        """One run with its time series kept every `record_every` steps (and
        at the last): the RigResult of rig.run, from the compiled loop."""
        if isinstance(record_every, bool) or not isinstance(record_every, int) or record_every < 1:
            raise ValueError(f"record_every must be a whole number >= 1, got {record_every!r}")
        n_steps = self._lib.rig_step_count(rig.travel_m, rig.velocity_m_s, rig.step_s)
        if n_steps < 1:
            raise ValueError(f"travel {rig.travel_m} m at {rig.velocity_m_s} m/s in steps of "
                             f"{rig.step_s} s is not a whole number of steps in [1, 2^53]")
        capacity = n_steps // record_every + 1
        rows = np.empty((capacity, len(_RECORD_COLUMNS)))
        c, r = _structs(params, rig)
        n_rows, f = ctypes.c_long(), _Figures()
        err = ctypes.create_string_buffer(512)
        if self._lib.rm_record(self._h, ctypes.byref(c), ctypes.byref(r), record_every,
                               rows.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), capacity,
                               ctypes.byref(n_rows), ctypes.byref(f), err, 512) != 0:
            raise FMUError(err.value.decode(errors="replace"))
        cols = dict(zip(_RECORD_COLUMNS, rows[:n_rows.value].T.copy()))
        return RigResult(**cols, phi_deg=f.phi_deg, drive_mean_N=f.drive_mean_N,
                         newton_iterations=f.newton_iterations, phi_head_deg=f.phi_head_deg,
                         phi_tail_deg=f.phi_tail_deg)

    def close(self):
        if getattr(self, "_h", None):
            self._lib.rm_close(self._h)
            self._h = None

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass
