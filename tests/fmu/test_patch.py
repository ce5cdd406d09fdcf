"""The ContactPatch FMU's Python access (orthocontact.fmu.patch): the patch
in uniform translation is the point FMU through fmu.contact (the point law's
T for any grid, Mz = 0), the FMU's refusals arrive as one FMUError naming
its reason, bad geometry is refused before the FMU sees it."""
import math

import pytest

from orthocontact.fmu.contact import ContactFMU, FMUError
from orthocontact.fmu.params import ContactParams
from orthocontact.fmu.patch import PatchFMU, PatchGeometry

AGED = ContactParams.from_degrees(0.408, 0.625, 1.251e4, 1e4, 129.2, 39.2, "coupled")


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_uniform_translation_is_the_point_fmus_force(fmi_version):
    with PatchFMU(fmi_version=fmi_version) as patch, ContactFMU(fmi_version=fmi_version) as point:
        patch.initialize(AGED, PatchGeometry(0.08, 0.03, 5, 3), (0.0, 0.0, 0.0, 18.0))
        point.initialize(AGED, inputs=(0.0, 0.0, 18.0))
        slid = False
        for k in range(1, 150):
            u1, u2 = 2e-5 * k, 1e-5 * k * math.sin(0.05 * k)
            patch.set_inputs(u1, u2, 0.0, 18.0)
            point.set_inputs(u1, u2, 18.0)
            T1, T2, Mz = patch.load()
            assert (T1, T2) == pytest.approx(point.force(), rel=1e-12, abs=1e-12 * 18.0)
            assert abs(Mz) < 1e-13 * 18.0 * 0.08
            out = patch.outputs()
            slid |= out["contactState"] == 3
            patch.do_step(1e-3)
            point.do_step(1e-3)
        assert slid
        # the tangent along u1 is the point's
        assert patch.derivative("u1")[:2] == pytest.approx(point.tangent_column("u1"), rel=1e-10)


def test_a_centre_of_pressure_outside_the_kern_is_refused_with_the_fmus_reason():
    with PatchFMU() as patch:
        patch.initialize(AGED, PatchGeometry(0.1, 0.05, 4, 4), (0.0, 0.0, 0.0, 18.0))
        with pytest.raises(FMUError) as e:
            patch.set_inputs(0.0, 0.0, 0.0, 18.0, 0.05, 0.0)
        assert "outside the kern" in str(e.value) and "p1=0.05 m" in str(e.value), str(e.value)


@pytest.mark.parametrize("kw,word", [(dict(length=0.0, width=0.1), "length"),
                                     (dict(length=0.1, width=math.inf), "width"),
                                     (dict(length=0.1, width=0.1, n1=0), "n1"),
                                     (dict(length=0.1, width=0.1, n2=65), "n2"),
                                     (dict(length=0.1, width=0.1, n1=2.0), "n1")])
def test_bad_geometry_is_refused_naming_it(kw, word):
    with pytest.raises(ValueError, match=f"PatchGeometry: {word}"):
        PatchGeometry(**kw)


def test_an_fmu_of_the_other_version_is_refused():
    from orthocontact.fmu.files import find_fmu
    with pytest.raises(ValueError, match="is an FMI 3.0 FMU, not 2.0"):
        PatchFMU(find_fmu(fmi_version=3, model="ContactPatch"), fmi_version=2)


def test_cell_states_in_a_first_twist_are_the_isotropic_stick_criterion_cell_by_cell():
    """Pure rotation, isotropic law, uniform pressure: the cell at r moves by
    (R(theta) - I) r, of length 2 r sin(theta / 2), against its share of the
    stiffness and of the load alike, so on the first loading it sticks while
    eps 2 r sin(theta / 2) <= mu N; the centre cell (r = 0) never slides.
    Element [i][j] is the i-th cell along length, the j-th along width."""
    law = ContactParams.from_degrees(0.5, 0.5, 1e4, 1e4, 0.0, 90.0, "coupled")
    g, N = PatchGeometry(0.08, 0.03, 5, 3), 10.0
    r = [[math.hypot((i + 0.5) * g.length / g.n1 - g.length / 2, (j + 0.5) * g.width / g.n2 - g.width / 2)
          for j in range(g.n2)] for i in range(g.n1)]
    seen = set()
    with PatchFMU(fmi_version=3) as patch:
        patch.initialize(law, g, (0.0, 0.0, 0.0, N))
        for k in range(1, 101):
            theta = 1e-3 * k
            patch.set_inputs(0.0, 0.0, theta, N)
            states = patch.cell_states()
            ratio = [[1e4 * 2 * r[i][j] * math.sin(theta / 2) / (0.5 * N) for j in range(g.n2)]
                     for i in range(g.n1)]
            assert all(abs(x - 1) > 1e-9 for row in ratio for x in row)   # no cell on the threshold
            expected = [[2 if x > 1 else 1 for x in row] for row in ratio]
            assert states == expected, theta
            seen |= {s for row in states for s in row}
            patch.do_step(1e-3)
    assert seen == {1, 2} and states[2][1] == 1    # both states met; the centre sticks


def test_cell_states_are_fmi_3_only():
    with PatchFMU(fmi_version=2) as patch:
        patch.initialize(AGED, PatchGeometry(0.1, 0.05, 4, 4), (0.0, 0.0, 0.0, 18.0))
        with pytest.raises(ValueError, match="FMI 2.0 has no arrays"):
            patch.cell_states()
