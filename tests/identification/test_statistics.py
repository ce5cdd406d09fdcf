"""The statistics of identification (orthocontact.identification.statistics)
against published table values and hand-computed sums."""
import math

import numpy as np
import pytest

from orthocontact.identification.statistics import json_dof, positive_ci, res_stats, satterthwaite, t975

# Student's t, 97.5 % quantile, to 6 decimals (the standard tables, e.g.
# Abramowitz & Stegun table 26.10).
T_TABLE = {3: 3.182446, 4: 2.776445, 5: 2.570582, 6: 2.446912, 8: 2.306004, 10: 2.228139,
           15: 2.131450, 20: 2.085963, 30: 2.042272, 60: 2.000298, 100: 1.983972}


@pytest.mark.parametrize("dof", [8, 10, 15, 20, 30, 60, 100])
def test_t975_is_the_tables_quantile(dof):
    assert t975(dof) == pytest.approx(T_TABLE[dof], abs=1e-4)


@pytest.mark.parametrize("dof", [3, 4, 5, 6])
def test_t975_is_the_tables_quantile_down_to_3_dof(dof):
    """The series in 1/dof used before was 3.8e-3 low at 3 dof (intervals
    too narrow); t975 is now exact there."""
    assert t975(dof) == pytest.approx(T_TABLE[dof], abs=1e-4)


def test_t975_between_whole_dof_limit_and_no_dof():
    assert T_TABLE[6] > t975(7.5) > T_TABLE[8]     # Welch-Satterthwaite gives fractions
    assert t975(1e12) == pytest.approx(1.959963984540054, abs=1e-9)
    for bad in (0, -2, 0.5, math.nan):   # no quantile below one degree of freedom: refused
        with pytest.raises(ValueError, match="dof >= 1"):
            t975(bad)


def test_residual_summary_by_hand():
    s = res_stats(np.array([3.0, -4.0, 0.0, 1.0]))
    assert s == {"rms": math.sqrt((9 + 16 + 0 + 1) / 4), "max_abs": 4.0, "mean": 0.0, "n": 4}


def test_dof_in_json():
    assert json_dof(None) is None and json_dof(float("inf")) == "inf"
    assert json_dof(12.3456) == 12.35 and json_dof(7) == 7.0


@pytest.mark.parametrize("dof, table", [(1, 12.7062), (2, 4.3027), (3, 3.1824), (5, 2.5706),
                                        (10, 2.2281), (30, 2.0423), (99, 1.9842), (120, 1.9799),
                                        (1e4, 1.9602), (1e9, 1.9600), (math.inf, 1.9600)])
def test_t_quantile_is_the_tables(dof, table):
    """Student's t, 97.5 % (the printed table to 4 decimals): also at one and
    two dof, where the series in 1/dof used before gave 11.30 and 4.27, and
    at the large dof of an interval whose variance is nearly all known."""
    assert abs(t975(dof) - table) < 6e-5


def test_satterthwaite_is_welchs_formula_and_known_parts_add_no_dof():
    """The difference of two means, s1^2/n1 + s2^2/n2 with n1-1, n2-1 dof:
    Welch's dof; a known part adds variance but no uncertainty of it."""
    s1, n1, s2, n2 = 2.0, 4, 0.5, 12
    a, b = s1**2 / n1, s2**2 / n2
    g = np.array([1.0, -1.0])
    parts = [(np.diag([a, 0.0]), n1 - 1), (np.diag([0.0, b]), n2 - 1)]
    var, nu = satterthwaite(g, parts)
    assert var == pytest.approx(a + b)
    assert nu == pytest.approx((a + b) ** 2 / (a**2 / (n1 - 1) + b**2 / (n2 - 1)))
    var_k, nu_k = satterthwaite(g, parts + [(np.diag([0.3, 0.0]), math.inf)])
    assert var_k == pytest.approx(a + b + 0.3)
    assert nu_k == pytest.approx((a + b + 0.3) ** 2 / (a**2 / (n1 - 1) + b**2 / (n2 - 1)))
    assert satterthwaite(g, [(np.eye(2), math.inf)])[1] == math.inf


@pytest.mark.parametrize("value, stderr", [(0.27, 0.6), (1e-3, 5.0), (9.76, 40.0), (1e-8, 1.0)])
def test_an_interval_of_a_positive_quantity_stays_positive_under_a_large_stderr(value, stderr):
    """c_strip's linear interval went to -0.97 .. 1.50 N s/m; on the log scale
    (value * exp(-+ t stderr / value)) the interval stays above 0, holds the
    value, and is symmetric in log(value)."""
    t = t975(4.0)
    lo, hi = positive_ci(value, stderr, t)
    assert 0 < lo < value < hi and math.isfinite(hi)
    assert value - t * stderr < 0          # the linear interval would have crossed 0
    if t * stderr / value < 700:
        assert math.log(hi / value) == pytest.approx(math.log(value / lo), rel=1e-12)
        assert math.log(hi / value) == pytest.approx(t * stderr / value, rel=1e-12)


@pytest.mark.parametrize("rel", [1e-2, 1e-3, 1e-4])
def test_for_a_small_relative_stderr_the_interval_is_the_linear_one_to_first_order(rel):
    value, t = 12468.4, t975(12.0)
    stderr = rel * value
    lo, hi = positive_ci(value, stderr, t)
    # exp(-+z) = 1 -+ z + z^2/2 ...: each end differs from value -+ t stderr by
    # value z^2 / 2 (z = t stderr / value) to leading order, second order in rel
    z = t * rel
    for got, linear in ((lo, value - t * stderr), (hi, value + t * stderr)):
        assert got - linear == pytest.approx(value * z * z / 2, rel=z)
        assert abs(got - linear) / (t * stderr) < z


def test_an_interval_of_no_positive_value_is_refused():
    for bad in ((0.0, 1.0, 2.0), (-1.0, 1.0, 2.0), (1.0, -1.0, 2.0), (math.nan, 1.0, 2.0),
                (1.0, math.nan, 2.0)):
        with pytest.raises(ValueError, match="positive_ci"):
            positive_ci(*bad)
