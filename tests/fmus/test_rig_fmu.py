"""The CarriageBlock rig FMU: a second model of the shared FMI glue.  Coupled
with the contact FMU by a plain co-simulation master it gives the Python
harness's dynamic rig; a step or state whose x1 would overflow is refused.
Its importers and its state in a fresh instance: tests/conformance/."""
import math

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from orthocontact.fmu.contact import ContactFMU
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.params import ContactParams
from orthocontact.fmu.slave import instantiate
from orthocontact.rig.harness import LineFit, Rig, run

AGED = ContactParams.from_degrees(0.408, 0.625, 1.251e4, 1e4, 90 + 39.2, 39.2)


_KEEP = []  # the loggers' ctypes callbacks must outlive the instances


def _rig_slave(version, name="rig", messages=None):
    """A CarriageBlock instantiated as the package instantiates an FMU
    (orthocontact.fmu.slave); what it logs is appended to `messages` as
    (status, text) if given."""
    path = find_fmu(fmi_version=version, model="CarriageBlock")
    md = read_model_description(str(path))
    vr = {v.name: v.valueReference for v in md.modelVariables}

    def log(status, category, text):
        if messages is not None:
            messages.append((status, text))
    s, keep = instantiate(path, md, name, log)
    _KEEP.append(keep)
    set_real = s.setReal if version == 2 else s.setFloat64
    get_real = s.getReal if version == 2 else s.getFloat64
    return s, vr, md, set_real, get_real


def _start(s, version):
    """Into step mode at t = 0, as each FMI version spells it."""
    if version == 2:
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
    else:
        s.enterInitializationMode(startTime=0.0)
    s.exitInitializationMode()


@pytest.mark.parametrize("version", [2, 3])
def test_rig_fmu_validates_and_declares_no_feedthrough_of_the_positions(version):
    path = find_fmu(fmi_version=version, model="CarriageBlock")
    assert validate_fmu(str(path)) == []
    md = read_model_description(str(path))
    deps = {o.variable.name: {d.name for d in o.dependencies} for o in md.outputs}
    assert deps == {"u1": set(), "u2": set(), "N": set(), "x1": set(), "x2": set(),
                    "driveForce": {"T1"}}


def cosimulate(version, params, rig: Rig, n_steps):
    """A plain Gauss-Seidel master: the rig steps with the mat's force of the
    previous point, then the contact takes the rig's new position."""
    s, vr, _, set_real, get_real = _rig_slave(version)
    set_real([vr[k] for k in ("mass", "g", "fInt", "velocity", "muStrip", "cStrip")],
             [rig.mass_kg, rig.g, rig.f_int_N, rig.velocity_m_s, rig.mu_strip, rig.c_strip])
    _start(s, version)
    c = ContactFMU(fmi_version=version, instance_name="contact")
    c.initialize(params)
    h, T1, T2, t = rig.step_s, 0.0, 0.0, 0.0
    fit = LineFit()
    x1_fit = rig.fit_from * rig.velocity_m_s * n_steps * h
    out = ("u1", "u2", "N", "x1", "x2", "driveForce")
    for _k in range(1, n_steps + 1):
        set_real([vr["T1"], vr["T2"]], [T1, T2])
        s.doStep(t, h)
        t += h
        u1, u2, N, x1, x2, _ = get_real([vr[n] for n in out])
        c.set_inputs(u1, u2, N)
        T1, T2 = c.force()
        c.do_step(h)
        if x1 >= x1_fit:
            fit.add(x1, x2, rig.f_int_N - T1)
    s.terminate()
    s.freeInstance()
    c.close()
    return fit.angle_deg(), fit.mean_drive()


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("mu_strip,c_strip", [(0.0, 0.0), (0.1, 0.0), (0.0, 20.0), (0.05, 20.0)])
def test_rig_fmu_with_the_contact_fmu_gives_the_harness(version, mu_strip, c_strip):
    """The rig FMU (the C rig's step, fmu_src/rig/rig_core.c) against the harness's
    Python, the reference, strip terms included."""
    rig = Rig(mode="dynamic", travel_m=0.1, step_s=2e-4, mu_strip=mu_strip, c_strip=c_strip)
    n = int(math.ceil(rig.travel_m / (rig.velocity_m_s * rig.step_s) - 1e-9))
    phi, drive = cosimulate(version, AGED, rig, n)
    ref = run(AGED, rig)
    # Same scheme; the FMU counts time as a sum of steps where the harness
    # multiplies k h, so the positions agree to rounding.
    assert phi == pytest.approx(ref.phi_deg, abs=1e-9)
    assert drive == pytest.approx(ref.drive_mean_N, rel=1e-12)
    assert abs(phi) > 1.0  # the aged mat turns the block


