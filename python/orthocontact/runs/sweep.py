"""A scenario's sweep over the mat angle (with its extremum refined on the rig
itself and the trajectories recorded) and its step-size study; the closed
form the scenario names (closed_forms.FORMS), at its angles."""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .. import closed_forms as cf
from ..experiment import Scenario
from ..fmu import ContactFMU
from ..rig import RunChecks, check_runs, run, warning_line
from ..runtime import default_workers
from .batch import run_many
from .executors import resolve_master
from .progress import Heartbeat

# -- closed form for a scenario --------------------------------------------------


def scenario_form(sc: Scenario, rule: str | None = None) -> cf.NamedForm:
    """The closed form the scenario names (closed_forms.FORMS), or the
    general one for another rule than the law's."""
    return cf.FORMS["general" if rule not in (None, sc.law.rule) else sc.closed_form]


def closed_form_phi_deg(sc: Scenario, angle_deg: float, rule: str | None = None) -> float:
    """The steady trajectory angle [deg] the closed form predicts for the
    scenario at the mat angle [deg]."""
    p = sc.params_at(angle_deg, rule)
    return scenario_form(sc, rule).phi_deg(p, p.alpha, p.beta)


def closed_form_phi_deg_array(sc: Scenario, angles_deg, rule: str | None = None) -> np.ndarray:
    """closed_form_phi_deg over an array of mat angles [deg] at once (the
    fine scans of the report: tens of thousands of points)."""
    alpha, beta = sc.geometry.axes(np.asarray(angles_deg, dtype=float))
    law = sc.law if rule is None else sc.law.replace(rule=rule)
    return scenario_form(sc, rule).phi_deg_array(law, alpha, beta)


# -- sweeps ------------------------------------------------------------------------

@dataclass
class SweepResult:
    angles_deg: np.ndarray
    phi_deg: np.ndarray
    phi_closed_deg: np.ndarray
    drive_mean_N: np.ndarray
    extremum: dict
    grid_extremum: dict
    workers: int
    seconds: float
    trajectories: dict = field(default_factory=dict)  # angle_deg -> RigResult
    figures: list = field(default_factory=list)       # RunFigures of each angle
    checks: RunChecks | None = None                   # rig_checks of each angle

    @property
    def max_deviation_deg(self) -> float:
        return float(np.max(np.abs(self.phi_deg - self.phi_closed_deg)))

    def warning(self, sc: Scenario) -> str | None:
        """The user's one line if some runs are not steady sliding."""
        return warning_line(sc.name, self.angles_deg, self.checks, self.phi_deg,
                            [(sc.params_at(a), sc.rig) for a in self.angles_deg])


PARABOLA_RUNS = 12        # most rig runs of the parabolic refinement
GOLDEN_TOL_DEG = 1e-3     # the golden-section search's final bracket [deg]


def refinement_runs_at_most(step_deg: float) -> int:
    """The most rig runs a sweep's extremum refinement makes (run_sweep):
    the parabolas' PARABOLA_RUNS, then, if they fail, a golden-section search
    over at most two grid steps: its two first points, one a bracket
    shrinking by the golden ratio until GOLDEN_TOL_DEG, and its midpoint."""
    width = 2 * step_deg
    shrink = 0 if width <= GOLDEN_TOL_DEG else math.ceil(
        math.log(GOLDEN_TOL_DEG / width) / math.log((math.sqrt(5) - 1) / 2) - 1e-9)
    return PARABOLA_RUNS + 3 + shrink


