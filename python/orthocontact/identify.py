"""Parameter identification with casadi: friction coefficients, stiffness
ratio and absolute stiffness from measured forces, trajectory angles and a
pre-sliding ramp, with Gauss-Newton standard errors and 95% intervals.

A measurement set is a folder (see scenarios/example_identification/README.md):
  rig.toml     mass_kg, g, f_int_N, velocity_m_s, rule, geometry (required file)
  forces.csv   alpha_deg,force_N    driving force at an orientation (repeats allowed)
  angles.csv   alpha_deg,phi_deg    trajectory angle (repeats allowed)
  ramp.csv     x1_m,force_N         start of a pull, before and into sliding
`alpha_deg` is the orientation angle of the sweep (the mat angle in the
paper's experiment); the tensors' axes follow from it by the geometry offsets.

Models (closed_forms): driving force F_int + m g / sqrt(f11) (friction
ellipse, eq. 1 at 0 and 90 deg); steady angle eq. (10)/(23) from the tensors;
stick branch of the ramp F_int + k x1 with k = 1/(B^-1)_11.  Units: N, m, deg.
"""
from __future__ import annotations

import csv
import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import closed_forms as cf
from .errors import InputError
from .fmu import RULES, ContactParams

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

REPORTED = ("mu1", "mu2", "eps_ratio", "eps1", "eps2")


def _reported(j: dict) -> list:
    """The parameters a summary lists: the five, and l1/l2 when angles alone were fitted."""
    return list(REPORTED) + (["l1_l2_ratio"] if "l1_l2_ratio" in j else [])


# -- data ------------------------------------------------------------------------

@dataclass
class RigSetup:
    """What rig.toml says: the rig and the assumptions of the fit."""
    mass_kg: float
    g: float = cf.G_STANDARD
    f_int_N: float = 0.0
    velocity_m_s: float = 0.244
    rule: str = "coupled"
    alpha_offset_deg: float = 90.0   # the paper's mat: adhesion axis 1 across the ripples
    beta_offset_deg: float = 0.0     # friction axis 1 along the ripples
    phi_convention: str = "counterclockwise"   # or "paper" (opposite sign)
    ramp_angle_deg: float = 0.0
    mode: str = "dynamic"            # rig mode of the validation runs
    travel_m: float = 0.5
    step_s: float = 2e-4
    eps2_nominal_N_m: float = 1e4    # for validation runs when eps2 is not identifiable

    @property
    def normal_force(self) -> float:
        return self.mass_kg * self.g

    def axes(self, angle_deg: float) -> tuple[float, float]:
        """(alpha, beta) [rad] at a data orientation angle [deg]."""
        return (math.radians(angle_deg + self.alpha_offset_deg),
                math.radians(angle_deg + self.beta_offset_deg))

    def params_at(self, law: ContactParams, angle_deg: float) -> ContactParams:
        """The law's parameters with the tensors' axes of this orientation and rig.rule."""
        alpha, beta = self.axes(angle_deg)
        return law.replace(alpha=alpha, beta=beta, rule=self.rule)

    def harness(self, **overrides):
        """The rig harness (orthocontact.rig.Rig) for this setup."""
        from .rig import Rig
        kw = dict(mass_kg=self.mass_kg, g=self.g, f_int_N=self.f_int_N,
                  velocity_m_s=self.velocity_m_s, travel_m=self.travel_m, mode=self.mode,
                  step_s=self.step_s)
        kw.update(overrides)
        return Rig(**kw)

    @property
    def beta_minus_alpha(self) -> float:
        """Angle [rad] of the friction axes from the adhesion axes."""
        return math.radians(self.beta_offset_deg - self.alpha_offset_deg)


@dataclass
class MeasurementSet:
    folder: Path
    rig: RigSetup
    forces: np.ndarray | None = None   # (n, 2): alpha_deg, force_N
    angles: np.ndarray | None = None   # (n, 2): alpha_deg, phi_deg (counterclockwise)
    ramp: np.ndarray | None = None     # (n, 2): x1_m, force_N


_RIG_KEYS = {
    "mass_kg": ("pos", None), "g": ("pos", cf.G_STANDARD), "f_int_N": ("nonneg", 0.0),
    "velocity_m_s": ("pos", 0.244), "rule": (tuple(RULES), "coupled"),
    "alpha_offset_deg": ("angle", 90.0), "beta_offset_deg": ("angle", 0.0),
    "phi_convention": (("counterclockwise", "paper"), "counterclockwise"),
    "ramp_angle_deg": ("angle", 0.0), "mode": (("dynamic", "quasistatic"), "dynamic"),
    "travel_m": ("pos", 0.5), "step_s": ("pos", 2e-4), "eps2_nominal_N_m": ("pos", 1e4),
}


