"""A planar rigid body on the ContactPatch FMU: its centre (x1, x2) [m] and
yaw theta [rad] (counterclockwise about the normal) on the textured surface,
mass m [kg], moment of inertia I [kg m^2] about the normal through its
centre, pressed by N [N] with uniform pressure over its rectangular patch
(body axis 1 along `length`).  The FMU's inputs are u = (x1, x2) (the
surface frame's origin at the body's start), theta and N; its T [N] and
Mz [N m] act on the body at its centre.  Two prescribed motions:

twist        the centre held, theta = omega t: the torque the surface puts
             on the body against the angle.  While every cell sticks,
             Mz = -k theta with k = closed_forms.patch.torsional_stiffness_grid
             (exactly -k sin theta for isotropic stiffness); once every cell
             slides, the plateau is full_slip_rotation_grid with the
             texture's angles seen from the body, alpha - theta and
             beta - theta (the texture is the surface's).  The plateau is
             reached as the elastic lag fades: a cell at radius r trails its
             path by l = mu N / eps (the law's elastic slip length), which
             shortens its arm by the factor cos(asin(l / r)), a relative
             error (l / r)^2 / 2.

towed block  a pin at distance d [m] ahead of the centre along the body's
             axis 1 is pulled at constant velocity v [m/s] along the
             direction psi [rad]; the body is free to turn about the pin.
             With the pin's frame inertial (constant velocity), the yaw
             obeys (I + m d^2) theta'' = Mz + (c - P) x T, the moment of
             the surface's force about the pin P, c = P - d e(theta),
             e = (cos theta, sin theta).

The towed block's steady yaw (its closed form): in steady sliding every cell
slides along the motion m = (cos psi, sin psi) and the surface's force is
uniform over the patch, -N q with q the law's steady sliding force for the
sliding direction m (closed_forms.patch.steady_force_direction: q parallel
to H m on the yield ellipse); its resultant acts at the centre.  Its moment
about the pin, N d (e x q), vanishes with the centre trailing the pin when e
is parallel to q: the body's axis lines up with the pulling force N q, and

    theta_ss - psi = atan2(m x q, m . q),

the angle from the sliding direction to the steady sliding force, positive
counterclockwise.  It is the paper's trajectory angle phi read from the
motion's side: with the force along X1 the slip runs at phi
(closed_forms.paper.steady_tan_phi); turned by theta_ss, the force of the
towed block is along its axis, so theta_ss = psi - phi(alpha - theta_ss,
beta - theta_ss) with phi evaluated in the frame of the force, an implicit
equation whose root is the explicit form above.  On the paper's mat (alpha
= a + 90 deg, beta = a, motion along X1) that reads theta_ss(a) =
-phi(a - theta_ss(a)): the yaw is not -phi at the same mat angle, but it
takes the same values, -phi(a0) at a = a0 - phi(a0), so its extremum is
minus the paper's extremal phi, at the paper's extremal angle minus that
phi (coupled, aged mat: 11.526 deg at a = 50.76 deg against phi = -11.526
deg at 39.24 deg).  It is independent of the
grid (every cell carries the same force in uniform translation) and of the
time step (backward Euler's fixed point is the steady state, and the
return mapping's steady force q parallel to H m holds for any increment).

Integration of the towed block: backward Euler on theta, solved by Newton
with the FMU's directional derivatives on the pending (uncommitted) step,
then committed.  It is stable at any step for the stiff stuck contact, and
its numerical damping only shortens the transient: the steady yaw is its
fixed point, which is the continuous one.  The step's equation
R(x) = I_pin (x - theta - h omega) - h^2 M(x) always has a root: the
surface's force on a cell lies on or inside the law's yield ellipse, so
|T| <= max(mu) N and the moment about the pin |M| <= max(mu) N (d + r_c)
(r_c the half-diagonal of the patch), and R changes sign over
x - theta - h omega = -+ h^2 max|M| / I_pin.  Newton steps that leave
that bracket or stall (the stick-slip switches of the cells put kinks in
M(x), where the tangent may even have the wrong sign) are replaced by
bisection, which cannot fail."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..closed_forms import (
    full_slip_rotation_grid,
    of_law,
    steady_force_direction,
    steady_tan_phi,
    torsional_stiffness_grid,
)
from ..errors import InputError
from ..fmu import ContactParams, PatchFMU, PatchGeometry


@dataclass(frozen=True)
class PlanarBody:
    """The body.  mass_kg [kg], inertia_kg_m2 [kg m^2] about the normal
    through the centre, patch (its contact rectangle and grid), normal_N [N]
    its normal force.  PlanarBody.uniform gives a uniform block's inertia."""
    mass_kg: float
    inertia_kg_m2: float
    patch: PatchGeometry
    normal_N: float

    def __post_init__(self):
        for name in ("mass_kg", "inertia_kg_m2", "normal_N"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                raise ValueError(f"PlanarBody: {name} must be a finite number > 0, got {v!r}")

    @classmethod
    def uniform(cls, mass_kg: float, patch: PatchGeometry, normal_N: float) -> PlanarBody:
        """A uniform block over its patch: I = m (length^2 + width^2) / 12."""
        return cls(mass_kg, mass_kg * (patch.length**2 + patch.width**2) / 12.0, patch, normal_N)


@dataclass(frozen=True)
class TwistResult:
    """The twist test's record, one entry per step: theta [rad], Mz [N m]
    (the surface's moment on the body), slip_fraction [-], contact_state;
    cell_state (steps, n1, n2): each cell's state (0 open, 1 stick, 2 slip)
    when asked for (FMI 3.0), else None."""
    theta: np.ndarray
    Mz: np.ndarray
    slip_fraction: np.ndarray
    contact_state: np.ndarray
    cell_state: np.ndarray | None = None


@dataclass(frozen=True)
class TowResult:
    """The towed block's record, one entry per step: t [s], theta [rad],
    omega [rad/s], the centre x1, x2 [m], T1, T2 [N], Mz [N m] (at the
    centre, on the body), slip_fraction [-]."""
    t: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    x1: np.ndarray
    x2: np.ndarray
    T1: np.ndarray
    T2: np.ndarray
    Mz: np.ndarray
    slip_fraction: np.ndarray


def _positive(name: str, v) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
        raise ValueError(f"{name} must be a finite number > 0, got {v!r}")
    return float(v)


def twist(params: ContactParams, body: PlanarBody, rate_rad_s: float, angle_rad: float,
          step_s: float, fmi_version: int = 2, fmu_path=None, cells: bool = False) -> TwistResult:
    """Turns the pressed body about its fixed centre at rate_rad_s [rad/s]
    up to angle_rad [rad], a communication step step_s [s] at a time; with
    cells, records every cell's state at every step (FMI 3.0 only)."""
    rate = _positive("rate_rad_s", rate_rad_s)
    h = _positive("step_s", step_s)
    n = int(math.ceil(_positive("angle_rad", angle_rad) / (rate * h)))
    rec = np.empty((4, n))
    states = np.empty((n, body.patch.n1, body.patch.n2), dtype=int) if cells else None
    with PatchFMU(fmu_path, "twist", fmi_version) as fmu:
        fmu.initialize(params, body.patch, (0.0, 0.0, 0.0, body.normal_N))
        for i in range(n):
            theta = rate * h * (i + 1)
            fmu.set_inputs(0.0, 0.0, theta, body.normal_N)
            out = fmu.outputs()
            if cells:
                states[i] = fmu.cell_states()
            fmu.do_step(h)
            rec[:, i] = theta, out["Mz"], out["slipFraction"], out["contactState"]
    return TwistResult(rec[0], rec[1], rec[2], rec[3].astype(int), states)


def twist_stiffness(params: ContactParams, patch: PatchGeometry) -> float:
    """k [N m/rad] of the grid sticking: Mz = -k theta for small theta."""
    return torsional_stiffness_grid(params.eps1, params.eps2, params.alpha, patch.length, patch.width,
                                    patch.n1, patch.n2)


def twist_plateau(params: ContactParams, body: PlanarBody, theta) -> np.ndarray:
    """Mz [N m] of the grid with every cell in steady sliding, turning
    counterclockwise, at the body's angle theta [rad] (scalar or array): the
    texture seen from the body is turned by -theta, and the moment is the
    same in either frame."""
    p, g = params, body.patch
    th = np.atleast_1d(np.asarray(theta, dtype=float))
    return np.array([of_law(full_slip_rotation_grid, p, p.alpha - t, p.beta - t, g.length, g.width,
                            body.normal_N, g.n1, g.n2)[2]
                     for t in th]).reshape(np.shape(theta))


def steady_yaw(params: ContactParams, direction_rad: float = 0.0) -> float:
    """theta_ss [rad] of the towed block pulled along direction_rad: the
    direction of the law's steady sliding force for sliding along the
    motion, psi + atan2(m x q, m . q) (module docstring)."""
    p = params
    m = np.array([math.cos(direction_rad), math.sin(direction_rad)])
    q = of_law(steady_force_direction, p, p.alpha, p.beta, m)
    return direction_rad + math.atan2(m[0] * q[1] - m[1] * q[0], m @ q)


def steady_yaw_residual(params: ContactParams, theta: float, direction_rad: float = 0.0) -> float:
    """The same steady state from the paper's side [rad]: in the frame of
    the towed block's pulling force (turned by theta), the paper's push
    along X1 makes the slip run at phi (closed_forms.paper.steady_tan_phi),
    and that must be the motion's direction: theta + phi - direction_rad,
    zero at the steady yaw (|angles| < 90 deg)."""
    p = params
    phi = math.atan(of_law(steady_tan_phi, p, p.alpha - theta, p.beta - theta))
    return theta + phi - direction_rad


class StepNotSolved(InputError):
    """A towed block's backward Euler step that has no root where the law
    bounds it (a non-finite moment, or one beyond max(mu) N (d + r_c)): an
    input the harness cannot integrate; the message names the cause, the
    caller the step's key."""


def step_root(residual, x0: float, half_width: float, tol: float, newton_iterations: int) -> float:
    """The root of residual(x) -> (R, dR/dx), R <= 0 at x0 - half_width and
    >= 0 at x0 + half_width, to tol: Newton from x0 while its step stays
    inside the bracket of the signs seen and at least halves |R| (at most
    newton_iterations steps), bisection otherwise, which always converges.
    Raises StepNotSolved for a non-finite R or a bracket whose ends do not
    have the signs promised."""
    lo, hi = x0 - half_width, x0 + half_width
    ends_checked, newton, last, x = False, 0, math.inf, x0
    while True:
        R, J = residual(x)
        if not math.isfinite(R):
            raise StepNotSolved(f"the step's residual is {R!r} at theta = {x!r} rad")
        if R == 0:
            return x
        if R < 0:
            lo = x
        else:
            hi = x
        dx = -R / J if math.isfinite(J) and J > 0 else math.nan
        if abs(dx) <= tol:   # converged (a step this small may not move x at all)
            return x + dx
        if not (newton < newton_iterations and lo < x + dx < hi and abs(R) <= 0.5 * last):
            if not ends_checked:
                # the bound is the law's (module docstring): checked, not assumed, before bisecting on it
                ends_checked = True
                for end, sign in ((x0 - half_width, -1), (x0 + half_width, 1)):
                    R_end = residual(end)[0]
                    if not (math.isfinite(R_end) and sign * R_end >= 0):
                        raise StepNotSolved(f"the step's residual at theta = {end!r} rad is {R_end!r}, "
                                            "beyond the bound of the law's forces")
            dx = 0.5 * (lo + hi) - x
        else:
            newton += 1
        last = abs(R)
        x += dx
        if abs(dx) <= tol or hi - lo <= tol:
            return x


def towed_block(params: ContactParams, body: PlanarBody, velocity_m_s: float, pin_m: float,
                duration_s: float, step_s: float, direction_rad: float = 0.0,
                theta0_rad: float = 0.0, fmi_version: int = 2, fmu_path=None,
                newton_tol_rad: float = 1e-13, newton_iterations: int = 30) -> TowResult:
    """Pulls the body through a pin at pin_m [m] ahead of its centre along
    direction_rad at velocity_m_s [m/s] for duration_s [s], starting at yaw
    theta0_rad [rad] at rest (every cell unloaded); backward Euler with step
    step_s [s], each step's yaw solved to newton_tol_rad by step_root (at
    most newton_iterations Newton steps, then bisection).  A step it cannot
    solve raises StepNotSolved (a yaw that is not the step's solution is not
    recorded)."""
    v = _positive("velocity_m_s", velocity_m_s)
    d = _positive("pin_m", pin_m)
    h = _positive("step_s", step_s)
    n = int(math.ceil(_positive("duration_s", duration_s) / h))
    m = np.array([math.cos(direction_rad), math.sin(direction_rad)])
    I_pin = body.inertia_kg_m2 + body.mass_kg * d * d
    N = body.normal_N
    g = body.patch
    # the step's bracket (module docstring), a little wider than the bound of |M|
    bound = 1.01 * h * h * max(params.mu1, params.mu2) * N * (d + math.hypot(g.length, g.width) / 2) / I_pin
    theta, omega = float(theta0_rad), 0.0
    pin0 = d * np.array([math.cos(theta), math.sin(theta)])    # centre starts at the origin
    rec = np.empty((9, n))
    with PatchFMU(fmu_path, "towed", fmi_version) as fmu:
        fmu.initialize(params, body.patch, (0.0, 0.0, theta, N))

        def residual(x):
            """R(x) and dR/dx of the step at yaw x, from the pending step."""
            e = np.array([math.cos(x), math.sin(x)])
            de = np.array([-e[1], e[0]])
            c = pin - d * e
            fmu.set_inputs(c[0], c[1], x, N)
            T1, T2, Mz = fmu.load()
            # moment about the pin and its derivative along theta (the
            # centre moves by dc = -d de dtheta)
            M = Mz - d * (e[0] * T2 - e[1] * T1)
            d_th, d_u1, d_u2 = fmu.derivative("theta"), fmu.derivative("u1"), fmu.derivative("u2")
            dT = [d_th[k] - d * (de[0] * d_u1[k] + de[1] * d_u2[k]) for k in range(3)]
            dM = dT[2] - d * (de[0] * T2 - de[1] * T1) - d * (e[0] * dT[1] - e[1] * dT[0])
            return I_pin * (x - theta - h * omega) - h * h * M, I_pin - h * h * dM

        for i in range(n):
            t = h * (i + 1)
            pin = pin0 + v * t * m
            try:
                x = step_root(residual, theta + h * omega, bound, newton_tol_rad, newton_iterations)
            except StepNotSolved as e:
                raise StepNotSolved(f"towed block at t = {t:.6g} s: backward Euler's step: {e}") from None
            e = np.array([math.cos(x), math.sin(x)])
            c = pin - d * e
            fmu.set_inputs(c[0], c[1], x, N)
            out = fmu.outputs()
            fmu.do_step(h)
            omega, theta = (x - theta) / h, x
            rec[:, i] = (t, theta, omega, c[0], c[1], out["T1"], out["T2"], out["Mz"],
                         out["slipFraction"])
    return TowResult(*rec)
