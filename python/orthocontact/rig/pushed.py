"""The paper's block pushed at a height, on the ContactPad FMU: a quasi-static
rig.  The carriage pushes the block along X1 through a frictionless strip
at height h [m] above the contact (the paper's rig: the block is free to
drift along X2, its yaw held by the strip's face), the block pressed by its
weight m g.  Each step moves the block's X1 position by the carriage's
increment and solves its equilibrium for the four unknowns
x = (u2 [m], d [m], phi1 [rad], phi2 [rad]):

    T2 = 0                (the strip carries no lateral force)
    Fn = m g              (the weight)
    M2 = h T1             (the push P = -T1 at height h: its moment h P
                           about X2 balanced by the pressure's M2)
    M1 = -h T2            (a lateral force at h; 0 here)

by Newton with the FMU's directional derivatives of the pending step
(backtracking on the residual), then commits the step.  The push's moment
moves the pressure's centre toward the leading edge by e = h P / (m g):
in steady sliding P = mu m g with mu = 1/sqrt(F11) the law's friction along
X1 under lateral equilibrium (closed_forms.paper.steady_drive_force), so
e = mu h and the block is in full contact while mu h <= length/6, lifts its
trailing edge beyond, and tips past mu h = length/2
(closed_forms.pad.pushed_at_height).  Tipping is a result, not an error:
where the push's moment h |T1| reaches m g length/2 no pressure under the
pad can hold it (its centre would leave the pad), and the run stops there.
Each step first balances the block laterally at the last step's pose (u2
alone) and asks that of the push it then carries: T1 / Fn under lateral
equilibrium is the friction, which the pressure's shape does not change
once every pressed cell slides.

In steady sliding every pressed cell slides the same way, and the law is
homogeneous of degree one in the normal force: the cells' forces are their
normal forces times one steady force, whatever the pressure's shape, so the
trajectory angle is the point law's (closed_forms.paper.steady_tan_phi)
with or without the height, lift-off included; the height moves the
pressure, not the path."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..closed_forms import FULL_CONTACT, LIFT_OFF, TIPS
from ..errors import InputError
from ..fmu import ContactParams, FMUError, Foundation, PadFMU, PatchGeometry
from ..plausibility import FIT_FROM

# The unknowns of a step and the residuals' scales' names.
UNKNOWNS = ("u2", "d", "phi1", "phi2")
# Newton's tolerance on the residuals, relative to the weight (forces) and
# the weight times the pad's length (moments).
RESIDUAL_TOL = 1e-11
NEWTON_ITERATIONS = 40
# Halvings of a carriage step through which a step's Newton is continued.
CONTINUATION_DEPTH = 8
# The largest tilt [rad] a step may reach: the pad's approach d + phi2 X -
# phi1 Y is the first order of sin(phi) (relative error phi^2/6: 4e-4 here).
MAX_TILT_RAD = 0.05
# The trajectory's slope is fitted over the travel from FIT_FROM of it on
# (the rigs' fitted part: plausibility.FIT_FROM), through at least
# FIT_STEPS solved steps: fewer leave no slope to measure.  Three, not the
# carriage's MIN_FIT_STEPS (rig.checks): each step here is an equilibrium,
# on the steady path once settled, with no dynamics to average out.
FIT_STEPS = 3


class PushNotSolved(InputError):
    """A step whose equilibrium Newton did not find (not tipping: that is a
    result); the message names the step."""


@dataclass(frozen=True)
class PushedBlock:
    """The block: mass_kg [kg] under g [m/s^2] on its pad (geometry and
    foundation), pushed at height_m [m] above the contact (>= 0)."""
    mass_kg: float
    g: float
    pad: PatchGeometry
    foundation: Foundation
    height_m: float

    def __post_init__(self):
        for name in ("mass_kg", "g"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                raise ValueError(f"PushedBlock: {name} must be a finite number > 0, got {v!r}")
        # push() scales its residuals by RESIDUAL_TOL of the weight (and of its
        # moment over the pad): a weight so small that they underflow cannot be solved for
        W = self.weight
        if not RESIDUAL_TOL * W * max(self.pad.length, self.pad.width) > 0:
            raise ValueError(f"PushedBlock: mass_kg = {self.mass_kg!r} gives a weight of {W!r} N, too small "
                             f"to solve for (the push's tolerances, {RESIDUAL_TOL:g} of it, underflow to 0)")
        h = self.height_m
        if isinstance(h, bool) or not isinstance(h, (int, float)) or not math.isfinite(h) or h < 0:
            raise ValueError(f"PushedBlock: height_m must be a finite number >= 0, got {h!r}")

    @property
    def weight(self) -> float:
        """m g [N]."""
        return self.mass_kg * self.g


@dataclass(frozen=True)
class PushResult:
    """A push's record, one entry per step solved: the carriage's travel x1
    [m], the block's lateral position x2 [m], its pose d [m], phi1, phi2
    [rad], the wrench T1, T2 [N], Mz, M1, M2 [N m], Fn [N], contact_fraction
    and slip_fraction [-], Newton's iterations.  regime: FULL_CONTACT or
    LIFT_OFF at the last step, or TIPS (the run stopped at tipped_at_m [m]
    of travel, where h |T1| reached m g length/2).  cells: the cells' normal
    forces and states (n1, n2) at the last step solved, when asked (FMI 3.0)."""
    x1: np.ndarray
    x2: np.ndarray
    d: np.ndarray
    phi1: np.ndarray
    phi2: np.ndarray
    T1: np.ndarray
    T2: np.ndarray
    Mz: np.ndarray
    M1: np.ndarray
    M2: np.ndarray
    Fn: np.ndarray
    contact_fraction: np.ndarray
    slip_fraction: np.ndarray
    iterations: np.ndarray
    regime: str
    tipped_at_m: float | None = None
    cell_normal: np.ndarray | None = None
    cell_state: np.ndarray | None = None

    def trajectory_tan_phi(self, fit_from: float = FIT_FROM) -> float:
        """The steady slope dx2/dx1 of the path: a line fitted over the part
        of the travel from fit_from of it on; NaN for a run that tipped or
        has fewer than FIT_STEPS steps there (no slope to measure)."""
        if self.regime == TIPS or len(self.x1) == 0:
            return math.nan
        keep = self.x1 >= fit_from * self.x1[-1]
        if np.count_nonzero(keep) < FIT_STEPS:
            return math.nan
        return float(np.polyfit(self.x1[keep], self.x2[keep], 1)[0])


def fit_steps_problem(travel_m: float, step_m: float) -> str | None:
    """Why a push over travel_m [m] in steps of step_m [m] leaves no
    trajectory angle to measure (fewer than FIT_STEPS steps from FIT_FROM of
    the travel on), in words naming the largest step that does; None if it
    leaves one."""
    steps = math.floor((1.0 - FIT_FROM) * travel_m / step_m + 1e-9) + 1
    if steps >= FIT_STEPS:
        return None
    largest = (1.0 - FIT_FROM) * travel_m / (FIT_STEPS - 1)
    return (f"the trajectory angle is fitted over the last {1.0 - FIT_FROM:.0%} of the travel "
            f"({(1.0 - FIT_FROM) * travel_m:g} m) through at least {FIT_STEPS} steps; step_m = {step_m:g} m "
            f"leaves {steps}: step_m <= {largest:.3g} m")


def _positive(name: str, v) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
        raise ValueError(f"{name} must be a finite number > 0, got {v!r}")
    return float(v)


class _NotConverged(Exception):
    """Newton did not reach equilibrium from its start (a continuation may)."""


class _Tips(Exception):
    """The push's moment cannot be held: the run's result, not an error."""


class _Equilibrium:
    """A step's equilibrium on the pad FMU (module docstring): the scaled
    residuals and their Jacobian at a carriage position u1 [m] and pose x,
    Newton on them, the lateral balance that starts it, and the
    continuation through intermediate carriage positions."""

    def __init__(self, fmu: PadFMU, block: PushedBlock):
        g, W = block.pad, block.weight
        self.fmu, self.W, self.h, self.length = fmu, W, float(block.height_m), g.length
        self.force_tol, self.moment_tol = RESIDUAL_TOL * W, RESIDUAL_TOL * W * max(g.length, g.width)

    def residual(self, u1, x):
        """_NotConverged where Newton left the poses the pad can be in (a
        pose that is not finite, or one the FMU refuses: forces that overflow)."""
        if not np.all(np.isfinite(x)):
            raise _NotConverged("its pose not finite")
        try:
            self.fmu.set_inputs(u1, x[0], 0.0, x[1], x[2], x[3])
        except FMUError as e:
            raise _NotConverged(f"a pose the pad refuses: {e}") from None
        T1, T2, Mz, Fn, M1, M2 = self.fmu.load()
        h, force_tol, moment_tol = self.h, self.force_tol, self.moment_tol
        R = np.array([T2 / force_tol, (Fn - self.W) / force_tol, (M1 + h * T2) / moment_tol,
                      (M2 - h * T1) / moment_tol])
        return R, (T1, T2, Mz, Fn, M1, M2)

    def jacobian(self):
        J = np.array(self.fmu.jacobian(UNKNOWNS, ("T1", "T2", "Fn", "M1", "M2")))
        dT1, dT2, dFn, dM1, dM2 = J
        h, force_tol, moment_tol = self.h, self.force_tol, self.moment_tol
        return np.array([dT2 / force_tol, dFn / force_tol, (dM1 + h * dT2) / moment_tol,
                         (dM2 - h * dT1) / moment_tol])

    def equilibrium(self, u1, x):
        """Newton from x at carriage position u1, backtracking on the residual."""
        R, w = self.residual(u1, x)
        it = 0
        while np.max(np.abs(R)) > 1.0:
            if it == NEWTON_ITERATIONS:
                raise _NotConverged(f"residual {np.max(np.abs(R)):.3g} tolerances")
            try:
                dx = np.linalg.solve(self.jacobian(), -R)
            except np.linalg.LinAlgError:   # e.g. every cell slides: u2 leaves T2 as it is
                raise _NotConverged("a singular Jacobian") from None
            step, norm = 1.0, np.max(np.abs(R))
            while True:   # backtracking: a step that does not reduce the residual is halved
                trial = x + step * dx
                R_new, w_new = self.residual(u1, trial)
                if np.max(np.abs(R_new)) < norm or step < 1e-6:
                    break
                step *= 0.5
            x, R, w = trial, R_new, w_new
            it += 1
        return x, w, it

    def lateral(self, u1, x):
        """x with u2 such that T2 = 0 at x's pose (Newton in u2 alone, at most
        NEWTON_ITERATIONS steps), and T1 / Fn there; _Tips if the push's
        moment needs the pressure's centre beyond the leading edge, h |T1|
        >= Fn length/2: T1 / Fn under lateral equilibrium is the friction
        the pressure's shape hardly changes (not at all in full slip)."""
        x = x.copy()
        R, w = self.residual(u1, x)
        for _ in range(NEWTON_ITERATIONS):
            if abs(R[0]) <= 1.0:
                break
            slope = self.fmu.jacobian(("u2",), ("T2",))[0][0]
            if not (math.isfinite(slope) and slope != 0.0):
                break   # T2 does not follow u2 (every cell slides): the full Newton takes over
            trial = x.copy()
            trial[0] -= w[1] / slope
            try:
                R, w = self.residual(u1, trial)
            except _NotConverged:   # a step beyond the poses the pad can be in: likewise
                R, w = self.residual(u1, x)
                break
            x = trial
        T1, Fn = w[0], w[3]
        if Fn > 0 and self.h * abs(T1) >= 0.5 * Fn * self.length:
            raise _Tips
        return x

    def continued(self, u0, u1, x, depth=0):
        """equilibrium at u1, through the midpoint of (u0, u1) where it does not converge."""
        try:
            return self.equilibrium(u1, x)
        except _NotConverged as e:
            if depth == CONTINUATION_DEPTH:
                raise PushNotSolved(f"the push at travel {u1:.6g} m (height {self.h:g} m): Newton did not "
                                    f"reach equilibrium ({e})") from None
            xm, _, im = self.continued(u0, 0.5 * (u0 + u1), x, depth + 1)
            x1, w1, i1 = self.continued(0.5 * (u0 + u1), u1, xm, depth + 1)
            return x1, w1, im + i1


