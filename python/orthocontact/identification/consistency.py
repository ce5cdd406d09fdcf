"""A recording set checked as a whole, each stream against the others,
before the fit: a column in another unit, on another clock or with the
other sign is refused in one line (InputError) naming its file, its column
and the likely cause, instead of reaching the fit (docs/guides/
recordings-to-fmu.md, "What is cross-checked").  reduce_recordings calls
check_streams before it reduces the runs and check_reduced after.

check_streams, on the raw samples:
* clocks: a trajectory's t_s against its run's velocity (x1's speed by it),
  a force log's t_s against its run's trajectory, a carriage run's against
  the time its carriage takes for the slides' travel: t_s in ms?
* signs: a force log that reads the pull as negative: force_N sign flipped?
check_reduced, on the reduced runs:
* the lateral tracker against the longitudinal one (lateral.py): x2_m in
  mm or cm?
* the carriage runs against the ramp runs' start and the sensor's noise in
  the slide runs, judged by the slides' mu (force_units.py): force_N in kN,
  daN, mN, gram-force?
* the slide angles' signs against those the law can give (angle_signs.py):
  x2_m sign flipped, or phi_convention?
Units: s, m, N, deg."""
from __future__ import annotations

import math

import numpy as np

from .. import plausibility
from ..errors import InputError
from .angle_signs import angle_sign_finding
from .force_units import force_unit_finding
from .lateral import lateral_finding
from .recordings import Recordings, Run
from .samples import noise_sd, peak_speed

# A force log whose median while the carriage moves lies this many times the
# sensor's noise below its level at rest reads the pull as negative (an
# honest pull lies hundreds of noise widths above it).
FLIP_NOISE = 10.0

# The stretch of a pull's travel taken as "moving" when a force log's sign
# is judged: past the start's noise, before the carriage slows down.
MOVING = (0.1, 0.9)


def one_line(found: list[str]) -> str:
    """The first finding, and how many more there are, as one line."""
    more = f" ({len(found) - 1} more files alike)" if len(found) > 1 else ""
    return found[0] + more


def _track(run: Run):
    """(t, x1) of the tracked samples."""
    tr = run.trajectory
    ok = np.isfinite(tr[:, 1])
    return tr[ok, 0], tr[ok, 1]


def trajectory_clocks(rec: Recordings, spans: dict) -> list[str]:
    """Findings for trajectories whose t_s makes x1 move about 1000 times
    slower than the run's velocity_m_s (t_s in ms); fills `spans` {run: the
    trajectory's time span [s], in s where a slip was found}."""
    found = []
    for run in rec.runs:
        if run.trajectory is None:
            continue
        t, x1 = _track(run)
        sp = peak_speed(t, x1)
        slip = plausibility.slip(run.velocity_m_s / sp, plausibility.TIME_SLIPS) if sp > 0 else None
        spans[run.name] = (t[-1] - t[0]) / (slip[0] if slip else 1.0)
        if slip:
            found.append(f"{run.trajectory_path}: run {run.name}: t_s: by it x1_m moves at {sp:.3g} m/s, "
                         f"{run.velocity_m_s / sp:.0f} times slower than velocity_m_s = "
                         f"{run.velocity_m_s:g} (runs.csv line {run.line}): t_s in {slip[1]}? the column "
                         "is in s")
    return found


def force_clocks(rec: Recordings, spans: dict) -> list[str]:
    """Findings for force logs whose time span is about 1000 times that of
    their run's trajectory (`spans`), or, for a carriage run, of the time
    its carriage takes for the slide runs' median travel: t_s in ms."""
    travels = [float(np.ptp(_track(r)[1])) for r in rec.runs if r.kind == "slide"]
    travel = float(np.median(travels)) if travels else math.nan
    found = []
    for run in rec.runs:
        tf = run.forces[:, 0]
        span = tf[-1] - tf[0]
        if run.name in spans:
            ref = spans[run.name]
            what = f"its tracker's {ref:.3g} s ({run.trajectory_path.name})"
        elif math.isfinite(travel) and travel > 0:
            ref = travel / run.velocity_m_s
            what = (f"the {ref:.3g} s its carriage takes at {run.velocity_m_s:g} m/s for the slide runs' "
                    f"{travel:.3g} m of travel")
        else:
            continue
        slip = plausibility.slip(span / ref, plausibility.TIME_SLIPS) if ref > 0 else None
        if slip:
            found.append(f"{run.forces_path}: run {run.name}: t_s spans {span:.4g} s, {span / ref:.0f} times "
                         f"{what}: t_s in {slip[1]}? the column is in s")
    return found


def pull_force(run: Run) -> tuple[float, float]:
    """(the force log's level while the carriage moves less its level at
    rest [N], the sensor's noise [N]).  With a trajectory: the median force
    over the MOVING stretch of the travel less the median before the
    tracker leaves its start (0 with fewer than 5 samples there); nan with
    fewer than 5 samples moving.  A carriage run (no trajectory): its
    larger excursion from 0, the 2nd or the 98th percentile."""
    tf, F = run.forces[:, 0], run.forces[:, 1]
    noise = noise_sd(F)
    if run.trajectory is None:
        lo, hi = np.percentile(F, [2, 98])
        return float(hi if hi >= -lo else lo), noise
    t, x1 = _track(run)
    x0 = float(np.median(x1[:5]))
    reach = float(np.max(x1)) - x0
    if not reach > 0:
        return math.nan, noise
    at = [float(t[np.argmax(x1 > x0 + f * reach)]) for f in (0.05,) + MOVING]
    moving = (tf >= at[1]) & (tf <= at[2])
    if moving.sum() < 5:
        return math.nan, noise
    rest = F[tf < at[0]]
    level = float(np.median(rest)) if len(rest) >= 5 else 0.0
    return float(np.median(F[moving])) - level, noise


def force_signs(rec: Recordings) -> list[str]:
    """Findings for force logs that read the pull as negative."""
    found = []
    for run in rec.runs:
        pull, noise = pull_force(run)
        floor = FLIP_NOISE * noise if math.isfinite(noise) and noise > 0 else 0.0
        if pull < -floor:
            found.append(f"{run.forces_path}: run {run.name}: force_N is {pull:.4g} N against its level at "
                         f"rest while the carriage moves ({run.kind} run): force_N sign flipped? (the sensor "
                         "reads the pull as positive)")
    return found


def check_streams(rec: Recordings) -> None:
    """The raw samples' clocks and signs against each other (the module's
    docstring); raises InputError (one line) on the first kind found."""
    spans = {}
    for found in (trajectory_clocks(rec, spans), force_clocks(rec, spans), force_signs(rec)):
        if found:
            raise InputError(one_line(found))


def check_reduced(rec: Recordings, runs: list, warnings: list) -> None:
    """The reduced runs (RunReduction, runs.csv's order) against each other
    and the law (the module's docstring); raises InputError (one line) on
    the first finding; appends warnings of unit slips that are likely but
    not certain."""
    for finding in (lateral_finding(rec, runs), force_unit_finding(rec, runs, warnings),
                    angle_sign_finding(rec, runs)):
        if finding:
            raise InputError(finding)