def _load_rig(path: Path) -> RigSetup:
    try:
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(f"{path}: expected a rig.toml in the data folder (mass_kg, f_int_N, ...)") from None
    except tomllib.TOMLDecodeError as e:
        raise InputError(f"{path}: expected valid TOML ({e})") from None
    out = {}
    for key, value in raw.items():
        if key not in _RIG_KEYS:
            raise InputError(f"{path}: {key}: expected one of the known keys {', '.join(sorted(_RIG_KEYS))}")
    for key, (kind, default) in _RIG_KEYS.items():
        if key not in raw:
            if default is None:
                raise InputError(f"{path}: {key}: expected a value (the key is required)")
            out[key] = default
            continue
        v = raw[key]
        if isinstance(kind, tuple):
            if v not in kind:
                raise InputError(f"{path}: {key}: expected one of {', '.join(map(repr, kind))}, got {v!r}")
        else:
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InputError(f"{path}: {key}: expected a finite number, got {v!r}")
            if (kind == "pos" and v <= 0) or (kind == "nonneg" and v < 0) or \
                    (kind == "angle" and abs(v) > 360):
                what = {"pos": "> 0", "nonneg": ">= 0", "angle": "in [-360, 360]"}[kind]
                raise InputError(f"{path}: {key}: expected a number {what}, got {v!r}")
            v = float(v)
        out[key] = v
    return RigSetup(**out)


