"""The law's parameters (orthocontact.fmu.params): the rules' numbers, degrees
to radians, the angle range the FMU takes."""
import math
import pytest

from orthocontact import ContactParams


def test_contact_params_refuse_angles_outside_4_pi_naming_radians():
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
    assert rule.find("Integer") is not None and f"{values['slidingRule']} associated (" in rule.get("description")
