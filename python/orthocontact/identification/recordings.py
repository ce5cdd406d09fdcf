"""A lab's raw recordings and their files (docs/reference/file-formats.md, "Raw recordings").

A recordings folder is recognised by its runs.csv:
  rig.toml                 as for reduced data; f_int_N optional when carriage runs are given
  runs.csv                 run,kind,mat_angle_deg,velocity_m_s   one row per run
                           kind: carriage (the carriage alone: F_int), slide (a pull at the
                           row's mat angle and velocity), ramp (a slow start of pull)
  trajectories/<run>.csv   t_s,x1_m,x2_m   the block's tracked position (slide, ramp runs);
                           an empty or nan cell is a tracker drop-out
  forces/<run>.csv         t_s,force_N     the sensor between rack and carriage (every run)
Both time columns are on one clock; each file has its own rate and start.
A bad file is an InputError naming the file, the line and the column.
Units: s, m, N, deg, m/s."""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import plausibility
from ..errors import InputError
from ..experiment import RigSetup, load_rig_toml
from ..textfiles import read_rows, read_toml

KINDS = ("carriage", "slide", "ramp")
RUN_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]*$")
MIN_SAMPLES = 10


@dataclass
class Run:
    name: str
    kind: str
    mat_angle_deg: float
    velocity_m_s: float
    line: int                          # its row in runs.csv
    trajectory: np.ndarray | None      # (n, 3): t_s, x1_m, x2_m; nan rows are drop-outs
    forces: np.ndarray                 # (n, 2): t_s, force_N
    trajectory_path: Path | None
    forces_path: Path


@dataclass
class Recordings:
    folder: Path
    rig: RigSetup
    runs: list
    f_int_given: bool                  # rig.toml names f_int_N
    warnings: tuple = ()


def is_recordings(folder) -> bool:
    return (Path(folder) / "runs.csv").is_file()


def _rows(path: Path, what: str):
    # One CSV reader for every format: BOM, CRLF, semicolons, decimal commas.
    if not path.exists():
        raise InputError(f"{path}: expected {what}")
    return read_rows(path, what)


def _header(path: Path, rows, columns) -> list:
    if not rows:
        raise InputError(f"{path}: expected a header line with columns {','.join(columns)}")
    line, header = rows[0]
    idx = []
    for c in columns:
        if c not in header:
            raise InputError(f"{path}: line {line}: expected column {c!r} (header has {','.join(header)})")
        idx.append(header.index(c))
    return idx


def parse_number(path, line, col, cell, missing_ok=False) -> float:
    """A CSV cell as a finite number (nan for an empty or 'nan' cell where
    missing_ok); InputError naming the file, line and column otherwise."""
    if missing_ok and cell.lower() in ("", "nan"):
        return math.nan
    try:
        v = float(cell)
    except ValueError:
        raise InputError(f"{path}: line {line}: {col}: expected a number, got {cell!r}") from None
    if not math.isfinite(v):
        raise InputError(f"{path}: line {line}: {col}: expected a finite number, got {cell!r}")
    return v


def read_series(path: Path, columns: tuple, what: str, missing_ok: tuple = ()) -> np.ndarray:
    """The numeric columns of a time series; t_s strictly increasing; cells
    of the missing_ok columns may be empty or nan (a drop-out)."""
    rows = _rows(path, what)
    idx = _header(path, rows, columns)
    body = rows[1:]
    data = _all_finite(body, idx)
    if data is None:    # some cell is not a finite number: read cell by cell, naming the first
        data = _cell_by_cell(path, body, columns, idx, missing_ok)
    late = np.flatnonzero(np.diff(data[:, 0]) <= 0) if len(data) else ()
    if len(late):
        i = int(late[0])
        raise InputError(f"{path}: line {body[i + 1][0]}: {columns[0]}: expected a time after line "
                         f"{body[i][0]}'s {data[i, 0]:g} s (samples in time order), got {data[i + 1, 0]:g}")
    if len(data) < MIN_SAMPLES:
        raise InputError(f"{path}: expected at least {MIN_SAMPLES} samples, got {len(data)}")
    return data


def _all_finite(body, idx):
    """The columns idx of every row as an array, if each cell is a finite
    number as float() reads it; None otherwise (a short row, a word, an empty
    cell or nan)."""
    try:
        data = np.array([list(map(float, (r[k] for _, r in body))) for k in idx]).T
    except (ValueError, IndexError):
        return None
    return data.reshape(len(body), len(idx)) if np.isfinite(data).all() else None


