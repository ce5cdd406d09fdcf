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
serial or on Dask.
"""
from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from .errors import InputError
from .rig import RunFigures
from .rig_checks import SETTLE_TOL_DEG, RunChecks, angle_list, check_runs, warning_line
from .scenarios import Scenario

LAW_PARAMETERS = ("mu1", "mu2", "eps_ratio", "eps2")
IMPLICIT_RULES = ("associated", "coupled")
# The step-size study (scenarios/step_study.toml; docs/benchmarks.md): the
# implicit rules' steady angle does not depend on the step, and the dynamic
# rig's lateral transient moves it by < 1e-6 deg between 0.2 and 4 ms.
DEFAULT_STEP_S = 4e-3
STEP_CHECK_WARN_DEG = 0.01


@dataclass
class Estimates:
    """What uq draws from: names, values and covariance of the identified
    parameters (mu1, mu2 [-], eps_ratio [-], eps2 [N/m], any subset), and the
    identification's rule, geometry and measured points."""
    path: Path
    names: list
    mean: np.ndarray
    cov: np.ndarray
    rule: str
    alpha_offset_deg: float
    beta_offset_deg: float
    angle_points: np.ndarray | None  # [[mat angle deg, phi deg counterclockwise]]
    angle_noise_deg: float | None    # the identification's noise estimate of a measured angle


def load_estimates(path) -> Estimates:
    """identified.json -> Estimates; InputError naming the file and the field."""
    path = Path(path)
    try:
        d = json.loads(path.read_text())
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})") from None
    except ValueError as e:
        raise InputError(f"{path}: expected JSON written by `orthocontact identify` ({e})") from None
    if not isinstance(d, dict):
        raise InputError(f"{path}: expected a JSON object written by `orthocontact identify`")
    cov = d.get("covariance")
    if not isinstance(cov, dict) or not {"parameters", "values", "matrix"} <= set(cov):
        raise InputError(f"{path}: covariance: expected parameters, values and matrix "
                         "(written by `orthocontact identify` since version 0.3; run it again)")
    names = cov["parameters"]
    unknown = [n for n in names if n not in LAW_PARAMETERS]
    if not isinstance(names, list) or not names or unknown:
        raise InputError(f"{path}: covariance.parameters: expected some of {', '.join(LAW_PARAMETERS)}"
                         f", got {names!r}")
    try:
        mean = np.array(cov["values"], dtype=float)
        C = np.array(cov["matrix"], dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{path}: covariance: expected numbers in values and matrix") from None
    k = len(names)
    if mean.shape != (k,) or C.shape != (k, k):
        raise InputError(f"{path}: covariance: expected {k} values and a {k}x{k} matrix, "
                         f"got {mean.shape[0] if mean.ndim else 0} and {C.shape}")
    if not (np.all(np.isfinite(mean)) and np.all(np.isfinite(C))):
        raise InputError(f"{path}: covariance: expected finite numbers")
    if np.any(mean <= 0):
        raise InputError(f"{path}: covariance.values: expected estimates > 0, got {mean.tolist()}")
    # Judged in correlation form: the parameters' scales differ by 1e8.
    sd = np.sqrt(np.clip(np.diag(C), 0, None))
    norm = np.outer(sd, sd)
    norm[norm == 0] = 1.0
    if np.any(np.diag(C) < 0) or np.abs(C - C.T).max(initial=0) > 1e-9 * norm.max() or \
            np.any(np.abs(C - C.T) / norm > 1e-6) or \
            np.linalg.eigvalsh(0.5 * (C + C.T) / norm).min() < -1e-9:
        raise InputError(f"{path}: covariance.matrix: expected a symmetric positive semidefinite "
                         "matrix")
    a = d.get("assumptions") or {}
    rule = a.get("rule")
    if rule not in IMPLICIT_RULES + ("eq20",):
        raise InputError(f"{path}: assumptions.rule: expected associated, coupled or eq20, got {rule!r}")
    pts = (d.get("points") or {}).get("angles")
    points = np.array(pts, dtype=float).reshape(-1, 2) if pts else None
    noise = (d.get("noise_estimate") or {}).get("angles_deg")
    if noise is not None and not (isinstance(noise, (int, float)) and math.isfinite(noise) and noise >= 0):
        raise InputError(f"{path}: noise_estimate.angles_deg: expected a number >= 0, got {noise!r}")
    return Estimates(path, list(names), mean, 0.5 * (C + C.T), rule,
                     float(a.get("alpha_offset_deg", 0.0)), float(a.get("beta_offset_deg", 0.0)), points,
                     None if noise is None else float(noise))


def draw(est: Estimates, n: int, seed: int) -> tuple[np.ndarray, float]:
    """n parameter sets (rows, columns est.names) from the normal
    distribution of the estimates, only those with every parameter > 0 (the
    normal truncated to the physical region); and the fraction of draws kept."""
    rng = np.random.default_rng(seed)
    kept, have, drawn = [], 0, 0
    while have < n:
        batch = max(1024, 2 * (n - have))
        # eigh: defined for a semidefinite covariance too, and the same on every machine
        x = rng.multivariate_normal(est.mean, est.cov, size=batch, method="eigh")
        drawn += batch
        kept.append(x[np.all(x > 0, axis=1)])
        have += len(kept[-1])
        if drawn >= 1000 * n + 10**6 and have < n:
            raise InputError(f"{est.path}: covariance: fewer than 1 in 1000 draws are physical "
                             "(all parameters > 0); the estimates are too uncertain to propagate")
    return np.concatenate(kept)[:n], have / drawn


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


def _run_chunk_on(run, chunk):
    """chunk = (scenario, rig, names, rows) -> phi, drive and head - tail
    (rig_checks: a settled run's halves agree) arrays [len(rows) x angles],
    the runs made by run([(params, rig)])."""
    sc, rig, names, rows = chunk
    arr = np.array(run(chunk_tasks(sc, rig, names, rows)), dtype=float)
    arr = arr.reshape(len(rows), len(sc.sweep_angles()), len(RunFigures._fields))
    return arr[:, :, 0], arr[:, :, 1], arr[:, :, 2] - arr[:, :, 3]


def run_chunk(fmu, chunk):
    """On a worker: _run_chunk_on the worker's compiled master for `fmu`."""
    from .cluster import run_tasks
    return _run_chunk_on(lambda tasks: run_tasks(fmu, tasks), chunk)


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
                            self.nominal_phi, self.nominal_tasks)
        if line:
            parts.append(line)
        if sc.law.rule != "eq20" and self.unsettled.any():
            bad = self.unsettled
            parts.append(f"uq {sc.name}: {int(bad.sum())} of {bad.size} runs over the drawn parameter "
                         f"sets did not settle (halves of the fitted path up to "
                         f"{np.nanmax(np.abs(np.where(bad, self.halves, 0))):.3g} deg apart; angles "
                         f"{angle_list(self.angles_deg[bad.any(axis=0)])} deg): their bands are not "
                         "steady-state predictions; use a quasi-static rig or a longer travel")
        return "; ".join(parts) or None


