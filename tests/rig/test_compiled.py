"""The compiled master gives the fmpy master's angles on every scenario, and
refuses what it cannot run with a clear message."""
import math
import subprocess
import sys
from dataclasses import replace

import pytest

from orthocontact.experiment.scenario import load
from orthocontact.fmu.contact import ContactFMU, FMUError
from orthocontact.fmu.files import find_fmu
from orthocontact.rig.compiled import CMaster
from orthocontact.rig.harness import Rig, run
from orthocontact.runs.batch import run_many
from paths import SCENARIOS

# every scenario the rig runs (the kinds of a body on the contact patch run on rig.planar)
RIG_SCENARIOS = sorted(p.stem for p in SCENARIOS.glob("*.toml")
                   if load(p).kind in ("sweep", "step_study"))


def same_figures(a, b) -> bool:
    """Bit for bit, a NaN (no fit) matching a NaN."""
    return all((math.isnan(x) and math.isnan(y)) or x == y for x, y in zip(a, b, strict=True))


@pytest.mark.parametrize("name", RIG_SCENARIOS)
def test_c_master_gives_the_fmpy_masters_angles(name):
    sc = load(SCENARIOS / f"{name}.toml")
    rig = replace(sc.rig, travel_m=min(sc.rig.travel_m, 0.08))
    if sc.kind == "sweep":
        tasks = [(sc.params_at(a), rig) for a in (0.0, 11.3, 26.6, 39.2, 78.7, 90.0)]
        tasks.append((sc.params_at(39.2), replace(rig, mu_strip=0.1)))
    else:  # the step study: every rule at two steps
        tasks = [(sc.params_at(sc.study["angle_deg"], r), replace(rig, step_s=h))
                 for r in sc.study["rules"] for h in sc.study["steps_s"][:2]]
    cm = CMaster(find_fmu())
    c = cm.run(tasks)
    cm.close()
    with ContactFMU(instance_name="ref") as f:
        py = [run(p, r, fmu=f) for p, r in tasks]
    for got, ref in zip(c, py):
        assert same_figures(got, ref.figures)


@pytest.mark.parametrize("mode,mu_strip,c_strip", [
    ("dynamic", 0.0, 0.0), ("dynamic", 0.1, 0.0), ("dynamic", 0.05, 20.0),
    ("quasistatic", 0.0, 0.0), ("quasistatic", 0.1, 0.0), ("quasistatic", 0.05, 20.0)])
def test_c_master_records_the_fmpy_masters_trajectory_bit_for_bit(mode, mu_strip, c_strip):
    sc = load(SCENARIOS / "case5.toml")
    rig = replace(sc.rig, travel_m=0.05, mode=mode, mu_strip=mu_strip, c_strip=c_strip)
    p = sc.params_at(26.565)
    cm = CMaster(find_fmu())
    try:
        got = cm.record(p, rig, record_every=7)
    finally:
        cm.close()
    with ContactFMU(instance_name="ref") as f:
        ref = run(p, rig, fmu=f, record_every=7)
    assert len(ref.t) > 10
    for col in ("t", "x1", "x2", "T1", "T2", "s1", "s2", "state", "energy", "drive"):
        assert getattr(got, col).tolist() == getattr(ref, col).tolist(), col
    assert got.figures == ref.figures
    assert got.newton_iterations == ref.newton_iterations
    assert (ref.newton_iterations > 0) == (mode == "quasistatic")


def test_the_halves_of_the_fit_range_tell_a_settled_run_from_an_unsettled_one():
    """Both masters fit the angle over each half of the fitted range, bit for
    bit alike.  The aged mat at its extremum slides steadily through the fit
    range (halves within 1e-8 deg, measured 3e-9); Case 2's law in the
    dynamic rig with the default 0.5 m travel is still turning there (halves
    8.0 deg apart at its extremum, beta = 11.31 deg)."""
    aged, case2 = load(SCENARIOS / "mat_aged.toml"), load(SCENARIOS / "case2.toml")
    tasks = [(aged.params_at(39.2), aged.rig), (case2.params_at(11.31), Rig(mode="dynamic"))]
    assert Rig().travel_m == 0.5
    cm = CMaster(find_fmu())
    try:
        c = cm.run(tasks)
    finally:
        cm.close()
    with ContactFMU(instance_name="ref") as f:
        py = [run(p, r, fmu=f, record_every=1 << 30) for p, r in tasks]
    assert [tuple(x) for x in c] == [r.figures for r in py]
    settled, turning = py
    assert abs(settled.phi_head_deg - settled.phi_tail_deg) < 1e-8
    assert abs(settled.phi_deg - settled.phi_tail_deg) < 1e-8
    assert abs(turning.phi_head_deg - turning.phi_tail_deg) > 5.0
    # the whole fit lies between its halves' fits as the trajectory turns one way
    assert turning.phi_tail_deg < turning.phi_deg < turning.phi_head_deg < 0


