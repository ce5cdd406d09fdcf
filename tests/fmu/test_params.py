"""The law's parameters (orthocontact.fmu.params): the rules' numbers, degrees
to radians, the angle range the FMU takes."""
import math

import pytest

from orthocontact import ContactParams
from orthocontact.fmu.params import ANGLE_LIMIT_RAD


def test_contact_params_refuse_angles_outside_4_pi_naming_radians():
    assert ANGLE_LIMIT_RAD == 4 * math.pi     # the table's range of both angles
    with pytest.raises(ValueError, match=r"alpha = 90 rad is outside \[-4 pi, 4 pi\] rad.*degrees\?"):
        ContactParams(0.408, 0.625, 1e4, 1e4, alpha=90)
    with pytest.raises(ValueError, match="beta"):
        ContactParams(0.408, 0.625, 1e4, 1e4, beta=-13.0)
    assert ContactParams(0.408, 0.625, 1e4, 1e4, alpha=4 * math.pi).alpha == 4 * math.pi


def test_fmu_values_are_the_contact_fmus_parameters_by_the_model_descriptions_names():
    """ContactParams.fmu_values against the installed FMU's own model
    description: every law parameter and slidingRule by name, as reals and
    the enumeration's number, in radians as the FMU takes them."""
    import xml.etree.ElementTree as ET
    import zipfile

    from orthocontact.fmu.files import find_fmu
    with zipfile.ZipFile(find_fmu(fmi_version=2)) as z:
        md = ET.fromstring(z.read("modelDescription.xml"))
    parameters = {v.get("name") for v in md.iter("ScalarVariable") if v.get("causality") == "parameter"}
    p = ContactParams.from_degrees(0.408, 0.625, 12510, 10000, 90, 0, "associated")
    values = p.fmu_values()
    assert set(values) <= parameters and {"mu1", "alpha", "slidingRule"} <= set(values)
    assert values["eps1"] == 12510.0 and type(values["eps1"]) is float
    assert values["alpha"] == pytest.approx(math.pi / 2) and values["beta"] == 0.0
    rule = next(v for v in md.iter("ScalarVariable") if v.get("name") == "slidingRule")
    assert rule.find("Integer") is not None
    assert f"{values['slidingRule']} associated (" in rule.get("description")


def test_contact_params_refuse_what_the_fmu_refuses_at_its_own_ranges():
    """ContactParams' checks come from the variable table: read the FMU's
    own model description (fmpy, not the package's manifest) and, for every
    law parameter, a value just past its min or max is refused by
    ContactParams with the parameter's name, and the value at the limit is
    taken; an angle's refusal names degrees, a range error the unit."""
    from fmpy import read_model_description

    from orthocontact.fmu.files import find_fmu
    md = read_model_description(str(find_fmu(fmi_version=2)))
    law = {v.name: v for v in md.modelVariables if v.name in ContactParams.law_parameters()}
    assert list(law) == list(ContactParams.law_parameters())
    base = dict(mu1=0.408, mu2=0.625, eps1=1.251e4, eps2=1e4)
    for name, v in law.items():
        lo, hi = float(v.min), float(v.max)
        assert getattr(ContactParams(**{**base, name: lo}), name) == lo
        assert getattr(ContactParams(**{**base, name: hi}), name) == hi
        for outside in (lo * (1 - 1e-9) if lo > 0 else lo - abs(lo) * 1e-9 - 1e-300, hi * (1 + 1e-9)):
            with pytest.raises(ValueError, match=rf"ContactParams: {name}\b"):
                ContactParams(**{**base, name: outside})
        if v.unit == "rad":
            with pytest.raises(ValueError, match="degrees"):
                ContactParams(**{**base, name: 90.0})
    with pytest.raises(ValueError, match=r"eps2 = 2e\+300 \[N/m\] is outside"):
        ContactParams(**{**base, "eps2": 2e300})
    with pytest.raises(ValueError, match=r"eps1 must be a finite number > 0, got -1"):
        ContactParams(**{**base, "eps1": -1.0})
    with pytest.raises(ValueError, match=r"alpha \[rad\] must be a finite number, got nan"):
        ContactParams(**{**base, "alpha": float("nan")})


def test_from_degrees_takes_the_angles_in_degrees_by_position_or_name():
    by_position = ContactParams.from_degrees(0.1, 0.5, 1e4, 1e3, 26.565, 116.565, "associated")
    by_name = ContactParams.from_degrees(mu1=0.1, mu2=0.5, eps1=1e4, eps2=1e3, alpha_deg=26.565,
                                         beta_deg=116.565, rule="associated")
    assert by_position == by_name
    assert by_name.alpha == math.radians(26.565) and by_name.beta_deg == pytest.approx(116.565)
    assert ContactParams.from_degrees(0.1, 0.5, 1e4, 1e3).alpha == 0.0
    with pytest.raises(TypeError, match="alpha_deg"):
        ContactParams.from_degrees(0.1, 0.5, 1e4, 1e3, alpha=0.5)
    import pickle
    assert pickle.loads(pickle.dumps(by_name)) == by_name      # crosses to worker processes


def test_numpy_numbers_are_taken_as_floats():
    """Angles from numpy (np.arange, np.int64, np.float32) as users have them."""
    import numpy as np
    p = ContactParams.from_degrees(np.float32(0.3), 0.4, np.int64(100000), 2e5,
                                   alpha_deg=np.int64(30), beta_deg=np.arange(0, 91, 15)[2])
    assert p.alpha == pytest.approx(math.radians(30)) and p.beta == pytest.approx(math.radians(30))
    assert all(type(getattr(p, n)) is float for n in ContactParams.law_parameters())
    assert ContactParams(0.3, 0.4, 1e5, 2e5, alpha=np.float64(0.5)) == ContactParams(0.3, 0.4, 1e5, 2e5, 0.5)
    with pytest.raises(ValueError, match="mu1 must be a finite number > 0, got True"):
        ContactParams(True, 0.4, 1e5, 2e5)
