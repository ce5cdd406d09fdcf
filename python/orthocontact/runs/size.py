"""How much work a command is about to do, said before any of it starts: a
sweep of 90 million angles or a run of 5e8 steps is almost always a typo in a
scenario file (step_deg = 1e-6, step_s = 1e-9), and would otherwise fill the
memory or run for days with nothing to show.  Each scenario kind's estimate
is written here and registered into its row (experiment.kinds: `estimates`)."""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from ..errors import InputError
from ..experiment import kind_of, register, roll_steps

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
    """rig_step_count of fmu_src/rig/rig_core.c, as a float that may exceed 2^53."""
    return math.ceil(travel_m / (velocity_m_s * step_s) - 1e-9)


@dataclass(frozen=True)
class Work:
    """The rig runs a command makes, by part: (what, runs, steps per run).
    Every run the command makes is in one part: the estimate said before
    any of them starts."""
    parts: tuple = ()

    def plus(self, what: str, runs: float, steps: float) -> Work:
        return Work(self.parts + ((what, runs, steps),)) if runs else self

    def __add__(self, other: Work) -> Work:
        """The runs of both: a command that makes another layer's runs too
        (identify's validation, reproduce's sensitivity study) adds their
        Work to its own, so one estimate is checked against the limits."""
        return Work(self.parts + other.parts)

    def named(self, what: str) -> Work:
        """The same runs, every part called `what` (a scenario's name in
        reproduce's estimate): describe() counts them together."""
        return Work(tuple((what, r, n) for _, r, n in self.parts))

    @property
    def runs(self) -> float:
        return sum(r for _, r, _ in self.parts)

    @property
    def steps(self) -> float:
        """Rig steps of all runs together."""
        return sum(r * n for _, r, n in self.parts)

    @property
    def most_steps(self) -> float:
        """Steps of the longest run."""
        return max((n for _, _, n in self.parts), default=0.0)

    def describe(self) -> str:
        """'N rig runs (n what, ...)'; the parts when there are several, the
        runs of parts of one name (of several step counts) counted together."""
        head = f"{self.runs:,.0f} rig runs"
        by_name: dict = {}
        for w, r, _ in self.parts:
            by_name[w] = by_name.get(w, 0) + r
        if len(by_name) < 2:
            return head
        return head + " (" + ", ".join(f"{r:,.0f} {w}" for w, r in by_name.items()) + ")"


def check_work(what: str, work: Work, runs_key: str, steps_key: str, yes: bool,
               remedy: str | None = None) -> None:
    """InputError unless `work` is a size a command takes without asking:
    naming `what` (the file or command), the keys or options that set the
    size, and --yes; `remedy`, where given, says what to do instead of
    "raise runs_key or steps_key, or pass --yes"."""
    if not work.parts:
        return   # no rig run (identify --no-validate's work, or data without forces)
    steps = work.most_steps
    if not 1 <= steps <= MAX_STEPS_PER_RUN:
        raise InputError(f"{what}: {steps_key}: gives {steps:.3g} steps a run; a run takes "
                         f"1 to 2^53 = {MAX_STEPS_PER_RUN:.3g} steps")
    total = work.steps
    if yes or (work.runs <= LIMIT_RUNS and total <= LIMIT_STEPS):
        return
    if len({n for _, _, n in work.parts}) == 1:
        size = f"{work.describe()} x {steps:,.0f} steps"
    else:
        size = f"{work.describe()} of up to {steps:,.0f} steps"
    raise InputError(f"{what}: {size} = {total:.3g} rig steps "
                     f"(limits without --yes: {LIMIT_RUNS:.0e} runs, {LIMIT_STEPS:.0e} steps, about 5 "
                     f"minutes on 2 cores); " + (remedy or f"raise {runs_key} (runs) or {steps_key} "
                                                 "(steps per run), or pass --yes to run it anyway"))


def check_run_size(what: str, runs: float, steps: float, runs_key: str, steps_key: str,
                   yes: bool) -> None:
    """check_work for `runs` rig runs of `steps` steps each."""
    check_work(what, Work().plus("runs", runs, steps), runs_key, steps_key, yes)


@dataclass(frozen=True)
class WorkEstimate:
    """A scenario kind's work estimate (its piece "work", experiment.kinds):
    work(sc) -> Work, every rig run `orthocontact run` makes for the
    scenario; runs_key and steps_key: the keys that set the number of runs
    and the steps per run, named when the size is refused."""
    work: Callable
    runs_key: str
    steps_key: str


def estimates(name: str, runs_key: str, steps_key: str):
    """Decorator: registers work(sc) -> Work as the kind `name`'s estimate."""
    def put(f):
        register(name, "work", WorkEstimate(f, runs_key, steps_key))
        return f
    return put


