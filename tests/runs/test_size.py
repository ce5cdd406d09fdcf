"""The size of the work (orthocontact.runs.size): huge work is refused before
it starts unless --yes, with a message naming the keys that set its size;
the step count is the rig's; the estimate counts every run the command
makes, against the runs the compiled master actually made."""
import time
from pathlib import Path

import pytest

from cli_run import run_cli as run
from cli_run import scenario_variant
from orthocontact.errors import InputError
from orthocontact.experiment.scenario import load
from orthocontact.runs.size import (
    LIMIT_RUNS,
    LIMIT_STEPS,
    check_run_size,
    check_scenario_size,
    check_uq_size,
    scenario_work,
    steps_per_run,
    uq_work,
)
from paths import SCENARIOS


def _aged_with(tmp_path, old, new) -> Path:
    return scenario_variant(SCENARIOS / "mat_aged.toml", old, new, tmp_path / "big.toml")


# -- huge work: said before it starts, and progress while it runs ---------------------

@pytest.mark.parametrize("old,new,key", [
    ("step_deg = 1.0", "step_deg = 1e-6", "sweep.step_deg"),      # 90 million angles
    ("step_deg = 1.0", "step_deg = 1e-320", "sweep.step_deg"),    # past 2^53 angles: OverflowError before
    ("step_s = 2.0e-4", "step_s = 1e-9", "rig.step_s"),           # 2e9 steps a run
])
def test_huge_work_is_refused_before_it_starts_unless_yes(tmp_path, old, new, key):
    big = _aged_with(tmp_path, old, new)
    t0 = time.monotonic()
    p = run(["run", big, "--out", tmp_path / "out"], tmp_path)
    lines = [x for x in p.stderr.strip().splitlines() if ": warning: " not in x]
    assert p.returncode == 2 and len(lines) == 1, p.stderr
    assert key in lines[0] and "--yes" in lines[0] and "rig steps" in lines[0]
    assert time.monotonic() - t0 < 20 and not (tmp_path / "out").exists()


def test_steps_per_run_is_the_rigs_step_count():
    # 0.5 m at 0.244 m/s in steps of 2e-4 s: 0.5 / 4.88e-5 = 10245.9 -> 10246 steps
    assert steps_per_run(0.5, 0.244, 2e-4) == 10246
    # a whole quotient stays whole (no extra step from rounding): 0.2 / (0.1 * 1e-3) = 2000
    assert steps_per_run(0.2, 0.1, 1e-3) == 2000


def test_the_limits_and_the_message_that_names_the_keys():
    check_run_size("s.toml", LIMIT_RUNS, LIMIT_STEPS / LIMIT_RUNS, "sweep.step_deg", "rig.step_s", False)
    with pytest.raises(InputError) as e:
        check_run_size("s.toml", 1000, 3e6, "sweep.step_deg", "rig.step_s", False)
    msg = str(e.value)
    assert msg.startswith("s.toml: 1,000 rig runs x 3,000,000 steps = 3e+09 rig steps")
    assert "sweep.step_deg (runs)" in msg and "rig.step_s (steps per run)" in msg and "--yes" in msg
    check_run_size("s.toml", 1000, 3e6, "sweep.step_deg", "rig.step_s", True)   # --yes
    with pytest.raises(InputError, match="runs"):
        check_run_size("s.toml", LIMIT_RUNS + 1, 1, "k", "h", False)
    # a run beyond 2^53 steps cannot be counted: refused even with --yes
    with pytest.raises(InputError, match=r"rig.step_s: gives 1e\+16 steps a run"):
        check_run_size("s.toml", 1, 1e16, "k", "rig.step_s", True)
    with pytest.raises(InputError, match="gives 0 steps"):
        check_run_size("s.toml", 1, 0, "k", "rig.step_s", True)


def test_a_scenarios_size_is_its_angles_times_its_runs_steps():
    sc = load(SCENARIOS / "mat_aged.toml")
    runs = sc.angle_count()
    steps = steps_per_run(sc.rig.travel_m, sc.rig.velocity_m_s, sc.rig.step_s)
    assert runs == 91   # 0 to 90 deg in steps of 1 deg
    check_scenario_size(sc, yes=False)
    # uq: the draws at each angle and its step check, two runs an angle, at the scenario's step here
    samples = int(LIMIT_STEPS / (runs * steps)) + 1
    with pytest.raises(InputError, match=f"{runs * samples + 2 * runs:,} rig runs .* x {steps:,.0f} steps"):
        check_uq_size(sc, False, samples, sc.rig.step_s, "--samples", "--step-s")


