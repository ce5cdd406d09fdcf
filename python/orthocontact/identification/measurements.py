"""Measurement data for identification and their files.

A measurement set is a folder (docs/reference/file-formats.md, "Reduced data"):
  rig.toml     mass_kg, g, f_int_N, velocity_m_s, rule, geometry (required file)
  forces.csv   mat_angle_deg,force_N    driving force at a mat angle (repeats allowed)
  angles.csv   mat_angle_deg,phi_deg    trajectory angle (repeats allowed)
  ramp.csv     x1_m,force_N             start of a pull, before and into sliding
`mat_angle_deg` is the mat angle: the mat's (the ripples') angle; the
tensors' axes follow from it by the geometry offsets.  The column's old name
`alpha_deg` (which read as the adhesion axis, and is not) is still read.
A lab's raw recordings (runs.csv, trajectories/, forces/) are read by
recordings.py and reduced to a MeasurementSet by reduction.py.
A bad file is an InputError naming the file, the line and the column.
Units: N, m, deg."""
from __future__ import annotations

import hashlib
import math
import os
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import plausibility
from ..errors import InputError
from ..experiment import RigSetup, load_rig_toml, write_rig_toml
from ..textfiles import read_rows
from .recordings import parse_number

if sys.version_info >= (3, 11):
    pass
else:  # pragma: no cover
    pass


@dataclass
class MeasurementSet:
    folder: Path
    rig: RigSetup
    forces: np.ndarray | None = None   # (n, 2): mat angle [deg], force [N]
    angles: np.ndarray | None = None   # (n, 2): mat angle [deg], phi [deg] (counterclockwise)
    ramp: np.ndarray | None = None     # (n, 2): x1_m, force_N
    angle_velocities: np.ndarray | None = None  # (n,): m/s of each angle (None: rig.velocity_m_s)
    warnings: tuple = ()               # one line each: unusual values in the files
    # From raw recordings (one value per run): each value's within-run
    # standard error (None: 0, the scatter is all estimated), the forces'
    # velocities, F_int per carriage run, the ramp runs' stick stiffness.
    force_se: np.ndarray | None = None      # (n,) N
    angle_se: np.ndarray | None = None      # (n,) deg
    force_velocities: np.ndarray | None = None  # (n,) m/s (None: rig.velocity_m_s)
    carriage: np.ndarray | None = None      # (n, 2): F_int [N], its standard error
    stiffness: np.ndarray | None = None     # (n, 3): mat angle [deg], dF/dx1 [N/m], its standard error
    # Provenance: every file read to make the set, its path under `folder`
    # (POSIX) -> SHA-256 (data_files); None for a set not read from files.
    files: dict | None = None

    @property
    def f_int_free(self) -> bool:
        """F_int is estimated (from carriage runs), not taken from rig.toml."""
        return self.carriage is not None

    def velocities_of_forces(self) -> np.ndarray:
        """The carriage velocity [m/s] of each measured force."""
        if self.force_velocities is not None:
            return self.force_velocities
        return np.full(0 if self.forces is None else len(self.forces), self.rig.velocity_m_s)

    def velocities_of_angles(self) -> np.ndarray:
        """The carriage velocity [m/s] of each measured angle."""
        if self.angle_velocities is not None:
            return self.angle_velocities
        return np.full(0 if self.angles is None else len(self.angles), self.rig.velocity_m_s)


def friction_axis_key(rig: RigSetup, angles_deg):
    """cos^2 of the friction axis angle: what the force depends on."""
    return np.cos(np.radians(np.asarray(angles_deg) + rig.beta_offset_deg)) ** 2


def visible(text: str) -> str:
    """text with every character a reader cannot see (a byte-order mark, a
    zero-width or no-break space, a control character) written as \\uXXXX."""
    return "".join(c if c.isprintable() or c == " " else f"\\u{ord(c):04x}" for c in text)


ANGLE, OLD_ANGLE = "mat_angle_deg", "alpha_deg"


