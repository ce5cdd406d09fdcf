"""The fit's noise model (orthocontact.identification.noise_model) against
hand-solved cases of the Paule-Mandel equation sum r^2 / (tau^2 + se^2) = dof."""
import math

import numpy as np
import pytest

from orthocontact.identification.noise_model import between_run_tau2, between_run_variance, tau_summary


def test_equal_within_run_errors_have_the_closed_form_solution():
    # with se_i^2 = s for all i: sum r^2 / (tau^2 + s) = dof  =>  tau^2 = sum r^2 / dof - s
    r = np.array([0.3, -0.5, 0.1, 0.7, -0.2])
    s, dof = 0.01, 4.0
    expected = float(np.sum(r ** 2)) / dof - s
    assert between_run_variance(r, np.full(5, s), dof) == pytest.approx(expected, rel=1e-12)


def test_unequal_errors_solve_the_equation():
    r = np.array([1.0, -2.0, 0.5, 1.5])
    se2 = np.array([0.1, 0.5, 0.05, 0.2])
    t2 = between_run_variance(r, se2, 3.0)
    assert float(np.sum(r ** 2 / (t2 + se2))) == pytest.approx(3.0, rel=1e-10)


def test_scatter_the_within_run_errors_explain_gives_zero_and_no_errors_the_plain_variance():
    r = np.array([0.1, -0.1, 0.05])
    assert between_run_variance(r, np.full(3, 1.0), 2.0) == 0.0
    assert between_run_variance(r, np.zeros(3), 2.0) == pytest.approx(0.0225 / 2.0, rel=1e-12)
    with pytest.raises(ValueError, match="degrees of freedom"):
        between_run_variance(r, np.zeros(3), 0)


def test_components_by_label_and_their_summary():
    r = np.array([1.0, -1.0, 1.0, -1.0, 3.0, -3.0, 3.0, -3.0])
    v = np.array([0.1] * 4 + [0.2] * 4)
    tau2 = between_run_tau2(r, np.zeros(8), charged=2, labels=v)
    # each velocity: 4 values, 4 * (1 - 2/8) = 3 degrees of freedom
    assert tau2[:4].tolist() == [4 / 3] * 4 and tau2[4:].tolist() == [36 / 3] * 4
    assert tau_summary(tau2, v) == {"0.1": math.sqrt(4 / 3), "0.2": math.sqrt(12.0)}
    whole = between_run_tau2(r, np.zeros(8), charged=2)
    assert whole.tolist() == [40 / 6] * 8 and tau_summary(whole) == math.sqrt(40 / 6)
