"""Optimal designs over candidates (identification.design_search) against
designs known in closed form: straight-line and quadratic regression on
[-1, 1] (D- and A-optimal at the ends, the quadratic's at -1, 0, 1 with
weight 1/3 each), and the equivalence theorem's check."""
import math

import numpy as np
import pytest

from orthocontact.errors import InputError
from orthocontact.identification import design_search as ds

X = np.linspace(-1.0, 1.0, 21)


def regression(degree, criterion="D", budget=(4,), fixed=None, designed=None):
    """Polynomial regression y = sum b_k x^k at the candidates X, unit noise."""
    F = np.vander(X, degree + 1, increasing=True)
    p = degree + 1
    return ds.Problem(info=np.einsum("ci,cj->cij", F, F), group=np.zeros(len(X), int), budget=budget,
                      fixed=np.zeros((p, p)) if fixed is None else fixed,
                      designed=tuple(range(p)) if designed is None else designed, criterion=criterion)


@pytest.mark.parametrize("criterion", ["D", "A"])
def test_a_straight_line_is_measured_at_both_ends(criterion):
    problem = regression(1, criterion)
    weights, eq = ds.approximate(problem)
    assert weights[0] + weights[-1] == pytest.approx(1.0, abs=2e-3)
    assert eq.holds and eq.max_ratio <= 1 + 1e-3
    counts = ds.exact(problem, weights)
    assert counts[0] == 2 and counts[-1] == 2 and counts.sum() == 4


def test_the_quadratic_d_optimum_is_a_third_at_each_end_and_the_middle():
    problem = regression(2, budget=(6,))
    weights, eq = ds.approximate(problem, tolerance=1e-4)
    assert [weights[0], weights[10], weights[-1]] == pytest.approx([1 / 3] * 3, abs=2e-3)
    assert eq.holds
    # for D with nothing fixed the theorem reads max_c tr(M^-1 I_c) = p, M per run
    M = problem.information(weights)
    assert max(np.trace(np.linalg.solve(M, info)) for info in problem.info) == pytest.approx(3, rel=1e-3)
    counts = ds.exact(problem, weights)
    assert (counts[0], counts[10], counts[-1]) == (2, 2, 2)


def test_the_loss_is_log_det_of_the_covariance_and_inf_where_singular():
    problem = regression(1)
    counts = np.zeros(len(X))
    counts[[0, -1]] = 1
    M = problem.information(counts)
    assert problem.loss(M) == pytest.approx(-math.log(np.linalg.det(M)))
    counts[-1] = 0   # one point cannot give a line
    assert problem.loss(problem.information(counts)) == math.inf
    assert problem.loss(np.stack([M, problem.information(counts)])).tolist() == [problem.loss(M), math.inf]


def test_a_parameter_told_only_rounding_is_singular_however_the_correlation_looks():
    """A line measured where its slope tells 1e-16 of what its intercept
    does: the correlation form of M is the identity, yet nothing is known of
    the slope."""
    M = np.diag([1.0, 1e-16])
    assert np.linalg.slogdet(M / np.sqrt(np.outer(np.diag(M), np.diag(M))))[1] == 0.0
    assert regression(1).loss(M) == math.inf
    assert regression(1).loss(np.diag([1.0, 1e-6])) < math.inf


def test_the_rank_bound_counts_each_runs_rank_within_its_budget():
    """A line's points each tell rank 1: one run cannot reach rank 2, two
    can; a run already made adds its rank."""
    assert regression(1, budget=(1,)).rank_bound() == 1
    assert regression(1, budget=(2,)).rank_bound() == 2
    made = np.einsum("i,j->ij", [1.0, 0.5], [1.0, 0.5])
    assert regression(1, budget=(1,), fixed=made).rank_bound() == 2


def test_a_nuisance_parameter_is_left_out_of_the_criterion():
    """Ds: only the slope designed; its variance sets the loss."""
    problem = regression(1, designed=(1,))
    counts = np.zeros(len(X))
    counts[[0, -1]] = 2
    M = problem.information(counts)
    assert problem.loss(M) == pytest.approx(math.log(np.linalg.inv(M)[1, 1]))
    # d_c = x_c^2 var(slope): the intercept's information counts for nothing
    assert problem.sensitivity(M)[[0, 10]] == pytest.approx([0.25, 0.0])


def test_efficiency_compares_designs_by_det_to_the_power_1_over_p():
    problem = regression(1)
    ends, middle = np.zeros(len(X)), np.zeros(len(X))
    ends[[0, -1]] = 2
    middle[[5, 15]] = 2    # x = -0.5, 0.5: the slope's information a quarter
    eff = problem.efficiency(problem.information(ends), problem.information(middle))
    assert eff == pytest.approx(2.0)    # (det ratio 4)^(1/2)


def test_runs_already_made_move_the_next_runs():
    """With two runs at x = 1 made, the D-optimal two more go to x = -1."""
    F = np.vander(X, 2, increasing=True)
    made = 2 * np.outer(F[-1], F[-1])
    problem = regression(1, budget=(2,), fixed=made)
    weights, eq = ds.approximate(problem)
    assert eq.holds
    counts = ds.exact(problem, weights)
    assert counts[0] == 2


def test_groups_keep_their_own_budgets():
    problem = regression(1)
    two = ds.Problem(problem.info, np.array([0] * 10 + [1] * 11), (3, 1), problem.fixed, (0, 1), "D")
    weights, eq = ds.approximate(two)
    assert eq.holds
    assert weights[:10].sum() == pytest.approx(1.0) and weights[10:].sum() == pytest.approx(1.0)
    counts = ds.exact(two, weights)
    assert counts[:10].sum() == 3 and counts[10:].sum() == 1


def test_candidates_that_cannot_determine_the_parameters_are_refused():
    problem = regression(1)
    zero_slope = ds.Problem(problem.info[10:11], np.zeros(1, int), (4,), problem.fixed, (0, 1), "D")
    with pytest.raises(InputError, match="singular"):
        ds.approximate(zero_slope)


def test_rounding_keeps_the_budget_and_the_support():
    problem = regression(2, budget=(7,))
    weights, _ = ds.approximate(problem)
    counts = ds.rounded(problem, weights)
    assert counts.sum() == 7 and set(np.flatnonzero(counts)) == {0, 10, 20}


def test_the_algorithm_says_its_iteration():
    status = ds.Status()
    ds.approximate(regression(2, budget=(6,)), tolerance=1e-9, max_iterations=50, status=status)
    assert status.text.startswith("approximate design: iteration 50, max sensitivity ratio 1.0")
