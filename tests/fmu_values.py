"""What an FMU file holds as an importer that sets nothing sees it: the
parameters' values of a fresh instance, and the FMI schema's errors on its
model description; and one unpacked copy of an FMU per test process
(unzipped), removed when the process ends.  Shared by the FMU tests."""
import atexit
import os
import shutil
import tempfile
import zipfile

import fmpy
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave
from lxml import etree

_UNZIPPED: dict = {}


def unzipped(path) -> str:
    """The FMU at `path` unpacked once in this process (again if the file
    changed), for fmpy's Slave classes: fmpy's extract() makes a new
    temporary folder a call and leaves it behind, which a test making an
    instance per perturbation multiplied into thousands.  The folders go
    when the process ends."""
    path = os.path.abspath(str(path))
    stat = os.stat(path)
    key = (path, stat.st_mtime_ns, stat.st_size)
    if key not in _UNZIPPED:
        if not _UNZIPPED:
            atexit.register(lambda: [shutil.rmtree(d, ignore_errors=True) for d in _UNZIPPED.values()])
        folder = tempfile.mkdtemp(prefix="orthocontact-test-fmu-")
        _UNZIPPED[key] = extract(path, unzipdir=folder)
    return _UNZIPPED[key]


def values_with_nothing_set(path, names):
    """The parameters' values of a fresh instance of the FMU at `path`
    initialized without any value set: the binary's own start values."""
    md = read_model_description(str(path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    kind = {v.name: v.type for v in md.modelVariables}
    fmi3 = md.fmiVersion.startswith("3")
    slave = (FMU3Slave if fmi3 else FMU2Slave)(
        guid=md.guid, unzipDirectory=unzipped(path), modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="nothing_set")
    try:
        slave.instantiate()
        if fmi3:
            slave.enterInitializationMode()
        else:
            slave.setupExperiment(startTime=0.0)
            slave.enterInitializationMode()
        slave.exitInitializationMode()
        out = {}
        for n in names:
            if kind[n] in ("Real", "Float64"):
                out[n] = (slave.getFloat64 if fmi3 else slave.getReal)([vr[n]])[0]
            elif fmi3:
                out[n] = slave.getInt64([vr[n]])[0]
            else:
                out[n] = slave.getInteger([vr[n]])[0]
        slave.terminate()
        return out
    finally:
        slave.freeInstance()


def schema_errors(path):
    """The FMI standard's XSD (shipped with fmpy) on the model description."""
    xml = etree.fromstring(zipfile.ZipFile(path).read("modelDescription.xml"))
    version = "fmi3" if xml.get("fmiVersion").startswith("3") else "fmi2"
    schema = etree.XMLSchema(file=os.path.join(os.path.dirname(fmpy.__file__), "schema", version,
                                               f"{version}ModelDescription.xsd"))
    schema.validate(xml)
    return [str(e) for e in schema.error_log]
