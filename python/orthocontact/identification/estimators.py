"""The estimators: the paper's calibration formulas (eq. 1, the maximum
rule eq. 29/37-39, eq. 40/41) and the joint weighted least-squares fit of all
data (casadi/IPOPT) with Gauss-Newton covariance and per-parameter
Welch-Satterthwaite intervals.

Models (closed_forms): driving force F_int + m g / sqrt(f11) (friction
ellipse, eq. 1 at 0 and 90 deg); steady angle eq. (10)/(23) from the tensors;
stick branch of the ramp F_int + k x1 with k = 1/(B^-1)_11.  Units: N, m, deg."""
from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass, field

import numpy as np

from .. import closed_forms as cf
from ..errors import InputError
from ..experiment import RigSetup
from . import fit_model
from .lack_of_fit import lack_of_fit
from .measurements import MeasurementSet, friction_axis_key
from .noise_model import between_run_tau2, tau_summary, variance_parts
from .solver import WeightedSolver, covariance
from .statistics import positive_ci, satterthwaite, t975
from .strip_model import strip_regimes


def eq1(data: MeasurementSet) -> dict | None:
    """mu1, mu2 by eq. (1) from the mean forces at the friction axes."""
    if data.forces is None:
        return None
    a, f = data.forces[:, 0], data.forces[:, 1]
    key = friction_axis_key(data.rig, a)
    on1, on2 = np.isclose(key, 1.0, atol=1e-12), np.isclose(key, 0.0, atol=1e-12)
    if not on1.any() or not on2.any():
        return None
    r = data.rig
    return {"mu1": cf.eq1_mu(float(np.mean(f[on1])), r.f_int_N, r.mass_kg, r.g),
            "mu2": cf.eq1_mu(float(np.mean(f[on2])), r.f_int_N, r.mass_kg, r.g)}


def _mean_by_angle(values: np.ndarray):
    angles = np.unique(values[:, 0])
    return angles, np.array([values[values[:, 0] == a, 1].mean() for a in angles])


def _tan_alpha(rig: RigSetup, angles_deg):
    return np.tan(np.radians(np.asarray(angles_deg) + rig.alpha_offset_deg))


def max_rule(data: MeasurementSet, mu1: float | None, mu2: float | None) -> dict | None:
    """The paper's maximum rule (eq. 29, 37-39): l1/l2 from the largest
    |phi| of the mean angle curve, then eps1/eps2 from mu1, mu2."""
    rig = data.rig
    if data.angles is None or rig.rule == "associated" or not _eq25_geometry(rig):
        return None
    a, phi = _mean_by_angle(data.angles)
    k = int(np.argmax(np.abs(phi)))
    # eq. (28): tan phi_ext = s (l2^2 - l1^2) / (2 l1 l2) with s the sign of tan(alpha)
    # at the extremum; eq. (29) is its positive root.
    s = 1.0 if _tan_alpha(rig, a[k]) > 0 else -1.0
    ratio = cf.eq29_ratio(s * math.tan(math.radians(phi[k])))
    out = {"phi_ext_deg": float(phi[k]), "at_alpha_deg": float(a[k]), "l1_l2_ratio": ratio}
    if mu1 is not None:
        out["eps_ratio"] = _eps_ratio_from_l(ratio, mu1, mu2, rig)
    return out


def _eps_ratio_from_l(ratio, mu1, mu2, rig: RigSetup):
    """eps1/eps2 from l1/l2: Case 5 geometry l = eps1 mu1/(eps2 mu2) (eq. 37, 39),
    Case 4 l = eps1 mu2/(eps2 mu1)."""
    d = math.degrees(rig.beta_minus_alpha) % 180.0
    return cf.eps_ratio_from_r(ratio, mu1, mu2) if abs(d - 90.0) < 1e-9 else ratio * mu1 / mu2