@estimates("sweep", "sweep.step_deg or sweep.trajectory_angles_deg", "rig.step_s or rig.travel_m")
def sweep_work(sc) -> Work:
    """A sweep's angles, its extremum's refinement (at most
    refinement_runs_at_most: the count depends on the angles found), the
    other implicit rule at the extremum and the recorded trajectories, each
    of the rig's steps (runs.sweep)."""
    from .sweep import refinement_runs_at_most
    rig = sc.rig
    n = sc.angle_count()
    steps = steps_per_run(rig.travel_m, rig.velocity_m_s, rig.step_s)
    refine = refinement_runs_at_most(sc.sweep["step_deg"]) if sc.sweep["refine_extremum"] and n >= 3 else 0
    other = 1 if sc.law.rule in ("coupled", "associated") else 0
    return (Work().plus("at the mat angles", n, steps).plus("refining the extremum, at most", refine, steps)
            .plus("by the other rule", other, steps)
            .plus("recorded trajectories", len(sc.sweep["trajectory_angles_deg"]), steps))


@estimates("step_study", "study.rules or study.steps_s", "study.steps_s or rig.travel_m")
def step_study_work(sc) -> Work:
    """A step study's rules at each of its steps."""
    rig = sc.rig
    work = Work()
    for h in sc.study["steps_s"]:
        work = work.plus(f"at step {h:g} s", len(sc.study["rules"]),
                         steps_per_run(rig.travel_m, rig.velocity_m_s, h))
    return work


@estimates("twist", "twist.rules", "twist.step_s, twist.rate_deg_s or twist.angle_deg")
def twist_work(sc) -> Work:
    """A twist under each of its rules, turning at its rate to its angle."""
    tw = sc.twist
    return Work().plus("twists", len(tw["rules"]), tw["angle_deg"] / (tw["rate_deg_s"] * tw["step_s"]))


@estimates("towed_block", "tow.angles_deg or tow.rules", "tow.step_s or tow.duration_s")
def towed_work(sc) -> Work:
    """A tow at each of its mat angles under each of its rules."""
    tw = sc.tow
    return Work().plus("tows", len(tw["rules"]) * len(tw["angles_deg"]), tw["duration_s"] / tw["step_s"])


@estimates("pushed_block", "push.angles_deg or push.heights_m", "push.travel_m or push.step_m")
def pushed_work(sc) -> Work:
    """A push at each of its heights and mat angles, a carriage step at a
    time, and the pressure's cells at the first angle of each height again
    where the FMU has no arrays (FMI 2.0: at most one run a height)."""
    pu = sc.push
    steps = math.ceil(pu["travel_m"] / pu["step_m"] - 1e-9)
    return (Work().plus("pushes", len(pu["heights_m"]) * len(pu["angles_deg"]), steps)
            .plus("the cells again (FMI 3.0), at most", len(pu["heights_m"]), steps))


@estimates("rolling", "roll.angles_deg, roll.rules or roll.creepages",
           "roll.rolled_lengths, roll.courant or pad.n1")
def rolling_work(sc) -> Work:
    """A roll at each mat angle, rule and direction (longitudinal, lateral)
    through each creepage, each held for rolled_lengths pad lengths of
    courant cells a step, and the longitudinal rolls of the first rule
    again for their cells where the FMU has no arrays (FMI 2.0)."""
    r = sc.roll
    steps = len(r["creepages"]) * roll_steps(r, sc.pad["n1"])
    return (Work().plus("rolls", 2 * len(r["rules"]) * len(r["angles_deg"]), steps)
            .plus("the cells again (FMI 3.0), at most", len(r["angles_deg"]), steps))


def scenario_work(sc) -> Work:
    """Every rig run `orthocontact run` makes for a scenario: its kind's
    estimate."""
    return kind_of(sc).part("work").work(sc)


def uq_work(sc, samples: int, step_s: float) -> Work:
    """Every rig run `orthocontact uq` makes (uq.propagate): `samples`
    parameter sets at each of the scenario's angles at the uq step `step_s`
    [s], and its step check, the estimates at each angle at the scenario's
    step and at the uq step."""
    rig = sc.rig
    n = sc.angle_count()
    at_uq = steps_per_run(rig.travel_m, rig.velocity_m_s, step_s)
    return (Work().plus("parameter-set runs", samples * n, at_uq)
            .plus("step check at the uq step", n, at_uq)
            .plus("step check at the scenario's step", n,
                  steps_per_run(rig.travel_m, rig.velocity_m_s, rig.step_s)))


def check_scenario_size(sc, yes: bool) -> None:
    """check_work for every run `orthocontact run` makes for the scenario."""
    est = kind_of(sc).part("work")
    check_work(str(sc.path), est.work(sc), est.runs_key, est.steps_key, yes)


def check_uq_size(sc, yes: bool, samples: int, step_s: float, samples_key: str, step_key: str) -> None:
    """check_work for every run `orthocontact uq` makes."""
    check_work(str(sc.path), uq_work(sc, samples, step_s), f"sweep.step_deg or {samples_key}",
               f"{step_key}, rig.step_s", yes)
