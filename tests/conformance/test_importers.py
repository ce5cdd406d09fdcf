"""Every importer the suite has runs every model of OC_MODELS in every FMI
version it reads, its inputs driven (drive.py's rule), and gives fmpy's
outputs bit for bit: fmpy FMI 2.0 and 3.0 (the reference), libcosim, Ecos
(a structure of one model, not an SSP) and fmu-manipulation-toolbox's FMU
container (one model embedded, its inputs and scalar outputs exposed).
Nothing here names a model.

Bit for bit, not within a tolerance: each importer calls the same binary
with the same inputs; only its clock differs (drive.clock: how it rounds
the communication points and steps, measured), and fmpy's reference runs
on that importer's clock.  A model whose outputs depend on time or step
(the rig) then agrees to the last bit too; on another clock it would
differ by about 1e-15 relative.

Compared: the scalar outputs.  FMI 3.0's arrays are not: libcosim and Ecos
have no calls for them, and the toolbox cannot size an array whose
dimension is a structural parameter ("depends on structuralParameter ...
which is not supported"), so its container leaves them out.  An importer
that cannot read a version says so in its own words, and is recorded not
run for it (tests/optional_parts.py); any other failure fails."""
from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import dataclass, field
from importlib.metadata import version as installed_version

import numpy as np
import pytest

from conformance.drive import STEP, clock, input_rows, inputs, outputs, run_fmpy
from optional_parts import record
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.variables import models

VERSIONS = (2, 3)

# Each script reads the spec (json, argv[1]): fmu, version, h, inputs (names),
# rows, outputs ([name, "real" | "int"]), t and steps (the clock's), work (a
# folder); prints the outputs after each step as a json list on its last
# line, or exits 3 with the importer's own refusal of the FMU on stderr.

_LIBCOSIM = r"""
import ctypes, json, sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimSlave import CosimLocalSlave
from libcosimpy.CosimManipulator import CosimManipulator
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimLogging import log_output_level, CosimLogLevel
log_output_level(CosimLogLevel.ERROR)
spec = json.load(open(sys.argv[1]))
ex = CosimExecution.from_step_size(step_size=round(spec["h"] * 1e9))   # libcosim counts time in ns
slave = CosimLocalSlave(fmu_path=spec["fmu"], instance_name="model")
if not slave.ptr():
    try:
        from libcosimpy.CosimLibrary import lib
    except ImportError:   # later libcosimpy
        from libcosimpy._internal import libcosimc
        lib = libcosimc()
    lib.cosim_last_error_message.restype = ctypes.c_char_p
    sys.stderr.write("libcosim refused the FMU: " + lib.cosim_last_error_message().decode() + "\n")
    sys.exit(3)
idx = ex.add_local_slave(local_slave=slave)
vr = {v.name.decode(): v.reference for v in ex.slave_variables(idx)}
man = CosimManipulator.create_override(); ex.add_manipulator(manipulator=man)
obs = CosimObserver.create_last_value(); ex.add_observer(observer=obs)
rows = []
for u in spec["rows"]:
    man.slave_real_values(idx, [vr[n] for n in spec["inputs"]], u)
    assert ex.step()
    rows.append([(obs.last_real_values if kind == "real" else obs.last_integer_values)(idx, [vr[n]])[0]
                 for n, kind in spec["outputs"]])
print(json.dumps(rows))
"""

_ECOS = r"""
import json, sys
from ecospy import EcosLib, EcosSimulation, EcosSimulationStructure
EcosLib.set_log_level("warn")
spec = json.load(open(sys.argv[1]))
with EcosSimulationStructure() as ss:
    try:
        ss.add_model("model", spec["fmu"])
    except Exception as e:
        sys.stderr.write(f"Ecos refused the FMU: {e}\n")
        sys.exit(3)
    with EcosSimulation(structure=ss, step_size=spec["h"]) as sim:
        assert sim.init()
        rows = []
        for u in spec["rows"]:
            for n, x in zip(spec["inputs"], u):
                sim.set_real("model::" + n, x)
            sim.step()
            rows.append([(sim.get_real if kind == "real" else sim.get_integer)("model::" + n)
                         for n, kind in spec["outputs"]])
        sim.terminate()
print(json.dumps(rows))
"""

