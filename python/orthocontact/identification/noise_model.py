"""The fit's noise model: each value of a data group scatters by the group's
between-run variance tau^2 (run-to-run scatter: drift, placement, the mat's
variation; estimated) plus its own within-run variance se_i^2 (from the run's
line fit or mean; known).  Ten runs at one angle are then ten draws of the
run-to-run scatter, each weighted by 1 / (tau^2 + se_i^2), not ten
measurements as precise as their within-run errors.  Reduced data without
within-run errors (se = 0) make tau^2 the plain residual variance."""
from __future__ import annotations

import numpy as np


def between_run_variance(r: np.ndarray, se2: np.ndarray, dof: float) -> float:
    """tau^2 >= 0 of the Paule-Mandel equation sum r_i^2 / (tau^2 + se_i^2)
    = dof (the generalised chi-square equal to its degrees of freedom); 0
    when the within-run errors alone explain the scatter."""
    r2 = np.asarray(r, float) ** 2
    se2 = np.asarray(se2, float)
    if dof <= 0:
        raise ValueError("between_run_variance: needs residual degrees of freedom")

    def q(t2):
        return float(np.sum(r2 / (t2 + se2)))
    if np.all(se2 == 0):
        return float(r2.sum() / dof)
    if q(0.0) <= dof:
        return 0.0
    lo, hi = 0.0, max(float(r2.sum() / dof), 1e-300)
    while q(hi) > dof:
        hi *= 2
    for _ in range(200):          # q decreases in tau^2: bisection
        mid = 0.5 * (lo + hi)
        if q(mid) > dof:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-14 * hi:
            break
    return 0.5 * (lo + hi)