def _cell_by_cell(path, body, columns, idx, missing_ok) -> np.ndarray:
    """The columns idx read cell by cell (parse_number), refusing the first
    cell in file order that is not a number, drop-outs kept as nan."""
    data = []
    for line, r in body:
        data.append([parse_number(path, line, c, r[k] if k < len(r) else "", c in missing_ok)
                     for c, k in zip(columns, idx)])
    return np.array(data, dtype=float).reshape(len(body), len(idx))


def load_recordings(folder) -> Recordings:
    """Reads and validates a recordings folder; raises InputError (one line)."""
    folder = Path(folder)
    rig = load_rig_toml(folder / "rig.toml")
    try:
        f_int_given = "f_int_N" in read_toml(folder / "rig.toml", "rig.toml")
    except (InputError, ValueError):  # pragma: no cover - load_rig_toml read it already
        f_int_given = False
    path = folder / "runs.csv"
    rows = _rows(path, "runs.csv")
    cols = ("run", "kind", "mat_angle_deg", "velocity_m_s")
    idx = _header(path, rows, cols)
    runs, seen, warnings = [], {}, list(rig.warnings)
    for line, r in rows[1:]:
        cell = dict(zip(cols, (r[k] if k < len(r) else "" for k in idx)))
        name = cell["run"]
        if not RUN_NAME.match(name):
            raise InputError(f"{path}: line {line}: run: expected a name of letters, digits, '_', '-', "
                             f"'.' (it names the run's files), got {name!r}")
        if name in seen:
            raise InputError(f"{path}: line {line}: run: {name!r} is already on line {seen[name]}")
        seen[name] = line
        if cell["kind"] not in KINDS:
            raise InputError(f"{path}: line {line}: kind: expected one of {', '.join(KINDS)}, "
                             f"got {cell['kind']!r}")
        angle = parse_number(path, line, "mat_angle_deg", cell["mat_angle_deg"])
        if not -180 <= angle <= 180:
            raise InputError(f"{path}: line {line}: mat_angle_deg: expected an angle in [-180, 180] deg, "
                             f"got {angle:g}")
        v = parse_number(path, line, "velocity_m_s", cell["velocity_m_s"])
        found = plausibility.check("velocity_m_s", v)
        if found is not None:
            if found[0] == "error" or v <= 0:
                raise InputError(f"{path}: line {line}: {found[1]}")
            warnings.append(f"{path}: line {line} (run {name}): {found[1]}")
        traj_path = folder / "trajectories" / f"{name}.csv"
        traj = None
        if cell["kind"] != "carriage":
            traj = read_series(traj_path, ("t_s", "x1_m", "x2_m"),
                               f"the tracked positions of {cell['kind']} run {name} (t_s,x1_m,x2_m)",
                               missing_ok=("x1_m", "x2_m"))
        force_path = folder / "forces" / f"{name}.csv"
        forces = read_series(force_path, ("t_s", "force_N"), f"the force log of run {name} (t_s,force_N)")
        runs.append(Run(name, cell["kind"], angle, v, line, traj, forces,
                        traj_path if traj is not None else None, force_path))
    kinds = {r.kind for r in runs}
    if "slide" not in kinds:
        raise InputError(f"{path}: expected at least one slide run (kind = slide)")
    angles = {r.mat_angle_deg for r in runs if r.kind == "slide"}
    if plausibility.looks_like_radians(sorted(angles), math.pi / 2 + 1e-9):
        raise InputError(f"{path}: mat_angle_deg: all mat angles lie within +-pi/2 "
                         f"({min(angles):g} .. {max(angles):g}): radians? the column is in degrees")
    if "carriage" not in kinds and not f_int_given:
        raise InputError(f"{folder / 'rig.toml'}: f_int_N: expected a value, or carriage runs "
                         "(kind = carriage) in runs.csv to measure it")
    if "carriage" in kinds and f_int_given:
        warnings.append(f"{folder / 'rig.toml'}: f_int_N = {rig.f_int_N:g} N is not used: the carriage "
                        "runs measure F_int, which the fit estimates with its uncertainty")
    return Recordings(folder, rig, runs, f_int_given, tuple(warnings))
