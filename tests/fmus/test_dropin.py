"""The FMU as an importer meets it: both FMI versions give the same outputs,
a state restores into a fresh instance anywhere, corrupted states are
refused, and a second importer (libcosim) runs it (the cross-check files:
test_crosscheck.py)."""
import math
import pickle
import struct
import subprocess
import sys
from importlib.metadata import version as installed_version
from pathlib import Path

import numpy as np
import pytest
from conftest import CASE5, G_N
from optional_parts import record

from orthocontact import closed_forms as cf
from orthocontact.fmu.contact import ContactFMU
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.params import ContactParams
from orthocontact.rig.harness import Rig, run

ROOT = Path(__file__).resolve().parents[2]
AGED = ContactParams(0.408, 0.625, 1.251e4, 1e4, math.radians(90 + 30), math.radians(30), "coupled")


@pytest.mark.parametrize("params,rig", [
    (CASE5.replace(alpha=0.46, beta=0.46 + math.pi / 2), Rig(mode="quasistatic", travel_m=0.05, step_s=1e-3)),
    (AGED, Rig(mode="dynamic", travel_m=0.05, step_s=2e-4)),
    (AGED.replace(rule="associated"), Rig(mode="dynamic", travel_m=0.05, step_s=2e-4, mu_strip=0.1)),
    (AGED.replace(rule="eq20"), Rig(mode="dynamic", travel_m=0.03, step_s=1e-3))])
def test_both_fmi_versions_give_identical_outputs_on_the_rig(params, rig):
    runs = []
    for v in (2, 3):
        with ContactFMU(fmi_version=v, instance_name=f"v{v}") as f:
            runs.append(run(params, rig, fmu=f))
    a, b = runs
    for key in ("x2", "T1", "T2", "s1", "s2", "energy", "state"):
        assert np.array_equal(getattr(a, key), getattr(b, key)), key
    assert a.phi_deg == b.phi_deg


def _drive(f, ks, sign=1.0):
    for k in ks:
        f.set_inputs(3e-4 * k, sign * 1e-4 * math.sin(k), G_N * (1 + 0.2 * math.sin(0.3 * k)) if k % 31 else 0.0)
        f.do_step(1e-3)


_FRESH_CHILD = r"""
import pickle, sys, math
from orthocontact.fmu import ContactFMU
data = pickle.load(open(sys.argv[1], "rb"))
f = ContactFMU(data["fmu"], instance_name="fresh")   # instantiated only: no parameters, no init
f.set_state(f.deserialize(data["state"]))
f.time = data["time"]
for u in data["inputs"]:
    f.set_inputs(*u)
    f.do_step(1e-3)
o = f.outputs()
print(repr([o[k] for k in ("T1", "T2", "s1", "s2", "dissipatedEnergy", "contactState")]))
"""


@pytest.mark.parametrize("version", [2, 3])
def test_state_restores_into_a_freshly_instantiated_instance_in_another_process(version, tmp_path):
    p = CASE5.replace(alpha=0.5, beta=0.5 + math.pi / 2)
    with ContactFMU(fmi_version=version) as f:
        f.initialize(p)
        _drive(f, range(1, 60))
        st = f.get_state()
        inputs = [(3e-4 * k, -1e-4 * math.cos(k), G_N) for k in range(60, 120)]
        data = {"state": f.serialize(st), "time": f.time, "fmu": str(f.path), "inputs": inputs}
        f.free_state(st)
        for u in inputs:
            f.set_inputs(*u)
            f.do_step(1e-3)
        o = f.outputs()
    here = [o[k] for k in ("T1", "T2", "s1", "s2", "dissipatedEnergy", "contactState")]
    path = tmp_path / "state.pkl"
    path.write_bytes(pickle.dumps(data))
    out = subprocess.run([sys.executable, "-c", _FRESH_CHILD, str(path)], capture_output=True,
                         text=True, check=True).stdout.strip().splitlines()[-1]
    assert eval(out) == here  # repr of floats round-trips: bit for bit


@pytest.mark.parametrize("version", [2, 3])
def test_serialized_state_layout_and_equal_bytes(version):
    """Little-endian header: tag OCST, format 3, length, FMI phase, time; equal
    states give equal bytes however they were reached."""
    with ContactFMU(fmi_version=version, instance_name="a") as a, \
            ContactFMU(fmi_version=version, instance_name="b") as b:
        a.initialize(CASE5)
        _drive(a, range(1, 40))
        st = a.get_state()
        data = a.serialize(st)
        a.free_state(st)
        assert data[:4] == b"OCST"
        fmt, length, phase = struct.unpack_from("<III", data, 4)
        time, = struct.unpack_from("<d", data, 16)
        assert (fmt, length, phase) == (3, len(data), 4) and time == pytest.approx(a.time)
        b.set_state(b.deserialize(data))  # b never initialized
        st2 = b.get_state()
        assert b.serialize(st2) == data
        b.free_state(st2)