def eq40_fit(data: MeasurementSet, mu1=None, mu2=None) -> dict | None:
    """l1/l2 by the exact least squares of eq. (40), solved with casadi/IPOPT,
    and the paper's closed form eq. (41) beside it."""
    import casadi as ca
    rig = data.rig
    if data.angles is None or rig.rule == "associated" or not _eq25_geometry(rig):
        return None
    ta = _tan_alpha(rig, data.angles[:, 0])
    tphi = np.tan(np.radians(data.angles[:, 1]))
    r2 = ca.SX.sym("r2")
    res = ca.vertcat(*[tp + (r2 - 1) * t / (r2 * t * t + 1) for t, tp in zip(ta, tphi)])
    solver = ca.nlpsol("eq40", "ipopt", {"x": r2, "f": ca.sumsqr(res)},
                       {"ipopt.print_level": 0, "print_time": False, "ipopt.tol": 1e-14,
                        "ipopt.sb": "yes"})
    # start from the maximum rule: IPOPT finds the minimiser nearest to it
    mr = max_rule(data, mu1, mu2)
    x0 = mr["l1_l2_ratio"] ** 2 if mr else 1.0
    sol = solver(x0=x0, lbx=1e-8, ubx=1e8)
    r2_fit = float(sol["x"])
    r2_41 = cf.eq41_r2(ta, tphi)
    out = {"r2": r2_fit, "l1_l2_ratio": math.sqrt(r2_fit), "objective": float(sol["f"]),
           "solver": solver.stats()["return_status"],
           "eq41": {"r2": r2_41, "l1_l2_ratio": math.sqrt(r2_41) if r2_41 > 0 else float("nan"),
                    "objective": cf.eq40_objective(r2_41, ta, tphi),
                    "note": "the paper's closed form (41); not the minimiser of eq. (40)"}}
    if mu1 is not None:
        out["eps_ratio"] = _eps_ratio_from_l(out["l1_l2_ratio"], mu1, mu2, rig)
        out["eq41"]["eps_ratio"] = _eps_ratio_from_l(out["eq41"]["l1_l2_ratio"], mu1, mu2, rig)
    return out


def keyword_only(cls):
    """The dataclass `cls` with an __init__ of keywords only (kw_only=True
    needs Python 3.10): a swapped pair is a TypeError, not a wrong result."""
    init = cls.__init__
    cls.__init__ = functools.wraps(init)(lambda self, **fields: init(self, **fields))  # signature: the fields
    return cls


@keyword_only
@dataclass
class JointFit:
    """The joint fit's result; values in their parameter's unit, a group's noise in its data's."""
    free: list                      # names of the fitted parameters
    values: dict                    # name -> value (incl. derived eps1)
    cov: np.ndarray                 # covariance of the free parameters
    stderr: dict                    # name -> standard error
    ci95: dict                      # name -> (low, high), the 95 % interval
    dof: int                        # residual degrees of freedom: values less parameters
    sigma: dict                     # group -> noise estimate
    residuals: dict                 # group -> array of residuals (data - model)
    not_identifiable: dict = field(default_factory=dict)   # name -> reason
    stick_points: int = 0
    sigma_assumed: list = field(default_factory=list)      # groups whose noise is the prior
    param_dof: dict = field(default_factory=dict)  # name -> Welch-Satterthwaite dof of its interval
    between_runs: dict = field(default_factory=dict)  # group -> tau, the run-to-run scatter
    within_run: dict = field(default_factory=dict)    # group -> rms of the within-run errors
    between_runs_dof: dict = field(default_factory=dict)  # group -> dof of its tau^2 (inf: the prior)
    solves: tuple = ()               # each solve's status, iterations, step left (solver.Solve.as_json)
    reweighting_rounds: int = 0      # solves of the last fit until the noise model settled
    convergence: dict = field(default_factory=dict)  # what converged: solver, noise_model, strip_*
    lack_of_fit: dict = field(default_factory=dict)  # group -> lack_of_fit.LackOfFit (groups with replicates)
    weights: dict = field(default_factory=dict)      # group -> each value's final weight 1/(tau^2 + se^2)

    @property
    def converged(self) -> bool:
        """The last solve met IPOPT's tolerance with no step left, the noise
        model settled, and the strip's regimes and roots are those at the solution."""
        return bool(self.convergence) and all(self.convergence.values())