def check_geometry(sc: Scenario, est: Estimates) -> None:
    if sc.kind != "sweep":
        raise InputError(f"{sc.path}: kind: expected a sweep scenario for uq, got {sc.kind!r}")
    if sc.law.rule != est.rule:
        raise InputError(f"{sc.path}: law.rule: expected {est.rule!r}, the rule the parameters of "
                         f"{est.path} were identified under, got {sc.law.rule!r}")


def propagate(est: Estimates, sc: Scenario, samples: int, seed: int, fmu_path,
              scheduler: str | None = "local", workers: int = 1, step_s: float | None = None,
              chunk_runs: int = 1000, progress: bool = True) -> UQResult:
    """The rig over the scenario's angles for `samples` parameter sets.
    scheduler None runs here, in this process; "local" or an address on Dask."""
    from .cmaster import CMaster
    from .fmu import find_fmu
    from .sweep import Progress
    t0 = time.time()
    check_geometry(sc, est)
    fmu_path = find_fmu(fmu_path)
    if step_s is None:
        step_s = DEFAULT_STEP_S if sc.law.rule in IMPLICIT_RULES else sc.rig.step_s
    rig = replace(sc.rig, step_s=step_s)
    x, accepted = draw(est, samples, seed)
    angles = sc.sweep_angles()
    nominal = scenario_with(sc, est.names, est.mean)
    per = max(1, chunk_runs // len(angles))
    chunks = [(sc, rig, est.names, x[i:i + per]) for i in range(0, samples, per)]
    bar = Progress(samples * len(angles), f"uq {sc.name}", progress)
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
                results.append(_run_chunk_on(cm.run, c))
                bar.update(len(c[3]) * len(angles))
            engine = "serial (this process)"
    finally:
        cm.close()
    dev = float(np.nanmax(np.abs(coarse - fine))) if np.any(np.isfinite(fine)) else float("nan")
    check = {"scenario_step_s": sc.rig.step_s, "uq_step_s": step_s, "max_abs_difference_deg": dev}
    if scheduler is not None:
        from .cluster import DaskRunner
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


# -- outputs ----------------------------------------------------------------------

def write_outputs(res: UQResult, est: Estimates, sc: Scenario, seed: int, out: Path) -> dict:
    """uq_bands.csv, samples.csv, uq.json, uq.png into out; returns the JSON."""
    from .tables import write_csv, write_json
    bp, bd = bands(res.phi), bands(res.drive)
    nan = np.full(len(res.angles_deg), np.nan)
    bm = bands(measurement_draws(res, est.angle_noise_deg, seed)) if est.angle_noise_deg is not None \
        else {"lo": nan, "hi": nan}
    header = ["angle_deg", "phi_median_deg", "phi_p2.5_deg", "phi_p97.5_deg", "measured_p2.5_deg",
              "measured_p97.5_deg", "phi_at_estimates_deg", "drive_median_N", "drive_p2.5_N",
              "drive_p97.5_N"]
    rows = [(float(a), float(bp["median"][i]), float(bp["lo"][i]), float(bp["hi"][i]),
             float(bm["lo"][i]), float(bm["hi"][i]),
             float(res.nominal_phi[i]), float(bd["median"][i]), float(bd["lo"][i]), float(bd["hi"][i]))
            for i, a in enumerate(res.angles_deg)]
    write_csv(out / "uq_bands.csv", header, rows)
    write_csv(out / "samples.csv", res.names, [tuple(float(v) for v in r) for r in res.samples])
    n_nan = int(np.sum(~np.isfinite(res.phi)))
    summary = {
        "identification": str(est.path), "scenario": sc.name, "scenario_file": str(sc.path),
        "rule": sc.law.rule, "parameters": res.names,
        "estimates": dict(zip(res.names, map(float, est.mean))),
        "draws": {n: {"mean": float(np.mean(res.samples[:, j])), "sd": float(np.std(res.samples[:, j]))}
                  for j, n in enumerate(res.names)},
        "samples": int(len(res.samples)), "seed": seed, "runs": int(res.phi.size),
        "accepted_fraction": res.accepted_fraction,
        "non_finite_runs": n_nan,
        "step_s": res.step_s, "step_check": res.step_check,
        "checks": {"unsettled_runs": int(res.unsettled.sum()),
                   "settle_tolerance_deg": SETTLE_TOL_DEG,
                   "at_estimates": [{"angle_deg": float(a), "check": st} for a, st in
                                    zip(res.angles_deg, res.nominal_checks.status())],
                   "warning": res.warning(sc)},
        "widest_band": _widest(res.angles_deg, bp),
        "measurement_noise_deg": est.angle_noise_deg,
        "data_inside_measurement_band": _inside(res.angles_deg, bm, est, sc),
        "bands": [dict(zip(header, r)) for r in rows],
        "band_meaning": {"phi": "2.5-97.5 % of the rig's phi over the drawn parameter sets: the "
                                "parameters' uncertainty alone",
                         "measured": "the same plus the identification's measurement noise: where "
                                     "95 % of new measured angles should fall"},
        "engine": res.engine, "seconds": round(res.seconds, 3),
        "units": "angles in degrees (phi counterclockwise), forces in N, eps2 in N/m",
    }
    write_json(out / "uq.json", summary)
    _figure(res, est, sc, bp, bm, out / "uq.png")
    return summary


def _same_geometry(sc: Scenario, est: Estimates) -> bool:
    return (math.isclose(math.degrees(sc.alpha_offset), est.alpha_offset_deg, abs_tol=1e-9)
            and math.isclose(math.degrees(sc.beta_offset), est.beta_offset_deg, abs_tol=1e-9))


def _inside(angles, bm, est: Estimates, sc: Scenario) -> dict | None:
    """How many of the identification's measured angles lie in the
    measurement band (interpolated at their angles): about 95 % if the
    model and its uncertainty hold."""
    if est.angle_points is None or not _same_geometry(sc, est) or not np.all(np.isfinite(bm["lo"])):
        return None
    a, phi = est.angle_points[:, 0], est.angle_points[:, 1]
    ok = (a >= angles[0]) & (a <= angles[-1])
    lo, hi = np.interp(a[ok], angles, bm["lo"]), np.interp(a[ok], angles, bm["hi"])
    inside = int(np.sum((phi[ok] >= lo) & (phi[ok] <= hi)))
    return {"inside": inside, "points": int(ok.sum()), "fraction": inside / max(int(ok.sum()), 1)}


def _widest(angles, bp) -> dict:
    w = bp["hi"] - bp["lo"]
    k = int(np.nanargmax(w))
    return {"angle_deg": float(angles[k]), "width_deg": float(w[k])}


def _figure(res: UQResult, est: Estimates, sc: Scenario, bp: dict, bm: dict, path: Path) -> None:
    from .figures import _finish, _plt, _swept_label
    plt = _plt()
    fig, ax = plt.subplots(figsize=(8, 4.5))
    a = res.angles_deg
    if np.all(np.isfinite(bm["lo"])):
        ax.fill_between(a, bm["lo"], bm["hi"], color="C1", alpha=0.18, lw=0,
                        label="95 %: a new measurement")
    ax.fill_between(a, bp["lo"], bp["hi"], color="C0", alpha=0.35, lw=0,
                    label="95 %: parameters only")
    ax.plot(a, bp["median"], "-", color="C0", label="median")
    ax.plot(a, res.nominal_phi, "--", color="0.25", lw=1, label="at the estimates")
    if est.angle_points is not None and _same_geometry(sc, est):
        ax.plot(est.angle_points[:, 0], est.angle_points[:, 1], "o", ms=4, color="C3",
                label="identification data")
    ax.set_xlabel(f"{_swept_label(sc)} [deg]")
    ax.set_ylabel("trajectory angle φ [deg] (counterclockwise)")
    _finish(fig, ax, path, f"{sc.name}: {len(res.samples)} parameter sets drawn from {est.path.name}",
            "bands over the draws", outside=True)