# -- the estimate counts every run: against the runs made --------------------------

@pytest.fixture
def counted(monkeypatch):
    """The rig runs made in this process, counted where they are made: the
    compiled master's (CMaster.run, record, run_grid) and the Python
    harness's (its loop, harness.simulate); each still runs.  made[0]: the
    runs, made[1]: the steps of CMaster.run's and the harness's runs."""
    from orthocontact.rig import harness
    from orthocontact.rig.compiled import CMaster
    made = [0, 0]
    run_, record_, grid_, simulate_ = CMaster.run, CMaster.record, CMaster.run_grid, harness.simulate

    def run(self, tasks):
        made[0] += len(tasks)
        made[1] += sum(steps_per_run(r.travel_m, r.velocity_m_s, r.step_s) for _, r in tasks)
        return run_(self, tasks)

    def simulate(fmu, params, rig, *a, **k):
        made[0] += 1
        made[1] += steps_per_run(rig.travel_m, rig.velocity_m_s, rig.step_s)
        return simulate_(fmu, params, rig, *a, **k)
    monkeypatch.setattr(harness, "simulate", simulate)

    def record(self, *a, **k):
        made[0] += 1
        return record_(self, *a, **k)

    def run_grid(self, laws, axes, *a, **k):
        made[0] += len(laws) * len(axes)
        return grid_(self, laws, axes, *a, **k)
    monkeypatch.setattr(CMaster, "run", run)
    monkeypatch.setattr(CMaster, "record", record)
    monkeypatch.setattr(CMaster, "run_grid", run_grid)
    return made


def _variant(tmp_path, path, *edits) -> Path:
    out = tmp_path / path.name
    text = path.read_text()
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new, 1)
    out.write_text(text)
    return out


SHORT = ("travel_m = 0.5", "travel_m = 0.05")   # 205 steps a run: quick


def test_a_one_angle_sweeps_estimate_is_the_runs_it_makes(tmp_path, counted):
    """A 1-angle sweep's estimate once said 1 run and the sweep
    made 9 (the other rule at the extremum, 7 recorded trajectories)."""
    from orthocontact.runs.sweep import run_sweep
    sc = load(_variant(tmp_path, SCENARIOS / "mat_aged.toml", SHORT, ("start_deg = 0.0", "start_deg = 45.0"),
                       ("stop_deg = 90.0", "stop_deg = 45.0")))
    work = scenario_work(sc)
    run_sweep(sc, workers=1, progress=False, master="c")
    assert counted[0] == 9 and work.runs == counted[0], work.parts
    assert work.steps == counted[0] * steps_per_run(0.05, 0.244, 2e-4)


def test_a_refined_sweeps_estimate_bounds_the_refinement_and_counts_the_rest(tmp_path, counted):
    """The refinement's count depends on the angles found: the estimate takes
    its most; every other run is counted exactly."""
    from orthocontact.runs.sweep import refinement_runs_at_most, run_sweep
    sc = load(_variant(tmp_path, SCENARIOS / "mat_aged.toml", SHORT, ("start_deg = 0.0", "start_deg = 36.0"),
                       ("stop_deg = 90.0", "stop_deg = 44.0"), ("step_deg = 1.0", "step_deg = 2.0")))
    work = scenario_work(sc)
    res = run_sweep(sc, workers=1, progress=False, master="c")
    refined = res.extremum.get("evaluations", 0)
    assert res.extremum["refined"] and refined > 0
    bound = refinement_runs_at_most(2.0)
    assert dict((w, r) for w, r, _ in work.parts)["refining the extremum, at most"] == bound
    assert counted[0] - refined == work.runs - bound == 5 + 1 + 7
    assert counted[0] <= work.runs