def identifiability(data: MeasurementSet) -> tuple[list, dict]:
    """Which of mu1, mu2, eps_ratio, eps2 the data determine, and why not the
    others (a statement instead of an arbitrary number)."""
    rig = data.rig
    free, why = [], {}
    if data.forces is not None:
        free += ["mu1", "mu2"]
    else:
        why["mu1"] = why["mu2"] = "needs driving forces (forces.csv) at two mat angles"
    informative_angles = data.angles is not None and np.any(
        np.abs(np.sin(2 * np.radians(data.angles[:, 0] + rig.alpha_offset_deg))) > 1e-9)
    if rig.rule == "associated":
        why["eps_ratio"] = "the associated rule's trajectory does not depend on the stiffness"
    elif not informative_angles:
        why["eps_ratio"] = "needs trajectory angles (angles.csv) away from the tensor axes"
    elif "mu1" not in free:
        why["eps_ratio"] = ("trajectory angles fix only l1/l2 = (eps1/eps2)(mu1/mu2); "
                            "mu1/mu2 needs forces.csv")
        if _eq25_geometry(rig):
            free.append("l1_l2_ratio")
    else:
        free.append("eps_ratio")
    if data.ramp is None and data.stiffness is None:
        why["eps2"] = why["eps1"] = ("absolute stiffness does not show in steady sliding (forces, "
                                     "angles); it needs the pre-sliding ramp (ramp.csv, or ramp runs)")
    else:
        ramp_angles = [rig.ramp_angle_deg] if data.stiffness is None else data.stiffness[:, 0]
        alpha_r = math.radians(float(ramp_angles[0]) + rig.alpha_offset_deg)
        if "eps_ratio" in free or abs(math.cos(alpha_r)) < 1e-9:
            free.append("eps2")
        else:
            why["eps2"] = ("the ramp's stiffness mixes eps1 and eps2 at this ramp angle; "
                           "separating them needs eps_ratio")
        if "eps_ratio" not in free:
            why["eps1"] = "eps1 = eps_ratio * eps2 needs eps_ratio"
    if data.f_int_free and ("mu1" in free or data.ramp is not None):
        free.append("f_int")
    if rig.c_strip is None:
        n_v = 0 if data.angles is None else len(np.unique(np.round(data.velocities_of_angles(), 9)))
        if "eps_ratio" in free and n_v >= 2:
            free.append("c_strip")
        else:
            why["c_strip"] = ("the strip's viscosity shows only as a change of the angle with "
                              "velocity: it needs angles.csv at two or more velocities "
                              "(velocity_m_s column) and eps_ratio; taken as 0")
    return free, why


def _eq25_geometry(rig: RigSetup) -> bool:
    """A = B F B has its eigenbasis at alpha (Case 4 or 5 geometry), so eq. (25) holds."""
    return cf.eq25_lambdas(1.0, 1.0, 1.0, 1.0, rig.beta_minus_alpha) is not None


# The reweighting (noise_model) ends when no group's variance moves by more than this share
TAU2_TOLERANCE = 1e-4
MAX_ROUNDS = 30
MAX_REGIME_FITS = 4
# No value is known better than this share of its group's largest: the weights' floor,
# which noise-free data reach (the data's own rounding is above it).
RELATIVE_FLOOR = 1e-10
# Each group's noise before its residuals tell: 0.05 N, 0.5 deg, 1 % of eps2.
PRIOR_SD = {"forces": 0.05, "angles": 0.5, "ramp": 0.05, "carriage": 0.05}


@dataclass(frozen=True)
class Weighting:
    """The noise model's state: each value's between-run tau^2 and
    within-run se^2, per group, and the groups whose tau^2 stays the prior."""
    tau2: dict
    se2: dict
    floor: dict
    assumed: tuple

    def weights(self, names) -> np.ndarray:
        return np.concatenate([1.0 / np.maximum(self.tau2[g] + self.se2[g], self.floor[g]) for g in names])


