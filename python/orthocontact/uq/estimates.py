"""What uq draws from: identified.json's estimates and covariance, as the one
reader gives them (identification.identified_file: every field checked, the
file as its identify run wrote it, the data it names unchanged), and the
seeded draws of physical parameter sets."""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..identification import IdentifiedFile, read_identified

LAW_PARAMETERS = ("mu1", "mu2", "eps_ratio", "eps2")


IMPLICIT_RULES = ("associated", "coupled")


@dataclass
class Estimates:
    """What uq draws from: names, values and covariance of the identified
    parameters (mu1, mu2 [-], eps_ratio [-], eps2 [N/m], any subset), and the
    identification's rule, geometry and measured points."""
    path: Path
    names: list
    mean: np.ndarray
    cov: np.ndarray
    rule: str
    alpha_offset_deg: float
    beta_offset_deg: float
    angle_points: np.ndarray | None  # [[mat angle deg, phi deg counterclockwise]]
    angle_noise_deg: float | None    # the identification's noise estimate of a measured angle
    angle_velocities: np.ndarray | None = None   # m/s of each measured angle (raw recordings)
    angle_noise_by_velocity: dict | None = None  # m/s -> noise of a measured angle at it [deg]

    def at_velocity(self, v: float):
        """(measured angles, noise of a new measured angle [deg]) at the
        carriage velocity v [m/s]: with runs at several velocities, those at
        v and their own scatter; otherwise all of them."""
        pts, noise = self.angle_points, self.angle_noise_deg
        if pts is not None and self.angle_velocities is not None:
            pts = pts[np.isclose(self.angle_velocities, v, rtol=1e-9)]
            pts = pts if len(pts) else None
        for key, n in (self.angle_noise_by_velocity or {}).items():
            if math.isclose(float(key), v, rel_tol=1e-9):
                noise = n
        return pts, noise


def load_estimates(path) -> Estimates:
    """identified.json -> Estimates (read_identified, then estimates_of);
    InputError naming the file and the field, or the data files that
    changed since the identification read them."""
    return estimates_of(read_identified(path))


def estimates_of(f: IdentifiedFile) -> Estimates:
    """What uq draws from in an identification read back (read_identified:
    every field checked, its data found unchanged): the covariance of the
    law's parameters, which must be some of LAW_PARAMETERS and positive
    semidefinite, and an implicit rule's measured angles."""
    path, cov = f.path, f.covariance
    names = list(cov.parameters)
    unknown = [n for n in names if n not in LAW_PARAMETERS]
    if unknown:
        raise InputError(f"{path}: covariance.parameters: expected some of {', '.join(LAW_PARAMETERS)}"
                         f", got {names!r}")
    mean, C = np.array(cov.values, dtype=float), np.array(cov.matrix, dtype=float)
    # Judged in correlation form: the parameters' scales differ by 1e8.
    sd = np.sqrt(np.clip(np.diag(C), 0, None))
    norm = np.outer(sd, sd)
    norm[norm == 0] = 1.0
    if np.any(np.diag(C) < 0) or np.abs(C - C.T).max(initial=0) > 1e-9 * norm.max() or \
            np.any(np.abs(C - C.T) / norm > 1e-6) or \
            np.linalg.eigvalsh(0.5 * (C + C.T) / norm).min() < -1e-9:
        raise InputError(f"{path}: covariance.matrix: expected a symmetric positive semidefinite "
                         "matrix")
    a = f.assumptions
    pts = f.points
    points = np.array(pts.angles, dtype=float).reshape(-1, 2) if pts.angles else None
    noise = f.noise_estimate.get("angles_deg")
    by_v = f.noise_estimate.get("angles_deg_by_velocity")
    return Estimates(
        path=path, names=names, mean=mean, cov=0.5 * (C + C.T), rule=a.rule,
        alpha_offset_deg=a.alpha_offset_deg, beta_offset_deg=a.beta_offset_deg, angle_points=points,
        angle_noise_deg=noise,
        angle_velocities=None if points is None or pts.angle_velocities is None
        else np.array(pts.angle_velocities, dtype=float),
        angle_noise_by_velocity=None if by_v is None else {float(k): float(v) for k, v in by_v.items()})


def draw(est: Estimates, n: int, seed: int) -> tuple[np.ndarray, float]:
    """n parameter sets (rows, columns est.names) from the normal
    distribution of the estimates, only those with every parameter > 0 (the
    normal truncated to the physical region); and the fraction of draws kept."""
    rng = np.random.default_rng(seed)
    kept, have, drawn = [], 0, 0
    while have < n:
        batch = max(1024, 2 * (n - have))
        # eigh: defined for a semidefinite covariance too, and the same on every machine
        x = rng.multivariate_normal(est.mean, est.cov, size=batch, method="eigh")
        drawn += batch
        kept.append(x[np.all(x > 0, axis=1)])
        have += len(kept[-1])
        if drawn >= 1000 * n + 10**6 and have < n:
            raise InputError(f"{est.path}: covariance: fewer than 1 in 1000 draws are physical "
                             "(all parameters > 0); the estimates are too uncertain to propagate")
    return np.concatenate(kept)[:n], have / drawn
