"""The paper's closed forms (orthocontact.closed_forms.paper) against a fine
scan of the formulas they are the extremum of, and the paper's printed numbers."""
import math

import numpy as np
import pytest

from orthocontact import closed_forms as cf


@pytest.mark.parametrize("l1,l2", [(1.0, 5.0), (10.0, 2.0), (1e4 / 0.5, 1e3 / 0.1), (0.8166, 1.0)])
def test_the_extremum_formulas_are_the_extremum_of_eq25(l1, l2):
    """eq. (27)-(29) against a fine scan of eq. (25) itself."""
    a = np.linspace(1e-6, math.pi / 2 - 1e-6, 2_000_001)
    t = cf.eq25_tan_phi(l1, l2, a)
    k = int(np.argmax(np.abs(t)))
    assert cf.eq27_alpha_ext(l1, l2) == pytest.approx(a[k], abs=2e-6)
    assert cf.eq28_tan_phi_ext(l1, l2) == pytest.approx(t[k], rel=1e-9)
    # eq. (29) inverts eq. (28)
    assert cf.eq29_ratio(cf.eq28_tan_phi_ext(l1, l2)) == pytest.approx(l1 / l2, rel=1e-12)


def test_case1s_extremum_formula_is_the_extremum_of_eq11():
    a = np.linspace(0, math.pi / 2 - 1e-6, 2_000_001)
    t = cf.eq11_tan_phi(0.1, 0.5, a)
    k = int(np.argmax(t))
    a_ext, phi_ext = cf.eq11_extremum(0.1, 0.5)
    assert a_ext == pytest.approx(a[k], abs=2e-6) and math.tan(phi_ext) == pytest.approx(t[k], rel=1e-9)
    assert math.degrees(phi_ext) == pytest.approx(67.38, abs=0.005)   # the paper's Case 1
    assert math.degrees(a_ext) == pytest.approx(78.69, abs=0.005)