def _parabolic_extremum(f, xs, fs, tol: float = 1e-4, max_evals: int = PARABOLA_RUNS):
    """Maximiser of a smooth f from three points about its maximum
    (successive parabolic interpolation through the three best points so
    far); None when a parabola opens upwards or its vertex leaves the
    points' span (the caller falls back to golden section)."""
    pts = list(zip(xs, fs))
    lo, hi = min(xs), max(xs)
    last = None
    for _ in range(max_evals):
        (x0, y0), (x1, y1), (x2, y2) = sorted(sorted(pts, key=lambda p: -p[1])[:3])
        s01, s12 = (y1 - y0) / (x1 - x0), (y2 - y1) / (x2 - x1)
        curvature = (s12 - s01) / (x2 - x0)
        if not curvature < 0:
            return None
        x = 0.5 * (x0 + x1) - s01 / (2 * curvature)  # where the parabola's slope vanishes
        if not lo < x < hi:
            return None
        if last is not None and abs(x - last) < tol or min(abs(x - p[0]) for p in pts) < 1e-12:
            break
        pts.append((x, f(x)))
        last = x
    return max(pts, key=lambda p: p[1])


def _golden_extremum(f, a: float, b: float, tol: float = GOLDEN_TOL_DEG) -> tuple[float, float]:
    """Maximiser of f on [a, b] by golden-section search."""
    g = (math.sqrt(5) - 1) / 2
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    while b - a > tol:
        if fc > fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = f(d)
    x = 0.5 * (a + b)
    return x, f(x)


def run_sweep(sc: Scenario, workers: int | None = None, progress: bool = True,
              fmu_path=None, master: str = "auto", dask=None) -> SweepResult:
    """phi(angle) over the scenario's grid, the extremum (refined by a
    golden-section search on the rig itself when asked), and recorded runs
    at the trajectory angles."""
    workers = workers or default_workers()
    fmu_path = fmu_path or sc.fmu
    t0 = time.time()
    angles = sc.sweep_angles()
    tasks = [(sc.params_at(a), sc.rig) for a in angles]
    res = run_many(tasks, workers, fmu_path, sc.name, progress, master, dask)
    checks = check_runs(tasks, res)
    phi = np.array([r[0] for r in res])
    drive = np.array([r[1] for r in res])
    closed = closed_form_phi_deg_array(sc, np.asarray(angles, dtype=float))
    k = int(np.argmax(np.abs(phi)))
    grid_ext = {"angle_deg": float(angles[k]), "phi_deg": float(phi[k])}
    extremum = dict(grid_ext, refined=False)
    beat = Heartbeat(f"{sc.name} extremum and trajectories", progress)
    single = SingleRuns(sc, fmu_path, master, beat)
    try:
        extremum = refined_extremum(sc, angles, phi, k, single.phi_deg) or extremum
        # The other implicit rule at the same angle: the sign of phi is what
        # tells the rules apart (report.md).
        other = {"coupled": "associated", "associated": "coupled"}.get(sc.law.rule)
        if other:
            extremum["other_rule"] = {"rule": other, "phi_deg": single.phi_deg(extremum["angle_deg"], other)}
        n_rec = max(1, int(sc.rig.travel_m / (sc.rig.velocity_m_s * sc.rig.step_s) / 400))
        traj = {float(a): single.record(a, n_rec) for a in sc.sweep["trajectory_angles_deg"]}
    finally:
        beat.close()
        single.close()
    return SweepResult(np.array(angles, dtype=float), phi, closed, drive, extremum, grid_ext, workers,
                       time.time() - t0, traj, list(res), checks)


class SingleRuns:
    """A sweep's runs one at a time after its batch (the extremum's
    refinement, the other rule's angle, the recorded trajectories) on the
    batch's master: the compiled one, or one fmpy instance; each run a beat
    of the sweep's progress line."""

    def __init__(self, sc: Scenario, fmu_path, master: str, beat: Heartbeat):
        self.sc, self.beat = sc, beat
        self.compiled = resolve_master(master, fmu_path) == "c"
        if self.compiled:
            from ..fmu import find_fmu
            from ..rig import CMaster
            self.engine = CMaster(find_fmu(fmu_path))
        else:
            self.engine = ContactFMU(fmu_path, instance_name="main")

    def phi_deg(self, a: float, rule: str | None = None) -> float:
        """The trajectory angle [deg] at the mat angle a [deg] (under `rule`)."""
        self.beat.update()
        if self.compiled:
            return self.engine.run([(self.sc.params_at(a, rule), self.sc.rig)])[0][0]
        return run(self.sc.params_at(a, rule), self.sc.rig, fmu=self.engine, record_every=1 << 30).phi_deg

    def record(self, a: float, every: int):
        """The run at the mat angle a [deg], every `every`-th step kept (RigResult)."""
        self.beat.update()
        if self.compiled:
            return self.engine.record(self.sc.params_at(a), self.sc.rig, every)
        return run(self.sc.params_at(a), self.sc.rig, fmu=self.engine, record_every=every)

    def close(self) -> None:
        self.engine.close()