_CONTAINER = r"""
import json, shutil, sys
from pathlib import Path
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave
from fmu_manipulation_toolbox.assembly import AssemblyNode
spec = json.load(open(sys.argv[1]))
work = Path(spec["work"])
inner = Path(spec["fmu"]).name
shutil.copy(spec["fmu"], work / inner)
node = AssemblyNode("container.fmu", step_size=spec["h"], auto_input=False, auto_output=False)
node.add_fmu(inner)
for n in spec["inputs"]:
    node.add_input(n, inner, n)
for n, _ in spec["outputs"]:
    node.add_output(inner, n, n)
v3 = spec["version"] == 3
node.make_fmu(work, fmi_version=spec["version"])   # the container in the embedded FMU's version
path = str(work / "container.fmu")
md = read_model_description(path)
vr = {v.name: v.valueReference for v in md.modelVariables}
s = (FMU3Slave if v3 else FMU2Slave)(guid=md.guid, unzipDirectory=extract(path, unzipdir=str(work / "x")),
                                     modelIdentifier=md.coSimulation.modelIdentifier,
                                     instanceName="container")
s.instantiate()
if v3:
    s.enterInitializationMode(startTime=0.0)
else:
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
s.exitInitializationMode()
set_real = s.setFloat64 if v3 else s.setReal
get = {"real": s.getFloat64 if v3 else s.getReal, "int": s.getInt32 if v3 else s.getInteger}
rows = []
for u, t, h in zip(spec["rows"], spec["t"], spec["steps"]):
    set_real([vr[n] for n in spec["inputs"]], u)
    s.doStep(t, h)
    rows.append([get[kind]([vr[n]])[0] for n, kind in spec["outputs"]])
s.terminate()
s.freeInstance()
print(json.dumps(rows))
"""


@dataclass(frozen=True)
class Importer:
    """One importer: its script, the optional part it needs, its clock
    (drive.clock, measured), and the versions it refuses in its own words
    (version -> (the optional part then recorded not run, the refusal))."""
    name: str
    part: str
    clock: str
    script: str
    refuses: dict = field(default_factory=dict)


IMPORTERS = (
    Importer("libcosim", "libcosimpy", "grid", _LIBCOSIM,
             {3: ("libcosim-fmi3", "libcosim refused the FMU: Unsupported feature: Unsupported FMI version "
                  "for FMU '{fmu}'")}),
    Importer("ecos", "ecospy", "sum", _ECOS),
    Importer("container", "fmu_manipulation_toolbox", "product", _CONTAINER),
)


def _differences(got: np.ndarray, ref: np.ndarray, names) -> list[str]:
    """Per output that differs: its first differing step and both values."""
    out = []
    for j, name in enumerate(names):
        k = np.flatnonzero(got[:, j] != ref[:, j])
        if len(k):
            out.append(f"{name}: {len(k)} steps differ, first k = {k[0]}: {float(got[k[0], j])!r} vs fmpy "
                       f"{float(ref[k[0], j])!r}")
    return out


def _moves(model: str, version: int, run: np.ndarray) -> list[str]:
    """The outputs that ModelStructure says depend on an input but took one
    value over the run: the drive did not reach them."""
    from fmpy import read_model_description
    md = read_model_description(str(find_fmu(fmi_version=version, model=model)))
    names = [v.name for v in outputs(model)]
    ins = {v.name for v in inputs(model)}
    driven = {u.variable.name for u in md.outputs
              if ins & {d.name for d in (u.dependencies or ())}}
    return [n for j, n in enumerate(names) if n in driven and len(set(run[:, j])) < 2]


@pytest.mark.parametrize("model", list(models().values()))
def test_fmpy_runs_every_model_alike_in_both_fmi_versions(model):
    rows = input_rows(model)
    runs = [run_fmpy(model, v, find_fmu(fmi_version=v, model=model), rows) for v in VERSIONS]
    assert _differences(runs[1], runs[0], [v.name for v in outputs(model)]) == []
    for v, run in zip(VERSIONS, runs):
        assert _moves(model, v, run) == [], f"FMI {v}.0: driven outputs that never moved"


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("model", list(models().values()))
@pytest.mark.parametrize("importer", [pytest.param(i, marks=pytest.mark.needs(i.part), id=i.name)
                                      for i in IMPORTERS])
def test_every_importer_runs_every_model_like_fmpy(importer, model, version, tmp_path):
    fmu = find_fmu(fmi_version=version, model=model)
    rows = input_rows(model)
    t, steps = clock(importer.clock, len(rows))
    spec = {"fmu": str(fmu), "version": version, "h": STEP, "inputs": [v.name for v in inputs(model)],
            "rows": rows.tolist(), "outputs": [[v.name, "real" if v.type == "Float64" else "int"]
                                               for v in outputs(model)],
            "t": t.tolist(), "steps": steps.tolist(), "work": str(tmp_path)}
    (tmp_path / "spec.json").write_text(json.dumps(spec))
    proc = subprocess.run([sys.executable, "-c", importer.script, str(tmp_path / "spec.json")],
                          capture_output=True, text=True, timeout=300, cwd=tmp_path)
    if proc.returncode == 3 and version in importer.refuses:
        part, said = importer.refuses[version]
        assert proc.stderr.strip().splitlines()[-1] == said.format(fmu=fmu), proc.stderr[-2000:]
        why = (f"{importer.part} {installed_version(importer.part)} refuses FMI {version}.0 FMUs: "
               f"{proc.stderr.strip().splitlines()[-1]}")
        record(part, why)
        pytest.skip(why)
    assert proc.returncode == 0, proc.stderr[-2000:]
    if version in importer.refuses:
        record(importer.refuses[version][0], None)
    got = np.array(json.loads(proc.stdout.strip().splitlines()[-1]), dtype=float)
    ref = run_fmpy(model, version, fmu, rows, kind=importer.clock)
    assert got.shape == ref.shape
    assert _differences(got, ref, [v.name for v in outputs(model)]) == []
