"""Orientation sweeps and step-size studies of the rig, run over local
worker processes.  Each worker holds its own FMU instance and resets it for
every run, so results do not depend on the number of workers or the order."""
from __future__ import annotations

import math
import os
import signal
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from multiprocessing import get_context

import numpy as np

from . import closed_forms as cf
from .fmu import ContactFMU, ContactParams
from .rig import Rig, RunFigures, run
from .rig_checks import RunChecks, check_runs, warning_line
from .scenarios import Scenario, ScenarioError

# -- closed form for a scenario --------------------------------------------------


def closed_form_phi_deg(sc: Scenario, angle_deg: float, rule: str | None = None) -> float:
    """The steady trajectory angle [deg] the paper's closed form predicts for
    the scenario at the swept angle.  'general' is eq. (10)/(23) from the
    tensors themselves; the named forms are the paper's case formulas."""
    p = sc.params_at(angle_deg, rule)
    form = sc.closed_form
    if form == "general" or rule not in (None, sc.law.rule):
        return cf.steady_phi_deg(p.mu1, p.mu2, p.eps1, p.eps2, p.alpha, p.beta, p.rule)
    if form == "eq11":
        return math.degrees(math.atan(cf.eq11_tan_phi(p.mu1, p.mu2, p.beta)))
    if form == "eq31":
        return math.degrees(math.atan(cf.eq31_tan_phi(p.mu1, p.mu2, p.beta)))
    if form == "eq33":
        return math.degrees(math.atan(cf.eq33_tan_phi(p.eps1, p.eps2, p.alpha)))
    if form == "eq25":
        l1, l2 = _eq25_eigenvalues(sc)
        return math.degrees(math.atan(cf.eq25_tan_phi(l1, l2, p.alpha)))
    if form == "mat":
        r = cf.mat_ratio(p.eps1 / p.eps2, p.mu1, p.mu2)
        return math.degrees(math.atan(cf.mat_tan_phi(r, math.radians(angle_deg))))
    raise ValueError(form)


def closed_form_phi_deg_array(sc: Scenario, angles_deg, rule: str | None = None) -> np.ndarray:
    """closed_form_phi_deg over an array of swept angles [deg] at once (the
    fine scans of the report: tens of thousands of points)."""
    a = np.radians(np.asarray(angles_deg, dtype=float))
    law, form = sc.law, sc.closed_form
    alpha, beta = a + sc.alpha_offset, a + sc.beta_offset
    if form == "general" or rule not in (None, law.rule):
        t = cf.steady_tan_phi(law.mu1, law.mu2, law.eps1, law.eps2, alpha, beta, rule or law.rule)
    elif form == "eq11":
        t = cf.eq11_tan_phi(law.mu1, law.mu2, beta)
    elif form == "eq31":
        t = cf.eq31_tan_phi(law.mu1, law.mu2, beta)
    elif form == "eq33":
        t = cf.eq33_tan_phi(law.eps1, law.eps2, alpha)
    elif form == "eq25":
        t = cf.eq25_tan_phi(*_eq25_eigenvalues(sc), alpha)
    elif form == "mat":
        t = cf.mat_tan_phi(cf.mat_ratio(law.eps1 / law.eps2, law.mu1, law.mu2), a)
    else:
        raise ValueError(form)
    return np.degrees(np.arctan(t))


def _eq25_eigenvalues(sc: Scenario) -> tuple[float, float]:
    """(lambda1, lambda2) of eq. (25) for the scenario's axis geometry: Case 4
    (beta = alpha) or Case 5 (beta = alpha + 90 deg)."""
    law = sc.law
    shift = math.degrees(sc.beta_offset - sc.alpha_offset) % 180.0
    if abs(shift) < 1e-9 or abs(shift - 180.0) < 1e-9:
        return cf.eigen_ratio_case4(law.mu1, law.mu2, law.eps1, law.eps2)
    if abs(shift - 90.0) < 1e-9:
        return cf.eigen_ratio_case5(law.mu1, law.mu2, law.eps1, law.eps2)
    raise ScenarioError(sc.path, "geometry.closed_form",
                        "eq25 only with beta_offset - alpha_offset = 0 or 90 deg")


# -- workers ----------------------------------------------------------------------

_worker_fmu: ContactFMU | None = None


_STOP_SIGNALS = {signal.SIGINT, signal.SIGTERM}


def _worker_signals():
    # The main process decides about interrupts: Ctrl-C reaches the whole
    # process group, and a worker must not die with its own traceback.
    # A forked worker starts with these signals held (process_pool): what
    # arrived meanwhile is delivered now, to these dispositions.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _STOP_SIGNALS)


def _init_worker(fmu_path):
    global _worker_fmu
    _worker_signals()
    _worker_fmu = ContactFMU(fmu_path, instance_name=f"worker{os.getpid()}")


