"""The joint fit's model: each data group's residuals (data - model) as one
casadi Function of the fitted parameters, with its Jacobian, built once per
fit from the closed forms (orthocontact.closed_forms) and the strip's
steady state (strip_model).

Groups and what each one's model is (units of the residuals):
  forces     driving force F_int + push of steady sliding [N]
  carriage   F_int of each carriage run [N]
  angles     steady trajectory angle phi [deg]
  ramp       stick branch of the pull F_int + k x1 [N]
  stiffness  stick stiffness k = 1/(B^-1)_11 of each ramp run [N/m]

The parameters enter in the fit's units (value / SCALES): O(1) for any
plausible set, so that the solver sees comparable steps."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import closed_forms as cf
from ..errors import InputError
from .measurements import MeasurementSet
from .strip_model import strip_steady_states

# The strip's steady states hold where the lateral force left is below this share of N
ROOT_TOLERANCE = 1e-12
# The fitted parameters' units in the fit: eps2 and F_int by their start values.
SCALES = {"mu1": 1.0, "mu2": 1.0, "eps_ratio": 1.0, "l1_l2_ratio": 1.0, "c_strip": 10.0}


@dataclass(frozen=True)
class Group:
    """One data group of the fit: its name, how many values, how many of
    the parameters it alone determines (its residual dof is size less
    that), each value's within-run variance se^2 (in the group's unit
    squared; 0 where none is known) and the variance component of each
    value (its carriage velocity [m/s]; None: one for the group)."""
    name: str
    size: int
    charged: int
    se2: np.ndarray
    magnitude: float          # the largest |value| (1 where all are 0): the scale of its noise floor
    components: np.ndarray | None = None
    cells: tuple | None = None    # each value's run conditions (replicates share them); None: no replicates


@dataclass(frozen=True)
class FitModel:
    """Residuals r(x) = data - model of every group, stacked in the groups'
    order, and their Jacobian, at x: the free parameters in the fit's units
    (value / scale)."""
    free: tuple
    scale: np.ndarray
    groups: tuple
    function: object          # casadi Function x -> (r, dr/dx)
    residual: object          # casadi Function x -> r (the objective needs no Jacobian)
    stick: np.ndarray         # the ramp's points on the stick branch (empty without ramp.csv)
    strip_force_left: object  # casadi Function x -> the lateral force [N] the strip's Newton steps leave

    def strip_roots_converged(self, x, normal_force: float) -> bool:
        """Whether the strip's unrolled Newton steps reached the root at x:
        the lateral force left under ROOT_TOLERANCE of the normal force."""
        left = np.array(self.strip_force_left(x)).ravel()
        return bool(np.all(np.abs(left) <= ROOT_TOLERANCE * normal_force))

    def evaluate(self, x) -> tuple[np.ndarray, np.ndarray]:
        """(r, J) as numpy arrays at the fit's x."""
        r, J = self.function(x)
        return np.array(r).ravel(), np.array(J).reshape(len(np.array(r).ravel()), len(self.free))

    def values(self, x) -> dict:
        """The parameters in their own units."""
        return {n: float(xi * s) for n, xi, s in zip(self.free, np.asarray(x, float).ravel(), self.scale)}

    def x_of(self, values: dict) -> np.ndarray:
        """The fit's x of parameter values (missing ones: 1 in the fit's unit)."""
        return np.array([values.get(n, s) / s for n, s in zip(self.free, self.scale)])

    @property
    def sizes(self) -> list:
        return [g.size for g in self.groups]

    def split(self, r: np.ndarray) -> dict:
        """A stacked vector of r's length as {group: its part}."""
        return dict(zip((g.name for g in self.groups), np.split(np.asarray(r), np.cumsum(self.sizes)[:-1])))


def stick_mask(data: MeasurementSet, mu1, mu2) -> np.ndarray:
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


def build(data: MeasurementSet, start: dict, free: list) -> FitModel:
    """The fit's model of `data` over the parameters `free`, the others
    at `start` (and the strip's regimes of motion at `start`:
    strip_model.strip_steady_states)."""
    import casadi as ca
    rig = data.rig
    scale = {**SCALES, "eps2": max(start.get("eps2", 1e4), 1e-9), "f_int": max(start.get("f_int", 1.0), 1e-3)}
    c_known = rig.c_strip or 0.0
    strip = "eps_ratio" in free and (rig.mu_strip > 0 or "c_strip" in free or c_known > 0)
    x = ca.SX.sym("x", len(free))
    sym = {n: x[i] * scale[n] for i, n in enumerate(free)}

    def val(n):
        return sym[n] if n in sym else start.get(n, 1.0)
    sliding = _steady_sliding(data, val, start, free, strip, c_known)
    stick = np.zeros(0, dtype=bool)
    if data.ramp is not None and "eps2" in free:
        stick = stick_mask(data, start.get("mu1"), start.get("mu2"))
        if stick.sum() < 2:
            raise InputError(f"{data.folder / 'ramp.csv'}: expected at least 2 points on the stick "
                             f"branch (below 90% of the sliding force), got {int(stick.sum())}")
    parts = _group_residuals(data, val, free, sliding, stick)
    r = ca.vertcat(*[residuals for _, residuals in parts])
    function = ca.Function("fit_residuals", [x], [r, ca.jacobian(r, x)])
    force_left = ca.vertcat(*sliding["left"]) if sliding["left"] else ca.SX(0, 1)
    left = ca.Function("strip_force_left", [x], [force_left])
    return FitModel(tuple(free), np.array([scale[n] for n in free]), tuple(g for g, _ in parts), function,
                    ca.Function("fit_residual", [x], [r]), stick, left)


