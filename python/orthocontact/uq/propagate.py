"""Uncertainty propagation: how the identified parameters' uncertainty moves
the predicted trajectory angle.

Parameter sets are drawn from the identification's estimates and joint
covariance (identified.json, written by `orthocontact identify`), keeping
only physical ones (mu1, mu2, eps > 0); each set runs the rig over the
scenario's angles; the result is, per angle, the median and the 2.5 / 97.5 %
quantiles of phi [deg] and of the mean driving force [N].

The draws are made in the calling process from one seeded generator, and each
run is deterministic, so the bands do not depend on how the runs are spread
over processes or machines: the same seed gives the same files bit for bit,
serial or on Dask."""
from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from ..errors import InputError
from ..experiment import Scenario, require_mat_angles
from ..rig import SETTLE_TOL_DEG, RunChecks, RunFigures, angle_list, check_runs, remedy, warning_line
from .estimates import IMPLICIT_RULES, Estimates, draw

# The step-size study (scenarios/step_study.toml; docs/benchmarks.md): the
# implicit rules' steady angle does not depend on the step, and the dynamic
# rig's lateral transient moves it by < 1e-6 deg between 0.2 and 4 ms.
DEFAULT_STEP_S = 4e-3


STEP_CHECK_WARN_DEG = 0.01


STEP_NAME = "--step-s"   # what sets uq's step, in its remedies


def step_check(scenario_step_s: float, step_s: float, coarse, fine) -> dict:
    """The step check's record: phi [deg] at the estimates at the uq step
    (coarse) against the scenario's own step (fine), over the angles fitted
    at both (max_abs_difference_deg None if there are none), and which step
    left angles without a fitted phi (not_fitted: {step [s]: count})."""
    coarse, fine = np.asarray(coarse, dtype=float), np.asarray(fine, dtype=float)
    both = np.isfinite(coarse) & np.isfinite(fine)
    missing = {"uq_step": int((~np.isfinite(coarse)).sum()), "scenario_step": int((~np.isfinite(fine)).sum())}
    return {"scenario_step_s": scenario_step_s, "uq_step_s": step_s,
            "max_abs_difference_deg": float(np.max(np.abs(coarse - fine)[both])) if both.any() else None,
            "angles": int(len(coarse)), "not_fitted": missing}


def step_warning(chk: dict) -> str | None:
    """The user's line if the uq step moves phi at the estimates by more
    than STEP_CHECK_WARN_DEG, or if a run at either step gave no angle."""
    parts = []
    for key, name in (("uq_step", f"the uq step {chk['uq_step_s']:g} s"),
                      ("scenario_step", f"the scenario's step {chk['scenario_step_s']:g} s")):
        n = chk["not_fitted"][key]
        if n:
            parts.append(f"at {name}, {n} of {chk['angles']} runs gave no angle (too few steps in the "
                         "fitted path to fit one)")
    dev = chk["max_abs_difference_deg"]
    if dev is not None and dev > STEP_CHECK_WARN_DEG:
        parts.append(f"phi at the uq step {chk['uq_step_s']:g} s differs from the scenario's step "
                     f"{chk['scenario_step_s']:g} s by {dev:.3g} deg")
    return ("at the estimates, " + "; ".join(parts) + "; choose --step-s") if parts else None


def scenario_with(sc: Scenario, names: list, row) -> Scenario:
    """The scenario with the law's parameters `names` set from `row`
    (eps1 follows from eps_ratio and eps2)."""
    v = dict(zip(names, (float(x) for x in row)))
    law = sc.law
    eps2 = v.get("eps2", law.eps2)
    ratio = v.get("eps_ratio", law.eps1 / law.eps2)
    law = law.replace(mu1=v.get("mu1", law.mu1), mu2=v.get("mu2", law.mu2), eps1=ratio * eps2,
                      eps2=eps2)
    return replace(sc, law=law)


def chunk_tasks(sc: Scenario, rig, names: list, rows) -> list:
    """The rig runs of parameter sets `rows`: every angle of the scenario for
    each, set after set."""
    angles = sc.sweep_angles()
    tasks = []
    for row in rows:
        s = scenario_with(sc, names, row)
        tasks += [(s.params_at(a), rig) for a in angles]
    return tasks