def stop_pool(ex: ProcessPoolExecutor) -> None:
    """Ends the pool now: queued tasks are cancelled and the worker processes
    terminated (shutdown(wait=True) would first run every queued task)."""
    procs = list((getattr(ex, "_processes", None) or {}).values())
    ex.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        if p.is_alive():
            p.terminate()
    for p in procs:
        p.join(timeout=5)
        if p.is_alive():
            p.kill()
            p.join(timeout=5)


def _run_one(task, fmu: ContactFMU | None = None):
    """(index, params, rig) -> (index, RunFigures), on `fmu` or the worker's
    own instance."""
    index, params, rig = task
    return index, run(params, rig, fmu=fmu or _worker_fmu, record_every=1 << 30).figures


class Progress:
    """A progress bar on stderr (a line per 10% when not a terminal)."""

    def __init__(self, total: int, label: str, enabled: bool = True):
        self.total, self.label, self.enabled = total, label, enabled
        self.done, self.t0, self.last_decile = 0, time.time(), -1
        self.tty = sys.stderr.isatty()

    def update(self, n: int = 1):
        self.done += n
        if not self.enabled:
            return
        frac = self.done / self.total
        if self.tty:
            bar = "#" * int(30 * frac)
            sys.stderr.write(f"\r{self.label:<22} [{bar:<30}] {self.done}/{self.total} "
                             f"{time.time() - self.t0:5.1f}s")
            if self.done == self.total:
                sys.stderr.write("\n")
            sys.stderr.flush()
        elif int(10 * frac) > self.last_decile:
            self.last_decile = int(10 * frac)
            print(f"{self.label}: {self.done}/{self.total} ({100 * frac:.0f}%, "
                  f"{time.time() - self.t0:.1f}s)", file=sys.stderr, flush=True)


def default_workers() -> int:
    return max(1, min(os.cpu_count() or 1, 8))


MASTERS = ("auto", "c", "fmpy")


def resolve_master(master: str, fmu_path) -> str:
    """"c" or "fmpy": auto takes the compiled master for an FMI 2.0 FMU."""
    if master not in MASTERS:
        raise ValueError(f"master must be one of {', '.join(map(repr, MASTERS))}, got {master!r}")
    from .fmu import find_fmu, fmi_version_of
    version = fmi_version_of(find_fmu(fmu_path))
    if master == "c" and version != 2:
        # checked here, in the main process, not in a worker's initializer
        raise ValueError(f"the compiled master runs FMI 2.0 FMUs, this one is FMI {version}.0; "
                         "use master='fmpy'")
    if master != "auto":
        return master
    return "c" if version == 2 else "fmpy"


_worker_cmaster = None


def _init_cworker(fmu_path):
    global _worker_cmaster
    _worker_signals()
    from .cmaster import CMaster
    from .fmu import find_fmu
    _worker_cmaster = CMaster(find_fmu(fmu_path))


def _run_chunk(chunk):
    """[(index, params, rig)] -> [(index, RunFigures)] on the worker's
    compiled master."""
    res = _worker_cmaster.run([(p, r) for _, p, r in chunk])
    return [(i, figures) for (i, _, _), figures in zip(chunk, res)]


class _SignalSafePool(ProcessPoolExecutor):
    """A pool whose submit holds SIGINT and SIGTERM while it runs.  submit
    forks the workers and records them; a signal landing in between would
    be raised inside Python's at-fork hooks (logging's lock release among
    them), reported as ignored, or leave a worker the pool does not know of
    and so never stops.  Held, it arrives once submit has returned; a forked
    worker inherits the hold until its initializer has set its dispositions
    (_worker_signals)."""

    def submit(self, fn, /, *args, **kwargs):
        if not hasattr(signal, "pthread_sigmask"):
            return super().submit(fn, *args, **kwargs)
        old = signal.pthread_sigmask(signal.SIG_BLOCK, _STOP_SIGNALS)
        try:
            return super().submit(fn, *args, **kwargs)
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)


def process_pool(workers: int, initializer, *initargs) -> ProcessPoolExecutor:
    """Worker processes: forked where that exists (they start in
    milliseconds; each creates its own FMU instance after the fork, so no FMU
    state is shared), spawned elsewhere.  The initializer must call
    _worker_signals first."""
    method = "fork" if sys.platform.startswith("linux") else "spawn"
    return _SignalSafePool(max_workers=workers, mp_context=get_context(method), initializer=initializer,
                           initargs=initargs)


