"""The carriage/block test rig of the paper (section 2) coupled with the
OrthotropicContact FMU.

A block of mass m [kg] lies on the mat.  A carriage driven at constant
velocity v [m/s] along X1 pushes it through a Teflon strip, so the block's
X1 position follows the carriage, x1 = v t, while it is free to drift along
X2, resisted only by the strip: Coulomb friction (coefficient mu_strip on the
carriage-block contact force P) and a viscous term c_strip [N s/m] on the
lateral velocity, both 0 by default (the paper assumes a frictionless strip
and measures neither).  The FMU's inputs are the block's
displacement (u1, u2) = (x1, x2) and N = m g; its force T acts on the block.
The force sensor reads F = F_int + P with P = -T1 (the carriage moves at
constant velocity, so the block's X1 inertia does not load it).

Modes:
  dynamic      the block's X2 motion m x2'' = T2 + f_strip - c_strip x2',
               integrated by the harness between communication points
               (symplectic Euler with the force held over the step, the
               viscous term implicit: stable at any step).
  quasistatic  massless lateral equilibrium T2 + f_strip - c_strip x2' = 0 at
               every step (x2' the step's lateral displacement over h),
               solved by a safeguarded Newton on u2 with the FMU's directional
               derivative, iterating on a saved FMU state before committing.

The same rig in C (fmu_src/rig/rig_core.c: the CarriageBlock FMU's step and the
compiled master's loop) is tested against this module bit for bit
(tests/rig/test_compiled.py): this is the reference, and the path that needs no
compiled master."""
from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from typing import NamedTuple

import numpy as np

from ..closed_forms import G_STANDARD
from ..fmu import ContactFMU, ContactParams
from ..plausibility import number_problem

MODES = ("dynamic", "quasistatic")


def limits(default, lo=None, hi=None, lo_open=False, options=None):
    """A field of Rig with its default and what it takes: a finite number in
    [lo, hi] ((lo, hi] with lo_open; None unbounded), or one of `options`."""
    return field(default=default, metadata={"range": (lo, hi, lo_open), "options": options})


def field_problem(f, v) -> str | None:
    """What Rig's field `f` (a dataclasses.Field) takes, in words, if `v` is
    not that; None if it is."""
    options = f.metadata["options"]
    if options is not None:
        return None if v in options else "one of " + ", ".join(map(repr, options))
    return number_problem(v, *f.metadata["range"])


@dataclass(frozen=True)
class Rig:
    """The test rig: the one place of its fields, their defaults and what
    each takes (`limits`); a scenario's [rig] table and a lab's rig.toml are
    read with them (experiment.keys.rig_spec).  Units: kg, m/s^2, N, m/s, m, s.

    mode: "dynamic" (the block's lateral inertia integrated) or "quasistatic"
    (lateral equilibrium every step); a field outside what it takes raises
    ValueError."""
    mass_kg: float = limits(1.875, 0, lo_open=True)
    g: float = limits(G_STANDARD, 0, lo_open=True)
    f_int_N: float = limits(5.0, 0)
    velocity_m_s: float = limits(0.244, 0, lo_open=True)
    travel_m: float = limits(0.5, 0, lo_open=True)
    mu_strip: float = limits(0.0, 0)
    # or "dynamic" (settles over a length: closed_forms.settling_length_array)
    mode: str = limits("quasistatic", options=MODES)
    # communication step; in a file at most 0.1 s too (the plausibility gate's hard range)
    step_s: float = limits(2e-4, 0, lo_open=True)
    fit_from: float = limits(0.5, 0, 0.95)   # fit phi over the travel after this fraction
    c_strip: float = limits(0.0, 0)          # N s/m: the strip's lateral viscous resistance

    def __post_init__(self):
        for f in fields(self):
            why = field_problem(f, getattr(self, f.name))
            if why is not None:
                raise ValueError(f"Rig: {f.name} must be {why}, got {getattr(self, f.name)!r}")

    @property
    def normal_force(self) -> float:
        return self.mass_kg * self.g


class RunFigures(NamedTuple):
    """What one run measures: the trajectory angle fitted over the fit range
    [deg], the mean driving force over it [N], and the angle fitted over the
    first and over the second half of the range [deg]."""
    phi_deg: float
    drive_mean_N: float
    phi_head_deg: float
    phi_tail_deg: float


@dataclass
class RigResult:
    """Time series of one run and the measured figures.

    t [s], x1, x2 [m] block path, T1, T2 [N], s1, s2 [m], state, energy [J],
    drive [N] the sensor's force; phi_deg the fitted trajectory angle
    (counterclockwise), drive_mean_N the mean driving force over the fit range;
    phi_head_deg, phi_tail_deg the angle fitted over the first and the second
    half of the fit range (equal when the block slides steadily throughout).
    """
    t: np.ndarray
    x1: np.ndarray
    x2: np.ndarray
    T1: np.ndarray
    T2: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    state: np.ndarray
    energy: np.ndarray
    drive: np.ndarray
    phi_deg: float
    drive_mean_N: float
    newton_iterations: int = 0
    phi_head_deg: float = math.nan
    phi_tail_deg: float = math.nan

    @property
    def figures(self) -> RunFigures:
        return RunFigures(self.phi_deg, self.drive_mean_N, self.phi_head_deg, self.phi_tail_deg)


