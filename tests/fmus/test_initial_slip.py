"""The contact FMU's initial condition through fmpy: a system
simulator that wires absolute positions from t0 sets the inputs in
initialization mode; by default the contact starts unloaded there (no force,
no slip, no dissipation on the first step), and the explicit initial slip 0
gives the earlier versions' full slide, bit for bit what inputs set only
after initialization give.  ContactFMU.initialize takes the same choice and
gives the same results bit for bit."""
import math

import pytest
from fmpy import read_model_description

from fmu_values import unzipped
from orthocontact.fmu import RULES, ContactFMU, ContactParams, find_fmu

U = (1.0, 0.5, 18.39)  # an absolute position from t0 and the rig's normal force


def _slave(version):
    path = str(find_fmu(fmi_version=version))
    md = read_model_description(path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    if version == 2:
        from fmpy.fmi2 import FMU2Slave as Slave
    else:
        from fmpy.fmi3 import FMU3Slave as Slave
    s = Slave(guid=md.guid, unzipDirectory=unzipped(path), modelIdentifier="OrthotropicContact",
              instanceName="initial")
    s.instantiate()
    return s, vr, md


def first_step(version, rule, initial_slip=None, s_start=None, inputs_in_init=True):
    """Outputs after one committed step at U."""
    s, vr, _ = _slave(version)
    set_real = s.setReal if version == 2 else s.setFloat64
    get_real = s.getReal if version == 2 else s.getFloat64
    set_enum = s.setInteger if version == 2 else s.setInt64
    get_state = s.getInteger if version == 2 else s.getInt32
    set_enum([vr["slidingRule"]], [rule])
    if initial_slip is not None:
        set_enum([vr["initialSlip"]], [initial_slip])
    if s_start is not None:
        set_real([vr["s1Start"], vr["s2Start"]], list(s_start))
    if version == 2:
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
    else:
        s.enterInitializationMode(startTime=0.0)
    inputs = [vr["u1"], vr["u2"], vr["N"]]
    if inputs_in_init:
        set_real(inputs, list(U))
    s.exitInitializationMode()
    set_real(inputs, list(U))
    s.doStep(0.0, 1e-3)
    names = ["T1", "T2", "s1", "s2", "dissipatedEnergy"]
    out = dict(zip(names, get_real([vr[n] for n in names])))
    out["contactState"] = get_state([vr["contactState"]])[0]
    s.terminate()
    s.freeInstance()
    return out


@pytest.mark.parametrize("version", [2, 3])
def test_model_description_declares_the_initial_condition(version):
    _, _, md = _slave(version)
    v = {x.name: x for x in md.modelVariables}
    assert v["initialSlip"].causality == "parameter" and v["initialSlip"].start in ("1", 1)
    assert v["s1Start"].unit == "m" and v["s2Start"].unit == "m"
    if version == 3:
        items = {i.name: int(i.value) for i in v["initialSlip"].declaredType.items}
        assert items == {"atInputs": 1, "explicit": 2}


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("rule", [1, 2, 3])
def test_absolute_positions_from_t0_give_no_slip_and_no_dissipation(version, rule):
    out = first_step(version, rule)
    assert out["contactState"] == 1
    assert (out["T1"], out["T2"]) == (0.0, 0.0)
    assert (out["s1"], out["s2"]) == (U[0], U[1])
    assert out["dissipatedEnergy"] == 0.0


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("rule", [1, 2, 3])
def test_explicit_initial_slip_zero_is_the_old_behaviour(version, rule):
    old = first_step(version, rule, inputs_in_init=False)  # the path starts at u = 0
    explicit = first_step(version, rule, initial_slip=2, s_start=(0.0, 0.0))
    assert explicit == old  # bit for bit
    assert explicit["contactState"] == 2 and explicit["dissipatedEnergy"] > 0
    if rule == 2:
        assert explicit["dissipatedEnergy"] == pytest.approx(8.55, abs=5e-3)  # the first step's full slide


@pytest.mark.parametrize("version", [2, 3])
def test_explicit_initial_slip_at_the_body_is_unloaded(version):
    out = first_step(version, 2, initial_slip=2, s_start=U[:2])
    assert out["contactState"] == 1 and out["dissipatedEnergy"] == 0.0


# -- the same through orthocontact.fmu.ContactFMU ------------------------------------------------

DEFAULTS = ContactParams(0.408, 0.625, 12510.0, 1e4, math.pi / 2, 0.0, "coupled")  # the FMU's own


def wrapper_first_step(version, rule, **initial):
    """Outputs after one committed step at U, through ContactFMU.initialize(**initial)."""
    with ContactFMU(fmi_version=version, instance_name="initial_wrapper") as f:
        f.initialize(DEFAULTS.replace(rule=next(k for k, v in RULES.items() if v == rule)), **initial)
        f.set_inputs(*U)
        f.do_step(1e-3)
        return f.outputs()


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("rule", [1, 2, 3])
def test_the_wrapper_given_the_inputs_starts_where_the_body_is(version, rule):
    """initialize(inputs=U), then set_inputs(U): stick, no force, 0 J on the
    first step, as the FMU driven directly gives (it slid 8.55 J when the
    wrapper set no inputs before the end of initialization)."""
    got = wrapper_first_step(version, rule, inputs=U)
    assert got == first_step(version, rule)  # bit for bit
    assert got["contactState"] == 1 and got["dissipatedEnergy"] == 0.0
    assert (got["T1"], got["T2"]) == (0.0, 0.0)


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("rule", [1, 2, 3])
def test_the_wrappers_explicit_slip_zero_is_the_old_dissipation(version, rule):
    got = wrapper_first_step(version, rule, inputs=U, initial_slip="explicit", s_start=(0.0, 0.0))
    assert got == first_step(version, rule, initial_slip=2, s_start=(0.0, 0.0))
    assert got == first_step(version, rule, inputs_in_init=False)  # the wrapper's old start
    assert got == wrapper_first_step(version, rule)  # inputs 0 until the first step: the same path
    assert got["contactState"] == 2 and got["dissipatedEnergy"] > 0
    if rule == 2:
        assert got["dissipatedEnergy"] == pytest.approx(8.55, abs=5e-3)


@pytest.mark.parametrize("version", [2, 3])
def test_the_wrappers_explicit_slip_at_the_body_is_unloaded(version):
    got = wrapper_first_step(version, 2, inputs=U, initial_slip="explicit", s_start=U[:2])
    assert got == first_step(version, 2, initial_slip=2, s_start=U[:2])
    assert got["contactState"] == 1 and got["dissipatedEnergy"] == 0.0