# What a push records at each step solved: PushResult's arrays.
RECORDED = ("x1", "x2", "d", "phi1", "phi2", "T1", "T2", "Mz", "M1", "M2", "Fn",
            "contact_fraction", "slip_fraction", "iterations")


def _check_tilt(u1: float, x, h: float) -> None:
    """PushNotSolved where the pose x tilts the block beyond MAX_TILT_RAD."""
    if max(abs(x[2]), abs(x[3])) > MAX_TILT_RAD:
        raise PushNotSolved(f"the push at travel {u1:.6g} m (height {h:g} m) tilts the block by "
                            f"{math.degrees(max(abs(x[2]), abs(x[3]))):.3g} deg, beyond the small "
                            f"tilts the pad models ({math.degrees(MAX_TILT_RAD):.3g} deg)")


def _record(rec: dict, u1: float, x, w, out: dict, it: int) -> None:
    """Appends a solved step to rec: travel, pose, wrench, the FMU's
    fractions and Newton's iterations."""
    for key, v in zip(("x1", "x2", "d", "phi1", "phi2"), (u1, *x)):
        rec[key].append(float(v))
    for key, v in zip(("T1", "T2", "Mz", "Fn", "M1", "M2"), w):
        rec[key].append(float(v))
    rec["contact_fraction"].append(out["contactFraction"])
    rec["slip_fraction"].append(out["slipFraction"])
    rec["iterations"].append(it)


