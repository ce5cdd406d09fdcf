"""Synthetic raw recordings with known truth (tools/make_recordings.py) for
the tests of a set's cross-checks: made in memory as a Recordings, or
written as a folder, with one column converted as a lab might have logged
it (x2 in mm, a force in kN, a time in ms, a sign flipped)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

import make_recordings as mr
from orthocontact.experiment.rig_setup import RigSetup
from orthocontact.identification.recordings import Recordings, Run
from orthocontact.identification.reduction import reduce_run

# The --small set of make_recordings, with fewer runs: 3 slides an angle, 2
# carriage runs, 1 ramp run (its reduction takes about 0.1 s).
TRUTH = mr.Truth(c_strip=0.0)
DESIGN = mr.Design(angles_deg=[0, 30, 60, 90], velocities={0.244: 3}, carriage_runs=2, ramp_runs=1)


def physics(truth: mr.Truth = TRUTH, design: mr.Design = DESIGN) -> tuple:
    """The reference simulator's steady paths and ramp for a design (the
    slow part, shared by a module's sets)."""
    return (mr.steady_paths(truth, design.angles_deg, list(design.velocities), design.settle_m),
            mr.ramp_path(truth, design.ramp_travel_m))


def made(physics, truth=TRUTH, design=DESIGN, seed=1, convert=None) -> dict:
    """make_recordings' runs {name: (kind, angle, velocity, trajectory or
    None, forces)}, each passed through convert(kind, trajectory copy,
    forces copy) -> (trajectory, forces) where given."""
    runs = mr.make_runs(truth, mr.Sensors(), design, np.random.default_rng(seed), *physics)
    if convert is None:
        return runs
    out = {}
    for name, (kind, a, v, traj, forces) in runs.items():
        traj, forces = convert(kind, None if traj is None else traj.copy(), forces.copy())
        out[name] = (kind, a, v, traj, forces)
    return out


def folder(path: Path, runs: dict, truth=TRUTH) -> Path:
    """The runs written as a recordings folder at `path`."""
    mr.write_folder(path, truth, runs)
    return path


def recordings(runs: dict, truth=TRUTH) -> Recordings:
    """The runs as a Recordings in memory (files named, none written)."""
    rig = RigSetup(truth.mass_kg, truth.g, rule=truth.rule, alpha_offset_deg=truth.alpha_offset_deg,
                   beta_offset_deg=truth.beta_offset_deg)
    rows = [Run(name, kind, a, v, line, traj, forces,
                None if traj is None else Path("set", "trajectories", f"{name}.csv"),
                Path("set", "forces", f"{name}.csv"))
            for line, (name, (kind, a, v, traj, forces)) in enumerate(runs.items(), start=2)]
    return Recordings(Path("set"), rig, rows, False)


def reduced(rec: Recordings) -> list:
    """Each run of `rec` reduced on its own (no cross-checks)."""
    return [reduce_run(run, []) for run in rec.runs]


def scaled(column: int, factor: float, kinds=("slide", "ramp", "carriage"), series="trajectory"):
    """A convert for made(): column `column` of each `series` ("trajectory"
    or "forces") of the runs of `kinds` times `factor`."""
    def convert(kind, traj, forces):
        arr = traj if series == "trajectory" else forces
        if kind in kinds and arr is not None:
            arr[:, column] *= factor
        return traj, forces
    return convert
