"""The table of closed forms a scenario can name (orthocontact.closed_forms.named):
each form against the steady state built here from the law's tensors, its
scalar and array forms alike, and each refusal where the form does not hold."""
import math

import numpy as np
import pytest

from orthocontact import closed_forms as cf
from orthocontact.closed_forms.named import FORMS, named
from orthocontact.fmu.params import ContactParams


def tensor_tan_phi(law, alpha, beta):
    """tan(phi) of steady sliding from the definition: the slip runs along
    G q with q = (q1, 0), G = F (associated) or (B F B)^-1 (implicit), so
    tan(phi) = G21 / G11; matrices through numpy, one pair of axes."""
    F = cf.friction_tensor(law.mu1, law.mu2, beta)
    B = cf.adhesion_tensor(law.eps1, law.eps2, alpha)
    G = F if law.rule == "associated" else np.linalg.inv(B @ F @ B)
    return G[1, 0] / G[0, 0]


# A law and axis offset (beta - alpha [deg]) where each form holds.
HOLDS = {
    "general": (ContactParams(0.3, 0.7, 2e3, 9e4, rule="coupled"), 37.0),
    "eq11": (ContactParams(0.1, 0.5, 1e4, 3e3, rule="associated"), 25.0),
    "eq31": (ContactParams(0.1, 0.5, 1e4, 1e4, rule="coupled"), 60.0),
    "eq33": (ContactParams(0.3, 0.3, 1e4, 5e4, rule="coupled"), -20.0),
    "eq25": (ContactParams(0.1, 0.5, 1e4, 5e4, rule="coupled"), 0.0),
    "mat": (ContactParams(0.408, 0.625, 12510.0, 1e4, rule="coupled"), -90.0),
}
# Where each form (but general) does not: (law, offset, what the refusal names).
REFUSED = {
    "eq11": (ContactParams(0.1, 0.5, 1e4, 1e4, rule="coupled"), 0.0, "associated"),
    "eq31": (ContactParams(0.1, 0.5, 1e4, 5e3, rule="coupled"), 0.0, "eps1 = eps2"),
    "eq33": (ContactParams(0.3, 0.4, 1e4, 5e4, rule="coupled"), 0.0, "mu1 = mu2"),
    "eq25": (ContactParams(0.1, 0.5, 1e4, 5e4, rule="coupled"), 45.0, "0 or 90"),
    "mat": (ContactParams(0.408, 0.625, 12510.0, 1e4, rule="coupled"), 0.0, "= 90"),
}


def test_the_table_holds_the_forms_scenarios_name():
    assert set(FORMS) == set(HOLDS)
    assert all(f.name == name and f.description for name, f in FORMS.items())


@pytest.mark.parametrize("name", sorted(HOLDS))
def test_each_form_is_the_steady_state_of_the_tensors_where_it_holds(name):
    law, offset = HOLDS[name]
    form = FORMS[name]
    assert form.refusal(law, offset) is None
    a = np.linspace(-80.0, 170.0, 251)
    alpha, beta = np.radians(a), np.radians(a + offset)
    truth = np.array([tensor_tan_phi(law, x, y) for x, y in zip(alpha, beta)])
    scalar = np.array([form.scalar(law, float(x), float(y)) for x, y in zip(alpha, beta)])
    np.testing.assert_allclose(scalar, truth, rtol=1e-9, atol=1e-9)
    # the array form gives the scalar form's numbers, and so do the angles in degrees
    np.testing.assert_allclose(form.array(law, alpha, beta), scalar, rtol=0, atol=1e-13)
    deg = np.array([form.phi_deg(law, float(x), float(y)) for x, y in zip(alpha, beta)])
    np.testing.assert_allclose(form.phi_deg_array(law, alpha, beta), deg, rtol=0, atol=1e-11)
    np.testing.assert_allclose(deg, np.degrees(np.arctan(truth)), rtol=0, atol=1e-7)


@pytest.mark.parametrize("name", sorted(REFUSED))
def test_each_form_refuses_a_law_or_axes_it_does_not_hold_for(name):
    law, offset, says = REFUSED[name]
    refusal = FORMS[name].refusal(law, offset)
    assert refusal is not None and says in refusal
    # and there it would be wrong: the refusal is needed
    alpha = np.radians(np.linspace(10.0, 80.0, 8))
    beta = alpha + math.radians(offset)
    truth = np.array([tensor_tan_phi(law, x, y) for x, y in zip(alpha, beta)])
    with np.errstate(invalid="ignore"):
        got = FORMS[name].array(law, alpha, beta)
    assert not np.allclose(got, truth, rtol=1e-6, atol=1e-9)
    assert FORMS["general"].refusal(law, offset) is None


def test_the_general_form_is_the_paper_modules_steady_state():
    law, _ = HOLDS["general"]
    assert FORMS["general"].phi_deg(law, 0.3, 1.1) == cf.steady_phi_deg(0.3, 0.7, 2e3, 9e4, 0.3, 1.1)
    assert cf.of_law(cf.steady_tan_phi, law, 0.3, 1.1) == cf.steady_tan_phi(0.3, 0.7, 2e3, 9e4, 0.3, 1.1)


def test_a_name_given_twice_is_refused():
    with pytest.raises(ValueError, match="'eq11' is named twice"):
        named("eq11", "another")(lambda law, alpha, beta: 0.0)
    assert FORMS["eq11"].scalar is cf.paper.eq11_form
