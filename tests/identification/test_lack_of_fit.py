"""The lack-of-fit test (orthocontact.identification.lack_of_fit): its F
distribution against closed forms, and its size where the model describes
the replicates."""
import math

import numpy as np
import pytest

from orthocontact.identification.lack_of_fit import lack_of_fit
from orthocontact.identification.statistics import f_survival, incomplete_beta


def test_the_f_distribution_against_its_closed_forms():
    # dof1 = 2: P(F > x) = (1 + 2x/dof2)^(-dof2/2); I_x(a, b) for whole a, b: a binomial tail
    for F, d2 in ((0.5, 3), (4.0, 20), (30.0, 7)):
        assert f_survival(F, 2, d2) == pytest.approx((1 + 2 * F / d2) ** (-d2 / 2), rel=1e-12)
    for a, b, x in ((2, 3, 0.4), (5, 1, 0.9), (3, 7, 0.05)):
        n = a + b - 1
        tail = sum(math.comb(n, j) * x**j * (1 - x) ** (n - j) for j in range(a, n + 1))
        assert incomplete_beta(a, b, x) == pytest.approx(tail, rel=1e-12)


@pytest.mark.parametrize("sd, top", [({0.1: 1.0}, 0.065), ({0.1: 2.0, 0.2: 0.5}, 0.08)])
def test_lack_of_fit_holds_its_size_where_the_model_describes_the_replicates(sd, top):
    """Data a two-parameter line describes, 7 angles x 4 replicates at each
    velocity, fitted by weighted least squares: P(p < 0.05) is 0.05 with
    one velocity (the test is exact: 0.05 +- 0.005 over 2000 draws); with
    two velocities' pooled variances it is approximate, a little liberal
    (0.068 measured here)."""
    rng = np.random.default_rng(4)
    cells = [(a, v) for a in range(7) for v in sd for _ in range(4)]
    X = np.array([[1.0, a] for a, _ in cells])
    w = np.array([1 / sd[v] ** 2 for _, v in cells])
    p = []
    for _ in range(2000):
        y = X @ [1.0, 0.3] + rng.normal(0, [sd[v] for _, v in cells])
        beta = np.linalg.solve(X.T @ (w[:, None] * X), X.T @ (w * y))
        p.append(lack_of_fit("forces", y - X @ beta, cells, 2, [v for _, v in cells]).p_value)
    assert 0.035 < np.mean(np.array(p) < 0.05) < top
