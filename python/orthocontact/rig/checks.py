"""Every rig run checks itself: did the block reach steady sliding inside
the fitted part of its path, and does its angle lie on the steady closed
form with the rig's strip terms?

- settled: the angles fitted over the two halves of the fitted range agree
  to SETTLE_TOL_DEG (a run still turning shows them apart);
- on the closed form: |phi - phi_steady| <= STEADY_TOL_DEG, phi_steady from
  closed_forms.steady_tan_phi_with_strip_array at the run's law, rule,
  strip friction, strip viscosity and velocity.  The literal eq. (20) rule
  slides with a step-dependent angle (docs/explanation/model-notes.md): no closed form
  is claimed for it, only the settling is checked.

A run that fails either is flagged; the commands print one warning line per
scenario with the remedy of the cause found (run_cause): the law's elastic
length mu N / eps against the fit's start (a stiffness in N/mm?), the step
(too few steps in the fitted path, or too long for the dynamic rig's
lateral motion), the dynamic rig's settling length
(closed_forms.settling_length_array) against the travel."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import closed_forms as cf
from .. import plausibility

SETTLE_TOL_DEG = 0.05   # |phi_head - phi_tail| of a run that reached steady sliding


STEADY_TOL_DEG = 0.05   # |phi - phi_steady| of a run on the closed form


# A travel whose fitted part starts this many settling lengths in leaves
# e^-8 (3e-4) of an initial disturbance: the travel the message proposes.
SETTLING_LENGTHS = 8.0


@dataclass
class RunChecks:
    """Per run (arrays in the order of the runs): head - tail [deg], the
    steady closed form [deg] (nan: none claimed), the dynamic settling
    length [m] (nan in quasi-static mode), and the verdicts."""
    halves_deg: np.ndarray
    steady_deg: np.ndarray
    settling_length_m: np.ndarray
    settled: np.ndarray
    on_steady: np.ndarray

    @property
    def ok(self) -> np.ndarray:
        return self.settled & self.on_steady

    def status(self) -> list[str]:
        """'ok', 'unsettled', 'off-steady' or 'unsettled, off-steady' per run."""
        out = []
        for s, o in zip(self.settled, self.on_steady):
            words = ([] if s else ["unsettled"]) + ([] if o else ["off-steady"])
            out.append(", ".join(words) or "ok")
        return out


def steady_phi_deg(tasks) -> np.ndarray:
    """The steady closed form [deg] of each (ContactParams, Rig), with the
    rig's strip terms; nan for the eq20 rule."""
    out = np.full(len(tasks), np.nan)
    groups: dict = {}
    for i, (p, r) in enumerate(tasks):
        if p.rule == "eq20":
            continue
        # runs that differ only in their axes share one call over arrays of them
        key = (p.replace(alpha=0.0, beta=0.0), r.mu_strip, r.c_strip, r.velocity_m_s, r.normal_force)
        groups.setdefault(key, []).append(i)
    for (law, *strip), idx in groups.items():
        alpha = np.array([tasks[i][0].alpha for i in idx])
        beta = np.array([tasks[i][0].beta for i in idx])
        t = cf.of_law(cf.steady_tan_phi_with_strip_array, law, alpha, beta, *strip)
        out[idx] = np.degrees(np.arctan(t))
    return out


def settling_lengths(tasks) -> np.ndarray:
    """closed_forms.settling_length_array of each dynamic run [m]; nan for
    quasi-static runs (no inertia: they settle over elastic lengths)."""
    out = np.full(len(tasks), np.nan)
    for i, (p, r) in enumerate(tasks):
        if r.mode == "dynamic":
            law = p.replace(rule="coupled") if p.rule == "eq20" else p
            out[i] = float(cf.of_law(cf.settling_length_array, law, p.alpha, p.beta, r.mu_strip,
                                     r.c_strip, r.velocity_m_s, r.normal_force, r.mass_kg))
    return out


def check_runs(tasks, figures) -> RunChecks:
    """The checks of each run: tasks [(ContactParams, Rig)], figures the
    RunFigures (or RigResult.figures) of each."""
    phi = np.array([f.phi_deg for f in figures], dtype=float)
    halves = np.array([f.phi_head_deg - f.phi_tail_deg for f in figures], dtype=float)
    steady = steady_phi_deg(tasks)
    settled = np.abs(halves) <= SETTLE_TOL_DEG
    on_steady = np.where(np.isnan(steady), True, np.abs(phi - steady) <= STEADY_TOL_DEG)
    return RunChecks(halves, steady, settling_lengths(tasks), settled, on_steady & np.isfinite(phi))


