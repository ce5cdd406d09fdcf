"""The checks of the law's parameters (orthocontact.fmu.param_checks) are
code reading rows as data: a made-up table gets the same checks, messages
and FMU values as the contact's, and from_degrees' helpers refuse a
misnamed angle and pass a non-number on for the check to name."""
import dataclasses
import math
from typing import ClassVar

import numpy as np
import pytest

from orthocontact.fmu.param_checks import LawParameters, Row, check, radians, refuse_misnamed

STIFF = Row("k", type="Float64", unit="N/m", min=1.0, max=10.0, start=2.0, description="a stiffness")
TURN = Row("phi", type="Float64", unit="rad", min=-math.pi, max=math.pi, start=0.0, description="an angle")
LOOSE = Row("s", type="Float64", unit="m", min=-1.0, max=1.0, start=0.0)


@dataclasses.dataclass(frozen=True)
class Toy(LawParameters):
    """Another law: the checks come from TABLE, the numbers from RULE_NUMBERS."""
    k: float
    phi: float = 0.0
    rule: str = "b"
    TABLE: ClassVar = (STIFF, TURN)
    RULE_NUMBERS: ClassVar = {"a": 4, "b": 5}
    RULE_VARIABLE: ClassVar = "toyRule"


@pytest.mark.parametrize("row,value,message", [
    (STIFF, 0.5, r"^X: k = 0.5 \[N/m\] is outside \[1.0, 10.0\], the FMU's range$"),
    (STIFF, -1, r"^X: k must be a finite number > 0, got -1$"),
    (STIFF, True, r"^X: k must be a finite number > 0, got True$"),
    (STIFF, "3", r"^X: k must be a finite number > 0, got '3'$"),
    (TURN, 4.0, r"^X: phi = 4.0 rad is outside \[-1 pi, 1 pi\] rad, the FMU's range; degrees\? "
                r"\(phi is in rad: X.from_degrees takes deg\)$"),
    (LOOSE, math.inf, r"^X: s \[m\] must be a finite number, got inf$"),
    (LOOSE, 2, r"^X: s = 2 \[m\] is outside \[-1.0, 1.0\], the FMU's range$"),
])
def test_a_value_outside_its_row_is_refused_naming_the_unit(row, value, message):
    with pytest.raises(ValueError, match=message):
        check("X", row, value)


def test_a_value_in_its_row_passes_numpy_numbers_too():
    for row, value in ((STIFF, 1.0), (STIFF, 10), (STIFF, np.float32(5.5)), (TURN, -math.pi), (LOOSE, 0)):
        assert check("X", row, value) is None


def test_the_checks_fmu_values_and_replace_follow_the_table():
    toy = Toy(np.int64(3), phi=np.float64(0.5))
    assert (toy.k, toy.phi) == (3.0, 0.5) and type(toy.k) is float
    assert toy.fmu_values() == {"k": 3.0, "phi": 0.5, "toyRule": 5}
    assert Toy.law_parameters() == ("k", "phi")
    assert toy.replace(rule="a").fmu_values()["toyRule"] == 4
    with pytest.raises(ValueError, match=r"^Toy: k = 20 \[N/m\] is outside"):
        toy.replace(k=20)
    with pytest.raises(ValueError, match=r"^Toy: rule must be one of 'a', 'b', got 'c'$"):
        Toy(3.0, rule="c")


def test_from_degrees_helpers():
    assert radians(180) == math.pi and radians(np.int64(90)) == math.pi / 2
    assert radians("90") == "90"       # the check refuses it as typed
    with pytest.raises(TypeError, match=r"^Toy.from_degrees takes phi_deg \(degrees\), not phi$"):
        refuse_misnamed(Toy, {"phi": 0.5})
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'kk'"):
        refuse_misnamed(Toy, {"kk": 1.0})
    assert refuse_misnamed(Toy, {}) is None