def _load_csv(path: Path, columns: tuple[str, str], checks, min_rows: int, why: str) -> np.ndarray | None:
    """Rows of two numeric columns, or None if the file is absent."""
    if not path.exists():
        return None
    try:
        with open(path, newline="", encoding="utf-8") as fh:
            rows = list(csv.reader(fh))
    except (OSError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: expected a readable UTF-8 CSV file ({e})") from None
    rows = [(i + 1, r) for i, r in enumerate(rows) if r and any(c.strip() for c in r)
            and not r[0].lstrip().startswith("#")]
    if not rows:
        raise InputError(f"{path}: expected a header line with columns {','.join(columns)}")
    line0, header = rows[0]
    header = [h.strip() for h in header]
    idx = []
    for c in columns:
        if c not in header:
            raise InputError(f"{path}: line {line0}: expected column {c!r} (header has {','.join(header)})")
        idx.append(header.index(c))
    data = []
    for line, r in rows[1:]:
        vals = []
        for c, k in zip(columns, idx):
            cell = r[k].strip() if k < len(r) else ""
            try:
                v = float(cell)
            except ValueError:
                raise InputError(f"{path}: line {line}: {c}: expected a number, got {cell!r}") from None
            if not math.isfinite(v):
                raise InputError(f"{path}: line {line}: {c}: expected a finite number, got {cell!r}")
            bad = checks[c](v)
            if bad:
                raise InputError(f"{path}: line {line}: {c}: expected {bad}, got {cell}")
            vals.append(v)
        data.append(vals)
    if len(data) < min_rows:
        raise InputError(f"{path}: expected at least {min_rows} data rows ({why}), got {len(data)}")
    return np.array(data, dtype=float)


def load_data(folder) -> MeasurementSet:
    """Reads and validates a measurement set; raises InputError (one line)."""
    folder = Path(folder)
    if not folder.is_dir():
        raise InputError(f"{folder}: expected a folder with rig.toml and forces.csv/angles.csv/ramp.csv")
    rig = _load_rig(folder / "rig.toml")
    angle = lambda v: None if -180 <= v <= 180 else "an angle in [-180, 180] deg"
    forces = _load_csv(folder / "forces.csv", ("alpha_deg", "force_N"),
                       {"alpha_deg": angle, "force_N": lambda v: None if v > 0 else "a force > 0"},
                       2, "two parameters, mu1 and mu2")
    angles = _load_csv(folder / "angles.csv", ("alpha_deg", "phi_deg"),
                       {"alpha_deg": angle, "phi_deg": lambda v: None if -90 < v < 90 else "an angle in (-90, 90) deg"},
                       1, "the stiffness ratio")
    ramp = _load_csv(folder / "ramp.csv", ("x1_m", "force_N"),
                     {"x1_m": lambda v: None if v >= 0 else "a travel >= 0",
                      "force_N": lambda v: None if v >= 0 else "a force >= 0"},
                     3, "stiffness needs points on the stick branch")
    if forces is None and angles is None and ramp is None:
        raise InputError(f"{folder}: expected at least one of forces.csv, angles.csv, ramp.csv")
    if angles is not None and rig.phi_convention == "paper":
        angles[:, 1] = -angles[:, 1]
    if forces is not None and len(np.unique(np.round(_beta_key(rig, forces[:, 0]), 9))) < 2:
        raise InputError(f"{folder / 'forces.csv'}: expected forces at two or more orientations "
                         "with different friction directions (mu1 and mu2 are two parameters)")
    return MeasurementSet(folder, rig, forces, angles, ramp)


def _beta_key(rig: RigSetup, angles_deg):
    """cos^2 of the friction axis angle: what the force depends on."""
    return np.cos(np.radians(np.asarray(angles_deg) + rig.beta_offset_deg)) ** 2


# -- the paper's calibration formulas -------------------------------------------------

def eq1(data: MeasurementSet) -> dict | None:
    """mu1, mu2 by eq. (1) from the mean forces at the friction axes."""
    if data.forces is None:
        return None
    a, f = data.forces[:, 0], data.forces[:, 1]
    key = _beta_key(data.rig, a)
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
    return ratio * mu2 / mu1 if abs(d - 90.0) < 1e-9 else ratio * mu1 / mu2


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


# -- the joint fit ---------------------------------------------------------------------

@dataclass
class JointFit:
    free: list                      # names of the fitted parameters
    values: dict                    # name -> value (incl. derived eps1)
    cov: np.ndarray                 # covariance of the free parameters
    stderr: dict
    ci95: dict
    dof: int
    sigma: dict                     # group -> noise estimate
    residuals: dict                 # group -> array of residuals (data - model)
    not_identifiable: dict = field(default_factory=dict)   # name -> reason
    stick_points: int = 0
    sigma_assumed: list = field(default_factory=list)      # groups whose noise is the prior
    param_dof: dict = field(default_factory=dict)  # name -> Welch-Satterthwaite dof of its interval


def _t975(dof: float) -> float:
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


def identifiability(data: MeasurementSet) -> tuple[list, dict]:
    """Which of mu1, mu2, eps_ratio, eps2 the data determine, and why not the
    others (a statement instead of an arbitrary number)."""
    rig = data.rig
    free, why = [], {}
    if data.forces is not None:
        free += ["mu1", "mu2"]
    else:
        why["mu1"] = why["mu2"] = "needs driving forces (forces.csv) at two orientations"
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
    if data.ramp is None:
        why["eps2"] = why["eps1"] = ("absolute stiffness does not show in steady sliding (forces, "
                                     "angles); it needs the pre-sliding ramp (ramp.csv)")
    else:
        alpha_r = math.radians(rig.ramp_angle_deg + rig.alpha_offset_deg)
        if "eps_ratio" in free or abs(math.cos(alpha_r)) < 1e-9:
            free.append("eps2")
        else:
            why["eps2"] = ("the ramp's stiffness mixes eps1 and eps2 at this ramp angle; "
                           "separating them needs eps_ratio")
        if "eps_ratio" not in free:
            why["eps1"] = "eps1 = eps_ratio * eps2 needs eps_ratio"
    return free, why


def _eq25_geometry(rig: RigSetup) -> bool:
    """A = B F B has its eigenbasis at alpha (Case 4 or 5 geometry), so eq. (25) holds."""
    return cf.eq25_lambdas(1.0, 1.0, 1.0, 1.0, rig.beta_minus_alpha) is not None


def _stick_mask(data: MeasurementSet, mu1, mu2) -> np.ndarray:
    """Ramp points on the stick branch: below 90% of the sliding force."""
    rig = data.rig
    F = data.ramp[:, 1] - rig.f_int_N
    if mu1 is not None:
        _, beta = rig.axes(rig.ramp_angle_deg)
        plateau = cf.steady_drive_force(mu1, mu2, beta, 0.0, rig.mass_kg, rig.g)
    else:
        top = np.sort(F)[-max(3, len(F) // 4):]
        plateau = float(np.median(top))
    return (F < 0.9 * plateau) & (data.ramp[:, 0] > 0)


def joint_fit(data: MeasurementSet, start: dict) -> JointFit:
    """Weighted nonlinear least squares of all data present over the
    identifiable parameters (casadi/IPOPT), each group weighted by its own
    noise, estimated from its residuals (three rounds); covariance
    (J^T W J)^-1 at the optimum (Gauss-Newton)."""
    import casadi as ca
    rig = data.rig
    free, why = identifiability(data)
    if not free:
        raise InputError(f"{data.folder}: expected data that determine at least one parameter: "
                         + "; ".join(f"{k}: {v}" for k, v in why.items()))
    scale = {"mu1": 1.0, "mu2": 1.0, "eps_ratio": 1.0, "l1_l2_ratio": 1.0,
             "eps2": max(start.get("eps2", 1e4), 1e-9)}
    x = ca.SX.sym("x", len(free))
    sym = {n: x[i] * scale[n] for i, n in enumerate(free)}
    val = lambda n: sym[n] if n in sym else start.get(n, 1.0)
    groups = {}
    if data.forces is not None and "mu1" in free:
        res = []
        for a, f in data.forces:
            _, beta = rig.axes(a)
            res.append(f - cf.steady_drive_force(val("mu1"), val("mu2"), beta, rig.f_int_N, rig.mass_kg, rig.g))
        groups["forces"] = (ca.vertcat(*res), 2)
    if data.angles is not None and ("eps_ratio" in free or "l1_l2_ratio" in free):
        res = []
        for a, phi in data.angles:
            al, be = rig.axes(a)
            if "eps_ratio" in free:
                tp = cf.steady_tan_phi(val("mu1"), val("mu2"), val("eps_ratio"), 1.0, al, be, rig.rule)
            else:
                tp = cf.eq25_tan_phi(val("l1_l2_ratio"), 1.0, al)
            res.append(phi - ca.atan(tp) * 180 / math.pi)
        groups["angles"] = (ca.vertcat(*res), 1)
    stick = np.zeros(0, dtype=bool)
    if data.ramp is not None and "eps2" in free:
        stick = _stick_mask(data, start.get("mu1"), start.get("mu2"))
        if stick.sum() < 2:
            raise InputError(f"{data.folder / 'ramp.csv'}: expected at least 2 points on the stick "
                             f"branch (below 90% of the sliding force), got {int(stick.sum())}")
        al, _ = rig.axes(rig.ramp_angle_deg)
        k = cf.stick_stiffness_x1(val("eps_ratio") * val("eps2"), val("eps2"), al)
        res = [F - (rig.f_int_N + k * x1) for x1, F in data.ramp[stick]]
        groups["ramp"] = (ca.vertcat(*res), 1)

    names = list(groups)
    r_all = ca.vertcat(*[groups[g][0] for g in names])
    J_all = ca.jacobian(r_all, x)
    w = ca.SX.sym("w", len(names))
    obj = 0
    for i, g in enumerate(names):
        obj += w[i] * ca.sumsqr(groups[g][0])
    solver = ca.nlpsol("joint", "ipopt", {"x": x, "p": w, "f": 0.5 * obj},
                       {"ipopt.print_level": 0, "print_time": False, "ipopt.tol": 1e-14,
                        "ipopt.sb": "yes", "ipopt.max_iter": 500})
    fres = ca.Function("res", [x], [r_all, J_all])
    sizes = [groups[g][0].numel() for g in names]
    x0 = np.array([start.get(n, 1.0) / scale[n] for n in free])
    # Prior noise levels; a group with no residual degrees of freedom (e.g.
    # two forces for mu1, mu2) keeps its prior, flagged as assumed.
    sigma = {"forces": 0.05, "angles": 0.5, "ramp": 0.05}
    floors = {"forces": 1e-12, "angles": 1e-12, "ramp": 1e-12}
    assumed = [g for g, n in zip(names, sizes) if n - groups[g][1] <= 0]
    for _round in range(3):
        wv = [1.0 / sigma[g] ** 2 for g in names]
        sol = solver(x0=x0, p=wv, lbx=1e-9, ubx=1e9)
        x0 = np.array(sol["x"]).ravel()
        r, _ = fres(x0)
        r = np.array(r).ravel()
        parts = np.split(r, np.cumsum(sizes)[:-1])
        for g, part in zip(names, parts):
            if g not in assumed:
                sigma[g] = max(math.sqrt(float(part @ part) / (len(part) - groups[g][1])), floors[g])
    r, J = fres(x0)
    r, J = np.array(r).ravel(), np.array(J)
    wdiag = np.concatenate([np.full(n, 1.0 / sigma[g] ** 2) for g, n in zip(names, sizes)])
    info = J.T @ (wdiag[:, None] * J)
    cov_scaled = np.linalg.pinv(info)
    S = np.diag([scale[n] for n in free])
    cov = S @ cov_scaled @ S
    values = {n: float(x0[i] * scale[n]) for i, n in enumerate(free)}
    dof = len(r) - len(free)
    # Each group's noise is estimated from its own residuals, with its own
    # degrees of freedom; a parameter's variance is a sum of the groups'
    # contributions (cov J_g' W_g J_g cov), so its interval takes the
    # Welch-Satterthwaite degrees of freedom of that sum: the forces' for
    # mu1, mu2, mostly the ramp's for eps2, a blend for the ratio.  A group
    # whose noise is the prior contributes with infinite dof.
    group_dof = {g: (math.inf if g in assumed else n - groups[g][1]) for g, n in zip(names, sizes)}
    rows = np.split(np.arange(len(r)), np.cumsum(sizes)[:-1])
    contrib = {}
    for g, idx in zip(names, rows):
        Jg = J[idx] / sigma[g]
        contrib[g] = S @ cov_scaled @ (Jg.T @ Jg) @ cov_scaled @ S
    grads = {n: np.eye(len(free))[i] for i, n in enumerate(free)}
    if "eps2" in free and "eps_ratio" in free:
        i, j = free.index("eps_ratio"), free.index("eps2")
        values["eps1"] = values["eps_ratio"] * values["eps2"]
        grad = np.zeros(len(free))
        grad[i], grad[j] = values["eps2"], values["eps_ratio"]
        grads["eps1"] = grad
    stderr, param_dof, ci = {}, {}, {}
    for n, gvec in grads.items():
        shares = {g: max(float(gvec @ C @ gvec), 0.0) for g, C in contrib.items()}
        var = max(float(gvec @ cov @ gvec), 0.0)
        stderr[n] = math.sqrt(var)
        den = sum(v * v / group_dof[g] for g, v in shares.items() if math.isfinite(group_dof[g]))
        nu = (sum(shares.values()) ** 2 / den) if den > 0 else math.inf
        param_dof[n] = nu
        t = 1.959963984540054 if not math.isfinite(nu) else _t975(nu)
        ci[n] = [values[n] - t * stderr[n], values[n] + t * stderr[n]]
    # Identifiability is about the shape of the information, not its scale:
    # judge the correlation form, which weights and units do not distort.
    dscale = np.sqrt(np.maximum(np.diag(info), 1e-300))
    cond = np.linalg.cond(info / np.outer(dscale, dscale)) if info.size else 0.0
    if not np.isfinite(cond) or cond > 1e14:
        raise InputError(f"{data.folder}: expected data that separate {', '.join(free)} "
                         f"(information matrix singular, condition {cond:.1e})")
    parts = np.split(r, np.cumsum(sizes)[:-1])
    return JointFit(free, values, cov, stderr, ci, dof, {g: sigma[g] for g in names},
                    dict(zip(names, parts)), why, int(stick.sum()), assumed, param_dof)


def _start_values(data: MeasurementSet) -> dict:
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
    if data.ramp is not None:
        stick = _stick_mask(data, start.get("mu1"), start.get("mu2"))
        if stick.sum() >= 2:
            xs, F = data.ramp[stick, 0], data.ramp[stick, 1] - rig.f_int_N
            k = float(xs @ F / (xs @ xs))
            al, _ = rig.axes(rig.ramp_angle_deg)
            # the stick stiffness is linear in eps2 for a given ratio
            start["eps2"] = max(k / cf.stick_stiffness_x1(start["eps_ratio"], 1.0, al), 1e-9)
    return start


# -- validation with the FMU ------------------------------------------------------------

def validate_with_fmu(data: MeasurementSet, values: dict, workers=None, fmu_path=None) -> dict:
    """Simulates the identified parameters in the rig harness with the FMU at
    the data's orientations (and the ramp) and returns the residuals
    data - simulation."""
    from .rig import run
    from .sweep import default_workers, run_many
    rig = data.rig
    mu1, mu2 = values.get("mu1"), values.get("mu2")
    if mu1 is None:
        return {"skipped": "mu1, mu2 not identified: nothing to simulate"}
    ratio = values.get("eps_ratio", 1.0)
    eps2 = values.get("eps2", rig.eps2_nominal_N_m)
    law = ContactParams(mu1, mu2, ratio * eps2, eps2)
    h = rig.harness()
    angles = sorted(set(np.concatenate([d[:, 0] for d in (data.forces, data.angles) if d is not None])))
    sims = run_many([(rig.params_at(law, a), h) for a in angles], workers or default_workers(), fmu_path,
                    "validation", progress=False)
    sim = dict(zip(angles, sims))
    out = {"rig_mode": rig.mode, "eps_used": {"eps1": ratio * eps2, "eps2": eps2,
                                               "eps2_identified": "eps2" in values}}
    if data.forces is not None:
        res = data.forces[:, 1] - np.array([sim[a][1] for a in data.forces[:, 0]])
        out["forces_N"] = _res_stats(res)
    if data.angles is not None:
        res = data.angles[:, 1] - np.array([sim[a][0] for a in data.angles[:, 0]])
        out["angles_deg"] = _res_stats(res)
    if data.ramp is not None:
        xmax = float(data.ramp[:, 0].max())
        # fine steps: the comparison interpolates the simulation at the data's x1
        r = run(rig.params_at(law, rig.ramp_angle_deg),
                rig.harness(travel_m=max(xmax * 1.01, 1e-6),
                            step_s=min(h.step_s, xmax / rig.velocity_m_s / 4000)))
        x = np.concatenate([[0.0], r.x1])
        F = np.concatenate([[rig.f_int_N], r.drive])
        res = data.ramp[:, 1] - np.interp(data.ramp[:, 0], x, F)
        out["ramp_N"] = _res_stats(res)
    return out


def _res_stats(res: np.ndarray) -> dict:
    return {"rms": float(np.sqrt(np.mean(res**2))), "max_abs": float(np.max(np.abs(res))),
            "mean": float(np.mean(res)), "n": int(len(res))}


# -- the whole job ------------------------------------------------------------------------

@dataclass
class Identification:
    data: MeasurementSet
    fit: JointFit
    eq1: dict | None
    max_rule: dict | None
    eq40: dict | None
    validation: dict | None
    start: dict

    def as_json(self) -> dict:
        f = self.fit
        out = {}
        for n in REPORTED:
            if n in f.values:
                out[n] = {"value": f.values[n], "stderr": f.stderr[n], "ci95": f.ci95[n],
                          "dof": _json_dof(f.param_dof.get(n))}
            else:
                out[n] = {"identifiable": False, "reason": f.not_identifiable.get(n, "not determined")}
        if "l1_l2_ratio" in f.values:
            n = "l1_l2_ratio"
            out[n] = {"value": f.values[n], "stderr": f.stderr[n], "ci95": f.ci95[n],
                      "note": "eigenvalue ratio lambda1/lambda2: what angles alone determine"}
        d = self.data
        out["max_rule"] = self.max_rule
        out["eq40"] = {k: v for k, v in (self.eq40 or {}).items() if k != "eq41"} or None
        out["eq41"] = (self.eq40 or {}).get("eq41")
        out["eq1"] = self.eq1
        unit = {"forces": "forces_N", "angles": "angles_deg", "ramp": "ramp_N"}
        out["noise_estimate"] = {unit[g]: s for g, s in f.sigma.items()}
        if f.sigma_assumed:
            out["noise_assumed"] = [unit[g] for g in f.sigma_assumed]
        out["fit_residuals"] = {g: _res_stats(r) for g, r in f.residuals.items()}
        out["dof"] = f.dof
        # What uncertainty propagation (orthocontact uq) draws from: the
        # joint Gauss-Newton covariance of the fitted parameters, and the
        # measured angles to show beside the predictions.
        out["covariance"] = {"parameters": list(f.free),
                             "values": [f.values[n] for n in f.free],
                             "matrix": [[float(c) for c in row] for row in 0.5 * (f.cov + f.cov.T)]}
        out["points"] = {"angles": None if d.angles is None else
                         [[float(a), float(p)] for a, p in d.angles],
                         "forces": None if d.forces is None else
                         [[float(a), float(F)] for a, F in d.forces]}
        out["ramp_stick_points"] = f.stick_points
        out["validation_fmu"] = self.validation
        out["data"] = {"folder": str(d.folder),
                       "forces": 0 if d.forces is None else len(d.forces),
                       "angles": 0 if d.angles is None else len(d.angles),
                       "ramp": 0 if d.ramp is None else len(d.ramp)}
        r = d.rig
        out["assumptions"] = {"rule": r.rule, "alpha_offset_deg": r.alpha_offset_deg,
                              "beta_offset_deg": r.beta_offset_deg, "mass_kg": r.mass_kg, "g": r.g,
                              "f_int_N": r.f_int_N, "ramp_angle_deg": r.ramp_angle_deg,
                              "phi_convention": "counterclockwise (data converted)" if r.phi_convention == "paper"
                              else "counterclockwise",
                              "ci": "95%, Student t with each parameter's Welch-Satterthwaite "
                                    "degrees of freedom over the data groups' noise estimates, "
                                    "Gauss-Newton covariance with per-group noise estimates"}
        return out


def _json_dof(nu):
    return None if nu is None else ("inf" if not math.isfinite(nu) else round(float(nu), 2))


def identify(data: MeasurementSet, validate: bool = True, workers=None,
             fmu_path=None) -> Identification:
    start = _start_values(data)
    fit = joint_fit(data, start)
    mu1, mu2 = fit.values.get("mu1"), fit.values.get("mu2")
    mr = max_rule(data, mu1, mu2)
    e40 = eq40_fit(data, mu1, mu2)
    val = validate_with_fmu(data, fit.values, workers, fmu_path) if validate else None
    return Identification(data, fit, eq1(data), mr, e40, val, start)


def run(data: MeasurementSet, out: Path, validate: bool = True, workers=None,
        fmu_path=None) -> Identification:
    """identify() and write identified.json, fit.png, identified.md into out."""
    from .tables import write_json
    res = identify(data, validate, workers, fmu_path)
    write_json(out / "identified.json", res.as_json())
    _figure(res, out / "fit.png")
    (out / "identified.md").write_text(_markdown(res))
    return res


def _figure(res: Identification, path: Path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    d, v, rig = res.data, res.fit.values, res.data.rig
    panels = [p for p, have in (("forces", d.forces is not None), ("angles", d.angles is not None),
                                ("ramp", d.ramp is not None)) if have]
    fig, axes = plt.subplots(1, len(panels), figsize=(5 * len(panels), 4), squeeze=False)
    grid = np.linspace(0, 90, 181)

    def phi_curve(eps_ratio):
        return [math.degrees(math.atan(cf.steady_tan_phi(v["mu1"], v["mu2"], eps_ratio, 1.0,
                                                         *rig.axes(a), rig.rule))) for a in grid]
    for ax, p in zip(axes[0], panels):
        if p == "forces":
            ax.plot(d.forces[:, 0], d.forces[:, 1], "o", ms=4, label="data")
            if "mu1" in v:
                ax.plot(grid, [cf.steady_drive_force(v["mu1"], v["mu2"], rig.axes(a)[1], rig.f_int_N,
                                                     rig.mass_kg, rig.g) for a in grid], "-",
                        label=f"fit: μ1={v['mu1']:.4f}, μ2={v['mu2']:.4f}")
            ax.set_ylabel("driving force [N]")
        elif p == "angles":
            ax.plot(d.angles[:, 0], d.angles[:, 1], "o", ms=4, label="data")
            if "eps_ratio" in v:
                ax.plot(grid, phi_curve(v["eps_ratio"]), "-", label=f"joint fit: ε1/ε2={v['eps_ratio']:.4f}")
            for key, style, lab in (("max_rule", ":", "maximum rule"), ("eq41", "--", "eq. (41)")):
                src = res.max_rule if key == "max_rule" else (res.eq40 or {}).get("eq41")
                if src and "eps_ratio" in src and "mu1" in v and math.isfinite(src["eps_ratio"]):
                    ax.plot(grid, phi_curve(src["eps_ratio"]), style, label=f"{lab}: ε1/ε2={src['eps_ratio']:.4f}")
            ax.set_ylabel("trajectory angle φ [deg] (counterclockwise)")
        else:
            ax.plot(d.ramp[:, 0] * 1e3, d.ramp[:, 1], "o", ms=3, label="data")
            if "eps2" in v:
                al, be = rig.axes(rig.ramp_angle_deg)
                k = cf.stick_stiffness_x1(v.get("eps_ratio", 1.0) * v["eps2"], v["eps2"], al)
                top = cf.steady_drive_force(v["mu1"], v["mu2"], be, 0.0, rig.mass_kg, rig.g) \
                    if "mu1" in v else float(np.max(d.ramp[:, 1]) - rig.f_int_N)
                xs = np.linspace(0, d.ramp[:, 0].max(), 200)
                ax.plot(xs * 1e3, rig.f_int_N + np.minimum(k * xs, top), "-", label=f"fit: k={k:.4g} N/m")
            ax.set_xlabel("travel x1 [mm]")
            ax.set_ylabel("driving force [N]")
        if p != "ramp":
            ax.set_xlabel("orientation angle [deg]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"orthocontact identify: {d.folder.name}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def summary_text(res: Identification) -> str:
    j = res.as_json()
    lines = []
    for n in _reported(j):
        e = j[n]
        if "value" in e:
            lines.append(f"{n:>9} = {e['value']:.6g} ± {e['stderr']:.2g}  (95%: {e['ci95'][0]:.6g} .. {e['ci95'][1]:.6g})")
        else:
            lines.append(f"{n:>9}: not identifiable: {e['reason']}")
    if j["max_rule"]:
        lines.append(f"maximum rule: l1/l2 = {j['max_rule']['l1_l2_ratio']:.4f}"
                     + (f", eps1/eps2 = {j['max_rule']['eps_ratio']:.4f}" if "eps_ratio" in j["max_rule"] else ""))
    if j["eq40"]:
        lines.append(f"eq. (40) least squares: l1/l2 = {j['eq40']['l1_l2_ratio']:.4f}; "
                     f"eq. (41) closed form: l1/l2 = {j['eq41']['l1_l2_ratio']:.4f} (not the minimiser)")
    return "\n".join(lines)


def _markdown(res: Identification) -> str:
    j = res.as_json()
    L = [f"# Identification: {res.data.folder.name}", "",
         f"Data: {j['data']['forces']} forces, {j['data']['angles']} angles, {j['data']['ramp']} ramp points. "
         f"Rule {j['assumptions']['rule']}, alpha = angle {j['assumptions']['alpha_offset_deg']:+g}°, "
         f"beta = angle {j['assumptions']['beta_offset_deg']:+g}°.", "",
         "| parameter | value | std. error | 95% interval |", "|---|---|---|---|"]
    for n in _reported(j):
        e = j[n]
        if "value" in e:
            L.append(f"| {n} | {e['value']:.6g} | {e['stderr']:.3g} | {e['ci95'][0]:.6g} … {e['ci95'][1]:.6g} |")
        else:
            L.append(f"| {n} | not identifiable | – | {e['reason']} |")
    L.append("")
    if j["eq1"]:
        L.append(f"- eq. (1) from the forces at the friction axes: μ1 = {j['eq1']['mu1']:.4f}, μ2 = {j['eq1']['mu2']:.4f}")
    if j["max_rule"]:
        mr = j["max_rule"]
        L.append(f"- maximum rule (eq. 29, 37–39): φ_ext = {mr['phi_ext_deg']:.3f}° → l1/l2 = {mr['l1_l2_ratio']:.4f}"
                 + (f", ε1/ε2 = {mr['eps_ratio']:.4f}" if "eps_ratio" in mr else ""))
    if j["eq40"]:
        L.append(f"- eq. (40) by IPOPT: l1/l2 = {j['eq40']['l1_l2_ratio']:.4f} (objective {j['eq40']['objective']:.3e}); "
                 f"the paper's eq. (41): l1/l2 = {j['eq41']['l1_l2_ratio']:.4f} (objective {j['eq41']['objective']:.3e}) — not the minimiser")
    L.append("- noise estimated from the residuals: " + ", ".join(f"{k} {v:.3g}" for k, v in j["noise_estimate"].items()))
    v = j["validation_fmu"]
    if v and "skipped" not in v:
        parts = [f"{k} rms {v[k]['rms']:.3g}" for k in ("forces_N", "angles_deg", "ramp_N") if k in v]
        L.append(f"- validation with the FMU in the rig harness ({v['rig_mode']}): " + ", ".join(parts))
    L += ["", "![data and fit](fit.png)", ""]
    return "\n".join(L)


# -- synthetic measurements from the FMU harness ---------------------------------------------

def simulate_measurements(truth: ContactParams, rig: RigSetup, force_angles, angle_angles,
                          ramp_max_x1_m: float | None = None, workers=1) -> dict:
    """Noise-free measurements made by the FMU in the rig harness (quasistatic
    mode: the steady state without inertial transients): mean driving forces
    and fitted trajectory angles at the given orientations [deg], and the
    start of a pull at rig.ramp_angle_deg up to ramp_max_x1_m [m].
    truth.alpha/beta are ignored: the rig's geometry sets them per angle."""
    from .rig import run
    from .sweep import run_many
    h = rig.harness(mode="quasistatic", step_s=1e-3, travel_m=0.2)
    angles = sorted(set(force_angles) | set(angle_angles))
    sims = dict(zip(angles, run_many([(rig.params_at(truth, a), h) for a in angles], workers, None,
                                     "synthesize", progress=False)))
    out = {"forces": np.array([[a, sims[a][1]] for a in force_angles]),
           "angles": np.array([[a, sims[a][0]] for a in angle_angles])}
    if ramp_max_x1_m:
        steps = 400
        r = run(rig.params_at(truth, rig.ramp_angle_deg),
                rig.harness(mode="quasistatic", travel_m=ramp_max_x1_m,
                            step_s=ramp_max_x1_m / rig.velocity_m_s / steps))
        out["ramp"] = np.column_stack([r.x1, r.drive])
    return out


def write_measurements(folder: Path, rig: RigSetup, forces=None, angles=None, ramp=None):
    """Writes a measurement set (rig.toml and CSV files) to folder."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    keys = ("mass_kg", "g", "f_int_N", "velocity_m_s", "rule", "alpha_offset_deg", "beta_offset_deg",
            "ramp_angle_deg")
    lines = []
    for k in keys:
        v = getattr(rig, k)
        lines.append(f'{k} = "{v}"' if isinstance(v, str) else f"{k} = {v!r}")
    (folder / "rig.toml").write_text("\n".join(lines) + "\n")
    for name, header, arr in (("forces.csv", "alpha_deg,force_N", forces),
                              ("angles.csv", "alpha_deg,phi_deg", angles),
                              ("ramp.csv", "x1_m,force_N", ramp)):
        if arr is not None:
            body = "\n".join(f"{a!r},{b!r}" for a, b in arr)
            (folder / name).write_text(header + "\n" + body + "\n")