def _load_csv(path: Path, columns: tuple[str, ...], checks, min_rows: int, why: str,
              optional: dict | None = None) -> np.ndarray | None:
    """Rows of the numeric columns (then the optional ones, their default
    where the header lacks them), or None if the file is absent."""
    optional = optional or {}
    if not path.exists():
        return None
    # One CSV reader for every format: BOM, CRLF, semicolons, decimal commas.
    rows = read_rows(path, f"a CSV file with columns {','.join(columns)}")
    if not rows:
        raise InputError(f"{path}: expected a header line with columns {','.join(columns)}")
    line0, header = rows[0]
    header = [h.strip() for h in header]
    if ANGLE in columns and ANGLE not in header and OLD_ANGLE in header:
        header[header.index(OLD_ANGLE)] = ANGLE
    idx = []
    for c in columns:
        if c not in header:
            raise InputError(f"{path}: line {line0}: expected column {c!r} (header has "
                             f"{','.join(map(visible, header))})")
        idx.append(header.index(c))
    present = [c for c in optional if c in header]
    columns = tuple(columns) + tuple(present)
    idx += [header.index(c) for c in present]
    data = []
    for line, r in rows[1:]:
        vals = []
        for c, k in zip(columns, idx):
            cell = r[k].strip() if k < len(r) else ""
            v = parse_number(path, line, c, cell)
            bad = checks[c](v)
            if bad:
                raise InputError(f"{path}: line {line}: {c}: expected {bad}, got {cell}")
            vals.append(v)
        data.append(vals + [optional[c] for c in optional if c not in present])
    if len(data) < min_rows:
        raise InputError(f"{path}: expected at least {min_rows} data rows ({why}), got {len(data)}")
    return np.array(data, dtype=float)


def load_data(folder) -> MeasurementSet:
    """Reads and validates a measurement set; raises InputError (one line)."""
    folder = Path(folder)
    if not folder.is_dir():
        raise InputError(f"{folder}: expected a folder with rig.toml and forces.csv/angles.csv/ramp.csv")
    rig = load_rig_toml(folder / "rig.toml")

    def angle(v):
        return None if -180 <= v <= 180 else "an angle in [-180, 180] deg"
    forces = _load_csv(folder / "forces.csv", (ANGLE, "force_N"),
                       {ANGLE: angle, "force_N": lambda v: None if v > 0 else "a force > 0"},
                       2, "two parameters, mu1 and mu2")
    angles = _load_csv(folder / "angles.csv", (ANGLE, "phi_deg"),
                       {ANGLE: angle,
                        "phi_deg": lambda v: None if -90 < v < 90 else "an angle in (-90, 90) deg",
                        "velocity_m_s": lambda v: None if v > 0 else "a velocity > 0"},
                       1, "the stiffness ratio", optional={"velocity_m_s": rig.velocity_m_s})
    velocities = None
    if angles is not None:
        velocities, angles = angles[:, 2].copy(), angles[:, :2].copy()
    ramp = _load_csv(folder / "ramp.csv", ("x1_m", "force_N"),
                     {"x1_m": lambda v: None if v >= 0 else "a travel >= 0",
                      "force_N": lambda v: None if v >= 0 else "a force >= 0"},
                     3, "stiffness needs points on the stick branch")
    if forces is None and angles is None and ramp is None:
        raise InputError(f"{folder}: expected at least one of forces.csv, angles.csv, ramp.csv")
    warnings = list(rig.warnings) + plausible_data(folder, rig, forces, angles, ramp=ramp,
                                                   velocities=velocities)
    if angles is not None and rig.phi_convention == "paper":
        angles[:, 1] = -angles[:, 1]
    if forces is not None and len(np.unique(np.round(friction_axis_key(rig, forces[:, 0]), 9))) < 2:
        raise InputError(f"{folder / 'forces.csv'}: expected forces at two or more mat angles "
                         "with different friction directions (mu1 and mu2 are two parameters)")
    return MeasurementSet(folder, rig, forces, angles, ramp, velocities, tuple(warnings))


def data_files(folder, read: dict) -> dict:
    """The files read (textfiles.files_read's record: path -> FileRead) as
    {path under `folder`, POSIX: SHA-256}, sorted by path."""
    root = Path(folder).resolve()
    files = {Path(os.path.relpath(Path(f.path).resolve(), root)).as_posix(): f.sha256 for f in read.values()}
    return {k: files[k] for k in sorted(files)}


def data_digest(files: dict) -> str:
    """The data set's SHA-256 [hex]: of the listing `sha256sum` prints for
    the files (data_files: path under the data folder -> SHA-256) in sorted
    order, so that `cd DATA && sha256sum FILE... | sha256sum`, the files in
    that order, gives the same; for reduced data, `sha256sum angles.csv
    forces.csv ramp.csv rig.toml | sha256sum` over those present."""
    listing = "".join(f"{files[n]}  {n}\n" for n in sorted(files))
    return hashlib.sha256(listing.encode()).hexdigest()


def changed_files(folder, files: dict) -> list[str]:
    """The files of `files` (path under `folder` -> SHA-256) that are
    missing or whose bytes differ now, each as "PATH (missing)" or "PATH"."""
    out = []
    for name in sorted(files):
        p = Path(folder) / name
        try:
            now = hashlib.sha256(p.read_bytes()).hexdigest()
        except OSError:
            out.append(f"{name} (missing)")
            continue
        if now != files[name]:
            out.append(name)
    return out


