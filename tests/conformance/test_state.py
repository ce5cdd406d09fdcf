"""Every model of OC_MODELS, both FMI versions: a state saved mid-run
(fmi2GetFMUstate / fmi3GetFMUState) restores into its own instance, and,
serialized, into a freshly instantiated one (nothing set, not initialized)
in this process and in another, and each continues bit for bit, every
output (FMI 3.0's arrays too) at every step.  The run's parameters are
moved off their starts (drive.changed_parameters: FMI 3.0's structural
parameters among them), so the state must carry them into the fresh
instance.  Nothing here names a model."""
from __future__ import annotations

import json
import subprocess
import sys

import pytest

from conformance.drive import Instance, changed_parameters, clock, input_rows
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.variables import models
from paths import TESTS

VERSIONS = (2, 3)


def _continue(f: Instance, rows, t, steps) -> list[list[float]]:
    """Every output after each step of rows."""
    out = []
    for row, tk, hk in zip(rows, t, steps):
        f.step(row, tk, hk)
        out.append(f.snapshot())
    return out


def _saved_mid_run(model: str, version: int):
    """(instance, its state's handle, the state serialized, the outputs when
    saved, the rows, times and steps after it, the outputs over them): the
    drive's run with changed parameters, saved half way."""
    rows = input_rows(model)
    t, steps = clock("grid", len(rows))
    half = len(rows) // 2
    a = Instance(model, version, find_fmu(fmi_version=version, model=model), "saved")
    a.set(changed_parameters(model))
    a.start()
    _continue(a, rows[:half], t[:half], steps[:half])
    state = a.get_state()
    data = a.serialize(state)
    at_save = a.snapshot()
    rest = (rows[half:], t[half:], steps[half:])
    return a, state, data, at_save, rest, _continue(a, *rest)


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("model", list(models().values()))
def test_a_state_restores_in_its_instance_and_in_a_fresh_one_and_continues_bit_for_bit(model, version):
    a, state, data, at_save, rest, after = _saved_mid_run(model, version)
    try:
        a.set_state(state)
        assert a.snapshot() == at_save
        assert _continue(a, *rest) == after
        a.free_state(state)
    finally:
        a.free()
    b = Instance(model, version, find_fmu(fmi_version=version, model=model), "fresh")
    try:
        b.set_state(b.deserialize(data))
        assert b.snapshot() == at_save
        changed = changed_parameters(model)
        assert dict(zip(changed, b.get(changed))) == changed
        again = b.get_state()
        assert b.serialize(again) == data   # the same state, the same bytes
        b.free_state(again)
        assert _continue(b, *rest) == after
    finally:
        b.free()


_CHILD = r"""
import json, sys
sys.path.insert(0, sys.argv[2])
from conformance.drive import Instance
spec = json.load(open(sys.argv[1]))
f = Instance(spec["model"], spec["version"], spec["fmu"], "other_process")   # instantiated only
f.set_state(f.deserialize(bytes.fromhex(spec["state"])))
out = [[x.hex() for x in f.snapshot()]]
for row, t, h in zip(spec["rows"], spec["t"], spec["steps"]):
    f.step(row, t, h)
    out.append([x.hex() for x in f.snapshot()])
f.free()
print(json.dumps(out))
"""


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("model", list(models().values()))
def test_a_serialized_state_continues_bit_for_bit_in_another_process(model, version, tmp_path):
    a, state, data, at_save, (rows, t, steps), after = _saved_mid_run(model, version)
    a.free_state(state)
    a.free()
    spec = {"model": model, "version": version, "fmu": str(find_fmu(fmi_version=version, model=model)),
            "state": data.hex(), "rows": rows.tolist(), "t": t.tolist(), "steps": steps.tolist()}
    (tmp_path / "spec.json").write_text(json.dumps(spec))
    proc = subprocess.run([sys.executable, "-c", _CHILD, str(tmp_path / "spec.json"), str(TESTS)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    there = [[float.fromhex(x) for x in r] for r in json.loads(proc.stdout.strip().splitlines()[-1])]
    assert there[0] == at_save
    assert there[1:] == after
