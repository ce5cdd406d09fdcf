"""The experiment as an SSP: `orthocontact ssp` writes a package that runs
unchanged in libcosim, Ecos, fmpy's SSP reader and fmu-manipulation-toolbox's
container, and its trajectory angle is the harness's in each.

Tolerance of the angle: every tool runs the same FMU binaries at the same
communication step, so the trajectories differ only by the order of
floating-point operations (and, in Ecos, a last-digit reading of the SSD's
decimal values): measured 6e-11 deg.  1e-6 deg is far above that and far
below anything a wrong parameter gives (the FMUs' defaults give 0 deg here,
the answer is -11.526 deg)."""
import json
import subprocess
import sys
import zipfile

import numpy as np
import pytest

from libcosim_rig import run_rig_ssp
from orthocontact.experiment.scenario import load
from orthocontact.experiment.ssp import contact_values, rig_values
from orthocontact.fmu.start_values import start_values_of
from orthocontact.rig.harness import LineFit, run
from paths import SCENARIOS

ANGLE = 39.2          # the aged mat's extremum
TOLERANCE_DEG = 1e-6  # see the module's docstring


@pytest.fixture(scope="module")
def aged():
    return load(SCENARIOS / "mat_aged.toml")


@pytest.fixture(scope="module")
def harness(aged):
    ref = run(aged.params_at(ANGLE), aged.rig)
    assert abs(ref.phi_deg) > 10   # the aged mat's extremum: far from the defaults' 0
    return ref