def test_the_master_describes_its_structs_and_a_drift_is_refused():
    """The structs' layout comes from the library (rm_layout); a description
    ctypes would lay out otherwise, or a field the package does not fill, is
    refused before any call."""
    from orthocontact.fmu.contact import FMUError
    from orthocontact.rig.compiled import filled, layout_text, structs_from_layout
    text = layout_text()
    assert "struct rig_figures" in text and "phi_tail_deg" in text
    structs = structs_from_layout(text)
    assert set(structs) == {"rm_contact", "rig_setup", "rig_figures"}
    shifted = text.replace("mu2 8 double", "mu2 12 double")
    assert shifted != text
    with pytest.raises(FMUError, match="rm_contact"):
        structs_from_layout(shifted)
    with pytest.raises(FMUError, match="does not read"):
        structs_from_layout(text.replace("rule 48 int", "rule 48 float"))
    with pytest.raises(FMUError, match="fields"):
        filled(structs["rig_setup"], mass=1.0)


@pytest.mark.parametrize("name", ["mat_aged", "case5"])
def test_run_grid_gives_runs_figures_bit_for_bit(name):
    """The uq path (numpy-filled structs) against run() (one struct per task)."""
    sc = load(SCENARIOS / f"{name}.toml")
    rig = replace(sc.rig, travel_m=min(sc.rig.travel_m, 0.05))
    laws = [sc.law, sc.law.replace(mu1=0.35, eps1=sc.law.eps1 * 1.1), sc.law.replace(rule="associated")]
    angles = (0.0, 26.6, 39.2, 90.0)
    axes = [(sc.params_at(a).alpha, sc.params_at(a).beta) for a in angles]
    cm = CMaster(find_fmu())
    grid = cm.run_grid(laws, axes, rig)
    runs = cm.run([(law.replace(alpha=a, beta=b), rig) for law in laws for a, b in axes])
    cm.close()
    assert grid.shape == (len(laws), len(axes), 4)
    for k, r in enumerate(runs):
        assert same_figures(grid[k // len(axes), k % len(axes)], r), (k, r)


def test_c_master_record_refuses_a_bad_interval():
    cm = CMaster(find_fmu())
    try:
        with pytest.raises(ValueError, match="whole number >= 1"):
            sc = load(SCENARIOS / "case5.toml")
            cm.record(sc.params_at(0.0), sc.rig, 0)
    finally:
        cm.close()


def test_c_master_refuses_an_fmi3_fmu_clearly(tmp_path):
    with pytest.raises(ValueError, match="FMI 2.0"):
        CMaster(find_fmu(fmi_version=3))
    p = subprocess.run([sys.executable, "-m", "orthocontact", "run", str(SCENARIOS / "case4.toml"),
                        "--out", str(tmp_path / "o"), "--fmi", "3", "--master", "c"],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 2 and "--master c runs FMI 2.0 FMUs" in p.stderr
    assert "Traceback" not in p.stderr and not (tmp_path / "o").exists()
    with pytest.raises(ValueError, match="FMI 2.0"):
        run_many([], 2, find_fmu(fmi_version=3), "t", progress=False, master="c")


# -- lanes: the master advances two runs in turn (master_src/rig_master.c) -------

@pytest.fixture
def master():
    cm = CMaster(find_fmu())
    yield cm
    cm.close()


def test_a_batch_gives_each_runs_figures_as_alone(master):
    sc = load(SCENARIOS / "mat_aged.toml")
    short, long_ = replace(sc.rig, travel_m=0.03), replace(sc.rig, travel_m=0.07)
    quasi = replace(short, mode="quasistatic", step_s=1e-3)
    # lengths and modes differ, so the two lanes finish runs at different
    # steps and take the next set in an order no single lane would
    tasks = [(sc.params_at(0.0), long_), (sc.params_at(30.0), short), (sc.params_at(45.0), quasi),
             (sc.params_at(60.0), short), (sc.params_at(39.2), replace(long_, mu_strip=0.1)),
             (sc.params_at(90.0), long_), (sc.params_at(11.3), quasi)]
    batch = master.run(tasks)
    alone = [master.run([t])[0] for t in tasks]
    assert len(batch) == len(tasks)
    for k, (b, a) in enumerate(zip(batch, alone)):
        assert same_figures(b, a), (k, b, a)
    # and in reverse order: no figure depends on which lane ran it
    assert all(same_figures(b, a) for b, a in zip(master.run(tasks[::-1]), alone[::-1]))


def test_a_failing_run_stops_the_batch_with_its_message(master):
    sc = load(SCENARIOS / "mat_aged.toml")
    ok = replace(sc.rig, travel_m=0.03)
    endless = replace(ok, travel_m=1e10, velocity_m_s=1e-10, step_s=1e-10)  # 1e30 steps
    tasks = [(sc.params_at(0.0), ok), (sc.params_at(10.0), ok), (sc.params_at(20.0), endless),
             (sc.params_at(30.0), ok)]
    with pytest.raises(FMUError, match="not a whole number of steps"):
        master.run(tasks)
    # the master is usable after the failure, its instances freed
    assert same_figures(master.run(tasks[:1])[0], master.run([tasks[0]])[0])
