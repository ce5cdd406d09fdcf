"""The fit's lack-of-fit test: whether the fitted law describes each data
group, judged by the group's own replicates.  Runs repeated at one mat
angle and velocity (a cell) scatter by the replicate error alone; the
cells' mean residuals scatter by that error too if the law fits, and by
more where it does not.  With s_v^2 the pooled replicate variance of the
cells at velocity v and n_c, m_c each cell's run count and mean residual,

    F = sum_c n_c m_c^2 / s_v(c)^2 / (cells - parameters the group determines)

follows Fisher's F with (cells - parameters, sum_c (n_c - 1)) degrees of
freedom under the hypothesis that the law fits (exactly with one velocity,
approximately when the pooled variances of several velocities are used).
A p-value under SIGNIFICANCE says the recordings hold something the law
cannot describe: a column in another unit, a sign, a rig.toml that is not
the rig's.  Units: those of the group's residuals."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .statistics import f_survival

SIGNIFICANCE = 1e-3
# What a group's lack of fit most likely means, for the user's line.
LIKELY_CAUSES = {
    "forces": "the driving forces do not follow the friction ellipse F_int + m g / sqrt(f11): forces "
              "logged in another unit than the carriage runs, a sensor's tare, or rig.toml's mass_kg",
    "angles": "the trajectory angles do not follow the law's steady angle: a tracker column in another "
              "unit or sign, the sliding rule (rig.toml's rule), the axes' offsets or the strip's terms",
    "stiffness": "the ramp runs' stiffness does not follow 1/(B^-1)_11 over the mat angles: "
                 "positions or forces of some ramp runs in another unit",
}


@dataclass(frozen=True)
class LackOfFit:
    """One group's test: the statistic F, its degrees of freedom (cells less
    the group's parameters; replicates less cells) and P(F' > F)."""
    group: str
    F: float
    dof_cells: int
    dof_replicates: int
    p_value: float

    @property
    def rejected(self) -> bool:
        return self.p_value < SIGNIFICANCE

    def line(self) -> str:
        """The user's line for a rejected group."""
        return (f"{self.group}: the fitted law does not describe the recordings (lack of fit: the "
                f"cells' mean residuals scatter {self.F:.3g} times the replicates' variance, p = "
                f"{self.p_value:.1e}); likely cause: {LIKELY_CAUSES.get(self.group, 'a unit or sign')}")

    def as_json(self) -> dict:
        return {"F": float(self.F), "dof_cells": self.dof_cells, "dof_replicates": self.dof_replicates,
                "p_value": float(self.p_value), "rejected": bool(self.rejected), "line": self.line()}


def lack_of_fit(group: str, residuals, cells, charged: int, components=None) -> LackOfFit | None:
    """The test of one group from its residuals (data - fit) and each
    value's cell (equal keys: replicates); the replicate variance pooled per
    component (e.g. velocity; None: one pool).  None where it cannot be
    tested: fewer cells than parameters plus one, under two replicate
    degrees of freedom, or replicates that do not scatter at all."""
    r = np.asarray(residuals, float)
    keys = list(cells)
    comp = list(components) if components is not None else [0] * len(r)
    by_cell: dict = {}
    for i, k in enumerate(keys):
        by_cell.setdefault(k, []).append(i)
    ss, dof = {}, {}
    for idx in by_cell.values():
        v = comp[idx[0]]
        ss[v] = ss.get(v, 0.0) + float(np.sum((r[idx] - r[idx].mean()) ** 2))
        dof[v] = dof.get(v, 0) + len(idx) - 1
    dof_cells, dof_replicates = len(by_cell) - charged, sum(dof.values())
    if dof_cells < 1 or dof_replicates < 2 or any(dof[v] > 0 and ss[v] <= 0 for v in ss):
        return None
    pooled = {v: ss[v] / dof[v] for v in ss if dof[v] > 0}
    if any(comp[idx[0]] not in pooled for idx in by_cell.values()):
        return None     # a velocity without replicates: no variance to judge its cells by
    stat = sum(len(idx) * r[idx].mean() ** 2 / pooled[comp[idx[0]]] for idx in by_cell.values()) / dof_cells
    p_value = f_survival(stat, dof_cells, dof_replicates)
    return LackOfFit(group, float(stat), dof_cells, dof_replicates, p_value)