@pytest.mark.parametrize("version", [2, 3])
def test_corrupted_states_are_refused_and_change_nothing(version):
    rng = np.random.default_rng(7)
    with ContactFMU(fmi_version=version) as f:
        f.initialize(CASE5)
        _drive(f, range(1, 30))
        st = f.get_state()
        good = f.serialize(st)
        f.free_state(st)
        before = f.outputs()
        bad = [good[:n] for n in (0, 1, 4, 12, 24, len(good) // 2, len(good) - 1)]
        bad.append(good + b"\0")
        for i in rng.choice(len(good), 40, replace=False):   # flipped bytes
            b = bytearray(good)
            b[i] ^= 0xFF
            bad.append(bytes(b))
        bad += [rng.bytes(len(good)) for _ in range(40)]     # random bytes
        bad += [good[:24] + rng.bytes(len(good) - 24) for _ in range(40)]  # valid header
        refused = 0
        for data in bad:
            try:
                s = f.deserialize(data)
            except Exception:  # fmpy raises on the error status; the FMU logged why
                refused += 1
                assert f.messages[-1][0] == 3 and "state" in f.messages[-1][2]
                continue
            # A flip that still decodes to a valid state (e.g. in a low mantissa bit)
            # must restore to finite outputs.
            f.set_state(s)
            assert all(math.isfinite(x) for x in f.outputs().values())
            f.free_state(s)
        assert refused >= len(bad) - 40  # every truncated, random and random-field state
        f.set_state(f.deserialize(good))
        assert f.outputs() == before


# -- a second importer: libcosim (Open Simulation Platform) ---------------------------

_COSIM = r"""
import ctypes, sys, json
import numpy as np
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimSlave import CosimLocalSlave
from libcosimpy.CosimManipulator import CosimManipulator
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimLogging import log_output_level, CosimLogLevel
log_output_level(CosimLogLevel.ERROR)
fmu, step_ns, inputs = sys.argv[1], int(sys.argv[2]), json.loads(sys.argv[3])
ex = CosimExecution.from_step_size(step_size=step_ns)     # libcosim counts time in ns
slave = CosimLocalSlave(fmu_path=fmu, instance_name="contact")
if not slave.ptr():   # libcosim refused the FMU: its own reason, exit 3
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
for u in inputs:
    man.slave_real_values(idx, [vr["u1"], vr["u2"], vr["N"]], u)
    assert ex.step()
    rows.append(obs.last_real_values(idx, [vr[n] for n in ("T1", "T2", "s1", "s2", "dissipatedEnergy")])
                + obs.last_integer_values(idx, [vr["contactState"]]))
print(json.dumps(rows))
"""


def _libcosim(version, inputs, step_ns):
    return subprocess.run([sys.executable, "-c", _COSIM, str(find_fmu(fmi_version=version)),
                           str(step_ns), __import__("json").dumps(inputs)],
                          capture_output=True, text=True, timeout=120)


@pytest.mark.needs("libcosimpy")
@pytest.mark.parametrize("version", [2, 3])
def test_libcosim_runs_the_fmu_like_fmpy(version):
    """On FMI 3.0 the one accepted way out is libcosim's own refusal of the
    version (it reads FMI 1.0 and 2.0 model descriptions only, and refuses
    before it loads the binary): recorded as not run.  A crash or any other
    error is a failure."""
    h = 1e-3
    inputs = [[2e-4 * k, 1.5e-4 * math.sin(0.05 * k), G_N if k % 97 > 10 else 0.0] for k in range(300)]
    proc = _libcosim(version, inputs, int(round(h * 1e9)))
    if version == 3 and proc.returncode == 3:
        said = proc.stderr.strip().splitlines()[-1]
        assert said == ("libcosim refused the FMU: Unsupported feature: Unsupported FMI version for FMU "
                        f"'{find_fmu(fmi_version=3)}'"), proc.stderr[-2000:]
        why = f"libcosimpy {installed_version('libcosimpy')} refuses FMI 3.0 FMUs: 'Unsupported FMI version'"
        record("libcosim-fmi3", why)
        pytest.skip(why)
    assert proc.returncode == 0, proc.stderr[-2000:]
    if version == 3:
        record("libcosim-fmi3", None)
    cosim = np.array(__import__("json").loads(proc.stdout.strip().splitlines()[-1]))
    with ContactFMU(fmi_version=version, instance_name="fmpy") as f:
        f.initialize(ContactParams(0.408, 0.625, 12510.0, 1e4, math.pi / 2, 0.0))  # the defaults
        rows = []
        for u in inputs:
            f.set_inputs(*u)
            f.do_step(h)
            o = f.outputs()
            rows.append([o[k] for k in ("T1", "T2", "s1", "s2", "dissipatedEnergy", "contactState")])
    assert np.array_equal(cosim, np.array(rows))
    assert set(cosim[:, 5]) == {0, 1, 2}  # the path opened, stuck and slid


def test_cli_runs_the_harness_on_either_fmi_version(tmp_path):
    """The real command, in a subprocess: --fmi 3 gives the FMI 2.0 results bit for bit."""
    import json
    sc = tmp_path / "quick.toml"
    sc.write_text((ROOT / "scenarios" / "case5.toml").read_text()
                  .replace("step_deg = 1.0", "step_deg = 15.0").replace("travel_m = 0.2", "travel_m = 0.03"))
    summaries = {}
    for v in (2, 3):
        out = tmp_path / f"out{v}"
        proc = subprocess.run([sys.executable, "-m", "orthocontact", "run", str(sc), "--out", str(out),
                               "--fmi", str(v), "--workers", "1"], capture_output=True, text=True, timeout=300)
        assert proc.returncode == 0, proc.stderr
        summaries[v] = json.loads((out / "summary.json").read_text())
        assert summaries[v].pop("fmi_version") == v
        summaries[v].pop("seconds")
    assert summaries[2] == summaries[3]
    assert (tmp_path / "out2" / "sweep.csv").read_text() == (tmp_path / "out3" / "sweep.csv").read_text()