def chunk_grid(sc: Scenario, names: list, rows) -> tuple[list, list]:
    """The runs of chunk_tasks as a grid: the law of each parameter set and
    the (alpha, beta) [rad] of each angle (the same numbers, each checked by
    ContactParams once, not once per run)."""
    laws = [scenario_with(sc, names, row).law for row in rows]
    axes = [(p.alpha, p.beta) for p in (sc.params_at(a) for a in sc.sweep_angles())]
    return laws, axes


def chunk_bounds(samples: int, most: int) -> list[tuple[int, int]]:
    """[start, end) of each task's parameter sets: `most` sets a task while
    much is left, then an eighth of what is left (down to a quarter of
    `most`), so that the workers end together instead of one waiting on
    another's last large task.  Large tasks first keep the scheduler's share
    small (a task costs ~7 ms of CPU on this 2-core machine: 1,000 tasks
    were 2 s of a 30 s run).  The results do not depend on the bounds."""
    bounds, i, least = [], 0, max(1, most // 4)
    while i < samples:
        n = min(most, max(least, -(-(samples - i) // 8)), samples - i)
        bounds.append((i, i + n))
        i += n
    return bounds


def _run_chunk_on(run_grid, chunk):
    """chunk = (scenario, rig, names, rows) -> phi, drive and head - tail
    (rig_checks: a settled run's halves agree) arrays [len(rows) x angles],
    the runs made by run_grid(laws, axes, rig) (CMaster.run_grid)."""
    sc, rig, names, rows = chunk
    laws, axes = chunk_grid(sc, names, rows)
    arr = run_grid(laws, axes, rig)
    assert arr.shape == (len(rows), len(sc.sweep_angles()), len(RunFigures._fields))
    return arr[:, :, 0], arr[:, :, 1], arr[:, :, 2] - arr[:, :, 3]


def run_chunk(fmu, chunk):
    """On a worker: _run_chunk_on the worker's compiled master for `fmu`."""
    from ..runs import run_grid
    return _run_chunk_on(lambda laws, axes, rig: run_grid(fmu, laws, axes, rig), chunk)


@dataclass
class UQResult:
    angles_deg: np.ndarray
    samples: np.ndarray          # n x len(names)
    names: list
    accepted_fraction: float
    phi: np.ndarray              # n x angles [deg]
    drive: np.ndarray            # n x angles [N]
    nominal_phi: np.ndarray      # at the estimates, the UQ step [deg]
    step_s: float
    step_check: dict
    engine: str
    seconds: float
    halves: np.ndarray           # n x angles: head - tail of each run [deg] (rig_checks)
    nominal_tasks: list          # the runs at the estimates, the UQ step
    nominal_checks: RunChecks    # their checks, the closed form included

    @property
    def unsettled(self) -> np.ndarray:
        """n x angles: the runs whose two halves disagree (rig_checks)."""
        return ~(np.abs(self.halves) <= SETTLE_TOL_DEG)

    def warning(self, sc: Scenario) -> str | None:
        """The user's one line if runs at the estimates or over the draws
        are not steady sliding."""
        parts = []
        line = warning_line(f"uq {sc.name} at the estimates", self.angles_deg, self.nominal_checks,
                            self.nominal_phi, self.nominal_tasks, STEP_NAME)
        if line:
            parts.append(line)
        if sc.law.rule != "eq20" and self.unsettled.any():
            bad = self.unsettled
            apart = np.abs(self.halves[bad])
            how = (f"halves of the fitted path up to {np.max(apart[np.isfinite(apart)]):.3g} deg apart"
                   if np.isfinite(apart).any()
                   else "too few steps in a half of the fitted path to fit an angle")
            at = bad.any(axis=0)
            parts.append(f"uq {sc.name}: {int(bad.sum())} of {bad.size} runs over the drawn parameter "
                         f"sets did not settle ({how}; angles {angle_list(self.angles_deg[at])} deg): their "
                         "bands are not steady-state predictions; remedy at the estimates: "
                         + remedy([t for t, a in zip(self.nominal_tasks, at) if a],
                                  self.nominal_checks.settling_length_m[at], STEP_NAME))
        return "; ".join(parts) or None


def uq_step(sc: Scenario, step_s: float | None = None) -> float:
    """The communication step [s] of uq's runs: `step_s` if given, else
    DEFAULT_STEP_S for the implicit rules and the scenario's for eq20."""
    if step_s is not None:
        return step_s
    return DEFAULT_STEP_S if sc.law.rule in IMPLICIT_RULES else sc.rig.step_s


def check_geometry(sc: Scenario, est: Estimates) -> None:
    require_mat_angles(sc, "uq")
    if sc.law.rule != est.rule:
        raise InputError(f"{sc.path}: law.rule: expected {est.rule!r}, the rule the parameters of "
                         f"{est.path} were identified under, got {sc.law.rule!r}")


def propagate(est: Estimates, sc: Scenario, samples: int, seed: int, fmu_path,
              scheduler: str | None = "local", workers: int = 1, step_s: float | None = None,
              chunk_runs: int = 20000, progress: bool = True) -> UQResult:
    """The rig over the scenario's angles for `samples` parameter sets.
    scheduler None runs here, in this process; "local" or an address on Dask."""
    from ..fmu import find_fmu
    from ..runs import Progress
    t0 = time.time()
    check_geometry(sc, est)
    fmu_path = find_fmu(fmu_path)
    step_s = uq_step(sc, step_s)
    rig = replace(sc.rig, step_s=step_s)
    x, accepted = draw(est, samples, seed)
    angles = sc.sweep_angles()
    nominal = scenario_with(sc, est.names, est.mean)
    chunks = [(sc, rig, est.names, x[i:j])
              for i, j in chunk_bounds(samples, max(1, chunk_runs // len(angles)))]
    bar = Progress(samples * len(angles), f"uq {sc.name}", progress)
    try:
        return _propagate(est, sc, samples, seed, fmu_path, scheduler, workers, step_s, x, accepted,
                          angles, nominal, chunks, rig, bar, t0)
    finally:
        bar.close()


def _propagate(est, sc, samples, seed, fmu_path, scheduler, workers, step_s, x, accepted, angles,
               nominal, chunks, rig, bar, t0) -> UQResult:
    from ..rig import CMaster
    cm = CMaster(fmu_path)
    try:
        # The step check: the estimates at the scenario's own step and at the UQ step.
        fine = np.array([r[0] for r in cm.run([(nominal.params_at(a), sc.rig) for a in angles])])
        nominal_tasks = [(nominal.params_at(a), rig) for a in angles]
        nominal_runs = cm.run(nominal_tasks)
        coarse = np.array([r[0] for r in nominal_runs])
        if scheduler is None:
            results = []
            for c in chunks:
                results.append(_run_chunk_on(cm.run_grid, c))
                bar.update(len(c[3]) * len(angles))
            engine = "serial (this process)"
    finally:
        cm.close()
    check = step_check(sc.rig.step_s, step_s, coarse, fine)
    if scheduler is not None:
        from ..runs import DaskRunner
        with DaskRunner(scheduler, workers) as dr:
            results = dr.map(run_chunk, chunks, fmu_path, lambda i, r: bar.update(r[0].size))
            engine = dr.description
    phi = np.concatenate([r[0] for r in results])
    drive = np.concatenate([r[1] for r in results])
    halves = np.concatenate([r[2] for r in results])
    return UQResult(np.array(angles, dtype=float), x, est.names, accepted, phi, drive, coarse, step_s,
                    check, engine, time.time() - t0, halves, nominal_tasks,
                    check_runs(nominal_tasks, nominal_runs))


def measurement_draws(res: UQResult, sigma_deg: float, seed: int) -> np.ndarray:
    """phi of a new measurement: each run's angle plus the identification's
    measurement noise (normal, sigma_deg), from its own seeded stream."""
    rng = np.random.default_rng([seed, 1])
    return res.phi + rng.normal(0.0, sigma_deg, size=res.phi.shape)


def bands(values: np.ndarray) -> dict:
    """Per column: median and the 2.5 / 97.5 % quantiles (NaN runs left out)."""
    q = np.nanpercentile(values, [2.5, 50.0, 97.5], axis=0)
    return {"lo": q[0], "median": q[1], "hi": q[2]}
