"""The FMU through fmpy (orthocontact.fmu.contact.ContactFMU), the wrapper's
own contract on both FMI versions: the force is the closed form's, an FMU's
refusal is an FMUError carrying the FMU's logged reason, time advances by the
steps taken, closing twice is harmless.  (The FMU binaries' behaviour itself:
tests/fmus/.)"""
import math

import numpy as np
import pytest

from orthocontact import closed_forms as cf
from orthocontact.fmu.contact import ContactFMU, FMUError
from orthocontact.fmu.params import ContactParams

LAW = ContactParams(0.3, 0.6, 2.5e4, 7e3, math.radians(33), math.radians(-20), "coupled")


@pytest.mark.parametrize("version", [2, 3])
def test_stick_force_tangent_and_time_through_the_wrapper(version):
    with ContactFMU(fmi_version=version, instance_name="w") as f:
        assert f.fmi_version == version and not f.initialized
        f.initialize(LAW)
        u = np.array([2e-5, -1.5e-5])
        f.set_inputs(*u, 20.0)
        B = cf.adhesion_tensor(LAW.eps1, LAW.eps2, LAW.alpha)
        np.testing.assert_allclose(f.force(), -B @ u, rtol=1e-13)
        np.testing.assert_allclose(f.tangent_column("u1"), -B[:, 0], rtol=1e-13)
        o = f.outputs()
        assert set(o) == {"T1", "T2", "s1", "s2", "dissipatedEnergy", "contactState"}
        assert o["contactState"] == 1 and (o["T1"], o["T2"]) == f.force()
        for _ in range(3):
            f.do_step(1e-3)
        assert f.time == pytest.approx(3e-3, abs=1e-18)


@pytest.mark.parametrize("version", [2, 3])
def test_a_refused_call_is_an_fmu_error_with_the_fmus_reason(version):
    f = ContactFMU(fmi_version=version, instance_name="refuse")
    try:
        f.initialize(LAW)
        f.set_inputs(1e-5, 0.0, 10.0)
        before = f.outputs()
        with pytest.raises(FMUError, match=r"setting inputs \(u1=nan.*failed \(status 3\): .*finite"):
            f.set_inputs(float("nan"), 0.0, 10.0)
        assert f.messages[-1][0] == 3                   # logged by the FMU, kept by the wrapper
        assert f.outputs() == before
        with pytest.raises(ValueError, match="rule must be one of"):
            f.initialize(_bad_rule())
    finally:
        f.close()
        f.close()                                        # twice: nothing left to free, no error
    assert f.slave is None


def _bad_rule():
    """ContactParams refuses an unknown rule itself; the wrapper checks again
    for an object built around that check."""
    p = ContactParams(0.3, 0.6, 1e4, 1e4)
    object.__setattr__(p, "rule", "sticky")
    return p


@pytest.mark.parametrize("version", [2, 3])
def test_initialize_takes_the_start_as_the_fmu_does_and_refuses_what_it_would_ignore(version):
    """The initial inputs are the FMU's at once (no set_inputs needed): the
    contact starts unloaded there.  An unknown initial slip, or a start slip
    with atInputs (which the FMU ignores), is refused before any FMI call.
    (The first step against the FMU driven directly: tests/fmus/test_initial_slip.py.)"""
    with ContactFMU(fmi_version=version, instance_name="start") as f:
        with pytest.raises(ValueError, match="initial_slip must be one of"):
            f.initialize(LAW, initial_slip="at_inputs")
        with pytest.raises(ValueError, match="s_start is used only with initial_slip='explicit'"):
            f.initialize(LAW, inputs=(1.0, 0.5, 18.39), s_start=(0.0, 0.0))
        assert not f.initialized
        f.initialize(LAW, inputs=(1.0, 0.5, 18.39))
        o = f.outputs()
        assert (o["s1"], o["s2"], o["T1"], o["T2"], o["contactState"]) == (1.0, 0.5, 0.0, 0.0, 1)
        f.reset(LAW)                                      # back to the defaults: inputs 0, atInputs
        f.set_inputs(2e-5, 0.0, 20.0)
        assert f.outputs()["s1"] == 0.0 and f.force()[0] < 0