# -- every output finite before OK ------------------------------------------------
# x1 = u1 = velocity time: velocity up to 1e6 m/s and any finite time are each
# accepted, but their product can overflow.  Each way in is refused with an
# error and a logged reason, and changes nothing.

def _refused(call, messages, why):
    from fmpy.fmi1 import FMICallException
    n = len(messages)
    with pytest.raises(FMICallException):
        call()
    assert any(status == 3 and why in text for status, text in messages[n:]), messages[n:]


@pytest.mark.parametrize("version", [2, 3])
def test_rig_fmu_refuses_a_start_time_whose_x1_overflows(version):
    messages = []
    s, vr, _, set_real, get_real = _rig_slave(version, messages=messages)
    set_real([vr["velocity"]], [1e6])
    if version == 2:
        _refused(lambda: s.setupExperiment(startTime=1e303), messages, "overflows")
        s.enterInitializationMode()  # at the time it had: 0
    else:
        _refused(lambda: s.enterInitializationMode(startTime=1e303), messages, "overflows")
        s.enterInitializationMode(startTime=0.0)  # still instantiated: it may enter now
    s.exitInitializationMode()
    assert get_real([vr["time"], vr["x1"], vr["u1"], vr["velocity"]]) == [0.0, 0.0, 0.0, 1e6]


@pytest.mark.parametrize("version", [2, 3])
def test_rig_fmu_refuses_a_velocity_whose_x1_overflows_at_the_start_time(version):
    messages = []
    s, vr, _, set_real, get_real = _rig_slave(version, messages=messages)
    if version == 2:
        s.setupExperiment(startTime=1e303)  # x1 = 0.244 * 1e303: finite
        s.enterInitializationMode()
    else:
        s.enterInitializationMode(startTime=1e303)
    _refused(lambda: set_real([vr["velocity"]], [1e6]), messages, "overflows")
    assert get_real([vr["velocity"], vr["x1"]]) == [0.244, 0.244 * 1e303]


@pytest.mark.parametrize("version", [2, 3])
def test_rig_fmu_refuses_a_step_whose_x1_overflows(version):
    messages = []
    s, vr, _, set_real, get_real = _rig_slave(version, messages=messages)
    set_real([vr["velocity"]], [1e6])
    t0 = 1.7e302  # x1 = 1.7e308, just below the largest double
    if version == 2:
        s.setupExperiment(startTime=t0)
        s.enterInitializationMode()
    else:
        s.enterInitializationMode(startTime=t0)
    s.exitInitializationMode()
    set_real([vr["T1"], vr["T2"]], [-5.0, 0.0])  # no lateral motion: only x1 can overflow
    before = get_real([vr["time"], vr["x1"], vr["x2"]])
    assert math.isfinite(before[1])
    _refused(lambda: s.doStep(t0, 1e301), messages, "overflows")
    assert get_real([vr["time"], vr["x1"], vr["x2"]]) == before
    s.doStep(t0, 1.0)  # an ordinary step still goes
    assert get_real([vr["time"]]) == [t0 + 1.0]


@pytest.mark.parametrize("version", [2, 3])
def test_rig_fmu_refuses_a_restored_state_whose_x1_overflows(version):
    import struct
    messages = []
    s, vr, _, set_real, get_real = _rig_slave(version, messages=messages)
    set_real([vr["velocity"]], [1e6])
    _start(s, version)
    set_real([vr["T1"], vr["T2"]], [-5.0, 1.0])
    s.doStep(0.0, 1e-3)
    get_state = s.getFMUstate if version == 2 else s.getFMUState
    ser = s.serializeFMUstate if version == 2 else s.serializeFMUState
    des = s.deSerializeFMUstate if version == 2 else s.deserializeFMUState
    data = bytearray(ser(get_state()))
    # the glue's header: tag, format, length, phase (4 bytes each), then the time
    assert struct.unpack_from("<d", data, 16)[0] == 1e-3
    struct.pack_into("<d", data, 16, 1e303)
    before = get_real([vr["time"], vr["x1"], vr["x2"]])
    _refused(lambda: des(bytes(data)), messages, "overflows")
    assert get_real([vr["time"], vr["x1"], vr["x2"]]) == before
    # the untouched bytes still restore
    struct.pack_into("<d", data, 16, 1e-3)
    (s.setFMUstate if version == 2 else s.setFMUState)(des(bytes(data)))
    assert get_real([vr["time"], vr["x1"], vr["x2"]]) == before