def joint_fit(data: MeasurementSet, start: dict, on_solve=None) -> JointFit:
    """Weighted nonlinear least squares of all data present over the
    identifiable parameters, each group weighted by its own noise,
    re-estimated from its residuals until it settles; covariance
    (J^T W J)^-1 at the optimum (Gauss-Newton).  With the strip's Coulomb
    friction, fitted again from its own result until the regimes of motion
    (strip_regimes) the model was built for are those at the solution, and
    with the strip until its Newton steps reach the steady states there.
    on_solve: called after each solve (a progress line's count)."""
    free, why = identifiability(data)
    if not free:
        raise InputError(f"{data.folder}: expected data that determine at least one parameter: "
                         + "; ".join(f"{k}: {v}" for k, v in why.items()))
    solves = []
    for _ in range(MAX_REGIME_FITS):
        model = fit_model.build(data, start, free)
        x, weighting, rounds, settled = _reweighted_fit(model, start, solves, on_solve)
        values = dict(start, **model.values(x))
        regimes_kept = strip_regimes(data, values) == strip_regimes(data, start)
        roots = model.strip_roots_converged(x, data.rig.normal_force)
        if regimes_kept and roots:
            break
        start = values      # the strip's model again, built at the solution
    converged = {"solver": solves[-1].converged, "noise_model": settled, "strip_regimes": regimes_kept,
                 "strip_roots": roots}
    return _fit_result(model, data, x, weighting, why, solves, rounds, converged)


def _reweighted_fit(model: fit_model.FitModel, start: dict, solves: list, on_solve=None):
    """(x, Weighting, rounds, settled) of the solve-and-reweight loop: each
    group's tau^2 from its residuals (noise_model) until it moves by less
    than TAU2_TOLERANCE of its variance; every solve appended to `solves`."""
    names = [g.name for g in model.groups]
    prior = {**PRIOR_SD, "stiffness": 0.01 * start.get("eps2", 1e4)}
    assumed = tuple(g.name for g in model.groups if g.size - g.charged <= 0)
    weighting = Weighting(tau2={g.name: np.full(g.size, prior[g.name] ** 2) for g in model.groups},
                          se2={g.name: g.se2 for g in model.groups},
                          floor={g.name: (RELATIVE_FLOOR * g.magnitude) ** 2 for g in model.groups},
                          assumed=assumed)
    solver = WeightedSolver(model)
    x, settled = model.x_of(start), False
    rounds = 0
    while rounds < MAX_ROUNDS:
        rounds += 1
        w = weighting.weights(names)
        solves.append(solver.solve(x, w))
        if on_solve is not None:
            on_solve()
        x = solves[-1].x
        parts = model.split(model.evaluate(x)[0])
        tau2 = {g.name: weighting.tau2[g.name] if g.name in assumed else
                between_run_tau2(parts[g.name], g.se2, g.charged, g.components) for g in model.groups}
        new = dataclasses.replace(weighting, tau2=tau2)
        moved = np.max(np.abs(1.0 / new.weights(names) - 1.0 / w) * w)
        weighting = new
        if moved <= TAU2_TOLERANCE:
            settled = True
            break
    return x, weighting, rounds, settled


