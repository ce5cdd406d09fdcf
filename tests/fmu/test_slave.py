"""One way to instantiate an FMU through fmpy, FMI 2.0 and 3.0, every model:
the instance works, its log reaches the caller decoded, and free() frees it
whether or not it was initialized (or its terminate fails)."""
import pytest
from fmpy.fmi1 import FMICallException

from orthocontact.fmu.files import find_fmu, model_description
from orthocontact.fmu.slave import FreedOnClose, free, instantiate, integer_call
from orthocontact.fmu.variables import models


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("model", list(models().values()))
def test_an_instance_of_every_model_logs_what_it_refuses(model, version):
    path = find_fmu(fmi_version=version, model=model)
    md = model_description(path)
    said = []
    s, keep = instantiate(path, md, "probe", lambda status, category, text: said.append((status, text)),
                          logging_on=True)
    assert keep   # the callbacks the caller must keep alive
    time_vr = next(v.valueReference for v in md.modelVariables if v.name == "time")
    set_real = s.setReal if version == 2 else s.setFloat64
    with pytest.raises(FMICallException):   # fmpy raises on the error status
        set_real([time_vr], [1.0])   # the independent variable cannot be set
    assert said and all(isinstance(t, str) for _, t in said), said
    assert any("time" in t or str(time_vr) in t for _, t in said), said
    free(s, initialized=False)


@pytest.mark.parametrize("version", [2, 3])
def test_free_after_initialization_terminates_first(version):
    path = find_fmu(fmi_version=version)
    md = model_description(path)
    s, keep = instantiate(path, md, "probe", lambda *a: None)
    if version == 2:
        s.setupExperiment()
    s.enterInitializationMode()
    s.exitInitializationMode()
    free(s, initialized=True)
    s2, keep2 = instantiate(path, md, "probe", lambda *a: None)
    s2.terminate = lambda: (_ for _ in ()).throw(Exception("terminate failed"))
    free(s2, initialized=True)   # a failed terminate still frees


def test_an_owner_frees_its_instance_once_on_close_and_on_leaving_with():
    freed = []

    class Slave:
        def terminate(self):
            freed.append("terminate")

        def freeInstance(self):
            freed.append("free")

    class Owner(FreedOnClose):
        def __init__(self):
            self._slave, self.initialized = Slave(), True

    with Owner() as o:
        pass
    o.close()
    assert freed == ["terminate", "free"] and o._slave is None


@pytest.mark.parametrize("version", [2, 3])
def test_an_interrupt_while_fmpy_loads_the_binary_leaves_the_working_folder(tmp_path, monkeypatch, version):
    """fmpy loads the binary with the working folder changed to the FMU's
    and changes it back after: SIGINT right as the library loads used to
    raise between the two, and the interrupted command ran on in the FMU's
    folder (its relative staging folder then stayed: 2 runs of 50 of the
    interrupt test).  Now the interrupt comes after the folder is back."""
    import ctypes
    import os
    import signal

    import fmpy.fmi1
    load = ctypes.cdll.LoadLibrary

    def load_and_interrupt(path):
        os.kill(os.getpid(), signal.SIGINT)   # arrives as the library loads
        return load(path)
    monkeypatch.setattr(fmpy.fmi1.cdll, "LoadLibrary", load_and_interrupt)
    monkeypatch.chdir(tmp_path)
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    path = find_fmu(fmi_version=version)
    try:
        with pytest.raises(KeyboardInterrupt):
            instantiate(path, model_description(path), "probe", lambda *a: None)
        assert os.getcwd() == str(tmp_path)
    finally:
        signal.signal(signal.SIGINT, old)


def test_an_owner_closed_twice_frees_once_even_if_interrupted_in_between():
    """close() forgets the instance before it frees it: an interrupt right
    after the free used to leave it remembered, and the owner's collection
    freed it again (a double free: the process crashed)."""
    freed = []

    class Slave:
        def freeInstance(self):
            freed.append("free")
            if len(freed) == 1:
                raise KeyboardInterrupt   # as a signal arriving when the call returns

    class Owner(FreedOnClose):
        def __init__(self):
            self._slave = Slave()

    o = Owner()
    with pytest.raises(KeyboardInterrupt):
        o.close()
    o.close()
    del o
    assert freed == ["free"]


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("model", list(models().values()))
def test_every_integer_parameter_round_trips_through_its_types_call(model, version):
    """integer_call picks the call of each integer parameter's declared type
    (FMI 3.0: Int32, UInt64 for an array's dimension, Int64 for an
    enumeration; FMI 2.0: Integer): its start value set before
    initialization reads back after it; a type without one is refused."""
    path = find_fmu(fmi_version=version, model=model)
    md = model_description(path)
    ints = [v for v in md.modelVariables if v.causality in ("parameter", "structuralParameter")
            and v.type not in ("Real", "Float64")]   # none in the rig
    s, keep = instantiate(path, md, "integers", lambda *a: None)
    try:
        for v in ints:
            integer_call(s, version, v.type)([v.valueReference], [int(v.start)])
        if version == 2:
            s.setupExperiment()
        s.enterInitializationMode()
        s.exitInitializationMode()
        got = [integer_call(s, version, v.type, get=True)([v.valueReference])[0] for v in ints]
        assert got == [int(v.start) for v in ints]
    finally:
        free(s, initialized=True)
    with pytest.raises(ValueError, match="no FMI 3.0 integer function"):
        integer_call(s, 3, "Float64")


@pytest.mark.parametrize("version", [2, 3])
def test_each_instance_hears_only_its_own_messages(version):
    """fmpy's FMI 2.0 logger proxy calls one logger for the whole process,
    the last registered: two live instances, the first refusing a call, and
    the refusal is logged to the first only (its FMUError's reason)."""
    path = find_fmu(fmi_version=version)
    md = model_description(path)
    said = {"first": [], "second": []}
    made = [instantiate(path, md, name, lambda status, category, text, name=name: said[name].append(text))
            for name in said]
    first = made[0][0]
    time_vr = next(v.valueReference for v in md.modelVariables if v.name == "time")
    with pytest.raises(FMICallException):
        (first.setReal if version == 2 else first.setFloat64)([time_vr], [1.0])
    assert said["first"] and said["second"] == [], said
    for s, _ in made:
        free(s, initialized=False)