def refined_extremum(sc: Scenario, angles, phi, k: int, phi_at) -> dict | None:
    """The extremum refined on the rig (phi_at(a): a run's angle [deg]) about
    the grid's, angles[k]: None where the scenario does not ask, or the
    refinement finds none beyond the grid's."""
    if not (sc.sweep["refine_extremum"] and len(angles) >= 3 and abs(phi[k]) > 1e-6):
        return None
    sign = 1.0 if phi[k] > 0 else -1.0
    step = sc.sweep["step_deg"]
    lo, hi = max(angles[0], angles[k] - step), min(angles[-1], angles[k] + step)
    cache, runs = {}, [0]

    def f(a):
        if a not in cache:
            cache[a] = sign * phi_at(a)
            runs[0] += 1
        return cache[a]
    # phi is smooth about its extremum: parabolas through the grid's
    # three best points converge in a few runs; golden section if not.
    idx = [j for j in (k - 1, k, k + 1) if 0 <= j < len(angles)]
    found = None
    if len(idx) == 3:
        for j in idx:
            cache[float(angles[j])] = sign * float(phi[j])
        found = _parabolic_extremum(f, [float(angles[j]) for j in idx], [sign * float(phi[j]) for j in idx])
    a_ext, v = found if found is not None else _golden_extremum(f, lo, hi)
    if v >= sign * phi[k]:
        return {"angle_deg": a_ext, "phi_deg": sign * v, "refined": True, "evaluations": runs[0]}
    return None


@dataclass
class StepStudyResult:
    rows: list  # dicts: rule, step_s, phi_deg, phi_closed_deg, deviation_deg, check
    angle_deg: float
    seconds: float
    checks: RunChecks | None = None
    tasks: list = field(default_factory=list)

    def warning(self, sc: Scenario) -> str | None:
        """The user's one line if some runs are not steady sliding."""
        labels = [f"{r['rule']} at step {r['step_s']:g} s" for r in self.rows]
        line = warning_line(sc.name, [self.angle_deg] * len(self.rows), self.checks,
                            [r["phi_deg"] for r in self.rows], self.tasks)
        if line is None:
            return None
        bad = [lab for lab, ok, r in zip(labels, self.checks.ok, self.rows) if not ok and r["rule"] != "eq20"]
        return line + f" (runs: {', '.join(bad)})"


def run_step_study(sc: Scenario, workers: int | None = None, progress: bool = True,
                   fmu_path=None, master: str = "auto", dask=None) -> StepStudyResult:
    """The steady angle of each sliding rule at each communication step."""
    from dataclasses import replace
    workers = workers or default_workers()
    t0 = time.time()
    a = sc.study["angle_deg"]
    combos = [(rule, h) for rule in sc.study["rules"] for h in sc.study["steps_s"]]
    tasks = [(sc.params_at(a, rule), replace(sc.rig, step_s=h)) for rule, h in combos]
    res = run_many(tasks, workers, fmu_path or sc.fmu, sc.name, progress, master, dask)
    checks = check_runs(tasks, res)
    rows = []
    for (rule, h), (phi, drive, _, _), status in zip(combos, res, checks.status()):
        closed = closed_form_phi_deg(sc, a, rule)
        rows.append({"rule": rule, "step_s": h, "phi_deg": phi, "phi_closed_deg": closed,
                     "deviation_deg": phi - closed, "drive_mean_N": drive, "check": status})
    return StepStudyResult(rows, a, time.time() - t0, checks, tasks)
