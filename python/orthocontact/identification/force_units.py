"""The carriage runs' force logs against the slide runs': F_int, the
carriage runs' plateau, is measured again by the step the ramp runs make
as their carriage starts, and the same sensor's noise at rest should not
differ between the runs; where either says the carriage runs were logged
some factor off (kN, daN, mN, gram-force), the slides' friction
coefficients mu = (F - F_int)/(m g) decide which runs are off.  Units: N."""
from __future__ import annotations

import math

import numpy as np

from .. import plausibility
from .recordings import Recordings
from .samples import noise_sd

# The sensor's noise alone refuses a factor at least this far from 1: one
# sensor's noise differs by a few times between runs (filters, rates,
# vibration), never by a hundred; a daN slip it only warns of.
NOISE_ALONE_FACTOR = 100.0


def force_slip(ratio: float) -> tuple[float, str] | None:
    """(N per unit, unit) of plausibility.FORCE_SLIPS within a factor 2 of
    `ratio` (the force a reference gives over what a log gives)."""
    return plausibility.slip(ratio, plausibility.FORCE_SLIPS)


def rest_noise(run) -> float:
    """The force sensor's noise [N] in a run's log at rest: over the samples
    below the midpoint of its 5th and 95th percentiles (the carriage
    moving lifts the force above it)."""
    F = run.forces[:, 1]
    p5, p95 = np.percentile(F, [5, 95])
    return noise_sd(F, F < 0.5 * (p5 + p95))


def plausible_mu(forces, f_int: float, normal_force: float) -> bool:
    """Every force [N] above f_int [N], with (F - F_int)/(m g) in the usual
    range of a friction coefficient (plausibility: mu1)."""
    lo, hi = plausibility.QUANTITIES["mu1"].usual
    mu = (np.asarray(forces) - f_int) / normal_force
    return bool(np.all(forces > f_int) and np.all((mu >= lo) & (mu <= hi)))


def times(ratio: float) -> str:
    """'N times below' (ratio > 1) or 'N times above' (ratio < 1)."""
    k = ratio if ratio >= 1 else 1 / ratio
    shown = f"{k:.0f}" if k >= 100 else f"{k:.3g}"
    return shown + (" times below" if ratio >= 1 else " times above")


def evidence(rec: Recordings, runs: list, f_int: float) -> list:
    """[(ratio, words, counts alone)]: the slide runs' scale over the
    carriage runs' (what their forces are off by) from the ramp runs' start
    step (F_int again) and from the sensor's noise at rest, each where it
    can be told; words say it of the carriage runs."""
    out = []
    steps = [r.start_step_N for r in runs if r.kind == "ramp" and math.isfinite(r.start_step_N)]
    if steps and f_int > 0:
        step = float(np.median(steps))
        out.append((step / f_int, f"F_int {times(step / f_int)} the step the ramp runs make as the "
                                  f"carriage starts ({step:.3g} N)", True))
    raw = {r.name: r for r in rec.runs}
    noise = {k: [rest_noise(raw[r.run]) for r in runs if r.kind == k] for k in ("slide", "carriage")}
    slide, carriage = (float(np.median(noise[k])) if noise[k] else math.nan for k in ("slide", "carriage"))
    if slide > 0 and carriage > 0:
        ratio = slide / carriage
        out.append((ratio, f"the sensor's noise at rest {times(ratio)} the slide runs' ({carriage:.2g} N "
                           f"against {slide:.2g} N)", max(ratio, 1 / ratio) >= NOISE_ALONE_FACTOR))
    return out


def agreed_slip(found: list) -> tuple | None:
    """(N per unit, unit, the evidence naming it) where the evidence names
    one unit and none of it says the runs share one (a ratio within 2 of
    1); None otherwise."""
    slips = {force_slip(ratio) for ratio, _, _ in found} - {None}
    if len(slips) != 1 or any(0.5 < ratio < 2 for ratio, _, _ in found):
        return None
    (factor, unit), = slips
    return factor, unit, [f for f in found if force_slip(f[0])]


def force_unit_finding(rec: Recordings, runs: list, warnings: list) -> str | None:
    """One line if the carriage runs and the slide runs cannot share a unit:
    what the carriage runs' mean plateau F_int is off by (evidence), and the
    runs whose force_N the slides' mu say is in which unit; without such
    evidence, F_int above every group of slide forces.  A slip named by
    evidence too weak to refuse on goes to `warnings`."""
    carriage = [r for r in runs if r.kind == "carriage" and math.isfinite(r.force_N)]
    slides = {}
    for r in runs:
        if r.kind == "slide" and r.used:
            slides.setdefault((r.mat_angle_deg, r.velocity_m_s), []).append(r)
    if not carriage or not slides:
        return None
    f_int = float(np.mean([r.force_N for r in carriage]))
    forces = np.array([np.median([r.force_N for r in v]) for v in slides.values()])
    N = rec.rig.normal_force
    paths = {r.name: r.forces_path for r in rec.runs}
    where = f"the {len(carriage)} carriage runs (F_int = {f_int:.4g} N)"
    slip = agreed_slip(evidence(rec, runs, f_int))
    if slip:
        factor, unit, found = slip
        why = f"{where}: " + ", ".join(words for _, words, _ in found)
        first = paths[carriage[0].run]
        if not any(alone for _, _, alone in found):
            warnings.append(f"{first}: force_N: {why}: force_N in {unit}? (the column is in N)")
        elif plausible_mu(forces, factor * f_int, N):
            return (f"{first}: force_N: {why}: the carriage runs' force_N in {unit}? (the column is in N; "
                    f"{factor * f_int:.4g} N gives the slides mu = {(forces.min() - factor * f_int) / N:.3g} "
                    f".. {(forces.max() - factor * f_int) / N:.3g})")
        elif plausible_mu(forces / factor, f_int, N) and force_slip(1 / factor):
            lo, hi = forces.min() / factor, forces.max() / factor
            return (f"{paths[next(iter(slides.values()))[0].run]}: force_N: {why}: the slide and ramp runs' "
                    f"force_N in {force_slip(1 / factor)[1]}? (the column is in N; {lo:.4g} .. {hi:.4g} N "
                    f"give the slides mu = {(lo - f_int) / N:.3g} .. {(hi - f_int) / N:.3g})")
    if np.all(forces <= f_int):
        return (f"{paths[carriage[0].run]}: force_N: {where}: F_int is above every slide run's force "
                f"({forces.min():.4g} .. {forces.max():.4g} N, which reads F_int plus the push): the "
                "carriage runs or the slide runs in another unit than N?")
    return None