class LineFit:
    """Streaming least-squares line x2 = a + b x1 and mean driving force,
    over every step of the steady range (independent of what is recorded).
    Sums are taken about the first point to avoid cancellation."""

    def __init__(self):
        self.n = 0
        self.x0 = self.y0 = 0.0
        self.sx = self.sy = self.sxx = self.sxy = self.sf = 0.0

    def add(self, x1: float, x2: float, drive: float):
        if self.n == 0:
            self.x0, self.y0 = x1, x2
        dx, dy = x1 - self.x0, x2 - self.y0
        self.n += 1
        self.sx += dx
        self.sy += dy
        self.sxx += dx * dx
        self.sxy += dx * dy
        self.sf += drive

    def angle_deg(self) -> float:
        n = self.n
        den = n * self.sxx - self.sx * self.sx
        if n < 2 or den <= 0:
            return math.nan
        return math.degrees(math.atan((n * self.sxy - self.sx * self.sy) / den))

    def mean_drive(self) -> float:
        return self.sf / self.n if self.n else math.nan


class LateralSolveError(RuntimeError):
    pass


def solve_lateral(fmu: ContactFMU, u1: float, u2: float, N: float, strip: float = 0.0,
                  scale: float = 1e-4, tol: float = 1e-12, max_iter: int = 200,
                  visc: float = 0.0, u2_ref: float = 0.0):
    """u2 [m] with lateral equilibrium r(u2) = T2 - strip * P - visc (u2 - u2_ref)
    = 0, where P = max(-T1, 0) [N] is the push, `strip` = mu_strip sgn(v2)
    the strip's signed friction coefficient (0: free block, T2 = 0), and
    visc = c_strip / h [N/m] the viscous term over a step from u2_ref [m].
    Leaves the FMU's pending step at the solution (not committed).

    r falls with u2 (the return map is monotone), so every evaluation
    tightens a bracket; Newton steps with the consistent tangent are taken
    when they stay inside it, bisection otherwise, and before a bracket
    exists steps are limited to a growing multiple of `scale` [m] (the
    elastic displacement mu N / eps is a good scale).  tol is relative to N.
    Returns (u2, iterations)."""
    lo = hi = None  # r(lo) > 0 > r(hi)
    grow = scale
    for it in range(1, max_iter + 1):
        fmu.set_inputs(u1, u2, N)
        T1, T2 = fmu.force()
        r = T2 - strip * max(-T1, 0.0) - visc * (u2 - u2_ref)
        if abs(r) <= tol * max(abs(N), 1e-300):
            return u2, it
        if r > 0:
            lo = u2
        else:
            hi = u2
        dT1, dT2 = fmu.tangent_column("u2")
        d = dT2 + (strip * dT1 if T1 < 0 else 0.0) - visc
        cand = u2 - r / d if d < 0 else math.nan
        if lo is not None and hi is not None:
            if not (min(lo, hi) < cand < max(lo, hi)):
                cand = 0.5 * (lo + hi)
            if abs(hi - lo) <= 4e-16 * max(abs(lo), abs(hi)):
                return u2, it  # bracket at rounding level: r jumps across zero
        elif not math.isfinite(cand) or abs(cand - u2) > grow:
            cand = u2 + math.copysign(grow, r)  # r > 0: T2 too big, increase u2
            grow *= 4
        u2 = cand
    raise LateralSolveError(f"lateral equilibrium not reached in {max_iter} iterations "
                            f"(u1={u1}, last u2={u2})")


def run(params: ContactParams, rig: Rig, fmu: ContactFMU | None = None,
        record_every: int = 1) -> RigResult:
    """One rig run over rig.travel_m.  Uses `fmu` if given (reset here), else
    a new instance."""
    own = fmu is None
    if own:
        fmu = ContactFMU(instance_name="rig")
    else:
        fmu.reset()
    try:
        fmu.initialize(params)
        return simulate(fmu, params, rig, record_every)
    finally:
        if own:
            fmu.close()