RADIAN_ORIENTATIONS = math.pi / 2 + 1e-9   # |mat angle| [deg] of a sweep typed in rad


# |phi| [deg] of angles typed in rad (the aged mat peaks at 0.2007 rad)
RADIAN_TRAJECTORY = 0.25


TRAVEL_SAID = " (rig.toml's travel_m; 0.5 m unless given)"


def plausible_data(folder: Path, rig: RigSetup, forces, angles, names=None, ramp=None,
                   velocities=None, stiffness=None, ramp_names=None) -> list[str]:
    """The data against the one gate (orthocontact.plausibility) and the rig
    that bounds them: raises InputError for data that cannot be right
    (mat angles in radians, forces at or below F_int or implying mu
    outside (0, 5), a ramp reaching beyond the rig's travel, a velocity or a
    ramp run's stiffness outside its hard range); returns warnings for
    unusual ones (trajectory angles that all look like radians; every force,
    with ramp.csv's sliding level, so small against m g that kN is likely:
    plausibility.force_unit_check).  names: the run of each force and
    angle (raw recordings), else rows of the files; velocities [m/s] of
    angles.csv's rows; stiffness the ramp runs' (n, 3) array and ramp_names
    their runs."""
    warnings = []
    for name, arr in (("forces.csv", forces), ("angles.csv", angles)):
        if arr is not None and plausibility.looks_like_radians(arr[:, 0], RADIAN_ORIENTATIONS):
            raise InputError(f"{folder / name}: {ANGLE}: all mat angles lie within +-pi/2 "
                             f"({arr[:, 0].min():g} .. {arr[:, 0].max():g}): radians? the column is "
                             "in degrees")
    if angles is not None and plausibility.looks_like_radians(angles[:, 1], RADIAN_TRAJECTORY):
        warnings.append(f"{folder / 'angles.csv'}: phi_deg: all trajectory angles lie within "
                        f"+-{RADIAN_TRAJECTORY} deg: radians? the column is in degrees")
    found = []
    if forces is not None:
        # the whole set against m g: in kN, every ratio (and the angles) looks sane
        tops = forces[:, 1] if ramp is None else np.append(forces[:, 1], ramp[:, 1].max())
        found.append(plausibility.force_unit_check((tops - rig.f_int_N) / rig.normal_force, rig.f_int_N,
                                                   f"{folder}: ", "its driving forces' (F - F_int)/(m g)",
                                                   rig.normal_force))
        for k, (a, F) in enumerate(forces):
            where = (f"{folder}: run {names[k]}" if names else f"{folder / 'forces.csv'}: row {k + 1}")
            found.append(plausibility.force_check(F, rig.f_int_N, rig.normal_force,
                                                  f"{where} ({ANGLE} = {a:g}): "))
    if velocities is not None:
        for k, v in enumerate(velocities):
            if v != rig.velocity_m_s:   # rig.toml's (the column's default) is judged as rig.toml's
                found += plausibility.findings({"velocity_m_s": float(v)},
                                               f"{folder / 'angles.csv'}: row {k + 1}: ")
    if ramp is not None:
        found.append(plausibility.ramp_extent_check(float(ramp[:, 0].max()), rig.travel_m,
                                                    f"{folder / 'ramp.csv'}: ", TRAVEL_SAID))
    if stiffness is not None:
        for k, (a, s, _) in enumerate(stiffness):
            found += plausibility.findings({"stiffness_N_m": float(s)}, f"{folder}: ramp run "
                                           f"{ramp_names[k] if ramp_names else k + 1} ({ANGLE} = {a:g}): ")
    return warnings + plausibility.gate({}, also=found)


def write_measurements(folder: Path, rig: RigSetup, forces=None, angles=None, ramp=None,
                       angle_velocities=None):
    """Writes a measurement set (rig.toml and CSV files) to folder; the
    angles with a velocity_m_s column if angle_velocities is given."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    write_rig_toml(folder / "rig.toml", rig)
    if angles is not None and angle_velocities is not None:
        angles = [(a, p, v) for (a, p), v in zip(angles, angle_velocities)]
    for name, header, arr in (("forces.csv", f"{ANGLE},force_N", forces),
                              ("angles.csv", f"{ANGLE},phi_deg" + (",velocity_m_s" if angle_velocities
                                                                     is not None else ""), angles),
                              ("ramp.csv", "x1_m,force_N", ramp)):
        if arr is not None:
            body = "\n".join(",".join(repr(float(x)) for x in row) for row in arr)
            (folder / name).write_text(header + "\n" + body + "\n")
