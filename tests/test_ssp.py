"""The experiment as an SSP: `orthocontact ssp` writes a package that runs
unchanged in libcosim, and its trajectory angle is the harness's."""
import json
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

from orthocontact.experiment.scenario import load
from orthocontact.rig.harness import LineFit, run

ROOT = Path(__file__).resolve().parents[1]

_LIBCOSIM = r"""
import sys, json
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimLogging import log_output_level, CosimLogLevel
log_output_level(CosimLogLevel.ERROR)
ex = CosimExecution.from_ssp_file(sys.argv[1])
rig = {i.name.decode(): i.index for i in ex.slave_infos()}["rig"]
vr = {v.name.decode(): v.reference for v in ex.slave_variables(rig)}
obs = CosimObserver.create_last_value(); ex.add_observer(observer=obs)
rows = []
for k in range(int(sys.argv[2])):
    assert ex.step()
    rows.append(obs.last_real_values(rig, [vr["x1"], vr["x2"], vr["driveForce"]]))
print(json.dumps(rows))
"""


def test_ssp_runs_in_libcosim_with_the_harness_angle(tmp_path):
    pytest.importorskip("libcosimpy")
    ssp = tmp_path / "aged.ssp"
    p = subprocess.run([sys.executable, "-m", "orthocontact", "ssp", str(ROOT / "scenarios/mat_aged.toml"),
                        "--angle", "39.2", "--out", str(ssp)], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    names = set(zipfile.ZipFile(ssp).namelist())
    assert names == {"SystemStructure.ssd", "resources/OrthotropicContact.fmu",
                     "resources/CarriageBlock.fmu"}
    sc = load(ROOT / "scenarios/mat_aged.toml")
    n = int(np.ceil(sc.rig.travel_m / (sc.rig.velocity_m_s * sc.rig.step_s) - 1e-9))
    q = subprocess.run([sys.executable, "-c", _LIBCOSIM, str(ssp), str(n)], capture_output=True,
                       text=True, timeout=600)
    assert q.returncode == 0, q.stderr[-2000:]
    rows = np.array(json.loads(q.stdout.strip().splitlines()[-1]))  # libcosim logs to stdout
    fit = LineFit()
    for x1, x2, drive in rows:
        if x1 >= sc.rig.fit_from * rows[-1, 0]:
            fit.add(x1, x2, drive)
    ref = run(sc.params_at(39.2), sc.rig)
    assert abs(fit.angle_deg() - ref.phi_deg) <= 0.05  # measured: 6e-11 deg
    assert fit.mean_drive() == pytest.approx(ref.drive_mean_N, rel=1e-6)
    assert abs(ref.phi_deg) > 10  # the aged mat's extremum


def test_ssp_refuses_a_bad_output_and_a_step_study(tmp_path):
    p = subprocess.run([sys.executable, "-m", "orthocontact", "ssp", str(ROOT / "scenarios/mat_aged.toml"),
                        "--angle", "10", "--out", str(tmp_path)], capture_output=True, text=True, timeout=60)
    assert p.returncode == 2 and "is a folder" in p.stderr
    p = subprocess.run([sys.executable, "-m", "orthocontact", "ssp", str(ROOT / "scenarios/step_study.toml"),
                        "--angle", "10", "--out", str(tmp_path / "x.ssp")], capture_output=True, text=True,
                       timeout=60)
    assert p.returncode == 2 and "expected a sweep scenario" in p.stderr
    assert not (tmp_path / "x.ssp").exists()
