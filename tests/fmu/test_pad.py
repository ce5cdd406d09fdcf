"""The ContactPad FMU's Python access (orthocontact.fmu.pad): the foundation
refused before the FMU sees a bad value, the pose's length, the FMU of the
other version, the FMI 3.0 arrays and the Jacobian's layout.  The binary's
physics: tests/fmus/test_pad.py."""
import math

import pytest

from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.pad import FOUNDATION, WRENCH, Foundation, PadFMU, foundation_problem, foundation_row
from orthocontact.fmu.params import ContactParams
from orthocontact.fmu.patch import PatchGeometry

LAW = ContactParams(0.5, 0.4, 1e4, 2e4, 0.3, 0.1)
PAD = PatchGeometry(0.08, 0.05, 4, 3)


def test_the_foundation_is_the_tables_kn_and_dn_with_their_ranges():
    assert FOUNDATION == ("kn", "dn")
    assert foundation_row("kn").unit == "N/m3" and foundation_row("dn").min == 0
    assert Foundation(1e8).dn == 0.0
    assert foundation_problem("kn", 1e8) is None
    assert "outside [1e-100, 1e+100] N/m3" in foundation_problem("kn", 1e200)
    with pytest.raises(KeyError, match="no foundation parameter 'k'"):
        foundation_row("k")


@pytest.mark.parametrize("kw,word", [(dict(kn=0.0), "kn"), (dict(kn=1.0, dn=-1.0), "dn"),
                                     (dict(kn=math.nan), "kn"), (dict(kn=True), "kn")])
def test_a_foundation_the_fmu_refuses_is_refused_first(kw, word):
    with pytest.raises(ValueError, match=f"Foundation: {word}"):
        Foundation(**kw)


def test_a_pose_of_the_wrong_length_and_an_fmu_of_the_other_version_are_refused():
    with PadFMU() as f, pytest.raises(ValueError, match=r"pose must be \(u1, u2, theta, d, phi1, phi2\)"):
        f.initialize(LAW, PAD, Foundation(1e8), (0.0, 0.0, 0.0, 1e-5))
    with pytest.raises(ValueError, match="is an FMI 3.0 FMU, not 2.0"):
        PadFMU(find_fmu(fmi_version=3, model="ContactPad"), fmi_version=2)


def test_the_jacobian_is_the_derivatives_row_by_output_and_fmi2_has_no_cells():
    with PadFMU() as f:
        f.initialize(LAW, PAD, Foundation(1e8), (0.0, 0.0, 0.0, 1e-5, 0.0, 1e-4))
        f.set_inputs(1e-5, 0.0, 1e-3, 1.1e-5, 0.0, 1e-4)
        J = f.jacobian(("d", "phi2"))
        assert [len(row) for row in J] == [2] * len(WRENCH)
        assert [row[0] for row in J] == pytest.approx(f.derivative("d"), rel=0, abs=0)
        assert J[3][0] == pytest.approx(1e8 * 0.08 * 0.05, rel=1e-12)    # dFn/dd = kn A
        with pytest.raises(ValueError, match="FMI 2.0 has no arrays"):
            f.cell_normal_forces()


def test_fmi3_gives_the_cells_normal_forces_and_states():
    with PadFMU(fmi_version=3) as f:
        f.initialize(LAW, PAD, Foundation(1e8), (0.0, 0.0, 0.0, 1e-5, 0.0, 0.0))
        cells = f.cell_normal_forces()
        assert len(cells) == 4 and len(cells[0]) == 3
        assert sum(map(sum, cells)) == pytest.approx(f.outputs()["Fn"], rel=1e-14)
        assert f.cell_states() == [[1] * 3] * 4