def warning_line(label: str, angles_deg, checks: RunChecks, phi_deg, tasks,
                 step_name: str = "rig.step_s") -> str | None:
    """One line for the user naming the flagged angles, the deviations and
    the remedy for the cause the checks find (run_cause); None if every run
    passed.  tasks: the (ContactParams, Rig) of each run; step_name: what
    sets the step (uq: --step-s).  Runs of the literal eq. (20) rule are
    flagged in the tables but not warned about: it has no step-independent
    steady state, and the step study shows exactly that
    (docs/explanation/model-notes.md).  No number in it is nan: a value that could not
    be fitted is said as such."""
    implicit = np.array([p.rule != "eq20" for p, _ in tasks], dtype=bool)
    bad = np.flatnonzero(~checks.ok & implicit)
    if len(bad) == 0:
        return None
    angles = np.asarray(angles_deg, dtype=float)
    phi = np.asarray(phi_deg, dtype=float)
    why = []
    unsettled = np.flatnonzero(~checks.settled & implicit)
    halves = np.abs(checks.halves_deg[unsettled])
    if np.isfinite(halves).any():
        why.append(f"the halves of the fitted path differ by up to {np.nanmax(halves):.3g} deg")
    if (~np.isfinite(halves)).any():
        why.append(f"{int((~np.isfinite(halves)).sum())} have too few steps in a half of the fitted path "
                   "to fit an angle")
    dev = np.abs(phi - checks.steady_deg)
    off = np.flatnonzero(~checks.on_steady)
    if len(off) and np.any(np.isfinite(dev[off])):
        k = off[np.nanargmax(dev[off])]
        why.append(f"phi departs from the steady closed form by up to {dev[k]:.3g} deg "
                   f"({phi[k]:.4g} against {checks.steady_deg[k]:.4g} deg at {angles[k]:g} deg)")
    elif len(off):
        why.append("phi could not be fitted")
    return (f"{label}: {len(bad)} of {len(angles)} rig runs are not steady sliding, at "
            f"{angle_list(angles[bad])} deg: {', and '.join(why)}; remedy: "
            f"{remedy([tasks[i] for i in bad], checks.settling_length_m[bad], step_name)}")


# The causes a run's check can have, most basic first: the law's elastic
# length (a stiffness typed in N/mm puts the stick branch over the fitted
# path), the step (too few steps in the fitted path, or one longer than the
# dynamic rig's lateral motion can follow), the dynamic rig's settling length.
CAUSES = ("elastic length", "step", "settling length")


# The fitted path's two halves each need steps to fit an angle to: 10 each.
MIN_FIT_STEPS = 20


def elastic_length_m(params, rig) -> float:
    """The law's longest elastic length max(mu) N / min(eps) [m]
    (plausibility.elastic_lengths)."""
    return plausibility.elastic_lengths(params.mu1, params.mu2, params.eps1, params.eps2,
                                        rig.normal_force)[1]


def fitted_steps(rig) -> int:
    """The steps of a run in the fitted part of its path (rig.harness: the
    steps from fit_from of the travel the run makes on)."""
    n = math.ceil(rig.travel_m / (rig.velocity_m_s * rig.step_s) - 1e-9)
    return n - math.ceil(rig.fit_from * n) + 1


def step_limit_s(params, rig, settling_m: float) -> float:
    """The largest step [s] the run can take: MIN_FIT_STEPS in the fitted
    path; in the dynamic rig, whose lateral update is explicit, at most half
    the settling time L / v and the stick stiffness's bound sqrt(m / eps_max)
    (half of 2 sqrt(m / eps_max), the explicit update's stability limit)."""
    v = rig.velocity_m_s
    limit = (1 - rig.fit_from) * rig.travel_m / (v * MIN_FIT_STEPS)
    if rig.mode == "dynamic":
        limit = min(limit, (rig.mass_kg / max(params.eps1, params.eps2)) ** 0.5)
        if 0 < settling_m < np.inf:
            limit = min(limit, 0.5 * settling_m / v)
    return limit


def run_cause(params, rig, settling_m: float) -> tuple[str, float] | None:
    """(cause of CAUSES, its severity: how far the run is past its bound)
    that explains why a run is not steady sliding, or None if none does."""
    start = rig.fit_from * rig.travel_m
    L = elastic_length_m(params, rig)
    if start < plausibility.ELASTIC_LENGTHS * L:
        return "elastic length", plausibility.ELASTIC_LENGTHS * L / start if start > 0 else np.inf
    if rig.step_s > step_limit_s(params, rig, settling_m) or fitted_steps(rig) < MIN_FIT_STEPS:
        return "step", rig.step_s / step_limit_s(params, rig, settling_m)
    if rig.mode == "dynamic" and not start >= SETTLING_LENGTHS * settling_m:
        return "settling length", SETTLING_LENGTHS * settling_m / start if start > 0 else np.inf
    return None