def run_many(tasks: list[tuple[ContactParams, Rig]], workers: int, fmu_path, label: str,
             progress: bool = True, master: str = "auto", dask=None) -> list[RunFigures]:
    """The RunFigures (phi_deg, drive_mean_N, phi_head_deg, phi_tail_deg) of
    each (params, rig), in order.  master: "c"
    (the compiled master, FMI 2.0 FMUs), "fmpy" (the Python harness), or
    "auto" (c where it applies); both give the same angles.  dask: a
    cluster.DaskRunner to run the compiled master's chunks on (else local
    processes)."""
    out: list = [None] * len(tasks)
    bar = Progress(len(tasks), label, progress)
    indexed = [(i, p, r) for i, (p, r) in enumerate(tasks)]
    use_c = resolve_master(master, fmu_path) == "c"
    if dask is not None:
        if not use_c:
            raise ValueError("a Dask cluster runs the compiled master: use master 'c' or 'auto' "
                             "with an FMI 2.0 FMU")
        from .cluster import run_tasks
        from .fmu import find_fmu
        size = max(1, min(1000, -(-len(tasks) // 8)))
        chunks = [tasks[k:k + size] for k in range(0, len(tasks), size)]
        res = dask.map(run_tasks, chunks, find_fmu(fmu_path), lambda i, r: bar.update(len(r)))
        return [RunFigures(*x) for part in res for x in part]
    if use_c:
        # chunks small enough to show progress and balance two workers
        size = max(1, min(256, -(-len(indexed) // (4 * max(workers, 1)))))
        chunks = [indexed[k:k + size] for k in range(0, len(indexed), size)]
    if workers <= 1:
        if use_c:
            from .cmaster import CMaster
            from .fmu import find_fmu
            cm = CMaster(find_fmu(fmu_path))
            try:
                for chunk in chunks:
                    for (i, _, _), res in zip(chunk, cm.run([(p, r) for _, p, r in chunk])):
                        out[i] = res
                    bar.update(len(chunk))
            finally:
                cm.close()
            return out
        fmu = ContactFMU(fmu_path, instance_name="serial")
        try:
            for t in indexed:
                i, out[i] = _run_one(t, fmu)
                bar.update()
        finally:
            fmu.close()
        return out
    ex = process_pool(workers, _init_cworker if use_c else _init_worker, fmu_path)
    try:
        if use_c:
            futures = [ex.submit(_run_chunk, c) for c in chunks]
            for fut in as_completed(futures):
                done = fut.result()
                for i, figures in done:
                    out[i] = figures
                bar.update(len(done))
        else:
            futures = [ex.submit(_run_one, t) for t in indexed]
            for fut in as_completed(futures):
                i, figures = fut.result()
                out[i] = figures
                bar.update()
    except BaseException:
        stop_pool(ex)
        raise
    ex.shutdown()
    return out


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


def _parabolic_extremum(f, xs, fs, tol: float = 1e-4, max_evals: int = 12):
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


def _golden_extremum(f, a: float, b: float, tol: float = 1e-3) -> tuple[float, float]:
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
    if resolve_master(master, fmu_path) == "c":
        from .cmaster import CMaster
        from .fmu import find_fmu
        engine = CMaster(find_fmu(fmu_path))
        one = lambda a, rule=None: engine.run([(sc.params_at(a, rule), sc.rig)])[0][0]
        record = lambda a, every: engine.record(sc.params_at(a), sc.rig, every)
    else:
        engine = ContactFMU(fmu_path, instance_name="main")
        one = lambda a, rule=None: run(sc.params_at(a, rule), sc.rig, fmu=engine,
                                       record_every=1 << 30).phi_deg
        record = lambda a, every: run(sc.params_at(a), sc.rig, fmu=engine, record_every=every)
    try:
        if sc.sweep["refine_extremum"] and len(angles) >= 3 and abs(phi[k]) > 1e-6:
            sign = 1.0 if phi[k] > 0 else -1.0
            step = sc.sweep["step_deg"]
            lo, hi = max(angles[0], angles[k] - step), min(angles[-1], angles[k] + step)
            cache, runs = {}, [0]

            def f(a):
                if a not in cache:
                    cache[a] = sign * one(a)
                    runs[0] += 1
                return cache[a]
            # phi is smooth about its extremum: parabolas through the grid's
            # three best points converge in a few runs; golden section if not.
            idx = [j for j in (k - 1, k, k + 1) if 0 <= j < len(angles)]
            found = None
            if len(idx) == 3:
                for j in idx:
                    cache[float(angles[j])] = sign * float(phi[j])
                found = _parabolic_extremum(f, [float(angles[j]) for j in idx],
                                            [sign * float(phi[j]) for j in idx])
            a_ext, v = found if found is not None else _golden_extremum(f, lo, hi)
            if v >= sign * phi[k]:
                extremum = {"angle_deg": a_ext, "phi_deg": sign * v, "refined": True,
                            "evaluations": runs[0]}
        # The other implicit rule at the same angle: the sign of phi is what
        # tells the rules apart (report.md).
        other = {"coupled": "associated", "associated": "coupled"}.get(sc.law.rule)
        if other:
            extremum["other_rule"] = {"rule": other, "phi_deg": one(extremum["angle_deg"], other)}
        n_rec = max(1, int(sc.rig.travel_m / (sc.rig.velocity_m_s * sc.rig.step_s) / 400))
        traj = {float(a): record(a, n_rec) for a in sc.sweep["trajectory_angles_deg"]}
    finally:
        engine.close()
    return SweepResult(np.array(angles, dtype=float), phi, closed, drive, extremum, grid_ext, workers,
                       time.time() - t0, traj, list(res), checks)


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