def test_a_step_studys_estimate_is_the_runs_it_makes(tmp_path, counted):
    from orthocontact.runs.sweep import run_step_study
    sc = load(_variant(tmp_path, SCENARIOS / "step_study.toml", ("travel_m = 1.0", "travel_m = 0.02"),
                       ("steps_s = [2.0e-3, 1.0e-3, 5.0e-4, 2.0e-4, 1.0e-4]", "steps_s = [2.0e-3, 1.0e-3]")))
    work = scenario_work(sc)
    run_step_study(sc, workers=1, progress=False, master="c")
    assert counted[0] == 3 * 2 and work.runs == counted[0]
    rig = sc.rig
    assert work.steps == 3 * sum(steps_per_run(0.02, rig.velocity_m_s, h) for h in (2e-3, 1e-3))


def test_a_pushs_estimate_is_its_heights_times_its_angles_and_the_fmi3_cells_at_most():
    """The bundled push: 4 heights x 4 angles of 25 carriage steps, and the
    cells of each height's first angle again where the FMU has no arrays."""
    work = scenario_work(load(SCENARIOS / "pushed_block.toml"))
    assert work.parts == (("pushes", 16, 25), ("the cells again (FMI 3.0), at most", 4, 25))


def test_a_rolls_estimate_is_its_rules_angles_and_directions_and_the_fmi3_cells_at_most():
    """The bundled wheel: 2 rules x 7 angles x 2 directions, 8 creepages of
    2 pad lengths of 32 cells at Courant 1, and the longitudinal rolls of
    the first rule again for their cells where the FMU has no arrays."""
    work = scenario_work(load(SCENARIOS / "rolling_wheel.toml"))
    assert work.parts == (("rolls", 28, 512), ("the cells again (FMI 3.0), at most", 7, 512))


def test_a_push_of_a_billion_steps_is_refused_naming_its_keys(tmp_path):
    big = scenario_variant(SCENARIOS / "pushed_block.toml", "step_m = 2.0e-4", "step_m = 1e-12",
                           tmp_path / "big.toml")
    with pytest.raises(InputError, match=r"push.travel_m or push.step_m"):
        check_scenario_size(load(big), yes=False)


def test_uqs_estimate_is_the_runs_it_makes(tmp_path, counted, identified):
    """uq's draws at each angle and its step check (the estimates at the
    scenario's step and at the uq step)."""
    from orthocontact import uq
    sc = load(_variant(tmp_path, SCENARIOS / "mat_aged.toml", SHORT, ("start_deg = 0.0", "start_deg = 30.0"),
                       ("stop_deg = 90.0", "stop_deg = 50.0"), ("step_deg = 1.0", "step_deg = 10.0")))
    est = uq.load_estimates(identified)
    work = uq_work(sc, 4, uq.uq_step(sc))
    uq.propagate(est, sc, 4, 1, None, scheduler=None, progress=False)
    assert counted[0] == 4 * 3 + 2 * 3 and work.runs == counted[0], work.parts


def test_work_the_old_estimate_let_through_is_refused_with_every_run_named(tmp_path):
    """A 1-angle sweep of 3e8 steps a run: 1 run was under the limit, the 9
    runs it makes are 2.7e9 steps."""
    big = _variant(tmp_path, SCENARIOS / "mat_aged.toml", ("start_deg = 0.0", "start_deg = 45.0"),
                   ("stop_deg = 90.0", "stop_deg = 45.0"), ("step_s = 2.0e-4", "step_s = 6.83e-9"))
    p = run(["run", big, "--out", tmp_path / "out"], tmp_path)
    lines = [x for x in p.stderr.strip().splitlines() if ": warning: " not in x]
    assert p.returncode == 2 and len(lines) == 1, p.stderr
    assert "9 rig runs (1 at the mat angles, 1 by the other rule, 7 recorded trajectories) x 300," \
        in lines[0], lines[0]
    assert "--yes" in lines[0] and not (tmp_path / "out").exists()


# -- the runs other layers add: identify's validation, the sensitivity study ---------

DATA = SCENARIOS / "example_identification"


@pytest.mark.parametrize("data", ["example_identification", "example_recordings"])
def test_identifys_estimate_is_its_validations_runs(data, counted):
    """The fit runs no rig; the validation runs one at each (mat angle,
    velocity) of the data and one over the ramp (the Python harness): the
    estimate counted none of them."""
    from orthocontact.fmu.files import find_fmu
    from orthocontact.identification import job
    d, _ = job.load_folder(SCENARIOS / data)
    work = job.validation_work(d)
    job.identify(d, validate=True, workers=1, fmu_path=str(find_fmu()))
    assert counted[0] == work.runs and counted[1] == work.steps, work.parts
    # by hand: 19 distinct (angle, velocity) points and the ramp; raw recordings: 7 angles at 2 velocities
    assert work.runs == {"example_identification": 19 + 1, "example_recordings": 14}[data]