def push(params: ContactParams, block: PushedBlock, travel_m: float, step_m: float,
         fmi_version: int = 2, fmu_path=None, cells: bool = False) -> PushResult:
    """Pushes the block over travel_m [m] in carriage steps of step_m [m]
    from rest (every cell unloaded where the block settles under its
    weight); each step's equilibrium by Newton (module docstring), started
    from the last step's and, where it does not converge, continued through
    intermediate carriage positions (pending steps, none committed).  With
    cells, the cells' normal forces and states at the last step solved
    (FMI 3.0).  A step it cannot solve, or whose tilt exceeds MAX_TILT_RAD
    (the pad's approach is linear in small tilts), raises PushNotSolved."""
    travel, h_step = _positive("travel_m", travel_m), _positive("step_m", step_m)
    n = int(math.ceil(travel / h_step - 1e-9))
    g, W = block.pad, block.weight
    x = np.array([0.0, W / (block.foundation.kn * g.length * g.width), 0.0, 0.0])   # settled, level
    rec = {k: [] for k in RECORDED}
    regime, tipped, last_cells = None, None, (None, None)
    with PadFMU(fmu_path, "pushed", fmi_version) as fmu:
        fmu.initialize(params, g, block.foundation, (0.0, x[0], 0.0, x[1], x[2], x[3]))
        solver = _Equilibrium(fmu, block)
        u_prev = 0.0
        for k in range(1, n + 1):
            u1 = min(k * h_step, travel)
            try:
                x, w, it = solver.continued(u_prev, u1, solver.lateral(u1, x))
            except _Tips:
                regime, tipped = TIPS, u1
                break
            except _NotConverged as e:   # the lateral balance's start refused
                raise PushNotSolved(f"the push at travel {u1:.6g} m (height {solver.h:g} m): its lateral "
                                    f"balance did not start ({e})") from None
            _check_tilt(u1, x, solver.h)
            u_prev = u1
            out = fmu.outputs()
            if cells and k == n:
                last_cells = (np.array(fmu.cell_normal_forces()), np.array(fmu.cell_states()))
            fmu.do_step(1.0)
            _record(rec, u1, x, w, out, it)
    if regime is None:
        regime = FULL_CONTACT if rec["contact_fraction"] and rec["contact_fraction"][-1] == 1.0 else LIFT_OFF
    arrays = {k: np.array(v) for k, v in rec.items()}
    return PushResult(**arrays, regime=regime, tipped_at_m=tipped, cell_normal=last_cells[0],
                      cell_state=last_cells[1])