class Recording:
    """simulate's observer: what a run keeps as it goes.  Every committed
    step goes into the line fits of the path from rig.fit_from of the travel
    on (the whole range, and each half); every record_every-th step and the
    last into the columns of RigResult, with the FMU's outputs then."""
    COLUMNS = ("t", "x1", "x2", "T1", "T2", "s1", "s2", "state", "energy", "drive")

    def __init__(self, fmu: ContactFMU, rig: Rig, n_steps: int, record_every: int):
        h, v = rig.step_s, rig.velocity_m_s
        self.fmu, self.f_int, self.every, self.n_steps = fmu, rig.f_int_N, record_every, n_steps
        self.cols = {k: np.empty(n_steps // record_every + 1) for k in self.COLUMNS}
        self.rec = 0
        self.fit, self.head, self.tail = LineFit(), LineFit(), LineFit()
        self.x1_fit = rig.fit_from * v * n_steps * h
        x1_end = v * n_steps * h
        self.x1_mid = self.x1_fit + 0.5 * (x1_end - self.x1_fit)

    def step(self, k: int, t: float, x1: float, x2: float, T1: float, T2: float) -> None:
        """Step k, committed at t [s] with the block at (x1, x2) [m] and the
        contact's force (T1, T2) [N]."""
        if x1 >= self.x1_fit:
            drive = self.f_int - T1
            self.fit.add(x1, x2, drive)
            (self.tail if x1 >= self.x1_mid else self.head).add(x1, x2, drive)
        if k % self.every == 0 or k == self.n_steps:
            o, cols, rec = self.fmu.outputs(), self.cols, self.rec
            cols["t"][rec], cols["x1"][rec], cols["x2"][rec] = t, x1, x2
            cols["T1"][rec], cols["T2"][rec] = T1, T2
            cols["s1"][rec], cols["s2"][rec] = o["s1"], o["s2"]
            cols["state"][rec], cols["energy"][rec] = o["contactState"], o["dissipatedEnergy"]
            cols["drive"][rec] = self.f_int - T1
            self.rec = rec + 1

    def result(self, newton: int) -> RigResult:
        """The run's RigResult: the steps kept and the fits' figures."""
        cols = {key: c[:self.rec] for key, c in self.cols.items()}
        return RigResult(**cols, phi_deg=self.fit.angle_deg(), drive_mean_N=self.fit.mean_drive(),
                         newton_iterations=newton, phi_head_deg=self.head.angle_deg(),
                         phi_tail_deg=self.tail.angle_deg())


def simulate(fmu: ContactFMU, params: ContactParams, rig: Rig, record_every: int) -> RigResult:
    """The rig's loop over rig.travel_m on `fmu`, initialized with `params`
    (run() resets and initializes it): every run of the Python harness passes
    here.  What it keeps, every `record_every`-th step and the fits: Recording."""
    h, v, m, N = rig.step_s, rig.velocity_m_s, rig.mass_kg, rig.normal_force
    n_steps = int(math.ceil(rig.travel_m / (v * h) - 1e-9))
    recording = Recording(fmu, rig, n_steps, record_every)
    scale = min(params.mu1, params.mu2) * N / max(params.eps1, params.eps2)
    x2 = v2 = 0.0
    T1 = T2 = 0.0
    t = 0.0
    newton = 0
    dynamic = rig.mode == "dynamic"
    mu_s = rig.mu_strip
    damp = 1.0 + h * rig.c_strip / m  # the viscous term, implicit (1.0 without it: exact)
    visc = rig.c_strip / h
    set_inputs, force, do_step, observe = fmu.set_inputs, fmu.force, fmu.do_step, recording.step
    snapshot = None
    for k in range(1, n_steps + 1):
        t = k * h
        x1 = v * t
        P = max(-T1, 0.0)  # the carriage can only push
        if dynamic:
            # Teflon strip: Coulomb friction on the lateral sliding, bounded by
            # what stops the block within this step (no reversal by friction),
            # inside the implicit viscous update like every other force, so
            # that a steady state balances T2 + f = c_strip v2 exactly.
            f_max = mu_s * P
            a_free = T2 / m
            if f_max > 0.0:
                w = v2 + h * a_free
                f = -math.copysign(min(f_max, abs(m * w / h)), w)
                v2 = (w + h * f / m) / damp
            else:
                v2 = (v2 + h * a_free) / damp
            x2 += h * v2
            set_inputs(x1, x2, N)
            T1, T2 = force()
        else:
            # The strip holds the block while |T2| <= mu_s P; beyond that the
            # block moves until T2 falls to the strip's limit.
            snapshot = fmu.get_state() if snapshot is None else fmu.refresh_state(snapshot)
            set_inputs(x1, x2, N)
            T1, T2 = force()
            if abs(T2) > mu_s * max(-T1, 0.0):
                fmu.set_state(snapshot)  # iterate from the committed state
                x2, it = solve_lateral(fmu, x1, x2, N, math.copysign(mu_s, T2), scale,
                                       visc=visc, u2_ref=x2)
                newton += it
                T1, T2 = force()
        do_step(h)
        observe(k, t, x1, x2, T1, T2)
    if snapshot is not None:
        fmu.free_state(snapshot)
    return recording.result(newton)
