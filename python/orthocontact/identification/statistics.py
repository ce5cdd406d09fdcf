"""The statistics of identification: Student-t quantiles for (not
necessarily whole) degrees of freedom, intervals of positive quantities,
residual summaries, JSON forms."""
from __future__ import annotations

import math

import numpy as np


def t975(dof: float) -> float:
    """97.5% quantile of Student's t for dof >= 1 degrees of freedom (not
    necessarily whole), 1.96 for infinite dof.  Below 100 dof, with
    t = sqrt(dof) tan(theta), P(|T| <= t) = 1 - I_{cos^2 theta}(dof/2, 1/2)
    (the regularised incomplete beta, incomplete_beta), and a bisection in
    theta gives it to 1e-12 (exact also at the few dof of a small design,
    where the series in 1/dof is not: 11.3 for 12.71 at one dof)."""
    if not dof >= 1:
        raise ValueError(f"t975: expected dof >= 1, got {dof}")
    z = 1.959963984540054
    if not math.isfinite(dof):
        return z
    if dof >= 100:
        # the integrand narrows to a width of 1/sqrt(dof), under the grid's step
        # beyond 1e6: the Cornish-Fisher series instead, good to 1e-9 here
        g = ((z**3 + z) / 4, (5 * z**5 + 16 * z**3 + 3 * z) / 96,
             (3 * z**7 + 19 * z**5 + 17 * z**3 - 15 * z) / 384,
             (79 * z**9 + 776 * z**7 + 1482 * z**5 - 1920 * z**3 - 945 * z) / 92160)
        return z + sum(gk / dof ** (k + 1) for k, gk in enumerate(g))

    def prob(theta):
        return 1.0 - incomplete_beta(dof / 2, 0.5, math.cos(theta) ** 2)
    lo, hi = 0.0, math.pi / 2
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if prob(mid) < 0.95 else (lo, mid)
    return math.sqrt(dof) * math.tan(0.5 * (lo + hi))


# exp(700) is near the largest double: beyond it an upper end is no bound at all
_MAX_LOG_SPAN = 700.0


def positive_ci(value: float, stderr: float, t: float) -> list:
    """[low, high] of a quantity positive by nature (a friction coefficient,
    a stiffness or its ratio, a viscosity, a force), in its own unit: the
    interval of log(value), whose standard error is stderr / value by the
    delta method, taken back, value * exp(-+ t stderr / value) (log-normal).
    It stays > 0 however large the standard error, holds the value, and for
    a small relative error equals value -+ t stderr to first order.  t: the
    quantile (t975)."""
    if not (value > 0 and math.isfinite(value)) or not (stderr >= 0 and math.isfinite(t) and t >= 0):
        raise ValueError(f"positive_ci: expected value > 0, stderr >= 0 and t >= 0, got "
                         f"{value!r}, {stderr!r}, {t!r}")
    span = min(t * stderr / value, _MAX_LOG_SPAN)
    return [value * math.exp(-span), value * math.exp(span)]


def satterthwaite(grad: np.ndarray, parts: list) -> tuple[float, float]:
    """(variance, Welch-Satterthwaite degrees of freedom) of a parameter
    g' theta whose covariance is a sum of parts (C, dof): each part the
    covariance one variance component contributes, dof the degrees of
    freedom of that component's estimate (inf: known, e.g. a within-run
    error from a line fit of hundreds of samples)."""
    shares = [(max(float(grad @ C @ grad), 0.0), nu) for C, nu in parts]
    var = sum(v for v, _ in shares)
    # a share under 1e-9 of the variance (a tau^2 of 0 up to rounding) cannot move the dof
    den = sum(v * v / nu for v, nu in shares if math.isfinite(nu) and v > 1e-9 * var)
    return var, (var * var / den if den > 0 else math.inf)


def res_stats(res: np.ndarray) -> dict:
    return {"rms": float(np.sqrt(np.mean(res**2))), "max_abs": float(np.max(np.abs(res))),
            "mean": float(np.mean(res)), "n": int(len(res))}


def json_dof(nu):
    return None if nu is None else ("inf" if not math.isfinite(nu) else round(float(nu), 2))


def incomplete_beta(a: float, b: float, x: float) -> float:
    """The regularised incomplete beta function I_x(a, b) for a, b > 0 and
    0 <= x <= 1, by its continued fraction (modified Lentz), on the side
    where it converges fast (x < (a+1)/(a+b+2), else 1 - I_{1-x}(b, a));
    to about 1e-14."""
    if not (a > 0 and b > 0 and 0.0 <= x <= 1.0):
        raise ValueError(f"incomplete_beta: expected a, b > 0 and x in [0, 1], got {a}, {b}, {x}")
    if x in (0.0, 1.0):
        return x
    if x > (a + 1) / (a + b + 2):
        return 1.0 - incomplete_beta(b, a, 1.0 - x)
    front = math.exp(math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x)
                     + b * math.log1p(-x)) / a
    tiny = 1e-300
    f, c, d = 1.0, 1.0, 0.0
    for i in range(400):
        m = i // 2
        if i == 0:
            num = 1.0
        elif i % 2 == 0:
            num = m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m))
        else:
            num = -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))
        d = 1.0 + num * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + num / c
        c = c if abs(c) > tiny else tiny
        f *= c * d
        if abs(1.0 - c * d) < 1e-15:
            break
    return front * (f - 1.0)


def f_survival(F: float, dof1: float, dof2: float) -> float:
    """P(X > F) for X of Fisher's F distribution with (dof1, dof2) degrees
    of freedom: I_{dof2/(dof2 + dof1 F)}(dof2/2, dof1/2)."""
    if F <= 0:
        return 1.0
    return incomplete_beta(dof2 / 2, dof1 / 2, dof2 / (dof2 + dof1 * F))
