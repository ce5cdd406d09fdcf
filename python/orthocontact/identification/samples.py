"""Numbers of one run's samples that both the reduction (reduction.py) and
the set's cross-checks (consistency.py) take: a line fit, a mean with its
standard error, the longest stretch of a mask, the speed of a tracked
coordinate, the noise of a sensor.  Units: those of the samples given (s, m,
N)."""
from __future__ import annotations

import math

import numpy as np

# noise_sd keeps the smallest 95 % of the differences: the mean of |X| below
# its 95th percentile (1.96) for X normal of unit standard deviation is
# sqrt(2/pi) (1 - exp(-1.96^2 / 2)) / 0.95
NOISE_KEPT = 0.95
TRIMMED_HALF_NORMAL_MEAN = math.sqrt(2 / math.pi) * (1 - math.exp(-1.959964 ** 2 / 2)) / 0.95


def line_fit(x, y):
    """(intercept, slope, standard error of the slope) of least squares."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    mx = x.mean()
    sxx = float(((x - mx) ** 2).sum())
    b = float(((x - mx) * (y - y.mean())).sum() / sxx)
    a = float(y.mean() - b * mx)
    r = y - a - b * x
    s2 = float(r @ r) / max(len(x) - 2, 1)
    return a, b, math.sqrt(s2 / sxx)


def mean_se(v):
    """(mean, standard error of the mean) of samples; inf for one sample."""
    v = np.asarray(v, float)
    return float(v.mean()), float(v.std(ddof=1) / math.sqrt(len(v))) if len(v) > 1 else math.inf


def longest_true(mask: np.ndarray) -> tuple[int, int]:
    """[start, end) of the longest stretch of True."""
    best, start = (0, 0), None
    for i, m in enumerate(np.r_[mask, False]):
        if m and start is None:
            start = i
        elif not m and start is not None:
            if i - start > best[1] - best[0]:
                best = (start, i)
            start = None
    return best


def speed(t, x):
    """dx/dt [unit of x / s] at each sample, nan at the ends: central
    differences over about a 40th of the run, so that a tracker's noise
    moves the speed by well under a cruise's tolerance."""
    k = max(2, len(t) // 40)
    v = np.full(len(t), np.nan)
    v[k:-k] = (x[2 * k:] - x[:-2 * k]) / (t[2 * k:] - t[:-2 * k])
    return v


def peak_speed(t, x) -> float:
    """The speed [unit of x / s] the samples reach and keep: the 90th
    percentile of |speed| (a cruise, not a spike); nan for too few samples."""
    v = speed(np.asarray(t, float), np.asarray(x, float))
    v = v[np.isfinite(v)]
    return float(np.percentile(np.abs(v), 90)) if len(v) else math.nan


def noise_sd(values, keep=None) -> float:
    """The sensor's white noise [unit of values]: from the differences of
    consecutive samples (both in `keep`, a mask, where given), the mean of
    their smallest NOISE_KEPT in size over what it is for normal noise of
    unit standard deviation, over sqrt(2).  The largest differences (a
    step, a start, a spike) are left out; a mean, unlike a median, does not
    jump where a log's resolution is about its noise.  nan for fewer than 10
    differences."""
    d = np.abs(np.diff(np.asarray(values, float)))
    if keep is not None:
        d = d[keep[:-1] & keep[1:]]
    if len(d) < 10:
        return math.nan
    d = np.sort(d)[: max(int(NOISE_KEPT * len(d)), 1)]
    return float(d.mean()) / TRIMMED_HALF_NORMAL_MEAN / math.sqrt(2)
