"""The lateral tracker column (x2_m) against the longitudinal one (x1_m)
over a recording set's slide runs: a steady path of the law stays well
within +-90 deg of the pull, so slide runs whose angle sits near +-90 deg
(x2's travel many times x1's) were tracked with x2 in another unit; the
tracker's noise on each column names which.  Units: m, deg."""
from __future__ import annotations

import math

import numpy as np

from .. import plausibility
from .recordings import Recordings
from .samples import line_fit

# A slide group's median |phi| beyond this cannot be a steady path: the law
# gives l2/l1 > 11 for it (tan phi_ext = (l2^2 - l1^2) / (2 l1 l2)), where the
# paper's mats give |phi| < 20 deg; x2 in cm puts a 5 deg path at 83 deg.
STEEPEST_PHI_DEG = 80.0

# A unit is named if x2 divided by its factor puts every group within this:
# a plausible mat's paths (the law with eps1/eps2 and mu2/mu1 within 4).
PLAUSIBLE_PHI_DEG = 60.0


def slide_groups(runs: list) -> dict:
    """{(mat angle [deg], velocity [m/s]): the slide runs (RunReduction) with
    a fitted path}, in runs.csv's order."""
    groups = {}
    for r in runs:
        if r.kind == "slide" and math.isfinite(r.line[1]):
            groups.setdefault((r.mat_angle_deg, r.velocity_m_s), []).append(r)
    return groups


def noise_ratio(rec: Recordings, slides: list) -> float:
    """The median over slide runs of x2's scatter about the run's fitted
    path over its steady window against x1's about a line in time: the same
    tracker's noise on both columns, about 1 in one unit, 1000 with x2 in mm;
    nan where it cannot be told."""
    raw = {r.name: r for r in rec.runs}
    ratios = []
    for red in slides:
        tr = raw[red.run].trajectory
        t, x1, x2 = tr[:, 0], tr[:, 1], tr[:, 2]
        win = (t >= red.window_s[0]) & (t <= red.window_s[1]) & np.isfinite(x1) & np.isfinite(x2)
        if win.sum() < 10:
            continue
        a, b = red.line
        a1, b1, _ = line_fit(t[win], x1[win])
        s1 = float(np.std(x1[win] - a1 - b1 * t[win]))
        s2 = float(np.std(x2[win] - a - b * x1[win]))
        if s1 > 0:
            ratios.append(s2 / s1)
    return float(np.median(ratios)) if ratios else math.nan


def lateral_finding(rec: Recordings, runs: list) -> str | None:
    """One line if the steepest group of slide runs (by the median |tan phi|
    of a mat angle and velocity) goes at more than STEEPEST_PHI_DEG to x1:
    its first run's trajectory file, its angle, and x2_m's likely unit (a
    length unit whose factor brings every group within PLAUSIBLE_PHI_DEG;
    of two, the one the columns' noise ratio names).  None otherwise."""
    groups = slide_groups(runs)
    if not groups:
        return None
    tans = {k: float(np.median([r.line[1] for r in rs])) for k, rs in groups.items()}
    key = max(tans, key=lambda k: abs(tans[k]))
    steep = abs(tans[key])
    if math.degrees(math.atan(steep)) <= STEEPEST_PHI_DEG:
        return None
    fits = [(f, u) for f, u in plausibility.LENGTH_SLIPS
            if math.degrees(math.atan(steep / f)) <= PLAUSIBLE_PHI_DEG]
    named = plausibility.scale_slip(noise_ratio(rec, [r for rs in groups.values() for r in rs]))
    fits = [fu for fu in fits if fu[1] == named] or fits
    first = next(r for r in rec.runs if r.name == groups[key][0].run)
    angle, v = key
    text = (f"{first.trajectory_path}: x2_m: the slide runs at {angle:g} deg, {v:g} m/s go at "
            f"{math.degrees(math.atan(tans[key])):.2f} deg to x1 (tan phi = {tans[key]:.4g}, the median of "
            f"{len(groups[key])}): no steady path of the law is that steep (|phi| < "
            f"{PLAUSIBLE_PHI_DEG:g} deg for a plausible mat)")
    if not fits:
        return text + ": x2_m in another unit than x1_m? both columns are in m"
    shown = math.degrees(math.atan(tans[key] / fits[0][0]))
    return (text + f": x2_m in {' or '.join(u for _, u in fits)}? (x2 / {fits[0][0]:g} would give "
            f"{shown:.2f} deg) the column is in m")
