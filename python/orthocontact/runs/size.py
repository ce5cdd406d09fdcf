"""How much work a command is about to do, said before any of it starts: a
sweep of 90 million angles or a run of 5e8 steps is almost always a typo in a
scenario file (step_deg = 1e-6, step_s = 1e-9), and would otherwise fill the
memory or run for days with nothing to show."""
from __future__ import annotations

import math

from ..errors import InputError

# Rig steps a command may take without --yes.  The largest work of the
# documented commands is uq's benchmark, 10^6 runs of 512 steps (5.1e8 steps,
# 79 s here); the compiled master takes 6-7e6 steps/s on this project's 2-core
# machine (benchmarks/bench_uq.py), so 2e9 steps is about 5 minutes.
LIMIT_STEPS = 2e9

# Rig runs likewise: each run's parameters are held in memory (about 1 kB with
# its result), so 2e6 runs is about 2 GB; uq's benchmark takes 10^6.
LIMIT_RUNS = 2e6

# A run's step count is a whole number only up to 2^53 (rig_core.c).
MAX_STEPS_PER_RUN = 2.0 ** 53


def steps_per_run(travel_m: float, velocity_m_s: float, step_s: float) -> float:
    """rig_step_count of fmu_src/rig_core.c, as a float that may exceed 2^53."""
    return math.ceil(travel_m / (velocity_m_s * step_s) - 1e-9)


def check_run_size(what: str, runs: float, steps: float, runs_key: str, steps_key: str,
                   yes: bool) -> None:
    """InputError unless `runs` rig runs of `steps` steps each are a size a
    command takes without asking: naming `what` (the file or command), the
    keys or options that set the size, and --yes."""
    if not 1 <= steps <= MAX_STEPS_PER_RUN:
        raise InputError(f"{what}: {steps_key}: gives {steps:.3g} steps a run; a run takes "
                         f"1 to 2^53 = {MAX_STEPS_PER_RUN:.3g} steps")
    total = runs * steps
    if yes or (runs <= LIMIT_RUNS and total <= LIMIT_STEPS):
        return
    raise InputError(f"{what}: {runs:,.0f} rig runs x {steps:,.0f} steps = {total:.3g} rig steps "
                     f"(limits without --yes: {LIMIT_RUNS:.0e} runs, {LIMIT_STEPS:.0e} steps, about 5 "
                     f"minutes on 2 cores); raise {runs_key} (runs) or {steps_key} (steps per run), "
                     "or pass --yes to run it anyway")


def check_scenario_size(sc, yes: bool, samples: int = 1, step_s: float | None = None,
                        samples_key: str = "", step_key: str | None = None) -> None:
    """check_run_size for a scenario's sweep or step study (times `samples`
    parameter sets, at the step `step_s` if given)."""
    rig = sc.rig
    if sc.kind == "sweep":
        runs = sc.angle_count() * samples
        steps = steps_per_run(rig.travel_m, rig.velocity_m_s, step_s or rig.step_s)
        runs_key = "sweep.step_deg" + (f" or {samples_key}" if samples_key else "")
        check_run_size(str(sc.path), runs, steps, runs_key, step_key or "rig.step_s or rig.travel_m", yes)
        return
    steps = [steps_per_run(rig.travel_m, rig.velocity_m_s, h) for h in sc.study["steps_s"]]
    check_run_size(str(sc.path), len(sc.study["rules"]) * len(steps), max(steps),
                   "study.rules or study.steps_s", "study.steps_s or rig.travel_m", yes)
