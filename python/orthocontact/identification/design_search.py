"""Optimal designs over a finite set of candidate runs, given each run's
Fisher information: the approximate design by the multiplicative algorithm
(with its equivalence-theorem check), rounded to whole runs and improved by
exchange (Fedorov), and the criteria that judge a design.

The information of a design is M = M_fixed + sum_c n_c I_c (n_c runs of
candidate c; M_fixed the runs already made).  Its covariance is M^-1, and
of the designed parameters S (the others, F_int, are nuisance) the block
C_S.  D-optimal minimises log det C_S (with every parameter designed,
maximises log det M); A-optimal minimises tr C_S, in units that make each
parameter's variance relative (the caller's units: its prior values).
Candidates come in groups (slide runs, ramp samples), each with its own
number of runs.  No units here: the caller's."""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

CRITERIA = ("D", "A")
# The multiplicative algorithm's step exponent: 1 for D (monotone, Titterington),
# 1/2 for A (monotone for exponents up to 1/2, Yu 2010).
EXPONENT = {"D": 1.0, "A": 0.5}
# An information matrix in correlation form whose determinant is below this is singular.
SINGULAR = 1e-12


@dataclass(frozen=True)
class Problem:
    """A design problem: each candidate's information per run (C, p, p), its
    group (C,), each group's number of runs, the information of the runs
    already made (p, p), the designed parameters' indices and the criterion."""
    info: np.ndarray
    group: np.ndarray
    budget: tuple
    fixed: np.ndarray
    designed: tuple
    criterion: str

    def information(self, counts) -> np.ndarray:
        """M of a design: n_c runs (or a weight) of each candidate."""
        return self.fixed + np.einsum("c,cij->ij", np.asarray(counts, float), self.info)

    def rank_bound(self) -> int:
        """The highest rank the information of whole runs within the budget
        can reach: the runs made's, plus each run at most its group's highest."""
        ranks = np.linalg.matrix_rank(self.info) if len(self.info) else np.zeros(0, int)
        most = [int(ranks[self.group == g].max(initial=0)) for g in range(len(self.budget))]
        return int(np.linalg.matrix_rank(self.fixed)) + sum(n * r for n, r in zip(self.budget, most))

    def loss(self, M) -> np.ndarray:
        """The criterion of one M (p, p) or of many (k, p, p): log det C_S
        (D) or tr C_S (A); inf where M is singular."""
        M = np.asarray(M, float)
        one = M.ndim == 2
        M = M[None] if one else M
        diag = np.maximum(np.einsum("kii->ki", M), 1e-300)
        d = np.sqrt(diag)
        sign, logdet = np.linalg.slogdet(M / (d[:, :, None] * d[:, None, :]))
        # A parameter told SINGULAR times less than another (in the design's
        # units, each by its prior value) is told nothing: its row is rounding,
        # which the correlation form would scale up to look like information.
        told = diag.min(axis=1) > SINGULAR * diag.max(axis=1)
        ok = (sign > 0) & (logdet > math.log(SINGULAR)) & told
        out = np.full(len(M), np.inf)
        if ok.any():
            S = list(self.designed)
            cov = np.linalg.inv(M[ok])
            block = cov[:, S][:, :, S]
            out[ok] = np.linalg.slogdet(block)[1] if self.criterion == "D" else np.einsum("kii->k", block)
        return out[0] if one else out

    def sensitivity(self, M) -> np.ndarray:
        """d_c: the criterion's gain per unit of candidate c's weight at M,
        tr(I_c H) with H = Cov[:, S] C_S^-1 Cov[S, :] (D; Cov itself when every
        parameter is designed) or Cov[:, S] Cov[S, :] (A)."""
        cov = np.linalg.inv(M)
        S = list(self.designed)
        left = cov[:, S]
        H = left @ np.linalg.solve(cov[np.ix_(S, S)], left.T) if self.criterion == "D" else left @ left.T
        return np.einsum("cij,ji->c", self.info, H)

    def efficiency(self, M, M_reference) -> float:
        """How much better M is than M_reference: (det C_S,ref / det C_S)^(1/s)
        (D; with every parameter designed, (det M / det M_ref)^(1/p)) or
        tr C_S,ref / tr C_S (A): above 1, M is the better design."""
        a, b = self.loss(M), self.loss(M_reference)
        if self.criterion == "D":
            return math.exp((b - a) / len(self.designed))
        return b / a


@dataclass(frozen=True)
class Equivalence:
    """The equivalence theorem at an approximate design: within each group,
    no candidate's sensitivity d_c exceeds the design's average
    sum_c w_c d_c (for D with nothing fixed: max_c tr(M^-1 I_c)/p <= 1, M per
    run).  max_ratio is the largest d_c / average; holds when it is at most
    1 + tolerance."""
    max_ratio: float
    tolerance: float
    iterations: int

    @property
    def holds(self) -> bool:
        return self.max_ratio <= 1.0 + self.tolerance


