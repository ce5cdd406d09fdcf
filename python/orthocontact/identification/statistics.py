"""The statistics of identification: Student-t quantiles for (not
necessarily whole) degrees of freedom, residual summaries, JSON forms."""
from __future__ import annotations

import math

import numpy as np


def t975(dof: float) -> float:
    """97.5% quantile of Student's t for dof degrees of freedom (not
    necessarily whole; Cornish-Fisher expansion, better than 1e-4 for
    dof >= 3); 1.96 in the limit."""
    if dof <= 0:
        return float("nan")
    z = 1.959963984540054
    g1 = (z**3 + z) / 4
    g2 = (5 * z**5 + 16 * z**3 + 3 * z) / 96
    g3 = (3 * z**7 + 19 * z**5 + 17 * z**3 - 15 * z) / 384
    g4 = (79 * z**9 + 776 * z**7 + 1482 * z**5 - 1920 * z**3 - 945 * z) / 92160
    n = float(dof)
    return z + g1 / n + g2 / n**2 + g3 / n**3 + g4 / n**4


def res_stats(res: np.ndarray) -> dict:
    return {"rms": float(np.sqrt(np.mean(res**2))), "max_abs": float(np.max(np.abs(res))),
            "mean": float(np.mean(res)), "n": int(len(res))}


def json_dof(nu):
    return None if nu is None else ("inf" if not math.isfinite(nu) else round(float(nu), 2))
