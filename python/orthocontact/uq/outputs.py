"""uq's results: the bands as CSV and JSON, the drawn sets, and the figure."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..experiment import Scenario
from ..rig import SETTLE_TOL_DEG
from .estimates import Estimates
from .propagate import UQResult, bands, measurement_draws
from .source import Source

# -- outputs ----------------------------------------------------------------------

def write_outputs(res: UQResult, est: Estimates, sc: Scenario, seed: int, out: Path, source: Source) -> dict:
    """uq_bands.csv, samples.csv, uq.json, uq.png into out; returns the JSON,
    which names the identification drawn from (`source`)."""
    from ..output import write_csv, write_json
    bp, bd = bands(res.phi), bands(res.drive)
    nan = np.full(len(res.angles_deg), np.nan)
    noise = est.at_velocity(sc.rig.velocity_m_s)[1]
    bm = bands(measurement_draws(res, noise, seed)) if noise is not None else {"lo": nan, "hi": nan}
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
        "identification": source.as_json(), "scenario": sc.name, "scenario_file": str(sc.path),
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
        "widest_band": widest_band(res.angles_deg, bp),
        "measurement_noise_deg": noise,
        "data_inside_measurement_band": inside_measurement_band(res.angles_deg, bm, est, sc),
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
    return (math.isclose(sc.geometry.alpha_offset_deg, est.alpha_offset_deg, abs_tol=1e-9)
            and math.isclose(sc.geometry.beta_offset_deg, est.beta_offset_deg, abs_tol=1e-9))


def inside_measurement_band(angles, bm, est: Estimates, sc: Scenario) -> dict | None:
    """How many of the identification's measured angles lie in the
    measurement band (interpolated at their angles): about 95 % if the
    model and its uncertainty hold."""
    points = est.at_velocity(sc.rig.velocity_m_s)[0]
    if points is None or not _same_geometry(sc, est) or not np.all(np.isfinite(bm["lo"])):
        return None
    a, phi = points[:, 0], points[:, 1]
    ok = (a >= angles[0]) & (a <= angles[-1])
    lo, hi = np.interp(a[ok], angles, bm["lo"]), np.interp(a[ok], angles, bm["hi"])
    inside = int(np.sum((phi[ok] >= lo) & (phi[ok] <= hi)))
    return {"inside": inside, "points": int(ok.sum()), "fraction": inside / max(int(ok.sum()), 1)}


def widest_band(angles, bp) -> dict:
    """Where the parameters' band (bp's lo and hi [deg] at each of `angles`
    [deg]) is widest: that angle and the width, in degrees."""
    w = bp["hi"] - bp["lo"]
    k = int(np.nanargmax(w))
    return {"angle_deg": float(angles[k]), "width_deg": float(w[k])}


def _figure(res: UQResult, est: Estimates, sc: Scenario, bp: dict, bm: dict, path: Path) -> None:
    from ..output import finish, pyplot, swept_label
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 4.5))
    a = res.angles_deg
    if np.all(np.isfinite(bm["lo"])):
        ax.fill_between(a, bm["lo"], bm["hi"], color="C1", alpha=0.18, lw=0,
                        label="95 %: a new measurement")
    ax.fill_between(a, bp["lo"], bp["hi"], color="C0", alpha=0.35, lw=0,
                    label="95 %: parameters only")
    ax.plot(a, bp["median"], "-", color="C0", label="median")
    ax.plot(a, res.nominal_phi, "--", color="0.25", lw=1, label="at the estimates")
    points = est.at_velocity(sc.rig.velocity_m_s)[0]
    if points is not None and _same_geometry(sc, est):
        ax.plot(points[:, 0], points[:, 1], "o", ms=4, color="C3",
                label="identification data")
    ax.set_xlabel(f"{swept_label(sc)} [deg]")
    ax.set_ylabel("trajectory angle φ [deg] (counterclockwise)")
    finish(fig, ax, path, f"{sc.name}: {len(res.samples)} parameter sets drawn from {est.path.name}",
            "bands over the draws", outside=True)