def group_ratios(problem: Problem, weights: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Each candidate's d_c over its group's weighted average sum w d."""
    average = np.zeros(len(problem.budget))
    np.add.at(average, problem.group, weights * d)
    return d / average[problem.group]


def approximate(problem: Problem, tolerance: float = 1e-3, max_iterations: int = 50000,
                status: Status | None = None) -> tuple[np.ndarray, Equivalence]:
    """The approximate optimum: each group's weights (summing to 1, times
    its number of runs) by the multiplicative algorithm, w_c <- w_c (d_c /
    average)^k, until the equivalence theorem holds to tolerance / 10 (or
    max_iterations); `status` says the iteration (runs.progress.status_lines prints it)."""
    sizes = np.bincount(problem.group, minlength=len(problem.budget)).astype(float)
    weights = 1.0 / sizes[problem.group]
    runs = np.asarray(problem.budget, float)[problem.group]
    if not np.isfinite(problem.loss(problem.information(runs * weights))):
        raise InputError("expected candidate runs that determine every parameter: even all of them at "
                         "once leave the information matrix singular")
    k, iteration = EXPONENT[problem.criterion], 0
    for iteration in range(1, max_iterations + 1):
        ratio = group_ratios(problem, weights, problem.sensitivity(problem.information(runs * weights)))
        if ratio.max() <= 1.0 + tolerance / 10:
            break
        weights = weights * ratio ** k
        total = np.zeros(len(problem.budget))
        np.add.at(total, problem.group, weights)
        weights = weights / total[problem.group]
        if status is not None:
            status.text = (f"approximate design: iteration {iteration}, max sensitivity ratio "
                           f"{ratio.max():.5f}")
    return weights, Equivalence(float(ratio.max()), tolerance, iteration)


def rounded(problem: Problem, weights: np.ndarray) -> np.ndarray:
    """Whole runs from an approximate design, group by group, by efficient
    rounding (Pukelsheim and Rieder 1992): n_c = ceil((n - l/2) w_c) over
    the l points of the support, then one up or down where it costs least.
    The support: the weights worth a quarter run or more (the algorithm
    stops with a little weight left beside it), at most n of them."""
    counts = np.zeros(len(weights), int)
    for g, n in enumerate(problem.budget):
        idx = np.flatnonzero(problem.group == g)
        w = weights[idx]
        support = idx[np.argsort(-w)[:max(1, min(n, int(np.sum(w >= 0.25 / n))))]]
        ws = weights[support] / weights[support].sum()
        k = np.ceil((n - len(support) / 2) * ws).astype(int)
        while k.sum() < n:
            k[np.argmin(k / ws)] += 1
        while k.sum() > n:
            k[np.argmax((k - 1) / ws)] -= 1
        counts[support] = k
    return counts


def greedy(problem: Problem) -> np.ndarray:
    """Whole runs added one at a time, each the best given those before
    (a small ridge keeps the first steps' information invertible)."""
    counts = np.zeros(len(problem.group), int)
    top = max(float(np.max(np.einsum("cii->c", problem.info))), 1e-300)
    ridge = 1e-9 * top * np.eye(problem.fixed.shape[0])
    for g, n in enumerate(problem.budget):
        idx = np.flatnonzero(problem.group == g)
        for _ in range(n):
            M = problem.information(counts) + ridge
            counts[idx[int(np.argmin(problem.loss(M[None] + problem.info[idx])))]] += 1
    return counts


def exchange(problem: Problem, counts: np.ndarray) -> np.ndarray:
    """Fedorov's exchange: while some run of the design, replaced by another
    candidate of its group, improves the criterion, the best such swap."""
    counts = counts.copy()
    while True:
        M, best = problem.information(counts), (problem.loss(problem.information(counts)), None, None)
        for r in np.flatnonzero(counts):
            idx = np.flatnonzero(problem.group == problem.group[r])
            losses = problem.loss((M - problem.info[r])[None] + problem.info[idx])
            j = int(np.argmin(losses))
            if losses[j] < best[0] - 1e-12 * max(1.0, abs(best[0])):
                best = (losses[j], r, idx[j])
        if best[1] is None:
            return counts
        counts[best[1]] -= 1
        counts[best[2]] += 1


def exact(problem: Problem, weights: np.ndarray) -> np.ndarray:
    """The best whole-run design found: exchange from the rounded
    approximate optimum and from the greedy one."""
    starts = [rounded(problem, weights), greedy(problem)]
    found = [exchange(problem, c) for c in starts]
    return min(found, key=lambda c: problem.loss(problem.information(c)))


@dataclass
class Status:
    """What a design's search is doing now, for its progress lines."""
    text: str = ""


def stderr_say(text: str) -> None:
    """A progress line on stderr."""
    print(f"design: {text}", file=sys.stderr, flush=True)
