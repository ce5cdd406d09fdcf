"""One weighted least-squares solve of the joint fit: minimise
(1/2n) sum w_i r_i(x)^2 (n values, w_i = 1/variance) with casadi's IPOPT
and a Gauss-Newton Hessian, the parameters scaled by their information so
that the problem IPOPT sees is O(1) whatever the noise level (its Hessian
has a unit diagonal at the start: the correlation form), and the result
checked: IPOPT's own return status (ACCEPTED, or AT_PRECISION), and the
Gauss-Newton step left at the solution measured in standard errors.

Why scaled: with noise-free data the weights reach 1e20 and more; unscaled,
no double-precision point meets IPOPT's tolerance and it stops with
Search_Direction_Becomes_Too_Small.  Scaled, the same minimiser is reached
in a few iterations."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .fit_model import FitModel

# IPOPT's statuses that say it met its tolerance (the acceptable level too)
ACCEPTED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
# IPOPT's status when no double-precision step improves x: noise-free data, whose
# weights put the tolerance below rounding.  Converged only if the step left is nil.
AT_PRECISION = "Search_Direction_Becomes_Too_Small"
# A solve converged when the Gauss-Newton step still to go is below this
# many standard errors of each parameter: nothing a reader of the interval sees.
STEP_TOLERANCE_SE = 1e-3
BOUNDS = (1e-9, 1e9)            # every parameter positive, in the fit's units
IPOPT_OPTIONS = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes", "ipopt.tol": 1e-10,
                 "ipopt.acceptable_tol": 1e-3, "ipopt.acceptable_iter": 2, "ipopt.max_iter": 200,
                 "ipopt.nlp_scaling_method": "none", "ipopt.mu_init": 1e-8,
                 # the bounds exactly: a relaxed one let c_strip end at -9e-8 N s/m (x2 flipped)
                 "ipopt.bound_relax_factor": 0.0}


@dataclass(frozen=True)
class Solve:
    """One solve's outcome: x in the fit's units, IPOPT's return status and
    iteration count, and the largest Gauss-Newton step left at x in
    standard errors of its parameter."""
    x: np.ndarray
    status: str
    iterations: int
    step_se: float
    at_bound: tuple = ()     # the parameters their lower bound holds (a viscosity at 0, say)

    @property
    def converged(self) -> bool:
        return self.status in (*ACCEPTED, AT_PRECISION) and self.step_se <= STEP_TOLERANCE_SE

    def as_json(self) -> dict:
        return {"status": self.status, "iterations": self.iterations,
                "step_left_se": float(self.step_se), "converged": self.converged,
                "at_bound": list(self.at_bound)}


def information(J: np.ndarray, w: np.ndarray) -> np.ndarray:
    """J' W J: the weighted fit's Fisher information [1/unit^2 of x]."""
    return J.T @ (w[:, None] * J)


def covariance(M: np.ndarray) -> np.ndarray:
    """M^-1 (a pseudo-inverse where singular) taken in the correlation form
    D^-1 M D^-1, D = sqrt(diag M): parameters whose information differs by
    twenty orders of magnitude (F_int from noise-free carriage runs beside
    eps2 from one ramp run) each keep their own variance, which a plain
    pseudo-inverse's cut-off at 1e-15 of the largest would zero."""
    d = np.sqrt(np.maximum(np.diag(M), 1e-300))
    return np.linalg.pinv(M / np.outer(d, d)) / np.outer(d, d)


def gauss_newton_step_se(r: np.ndarray, J: np.ndarray, w: np.ndarray,
                         room: np.ndarray | None = None) -> tuple[float, np.ndarray]:
    """(the largest |Gauss-Newton step| still to go at (r, J) in standard
    errors of each parameter, 0 at a stationary point; which parameters
    their lower bound holds).  room: each parameter's distance to its lower
    bound (None: unbounded).  A parameter whose step would take it through
    its bound is held there (the bound's Karush-Kuhn-Tucker condition: an
    interior-point solver stops just short of it): the step is the others'."""
    held = np.zeros(J.shape[1], dtype=bool)
    room = np.full(J.shape[1], np.inf) if room is None else room
    while True:
        free = ~held
        cov = covariance(information(J[:, free], w))
        step = -cov @ (J[:, free].T @ (w * r))      # r = data - model: the descent is -J'Wr
        push = np.zeros(len(held))
        push[free] = step
        newly = ~held & (push < -room)
        if not newly.any():
            break
        held |= newly
    se = np.sqrt(np.maximum(np.diag(cov), 1e-300))
    return (float(np.max(np.abs(step) / se)) if len(step) else 0.0), held


class WeightedSolver:
    """IPOPT on a FitModel, built once and solved for any weights: the
    variables z = d x with d the square root of the information's diagonal
    (per value) at each solve's start, the weights and d parameters."""

    def __init__(self, model: FitModel):
        import casadi as ca
        self.model = model
        n, p = sum(model.sizes), len(model.free)
        z, w, d = ca.MX.sym("z", p), ca.MX.sym("w", n), ca.MX.sym("d", p)
        r, J = model.function(z / d)
        Jz = J / ca.repmat(d.T, n, 1)
        objective = 0.5 * ca.dot(w, r * r) / n
        r_alone = model.residual(z / d)
        lam_f, lam_g = ca.MX.sym("lam_f"), ca.MX.sym("lam_g", 0)
        hessian = ca.Function("nlp_hess_l", [z, ca.vertcat(w, d), lam_f, lam_g],
                              [ca.triu(lam_f * ca.mtimes(Jz.T, Jz * ca.repmat(w, 1, p)) / n)])
        # the gradient J' W r from the model's own Jacobian, already built: no
        # reverse mode through the strip's unrolled Newton steps
        gradient = ca.Function("nlp_grad_f", [z, ca.vertcat(w, d)], [objective, ca.mtimes(Jz.T, w * r) / n])
        problem = {"x": z, "p": ca.vertcat(w, d), "f": 0.5 * ca.dot(w, r_alone * r_alone) / n}
        self.nlp = ca.nlpsol("joint_fit", "ipopt", problem,
                             {**IPOPT_OPTIONS, "hess_lag": hessian, "grad_f": gradient})
        self.n = n

    def solve(self, x0: np.ndarray, w: np.ndarray) -> Solve:
        """Minimise from x0 (the fit's units) with weights w (one per value)."""
        r, J = self.model.evaluate(x0)
        d = np.sqrt(np.diag(information(J, w)) / self.n)
        d = np.where(d > 0, d, 1.0)
        sol = self.nlp(x0=x0 * d, p=np.concatenate([w, d]), lbx=BOUNDS[0] * d, ubx=BOUNDS[1] * d)
        stats = self.nlp.stats()
        x = np.array(sol["x"]).ravel() / d
        r, J = self.model.evaluate(x)
        step_se, held = gauss_newton_step_se(r, J, w, x - BOUNDS[0])
        return Solve(x, stats["return_status"], int(stats["iter_count"]), step_se,
                     tuple(n for n, h in zip(self.model.free, held) if h))
