"""The size of the work (orthocontact.runs.size): huge work is refused before
it starts unless --yes, with a message naming the keys that set its size;
the step count is the rig's."""
import time
from pathlib import Path

import pytest
from cli_run import run_cli as run, scenario_variant

from orthocontact.errors import InputError
from orthocontact.experiment.scenario import load
from orthocontact.runs.size import (LIMIT_RUNS, LIMIT_STEPS, check_run_size, check_scenario_size,
                                    steps_per_run)

ROOT = Path(__file__).resolve().parents[2]
SCEN = ROOT / "scenarios"



def _aged_with(tmp_path, old, new) -> Path:
    return scenario_variant(SCEN / "mat_aged.toml", old, new, tmp_path / "big.toml")


# -- huge work: said before it starts, and progress while it runs ---------------------

@pytest.mark.parametrize("old,new,key", [
    ("step_deg = 1.0", "step_deg = 1e-6", "sweep.step_deg"),      # 90 million angles
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
    sc = load(SCEN / "mat_aged.toml")
    runs = sc.angle_count()
    steps = steps_per_run(sc.rig.travel_m, sc.rig.velocity_m_s, sc.rig.step_s)
    assert runs == 91   # 0 to 90 deg in steps of 1 deg
    check_scenario_size(sc, yes=False)
    samples = int(LIMIT_STEPS / (runs * steps)) + 1
    with pytest.raises(InputError, match=f"{runs * samples:,} rig runs x {steps:,.0f} steps"):
        check_scenario_size(sc, yes=False, samples=samples, samples_key="--samples")
