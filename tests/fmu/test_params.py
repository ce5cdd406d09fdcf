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
