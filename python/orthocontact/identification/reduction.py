"""From a run's recordings to the values the fit takes, each with its
within-run standard error:

* slide: the steady window (the cruise at constant carriage speed, less the
  leading stretch whose path slope has not settled), phi from the line fit
  x2 = c + x1 tan(phi) over it, the mean driving force over the same time span;
* carriage: F_int, the mean force over the plateau of the carriage's motion;
* ramp: the stick stiffness dF/dx1, the force's samples placed on the
  tracker's travel by a hinge fit x1(t) = x0 + v max(0, t - t0) (the two
  sensors' own times on one clock: this is the alignment).

Errors (InputError) and warnings name the run and its file.  Outlying runs
(far from the median of their angle and velocity) are flagged, and kept.
reduce_recordings checks the set's streams against each other before and
after (consistency.py: clocks, signs, units).
Units: s, m, N, deg."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import plausibility
from ..errors import InputError
from .consistency import check_reduced, check_streams
from .recordings import Recordings, Run
from .samples import line_fit, longest_true, mean_se, speed

CRUISE_TOL = 0.03        # |speed / cruise speed - 1| inside the cruise
SEGMENTS = 8             # the cruise's pieces for finding where the path settled
SETTLE_Z = 4.0           # a piece's slope off the rest's by more than this many standard errors
HALVES_Z = 5.0           # never settled: the window's halves disagree by this many standard errors
HALVES_DEG = 0.05        #   and by this many degrees
OUTLIER_Z = 5.0          # robust z of an outlying run within its group


@dataclass
class RunReduction:
    run: str
    kind: str
    mat_angle_deg: float
    velocity_m_s: float
    window_s: tuple = (math.nan, math.nan)
    window_x1_m: tuple = (math.nan, math.nan)
    speed_m_s: float = math.nan           # tracked cruise speed
    phi_deg: float = math.nan             # counterclockwise, as tracked
    phi_se_deg: float = math.nan
    phi_halves_deg: tuple = (math.nan, math.nan)
    line: tuple = (math.nan, math.nan)    # intercept [m], slope of the fitted line
    force_N: float = math.nan
    force_se_N: float = math.nan
    stiffness_N_m: float = math.nan
    stiffness_se_N_m: float = math.nan
    samples: int = 0
    # ramp: the force's step as the carriage starts (the stick line at zero
    # travel less the force at rest): the carriage's F_int, measured apart
    # from the carriage runs (consistency.py compares them)
    start_step_N: float = math.nan
    flags: list = field(default_factory=list)   # "outlier", "not_steady", "dropout", ...

    @property
    def used(self) -> bool:
        return "not_steady" not in self.flags


def _where(run: Run, path=None) -> str:
    return f"{path or run.trajectory_path}: run {run.name}"


def _check_units(run: Run, speed_ref: float):
    ratio = speed_ref / run.velocity_m_s
    unit = plausibility.scale_slip(ratio)
    if unit:
        raise InputError(f"{_where(run)}: x1_m moves at {speed_ref:.4g} 'm/s', {ratio:.0f} times "
                         f"velocity_m_s = {run.velocity_m_s:g}: positions in {unit}? the columns are in m")
    if not 0.5 < ratio < 2:
        raise InputError(f"{_where(run)}: x1_m moves at {speed_ref:.4g} m/s, expected about "
                         f"velocity_m_s = {run.velocity_m_s:g} of runs.csv line {run.line}")


def _tracked(run: Run, warnings: list):
    """The valid samples (t, x1, x2) and a note of drop-outs."""
    tr = run.trajectory
    ok = np.isfinite(tr[:, 1]) & np.isfinite(tr[:, 2])
    t, x1, x2 = tr[ok, 0], tr[ok, 1], tr[ok, 2]
    if len(t) < 10:
        raise InputError(f"{_where(run)}: expected at least 10 tracked samples, got {len(t)}")
    dt = np.diff(t)
    step = float(np.median(dt))
    gaps = np.flatnonzero(dt > 3 * step)
    missing = int((~ok).sum())
    return t, x1, x2, step, gaps, missing


def reduce_slide(run: Run, warnings: list) -> RunReduction:
    out = RunReduction(run.name, run.kind, run.mat_angle_deg, run.velocity_m_s)
    t, x1, x2, step, gaps, missing = _tracked(run, warnings)
    v = speed(t, x1)
    fin = np.isfinite(v)
    speed_ref = float(np.percentile(np.abs(v[fin]), 90))
    _check_units(run, speed_ref)
    vc = float(np.median(v[fin & (v > 0.5 * speed_ref)]))
    if abs(vc / run.velocity_m_s - 1) > 0.05:
        warnings.append(f"{_where(run)}: the tracked cruise speed {vc:.4g} m/s is "
                        f"{100 * (vc / run.velocity_m_s - 1):+.0f} % off velocity_m_s = {run.velocity_m_s:g} "
                        f"(runs.csv line {run.line}), which the fit uses")
    lo, hi = longest_true(fin & (np.abs(v / vc - 1) < CRUISE_TOL))
    if hi - lo < 4 * SEGMENTS:
        raise InputError(f"{_where(run)}: never moves at a steady speed: {hi - lo} samples within "
                         f"{100 * CRUISE_TOL:g}% of {vc:.4g} m/s, expected at least {4 * SEGMENTS}")
    # Drop leading pieces of the cruise whose slope is off the rest's: the
    # block settling onto its steady path (the law's elastic length, the
    # strip's viscous transient).  At most half the cruise.
    pieces = np.array_split(np.arange(lo, hi), SEGMENTS)
    start = 0
    while start < SEGMENTS // 2:
        _, b_k, se_k = line_fit(x1[pieces[start]], x2[pieces[start]])
        rest = np.concatenate(pieces[start + 1:])
        _, b_r, se_r = line_fit(x1[rest], x2[rest])
        if abs(b_k - b_r) <= SETTLE_Z * math.hypot(se_k, se_r):
            break
        start += 1
    w = np.concatenate(pieces[start:])
    a, b, se = line_fit(x1[w], x2[w])
    out.window_s, out.window_x1_m = (float(t[w[0]]), float(t[w[-1]])), (float(x1[w[0]]), float(x1[w[-1]]))
    out.speed_m_s, out.line, out.samples = vc, (a, b), len(w)
    out.phi_deg = math.degrees(math.atan(b))
    out.phi_se_deg = math.degrees(se / (1 + b * b))
    h1, h2 = np.array_split(w, 2)
    (_, b1, s1), (_, b2, s2) = line_fit(x1[h1], x2[h1]), line_fit(x1[h2], x2[h2])
    p1, p2 = math.degrees(math.atan(b1)), math.degrees(math.atan(b2))
    out.phi_halves_deg = (p1, p2)
    if abs(b1 - b2) > HALVES_Z * math.hypot(s1, s2) and abs(p1 - p2) > HALVES_DEG:
        out.flags.append("not_steady")
        warnings.append(f"{_where(run)}: never settles: phi over the steady window's halves is "
                        f"{p1:.3f} / {p2:.3f} deg ({out.window_x1_m[0]:.3f}-{out.window_x1_m[1]:.3f} m); "
                        "left out of the fit")
    t0, t1 = out.window_s
    lost = [(t[g], t[g + 1]) for g in gaps if t0 <= t[g] < t1]
    if missing or lost:
        out.flags.append("dropout")
        span = ", ".join(f"{a_:.3f}-{b_:.3f} s" for a_, b_ in lost[:3]) or "outside the steady window"
        warnings.append(f"{_where(run)}: tracker drop-out: {missing} empty samples, gaps {span}; "
                        "the fit uses the samples that are there")
    tf, F = run.forces[:, 0], run.forces[:, 1]
    if tf[0] > t0 or tf[-1] < t1:
        raise InputError(f"{_where(run, run.forces_path)}: the force log ({tf[0]:.3f}-{tf[-1]:.3f} s) is "
                         f"shorter than the travel: the steady window is {t0:.3f}-{t1:.3f} s")
    out.force_N, out.force_se_N = mean_se(F[(tf >= t0) & (tf <= t1)])
    return out


def reduce_carriage(run: Run, warnings: list) -> RunReduction:
    out = RunReduction(run.name, run.kind, run.mat_angle_deg, run.velocity_m_s)
    t, F = run.forces[:, 0], run.forces[:, 1]
    noise = float(np.std(np.diff(F)) / math.sqrt(2))
    p5, p95 = np.percentile(F, [5, 95])
    if p95 - p5 < 10 * noise:
        raise InputError(f"{_where(run, run.forces_path)}: expected the carriage's motion (a plateau "
                         f"of F_int above the force at rest), the force stays within {p95 - p5:.3g} N")
    lo, hi = longest_true(F > 0.5 * (p5 + p95))
    trim = (hi - lo) // 6
    sel = slice(lo + trim, hi - trim)
    out.window_s = (float(t[lo + trim]), float(t[hi - trim - 1]))
    out.force_N, out.force_se_N = mean_se(F[sel])
    out.samples = hi - lo - 2 * trim
    return out


def _ramp_start(run: Run, t, x1) -> tuple:
    """(t0 [s], v [m/s], v's standard error, the fitted samples' last time
    [s]) of a ramp run's tracked start of motion: a hinge fit
    x1(t) = x0 + v max(0, t - t0) over the pull's first 70 %, then the speed
    from the samples after its first fifth."""
    x0 = float(np.median(x1[:5]))
    # the pull's first 70 %, cut by time (a cut on the noisy x1 itself
    # would drop the samples with positive noise near it and bias the speed)
    smooth = np.array([np.median(x1[max(i - 4, 0):i + 5]) for i in range(len(x1))])
    cut = int(np.argmax(smooth > x0 + 0.7 * (smooth.max() - x0)))
    cut = max(cut - 10, 10)     # the samples next to the cut share its noise
    te, xe = t[:cut], x1[:cut]
    best = None
    for t0 in te[2:-5]:
        h = np.maximum(te - t0, 0.0)
        A = np.column_stack([np.ones_like(h), h])
        coef, *_ = np.linalg.lstsq(A, xe, rcond=None)
        sse = float(((A @ coef - xe) ** 2).sum())
        if best is None or sse < best[0]:
            best = (sse, t0, coef)
    if best is None or best[2][1] <= 0:
        raise InputError(f"{_where(run)}: expected the carriage to start moving from rest")
    _, t0, (x0, v) = best
    # The hinge's corner is the carriage's acceleration, which a constant
    # speed from t0 does not model and which biases its slope: the speed
    # from the samples after the first fifth of the pull, t0 where that line
    # leaves the rest position.
    after = te > t0 + 0.2 * (te[-1] - t0)
    rest = te < t0
    if after.sum() >= 5 and rest.sum() >= 3:
        a, v, v_se = line_fit(te[after], xe[after])
        x0 = float(np.median(xe[rest]))
        t0 = (x0 - a) / v
    else:
        moved = te > t0
        v_se = line_fit(te[moved], xe[moved])[2] if moved.sum() >= 3 else math.inf
    return t0, v, v_se, float(te[-1])


def reduce_ramp(run: Run, warnings: list) -> RunReduction:
    out = RunReduction(run.name, run.kind, run.mat_angle_deg, run.velocity_m_s)
    t, x1, _, step, _, _ = _tracked(run, warnings)
    t0, v, v_se, t_end = _ramp_start(run, t, x1)
    _check_units(run, v)
    out.speed_m_s = float(v)
    tf, F = run.forces[:, 0], run.forces[:, 1]
    xf = v * np.maximum(tf - t0, 0.0)      # the force's samples on the tracked travel
    moving = (tf > t0) & (tf <= t_end)
    if moving.sum() < 10:
        raise InputError(f"{_where(run, run.forces_path)}: the force log ({tf[0]:.3f}-{tf[-1]:.3f} s) "
                         f"does not cover the pull (from {t0:.3f} s)")
    xm, Fm = xf[moving], F[moving]
    top = float(np.median(Fm[xm > 0.7 * xm.max()]))
    base = float(np.median(Fm[: max(5, len(Fm) // 50)]))
    stick = (Fm > base + 0.1 * (top - base)) & (Fm < base + 0.85 * (top - base))
    # the stick branch is where the force has not yet reached sliding: the
    # samples before the force stays at 85 % of the rise (five samples on;
    # a single spike, the block's inertia as the carriage starts, is not it)
    high = Fm >= base + 0.85 * (top - base)
    held = np.convolve(high, np.ones(5), "valid") == 5
    stick[int(np.argmax(held)) if held.any() else len(Fm):] = False
    if stick.sum() < 5:
        raise InputError(f"{_where(run, run.forces_path)}: expected at least 5 force samples on the "
                         f"stick branch (10-85% of the rise to sliding), got {int(stick.sum())}: "
                         "pull slower or sample faster")
    # Chosen by their own noisy force, the samples at the window's ends are
    # those whose noise points inwards, which flattens the line (-0.13 % on
    # eps2 at 0.05 N of noise): the window is the travel between the first
    # line's 10 % and 85 % crossings, every sample in it taken.
    c0, k0, _ = line_fit(xm[stick], Fm[stick])
    x_lo, x_hi = (base + 0.1 * (top - base) - c0) / k0, (base + 0.85 * (top - base) - c0) / k0
    last = int(np.flatnonzero(stick)[-1])
    by_travel = (xm >= x_lo) & (xm <= x_hi) & (np.arange(len(xm)) <= last + 5)
    if by_travel.sum() >= 5:
        stick = by_travel
    c, k, se_fit = line_fit(xm[stick], Fm[stick])
    # The travel is v (t - t0) with the tracked speed v, so the stiffness
    # carries v's relative error: on a tracker's noise it is the larger part
    # of the run's error, not run-to-run scatter.
    se = math.hypot(se_fit, abs(k) * v_se / v)
    out.stiffness_N_m, out.stiffness_se_N_m, out.samples = k, se, int(stick.sum())
    out.start_step_N = _start_step(tf, F, t0, c, step)
    out.window_s = (float(tf[moving][stick][0]), float(tf[moving][stick][-1]))
    out.window_x1_m = (float(xm[stick][0]), float(xm[stick][-1]))
    return out


def _start_step(tf, F, t0: float, intercept: float, step_s: float) -> float:
    """The stick line's force at zero travel [N] less the median force at
    rest (the samples more than two tracker steps `step_s` before the
    carriage starts at t0 [s]); nan with fewer than 5 samples at rest."""
    rest = F[tf < t0 - 2 * step_s]
    return intercept - float(np.median(rest)) if len(rest) >= 5 else math.nan


@dataclass
class Reduction:
    runs: list                     # RunReduction, in runs.csv order
    warnings: list

    def of_kind(self, kind, used=True):
        return [r for r in self.runs if r.kind == kind and (r.used or not used)]


def _flag_outliers(runs, value, se, what, unit, warnings):
    """Flags runs whose value lies more than OUTLIER_Z robust scales from
    the median of the other runs at its angle and velocity (leave-one-out:
    an outlier does not pull its own reference); the scale is pooled over
    the groups of its velocity (the larger of 1.4826 x their median and their inner rms),
    since a group of a few runs cannot give its own."""
    groups = {}
    for r in runs:
        groups.setdefault((r.mat_angle_deg, r.velocity_m_s), []).append(r)
    dev = {}
    for _k, rs in groups.items():
        if len(rs) >= 3:
            vals = np.array([value(r) for r in rs])
            for i, r in enumerate(rs):
                ref = float(np.median(np.delete(vals, i)))
                dev[r.run] = (vals[i] - ref, ref)
    for v in {k[1] for k in groups}:       # the scatter differs with velocity (drift / v)
        mine = [r for k, rs in groups.items() if k[1] == v for r in rs if r.run in dev]
        if len(mine) < 6:
            continue
        d = np.sort(np.abs([dev[r.run][0] for r in mine]))
        # the larger of two robust scales: the MAD alone is itself noisy from
        # a few small groups; the rms of the inner 90 % / 0.79 (normal)
        inner = d[: max(int(0.9 * len(d)), 1)]
        scale = max(1.4826 * float(np.median(d)), float(np.sqrt(np.mean(inner ** 2))) / 0.79)
        for r in mine:
            d, ref = dev[r.run]
            if abs(d) > OUTLIER_Z * max(scale, 3 * se(r)):
                r.flags.append("outlier")
                warnings.append(f"run {r.run}: outlying {what} {value(r):.4g} {unit} against the median "
                                f"{ref:.4g} {unit} of the other runs at {r.mat_angle_deg:g} deg, {v:g} m/s "
                                f"(robust scale {scale:.2g} {unit}); kept in the fit (remove its row from "
                                "runs.csv to leave it out)")


def reduce_run(run: Run, warnings: list) -> RunReduction:
    """One run reduced by its kind (reduce_slide, reduce_carriage,
    reduce_ramp), on its own: no check against the set's other runs."""
    return {"slide": reduce_slide, "carriage": reduce_carriage, "ramp": reduce_ramp}[run.kind](run, warnings)


def reduce_recordings(rec: Recordings) -> Reduction:
    """Every run reduced, the set's streams checked against each other
    before and after (consistency.py), outlying runs flagged; raises
    InputError (one line)."""
    warnings = []
    out = []
    check_streams(rec)
    for run in rec.runs:
        out.append(reduce_run(run, warnings))
    check_reduced(rec, out, warnings)
    slides = [r for r in out if r.kind == "slide" and r.used]
    _flag_outliers(slides, lambda r: r.phi_deg, lambda r: r.phi_se_deg, "phi", "deg", warnings)
    _flag_outliers(slides, lambda r: r.force_N, lambda r: r.force_se_N, "driving force", "N", warnings)
    if not slides:
        raise InputError(f"{rec.folder / 'runs.csv'}: expected at least one slide run that settles")
    return Reduction(out, warnings)