@pytest.fixture(scope="module")
def package(tmp_path_factory):
    ssp = tmp_path_factory.mktemp("ssp") / "aged.ssp"
    p = subprocess.run([sys.executable, "-m", "orthocontact", "ssp", str(SCENARIOS / "mat_aged.toml"),
                        "--angle", str(ANGLE), "--out", str(ssp)], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 0, p.stderr
    return ssp


def fitted(sc, x1, x2, drive) -> LineFit:
    """The rig's line fit over the trajectory, as the harness fits it."""
    fit = LineFit()
    for a, b, c in zip(x1, x2, drive):
        if a >= sc.rig.fit_from * x1[-1]:
            fit.add(a, b, c)
    return fit


def steps(sc) -> int:
    return int(np.ceil(sc.rig.travel_m / (sc.rig.velocity_m_s * sc.rig.step_s) - 1e-9))


@pytest.mark.needs("libcosimpy")
def test_ssp_runs_in_libcosim_with_the_harness_angle(tmp_path):
    ssp = tmp_path / "aged.ssp"
    p = subprocess.run([sys.executable, "-m", "orthocontact", "ssp", str(SCENARIOS / "mat_aged.toml"),
                        "--angle", "39.2", "--out", str(ssp)], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    names = set(zipfile.ZipFile(ssp).namelist())
    assert names == {"SystemStructure.ssd", "resources/OrthotropicContact.fmu",
                     "resources/CarriageBlock.fmu"}
    sc = load(SCENARIOS / "mat_aged.toml")
    n = int(np.ceil(sc.rig.travel_m / (sc.rig.velocity_m_s * sc.rig.step_s) - 1e-9))
    rows = np.array(run_rig_ssp(ssp, n))
    fit = LineFit()
    for x1, x2, drive in rows:
        if x1 >= sc.rig.fit_from * rows[-1, 0]:
            fit.add(x1, x2, drive)
    ref = run(sc.params_at(39.2), sc.rig)
    assert abs(fit.angle_deg() - ref.phi_deg) <= 0.05  # measured: 6e-11 deg
    assert fit.mean_drive() == pytest.approx(ref.drive_mean_N, rel=1e-6)
    assert abs(ref.phi_deg) > 10  # the aged mat's extremum


def test_ssp_refuses_a_bad_output_and_a_step_study(tmp_path):
    p = subprocess.run([sys.executable, "-m", "orthocontact", "ssp", str(SCENARIOS / "mat_aged.toml"),
                        "--angle", "10", "--out", str(tmp_path)], capture_output=True, text=True, timeout=60)
    assert p.returncode == 2 and "is a folder" in p.stderr
    p = subprocess.run([sys.executable, "-m", "orthocontact", "ssp", str(SCENARIOS / "step_study.toml"),
                        "--angle", "10", "--out", str(tmp_path / "x.ssp")], capture_output=True, text=True,
                       timeout=60)
    assert p.returncode == 2 and "expected a sweep scenario" in p.stderr
    assert not (tmp_path / "x.ssp").exists()


def test_the_fmus_inside_carry_the_scenarios_values(package, aged, tmp_path):
    with zipfile.ZipFile(package) as z:
        z.extractall(tmp_path)
        ssd = z.read("SystemStructure.ssd").decode()
    contact = start_values_of(tmp_path / "resources/OrthotropicContact.fmu")
    assert {k: contact[k] for k in contact_values(aged, ANGLE)} == contact_values(aged, ANGLE)
    rig = start_values_of(tmp_path / "resources/CarriageBlock.fmu")
    assert {k: rig[k] for k in rig_values(aged)} == rig_values(aged)
    # the bindings stay too, both sets under one name (Ecos applies one name)
    assert ssd.count('<ssv:ParameterSet version="1.0" name="scenario">') == 2


def test_ssp_runs_in_fmpys_ssp_reader_with_the_harness_angle(package, aged, harness):
    """fmpy's SSP reader ignores the inline parameter bindings: the FMUs'
    own start values are what makes it right."""
    from fmpy.ssp.simulation import simulate_ssp
    r = simulate_ssp(str(package), stop_time=aged.rig.travel_m / aged.rig.velocity_m_s,
                     step_size=aged.rig.step_s)
    fit = fitted(aged, r["rig.x1"], r["rig.x2"], r["rig.driveForce"])
    assert abs(fit.angle_deg() - harness.phi_deg) <= TOLERANCE_DEG   # measured 6e-11 deg
    assert fit.mean_drive() == pytest.approx(harness.drive_mean_N, rel=1e-9)


_ECOS = r"""
import sys, json
from ecospy import EcosSimulation, EcosLib
EcosLib.set_log_level("warn")
ssp, n, h = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
pset = sys.argv[4] or None
with EcosSimulation(ssp_path=ssp, step_size=h) as sim:
    assert sim.init(parameter_set=pset)
    rows = []
    for k in range(n):
        sim.step()
        rows.append([sim.get_real("rig::" + v) for v in ("x1", "x2", "driveForce")])
    alpha = sim.get_real("contact::alpha")
    sim.terminate()
print(json.dumps({"rows": rows, "alpha": alpha}))
"""


@pytest.mark.needs("ecospy")   # its library needs Debian's libtbb12 (tools/run_tests.sh installs it)
@pytest.mark.parametrize("parameter_set", ["", "scenario"], ids=["no-set", "named-set"])
def test_ssp_runs_in_ecos_with_the_harness_angle(package, aged, harness, parameter_set):
    q = subprocess.run([sys.executable, "-c", _ECOS, str(package), str(steps(aged)), repr(aged.rig.step_s),
                        parameter_set], capture_output=True, text=True, timeout=600)
    assert q.returncode == 0, q.stderr[-2000:]
    out = json.loads(q.stdout.strip().splitlines()[-1])
    rows = np.array(out["rows"])
    fit = fitted(aged, rows[:, 0], rows[:, 1], rows[:, 2])
    assert abs(fit.angle_deg() - harness.phi_deg) <= TOLERANCE_DEG   # measured 6e-11 deg
    assert fit.mean_drive() == pytest.approx(harness.drive_mean_N, rel=1e-9)
    assert out["alpha"] == pytest.approx(aged.params_at(ANGLE).alpha, rel=1e-15)


_CONTAINER = r"""
import sys, json
from pathlib import Path
from fmpy import simulate_fmu
from fmu_manipulation_toolbox.assembly import Assembly
folder, n, h = Path(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3])
assembly = Assembly("aged.ssp", default_step_size=h, fmu_directory=folder)
rig = next(f for f in assembly.root.fmu_names_list if f.endswith("CarriageBlock.fmu"))
for c in ("x1", "x2", "driveForce"):
    assembly.root.add_output(rig, c, c)
assembly.make_fmu()
r = simulate_fmu(str(folder / "aged.fmu"), stop_time=n * h, step_size=h, output_interval=h,
                 output=["x1", "x2", "driveForce"])
print(json.dumps([r["x1"].tolist(), r["x2"].tolist(), r["driveForce"].tolist()]))
"""


@pytest.mark.needs("fmu_manipulation_toolbox")
def test_ssp_runs_as_fmu_manipulation_toolbox_container_with_the_harness_angle(package, aged, harness,
                                                                               tmp_path):
    """The container is built from the SSP itself (in a process of its own,
    as the other tools: it loads the FMUs' libraries again); it ignores
    parameter bindings, and it exposes only the system's outputs, which this
    SSD cannot declare (libcosim refuses a connection to the system's own
    connectors: "No such node (<xmlattr>.endElement)"), so the three
    measured outputs are added through the toolbox's API."""
    (tmp_path / "aged.ssp").write_bytes(package.read_bytes())
    q = subprocess.run([sys.executable, "-c", _CONTAINER, str(tmp_path), str(steps(aged)),
                        repr(aged.rig.step_s)], capture_output=True, text=True, timeout=600)
    assert q.returncode == 0, q.stderr[-2000:]
    x1, x2, drive = json.loads(q.stdout.strip().splitlines()[-1])
    fit = fitted(aged, x1, x2, drive)
    assert abs(fit.angle_deg() - harness.phi_deg) <= TOLERANCE_DEG   # measured 6e-11 deg
    assert fit.mean_drive() == pytest.approx(harness.drive_mean_N, rel=1e-9)


def test_the_ssp_command_says_when_its_dynamic_rig_would_not_settle(tmp_path):
    """The SSP's CarriageBlock integrates the block's lateral inertia whatever
    the scenario's mode: Case 2 at its extremum settles over 0.40 m (the
    model notes' figure), far beyond its 0.2 m travel."""
    cmd = [sys.executable, "-m", "orthocontact", "ssp"]
    p = subprocess.run(cmd + [str(SCENARIOS / "case2.toml"), "--angle", "11.31", "--out", "c2.ssp"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0 and (tmp_path / "c2.ssp").is_file()
    assert p.stderr.startswith("orthocontact: warning: case2 at 11.31 deg: the system's dynamic rig settles "
                               "over 0.403 m") and "rig.travel_m >=" in p.stderr
    p = subprocess.run(cmd + [str(SCENARIOS / "mat_aged.toml"), "--angle", "39.2", "--out", "a.ssp"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0 and p.stderr == ""


def test_a_killed_ssps_scratch_goes_with_the_next_package_written_there(tmp_path):
    """The FMUs and the package are made in a locked folder beside --out
    (.rig.ssp.partial-*; they were in the system's temp folder and a
    .rig.ssp.partial file, both left by a SIGKILL): `ssp` killed while it
    writes leaves it, the next `ssp` into that path removes it, and a
    package written leaves nothing else."""
    import os
    import signal
    import time
    cmd = [sys.executable, "-m", "orthocontact", "ssp", str(SCENARIOS / "mat_aged.toml"),
           "--angle", "10", "--out", "rig.ssp"]

    def partials():
        return list(tmp_path.glob(".rig.ssp.partial-*"))
    for _ in range(10):   # until the kill lands while it writes (it writes for a fraction of a second)
        proc = subprocess.Popen(cmd, cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        while proc.poll() is None and not partials():
            time.sleep(0.002)
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(timeout=30)
        if partials() and not (tmp_path / "rig.ssp").exists():
            break
        (tmp_path / "rig.ssp").unlink(missing_ok=True)
    assert len(partials()) == 1, sorted(os.listdir(tmp_path))
    p = subprocess.run(cmd, cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    assert sorted(os.listdir(tmp_path)) == ["rig.ssp"]
    assert zipfile.ZipFile(tmp_path / "rig.ssp").testzip() is None