def _group_residuals(data: MeasurementSet, val, free: list, sliding: dict, stick: np.ndarray) -> list:
    """[(Group, its residuals as a casadi column)] of every group the data
    and the free parameters make."""
    import casadi as ca
    rig, parts = data.rig, []
    f_int = val("f_int") if "f_int" in free else rig.f_int_N

    def add(name, residuals, charged, measured, se=None, components=None, cells=None):
        se2 = np.zeros(len(residuals)) if se is None else np.asarray(se, float) ** 2
        top = float(np.max(np.abs(measured)))
        parts.append((Group(name, len(residuals), charged, se2, top if top > 0 else 1.0, components, cells),
                      ca.vertcat(*residuals)))
    by_velocity = data.angle_se is not None     # raw recordings: a tracker's drift shows as drift / velocity
    if data.forces is not None and "mu1" in free:
        add("forces", [f - (f_int + q1) for (_, f), q1 in zip(data.forces, sliding["push"])], 2,
            data.forces[:, 1], data.force_se, data.velocities_of_forces() if by_velocity else None,
            tuple(zip(data.forces[:, 0], data.velocities_of_forces())))
    if "f_int" in free:
        add("carriage", [F - f_int for F in data.carriage[:, 0]], 1, data.carriage[:, 0], data.carriage[:, 1])
    if data.angles is not None and ("eps_ratio" in free or "l1_l2_ratio" in free):
        phi = [ca.atan(t) * 180 / math.pi for t in sliding["tan_phi"]]
        add("angles", [measured - model for (_, measured), model in zip(data.angles, phi)],
            1 + ("c_strip" in free), data.angles[:, 1], data.angle_se,
            data.velocities_of_angles() if by_velocity else None,
            tuple(zip(data.angles[:, 0], data.velocities_of_angles())))
    if data.ramp is not None and "eps2" in free:
        alpha = rig.axes(rig.ramp_angle_deg)[0]
        k = cf.stick_stiffness_x1(val("eps_ratio") * val("eps2"), val("eps2"), alpha)
        add("ramp", [F - (f_int + k * x1) for x1, F in data.ramp[stick]], 1, data.ramp[stick, 1])
    if data.stiffness is not None and "eps2" in free:
        k = [cf.stick_stiffness_x1(val("eps_ratio") * val("eps2"), val("eps2"), rig.axes(a)[0])
             for a in data.stiffness[:, 0]]
        add("stiffness", [measured - model for measured, model in zip(data.stiffness[:, 1], k)], 1,
            data.stiffness[:, 1], data.stiffness[:, 2], cells=tuple(data.stiffness[:, 0]))
    return parts


def _steady_sliding(data: MeasurementSet, val, start: dict, free: list, strip: bool, c_known: float) -> dict:
    """The model's push q1 [N] at each force and tan(phi) at each angle:
    with the strip, Newton's steps unrolled per distinct (mat angle, velocity)
    and the lateral force they leave (strip_model.strip_steady_states);
    without, the closed forms (eq. 1's friction ellipse, eq. 10/23's angle;
    angles alone: eq. 25 in l1/l2)."""
    rig = data.rig
    forces = [] if data.forces is None or "mu1" not in free else \
        list(zip(data.forces[:, 0], data.velocities_of_forces()))
    angles = [] if data.angles is None else list(zip(data.angles[:, 0], data.velocities_of_angles()))
    if strip:
        points = sorted({(float(a), float(v)) for a, v in forces + angles})
        tan_phi, push, left = strip_steady_states(val, start, rig, points, "c_strip" in free, c_known)
        at = {p: i for i, p in enumerate(points)}
        return {"push": [push[at[(float(a), float(v))]] for a, v in forces],
                "tan_phi": [tan_phi[at[(float(a), float(v))]] for a, v in angles], "left": left}
    push = [cf.steady_drive_force(val("mu1"), val("mu2"), rig.axes(a)[1], 0.0, rig.mass_kg, rig.g)
            for a, _ in forces]
    if "eps_ratio" in free:
        tan_phi = [cf.steady_tan_phi(val("mu1"), val("mu2"), val("eps_ratio"), 1.0, *rig.axes(a), rig.rule)
                   for a, _ in angles]
    else:
        tan_phi = [cf.eq25_tan_phi(val("l1_l2_ratio"), 1.0, rig.axes(a)[0]) for a, _ in angles]
    return {"push": push, "tan_phi": tan_phi, "left": []}
