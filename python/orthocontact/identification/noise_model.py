"""The fit's noise model: each value of a data group scatters by the group's
between-run variance tau^2 (run-to-run scatter: drift, placement, the mat's
variation; estimated) plus its own within-run variance se_i^2 (from the run's
line fit or mean; known).  Ten runs at one angle are then ten draws of the
run-to-run scatter, each weighted by 1 / (tau^2 + se_i^2), not ten
measurements as precise as their within-run errors.  Reduced data without
within-run errors (se = 0) make tau^2 the plain residual variance."""
from __future__ import annotations

import math

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
        # a value with no within-run error and no residual adds nothing (not 0/0)
        with np.errstate(divide="ignore"):
            return float(np.sum(np.where(r2 == 0, 0.0, r2 / np.maximum(t2 + se2, 0.0))))
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


def between_run_tau2(r, se2, charged: int, labels=None) -> np.ndarray:
    """Per value, its component's tau^2: one component per distinct label
    (e.g. the velocity), each with its share of the `charged` parameters'
    degrees of freedom; one for the whole group without labels, or when a
    component would have under one degree of freedom."""
    r, se2 = np.asarray(r, float), np.asarray(se2, float)
    n = len(r)
    whole = between_run_variance(r, se2, n - charged)
    if labels is None:
        return np.full(n, whole)
    labels = np.asarray(labels)
    out = np.full(n, whole)
    for c in np.unique(labels):
        m = labels == c
        dof = m.sum() * (1 - charged / n)
        if dof >= 1:
            out[m] = between_run_variance(r[m], se2[m], dof)
    return out


def tau_summary(tau2: np.ndarray, labels=None):
    """tau of a group: a number, or {label: tau} with several components."""
    tau2 = np.asarray(tau2, float)
    if labels is None or len(np.unique(labels)) < 2:
        return float(np.sqrt(tau2.mean()))
    labels = np.asarray(labels)
    return {f"{c:g}": float(np.sqrt(tau2[labels == c].mean())) for c in np.unique(labels)}


def variance_parts(A: np.ndarray, WJ: np.ndarray, sizes: list, between: list, within: list) -> list:
    """The fitted parameters' covariance A (WJ' Sigma WJ) A' as its parts, one per
    variance component, for satterthwaite(): (covariance, dof) of each group's
    between-run tau^2 (between: (tau2 per value, its dof)) and of its
    within-run se^2 (known: infinite dof).  A is the inverse information
    (in the fit's scaling and back), WJ the weighted Jacobian's rows, in the
    groups' order and sizes."""
    parts = []
    for rows, (tau2, nu), se2 in zip(np.split(WJ, np.cumsum(sizes)[:-1]), between, within):
        for var_c, dof in ((tau2, nu), (se2, math.inf)):
            parts.append((A @ (rows.T @ (np.asarray(var_c, float)[:, None] * rows)) @ A.T, dof))
    return parts