def remedy(tasks, settling_m, step_name: str = "rig.step_s") -> str:
    """The remedy of the most basic cause (CAUSES) found among the runs
    `tasks` [(ContactParams, Rig)] with their settling lengths [m] (nan in
    quasi-static mode), for the run furthest past its bound.  It never
    proposes a travel the rig already has."""
    found = {}
    for (p, r), L in zip(tasks, settling_m):
        c = run_cause(p, r, float(L))
        if c is not None and (c[0] not in found or c[1] > found[c[0]][0]):
            found[c[0]] = (c[1], p, r, float(L))
    if not found:
        r = tasks[0][1]
        return (f"a smaller {step_name} than {r.step_s:g} s, or a longer rig.travel_m than {r.travel_m:g} m "
                "(neither the elastic length, the settling length nor the step explains it)")
    cause = next(c for c in CAUSES if c in found)
    _, p, r, L = found[cause]
    start = r.fit_from * r.travel_m
    if cause == "elastic length":
        e = elastic_length_m(p, r)
        slip = (" (N/mm typed as N/m? 1000 times the stiffness would settle)"
                if plausibility.ELASTIC_LENGTHS * e / 1e3 <= start else "")
        return (f"check eps1, eps2 = {p.eps1:.4g}, {p.eps2:.4g} N/m{slip}: the elastic length max(mu) N / "
                f"min(eps) = {e:.3g} m puts the fit's start at {start:.3g} m within "
                f"{plausibility.ELASTIC_LENGTHS:g} elastic lengths, where the block has not settled (or "
                + (f"rig.travel_m >= {plausibility.ELASTIC_LENGTHS * e / r.fit_from:.3g} m)" if r.fit_from > 0
                   else "rig.fit_from > 0: the fit starts where the path does)"))
    if cause == "step":
        return (f"{step_name} <= {step_limit_s(p, r, L):.2g} s (the step {r.step_s:g} s leaves "
                f"{fitted_steps(r)} steps in "
                f"the fitted path" + (f", of {r.velocity_m_s * r.step_s:.3g} m each against a settling "
                                      f"length of {L:.3g} m" if r.mode == "dynamic" and 0 < L < np.inf
                                      else "") + ")")
    if np.isfinite(L):
        need = SETTLING_LENGTHS * L / r.fit_from if r.fit_from > 0 else SETTLING_LENGTHS * L
        return (f'rig.mode = "quasistatic", or rig.travel_m >= {need:.3g} m (the dynamic rig settles '
                f"over {L:.3g} m here, its fit starts at {start:.3g} m)")
    return 'rig.mode = "quasistatic" (the dynamic rig has no restoring lateral force here)'


def angle_list(a) -> str:
    """Angles [deg] as a short text: runs of an evenly spaced grid as 'a-b'."""
    a = sorted(set(float(x) for x in a))
    if len(a) <= 2:
        return ", ".join(f"{x:g}" for x in a)
    step = min(y - x for x, y in zip(a, a[1:]))
    parts, start = [], a[0]
    for prev, x in zip(a, a[1:] + [None]):
        if x is None or abs(x - prev - step) > 1e-9 * max(1.0, abs(step)):
            parts.append(f"{start:g}" if prev == start else f"{start:g}-{prev:g}")
            start = x
    return ", ".join(parts)


def system_settling_warning(label: str, params, rig) -> str | None:
    """A warning line if the dynamic rig (the CarriageBlock FMU of an SSP,
    which integrates the block's lateral inertia whatever the scenario's
    mode) does not settle before the fitted part of its path starts: that
    part must start SETTLING_LENGTHS settling lengths and
    plausibility.ELASTIC_LENGTHS elastic lengths in (the remedy says which)."""
    from dataclasses import replace
    dynamic = replace(rig, mode="dynamic")
    L = settling_lengths([(params, dynamic)])[0]
    start = rig.fit_from * rig.travel_m
    cause = run_cause(params, dynamic, L)
    if cause is not None and cause[0] == "elastic length":
        return (f"{label}: the system's dynamic rig would not settle before the fit of its path starts at "
                f"{start:.3g} m: its angle is not steady sliding; remedy: {remedy([(params, dynamic)], [L])}")
    if np.isfinite(L) and start >= SETTLING_LENGTHS * L:
        return None
    need = ("a quasi-static rig (there is no restoring lateral force here)" if not np.isfinite(L) else
            f"rig.travel_m >= {SETTLING_LENGTHS * L / rig.fit_from:.3g} m" if rig.fit_from > 0 else
            "rig.fit_from > 0 (the fit starts where the path does)")
    mode = "" if rig.mode == "dynamic" else f" (the scenario's rig is {rig.mode}; the SSP's is dynamic)"
    return (f"{label}: the system's dynamic rig settles over {L:.3g} m{mode}, and the fit of its path "
            f"would start at {start:.3g} m: its angle is not steady sliding; remedy: {need}")