def test_identify_without_forces_validates_nothing_and_estimates_nothing(tmp_path, counted):
    """mu1, mu2 need the driving forces: without them the validation is
    skipped, and the estimate says so."""
    import shutil

    from orthocontact.identification import job
    folder = tmp_path / "data"
    shutil.copytree(DATA, folder)
    (folder / "forces.csv").unlink()
    d, _ = job.load_folder(folder)
    work = job.validation_work(d)
    res = job.identify(d, validate=True, workers=1)
    assert work.runs == 0 == counted[0] and "skipped" in res.validation


def test_the_sensitivity_studys_estimate_is_the_runs_it_makes(counted):
    from orthocontact.reproduction import sensitivity
    sc = load(SCENARIOS / "mat_aged.toml")
    planned = sensitivity.plan(sc)
    work = sensitivity.work(planned)
    res = sensitivity.run(sc, 1, master="c", progress=False, planned=planned)
    assert counted[0] == work.runs == res.checks["runs"] and counted[1] == work.steps, work.parts
    # 7 strip frictions and the 5 viscous strips whose ratio is reachable, at both velocities,
    # 7 whole degrees about each peak; a run at 4 ms over 0.5 m: 1000 steps at 0.125 m/s, 513 at 0.244
    reached = sum(r["eps_ratio"] is not None for r in planned.viscous)
    assert work.runs == (7 + reached) * 2 * 7
    assert work.steps == (7 + reached) * 7 * (1000 + 513)


def test_identify_refuses_validation_runs_above_the_limits(tmp_path):
    """A rig.toml step of 1e-8 s (plausible, with a warning): 19 validation
    runs of 2e8 steps each; refused before any run unless --no-validate or
    --yes."""
    import shutil
    folder = tmp_path / "data"
    shutil.copytree(DATA, folder)
    with open(folder / "rig.toml", "a") as f:
        f.write("step_s = 1e-8\n")
    p = run(["identify", folder, "--out", tmp_path / "out"], tmp_path)
    lines = [x for x in p.stderr.strip().splitlines() if ": warning: " not in x]
    assert p.returncode == 2 and len(lines) == 1, p.stderr
    assert "20 rig runs (19 validation runs, 1 validation ramp run)" in lines[0], lines[0]
    assert "--no-validate" in lines[0] and "--yes" in lines[0] and not (tmp_path / "out").exists()
    p = run(["identify", folder, "--out", tmp_path / "out", "--no-validate"], tmp_path)
    assert p.returncode == 0, p.stderr


def test_reproduce_counts_its_scenarios_together(tmp_path):
    """Two scenarios each within the limits, together above them: reproduce
    makes both (and the sensitivity study), so it is refused before any run,
    naming each part."""
    folder = tmp_path / "scenarios"
    folder.mkdir()
    sc = load(SCENARIOS / "mat_aged.toml")
    steps = LIMIT_STEPS * 0.6 / scenario_work(sc).runs     # each 60 % of the limit
    h = sc.rig.travel_m / sc.rig.velocity_m_s / steps
    for name in ("one", "two"):
        _variant(tmp_path, SCENARIOS / "mat_aged.toml", ('name = "mat_aged"', f'name = "{name}"'),
                 ("step_s = 2.0e-4", f"step_s = {h:.6g}")).rename(folder / f"{name}.toml")
    for f in folder.glob("*.toml"):
        check_scenario_size(load(f), yes=False)     # each alone passes
    p = run(["reproduce", "--scenarios", folder, "--out", tmp_path / "out"], tmp_path)
    lines = [x for x in p.stderr.strip().splitlines() if ": warning: " not in x]
    assert p.returncode == 2 and len(lines) == 1, p.stderr
    n = scenario_work(sc).runs
    assert lines[0].startswith(f"orthocontact: error: {folder}: {2 * n + 168:,} rig runs ({n} one, {n} two, "
                               "168 sensitivity)"), lines[0]
    assert "--yes" in lines[0] and not (tmp_path / "out").exists()
