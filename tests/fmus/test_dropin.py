"""The contact FMU as the harness and an importer meet it: both FMI versions
give the same rig results, its serialized state's layout, corrupted states
refused.  What every model must do for every importer (libcosim, Ecos, the
FMU container) and a state restored into a fresh instance anywhere: the
conformance suite (tests/conformance/); the cross-check files:
test_crosscheck.py."""
import math
import struct
import subprocess
import sys

import numpy as np
import pytest

from conftest import CASE5, G_N
from orthocontact.fmu.contact import ContactFMU
from orthocontact.fmu.params import ContactParams
from orthocontact.rig.harness import Rig, run
from paths import SCENARIOS

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
        f.set_inputs(3e-4 * k, sign * 1e-4 * math.sin(k),
                     G_N * (1 + 0.2 * math.sin(0.3 * k)) if k % 31 else 0.0)
        f.do_step(1e-3)


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


def test_cli_runs_the_harness_on_either_fmi_version(tmp_path):
    """The real command, in a subprocess: --fmi 3 gives the FMI 2.0 results bit for bit."""
    import json
    sc = tmp_path / "quick.toml"
    sc.write_text((SCENARIOS / "case5.toml").read_text()
                  .replace("step_deg = 1.0", "step_deg = 15.0").replace("travel_m = 0.2", "travel_m = 0.03"))
    summaries = {}
    for v in (2, 3):
        out = tmp_path / f"out{v}"
        proc = subprocess.run([sys.executable, "-m", "orthocontact", "run", str(sc), "--out", str(out),
                               "--fmi", str(v), "--workers", "1"],
                              capture_output=True, text=True, timeout=300)
        assert proc.returncode == 0, proc.stderr
        summaries[v] = json.loads((out / "summary.json").read_text())
        assert summaries[v].pop("fmi_version") == v
        summaries[v].pop("seconds")
    assert summaries[2] == summaries[3]
    assert (tmp_path / "out2" / "sweep.csv").read_text() == (tmp_path / "out3" / "sweep.csv").read_text()