def _fit_result(model, data, x, weighting: Weighting, why: dict, solves: list, rounds: int,
                converged: dict) -> JointFit:
    """The JointFit at the solution x: covariance, intervals, noise summary."""
    free, groups = list(model.free), model.groups
    names, sizes = [g.name for g in groups], model.sizes
    r, J = model.evaluate(x)
    wdiag = weighting.weights(names)
    info = J.T @ (wdiag[:, None] * J)
    # Identifiability is about the shape of the information, not its scale:
    # judge the correlation form, which weights and units do not distort.
    dscale = np.sqrt(np.maximum(np.diag(info), 1e-300))
    cond = np.linalg.cond(info / np.outer(dscale, dscale)) if info.size else 0.0
    if not np.isfinite(cond) or cond > 1e14:
        raise InputError(f"{data.folder}: expected data that separate {', '.join(free)} "
                         f"(information matrix singular, condition {cond:.1e})")
    cov_scaled = covariance(info)
    S = np.diag(model.scale)
    cov = S @ cov_scaled @ S
    values = model.values(x)
    tau2, se2 = weighting.tau2, weighting.se2
    # A parameter's variance is a sum of the variance components'
    # contributions (cov J' W Sigma_c W J cov): each group's between-run
    # tau^2, estimated from its residuals with the group's degrees of freedom,
    # and its within-run se^2, known (the run's own line fit or mean).  Its
    # interval takes the Welch-Satterthwaite dof of that sum.  A group whose tau is the prior is known.
    group_dof = {g.name: (math.inf if g.name in weighting.assumed else g.size - g.charged) for g in groups}
    parts = variance_parts(S @ cov_scaled, J * wdiag[:, None], sizes,
                           [(tau2[g], group_dof[g]) for g in names], [se2[g] for g in names])
    grads = {n: np.eye(len(free))[i] for i, n in enumerate(free)}
    if "eps2" in free and "eps_ratio" in free:
        i, j = free.index("eps_ratio"), free.index("eps2")
        values["eps1"] = values["eps_ratio"] * values["eps2"]
        grads["eps1"] = np.zeros(len(free))
        grads["eps1"][i], grads["eps1"][j] = values["eps2"], values["eps_ratio"]
    stderr, param_dof, ci = {}, {}, {}
    for n, gvec in grads.items():
        stderr[n] = math.sqrt(max(float(gvec @ cov @ gvec), 0.0))
        param_dof[n] = nu = satterthwaite(gvec, parts)[1]
        # every fitted quantity is positive by nature (the solver's bounds keep it so): its
        # interval on the log scale, which a linear one left for c_strip (below 0)
        ci[n] = positive_ci(values[n], stderr[n], t975(max(nu, 1.0)))
    components = {g.name: g.components for g in groups}
    tests = {g.name: lack_of_fit(g.name, part, g.cells, g.charged, g.components)
             for g, part in zip(groups, model.split(r).values()) if g.cells is not None}
    return JointFit(free=free, values=values, cov=cov, stderr=stderr, ci95=ci, dof=len(r) - len(free),
                    sigma={g: math.sqrt(float(np.mean(tau2[g] + se2[g]))) for g in names},
                    residuals=model.split(r), not_identifiable=why, stick_points=int(model.stick.sum()),
                    sigma_assumed=list(weighting.assumed), param_dof=param_dof, between_runs_dof=group_dof,
                    between_runs={g: tau_summary(tau2[g], components[g]) for g in names},
                    within_run={g: math.sqrt(float(np.mean(se2[g]))) for g in names},
                    solves=tuple(s.as_json() for s in solves), reweighting_rounds=rounds,
                    convergence=converged, lack_of_fit={g: t for g, t in tests.items() if t is not None},
                    weights=model.split(wdiag))


def start_values(data: MeasurementSet) -> dict:
    """Starting point: eq. (1) or a one-parameter-per-axis guess, the
    maximum rule, a straight line through the ramp's stick branch."""
    rig = data.rig
    start = {}
    e1 = eq1(data)
    if e1:
        start.update(e1)
    elif data.forces is not None:
        mu = float(np.mean(data.forces[:, 1]) - rig.f_int_N) / rig.normal_force
        start.update(mu1=max(mu, 0.05), mu2=max(mu, 0.05))
    mr = max_rule(data, start.get("mu1"), start.get("mu2"))
    start["eps_ratio"] = mr["eps_ratio"] if mr and "eps_ratio" in mr else 1.0
    start["l1_l2_ratio"] = mr["l1_l2_ratio"] if mr else 1.0
    start["c_strip"] = rig.c_strip if rig.c_strip is not None else 0.0
    if data.f_int_free:
        start["f_int"] = float(np.mean(data.carriage[:, 0]))
    if data.stiffness is not None:
        al, _ = rig.axes(float(data.stiffness[0, 0]))
        k = float(np.mean(data.stiffness[:, 1]))
        start["eps2"] = max(k / cf.stick_stiffness_x1(start["eps_ratio"], 1.0, al), 1e-9)
    if data.ramp is not None:
        stick = fit_model.stick_mask(data, start.get("mu1"), start.get("mu2"))
        if stick.sum() >= 2:
            xs, F = data.ramp[stick, 0], data.ramp[stick, 1] - rig.f_int_N
            k = float(xs @ F / (xs @ xs))
            al, _ = rig.axes(rig.ramp_angle_deg)
            # the stick stiffness is linear in eps2 for a given ratio
            start["eps2"] = max(k / cf.stick_stiffness_x1(start["eps_ratio"], 1.0, al), 1e-9)
    return start
