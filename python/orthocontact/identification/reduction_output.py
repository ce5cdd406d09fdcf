"""What a reduction of raw recordings gives on: the MeasurementSet the fit
takes (one value per run with its within-run error), the reduction table
(reduction.csv, reduction.json) and a figure per mat angle (the runs' paths
with their windows and fitted lines).  Units: s, m, N, deg."""
from __future__ import annotations

import csv
import dataclasses
import math
from pathlib import Path

import numpy as np

from .identified import ReductionSummary
from .measurements import MeasurementSet, plausible_data
from .recordings import Recordings
from .reduction import Reduction

COLUMNS = ("run", "kind", "mat_angle_deg", "velocity_m_s", "window_t0_s", "window_t1_s",
           "window_x1_start_m", "window_x1_end_m", "speed_m_s", "phi_deg", "phi_se_deg",
           "phi_first_half_deg", "phi_second_half_deg", "force_N", "force_se_N",
           "stiffness_N_m", "stiffness_se_N_m", "samples", "flags")


def to_measurements(rec: Recordings, red: Reduction) -> MeasurementSet:
    """The runs' values as a MeasurementSet: angles and forces from the
    slide runs that settled, F_int per carriage run, the ramp runs' stick
    stiffness.  With carriage runs, rig.f_int_N is their mean (for the
    paper's formulas); the joint fit estimates F_int itself."""
    rig = rec.rig
    slides = red.of_kind("slide")
    carriage = red.of_kind("carriage")
    ramps = red.of_kind("ramp")
    if carriage:
        rig = dataclasses.replace(rig, f_int_N=float(np.mean([r.force_N for r in carriage])))
    sign = -1.0 if rig.phi_convention == "paper" else 1.0
    angles = np.array([[r.mat_angle_deg, sign * r.phi_deg] for r in slides])
    forces = np.array([[r.mat_angle_deg, r.force_N] for r in slides])
    velocities = np.array([r.velocity_m_s for r in slides])
    warnings = list(rec.warnings) + list(red.warnings)
    stiffness = (np.array([[r.mat_angle_deg, r.stiffness_N_m, r.stiffness_se_N_m] for r in ramps])
                 if ramps else None)
    warnings += plausible_data(rec.folder, rig, forces, angles, names=[r.run for r in slides],
                               stiffness=stiffness, ramp_names=[r.run for r in ramps])
    return MeasurementSet(
        rec.folder, rig, forces, angles, None, velocities, tuple(warnings),
        force_se=np.array([r.force_se_N for r in slides]),
        angle_se=np.array([r.phi_se_deg for r in slides]),
        force_velocities=velocities,
        carriage=np.array([[r.force_N, r.force_se_N] for r in carriage]) if carriage else None,
        stiffness=stiffness)


def reduction_summary(red: Reduction, figures, scenario: Path | None) -> ReductionSummary:
    """What identified.json says of the reduction: runs of each kind, those
    left out and flagged, and the files written beside it."""
    return ReductionSummary(runs={k: sum(r.kind == k for r in red.runs)
                                  for k in ("slide", "carriage", "ramp")},
                            left_out=tuple(r.run for r in red.runs if not r.used),
                            flagged={r.run: r.flags for r in red.runs if r.flags},
                            table="reduction.csv", figures=tuple(Path(f).name for f in figures),
                            scenario=scenario.name if scenario else None)


def rows(red: Reduction) -> list:
    out = []
    for r in red.runs:
        out.append({"run": r.run, "kind": r.kind, "mat_angle_deg": r.mat_angle_deg,
                    "velocity_m_s": r.velocity_m_s, "window_t0_s": r.window_s[0],
                    "window_t1_s": r.window_s[1], "window_x1_start_m": r.window_x1_m[0],
                    "window_x1_end_m": r.window_x1_m[1], "speed_m_s": r.speed_m_s,
                    "phi_deg": r.phi_deg, "phi_se_deg": r.phi_se_deg,
                    "phi_first_half_deg": r.phi_halves_deg[0], "phi_second_half_deg": r.phi_halves_deg[1],
                    "force_N": r.force_N, "force_se_N": r.force_se_N, "stiffness_N_m": r.stiffness_N_m,
                    "stiffness_se_N_m": r.stiffness_se_N_m, "samples": r.samples,
                    "flags": " ".join(r.flags)})
    return out


def _json_value(v):
    return None if isinstance(v, float) and not math.isfinite(v) else v


def write_table(red: Reduction, out: Path):
    """reduction.csv (one row per run; empty cells where a kind has no
    such value) and reduction.json (the same, and the warnings)."""
    from ..output import write_json
    table = rows(red)
    with open(out / "reduction.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, COLUMNS)
        w.writeheader()
        for row in table:
            w.writerow({k: ("" if isinstance(v, float) and not math.isfinite(v) else
                            (f"{v:.10g}" if isinstance(v, float) else v)) for k, v in row.items()})
    write_json(out / "reduction.json", {
        "runs": [{k: _json_value(v) for k, v in row.items()} for row in table],
        "warnings": list(red.warnings),
        "method": {"window": "the longest stretch at the cruise speed (within 3 %), less the leading "
                             "eighths whose path slope differs from the rest's by more than 4 standard "
                             "errors (at most half)",
                   "phi": "line fit x2 = c + x1 tan(phi) over the window, standard error from its residuals",
                   "force": "mean over the window's time span, standard error of the mean",
                   "not_steady": "the window's halves disagree by > 5 standard errors and > 0.05 deg; "
                                 "left out of the fit",
                   "outlier": "robust z > 5 within its angle and velocity (median, 1.4826 MAD); kept",
                   "ramp": "stick stiffness: line fit of the force against the hinge-fitted travel, "
                           "10-85 % of the rise to sliding"}})


def write_figures(rec: Recordings, red: Reduction, out: Path) -> list:
    """reduction_<angle>deg.png per mat angle: each run's path against x1
    as its deviation from the mean fitted line of the runs at its velocity
    (a run's slope then shows as a tilt), the window bold, the run's fitted
    line dashed.  Returns the files written."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = {r.name: r for r in rec.runs}
    written = []
    by_angle = {}
    for r in red.runs:
        if r.kind == "slide":
            by_angle.setdefault(r.mat_angle_deg, []).append(r)
    for angle, reds in sorted(by_angle.items()):
        fig, ax = plt.subplots(figsize=(7, 4.2))
        velocities = sorted({r.velocity_m_s for r in reds})
        mean_slope = {v: np.mean([r.line[1] for r in reds if r.velocity_m_s == v]) for v in velocities}
        for r in reds:
            tr = runs[r.run].trajectory
            ok = np.isfinite(tr[:, 1]) & np.isfinite(tr[:, 2])
            b0 = mean_slope[r.velocity_m_s]
            x1, x2 = tr[ok, 1], tr[ok, 2] - r.line[0] - b0 * tr[ok, 1]
            c = f"C{velocities.index(r.velocity_m_s)}"
            ax.plot(x1, 1e3 * x2, "-", color=c, lw=0.6, alpha=0.5)
            win = (x1 >= r.window_x1_m[0]) & (x1 <= r.window_x1_m[1])
            ax.plot(x1[win], 1e3 * x2[win], "-", color=c, lw=1.6)
            xs = np.array(r.window_x1_m)
            ax.plot(xs, 1e3 * (r.line[1] - b0) * xs, "--", color="k", lw=0.8)
            if r.flags:
                ax.annotate(f"{r.run}: {' '.join(r.flags)}", (x1[-1], 1e3 * x2[-1]), fontsize=7)
        for i, v in enumerate(velocities):
            phis = [r.phi_deg for r in reds if r.velocity_m_s == v]
            sd = np.std(phis, ddof=1) if len(phis) > 1 else 0
            ax.plot([], [], "-", color=f"C{i}",
                    label=f"{v:g} m/s: {len(phis)} runs, φ = {np.mean(phis):.2f} ± {sd:.2f}° (sd)")
        ax.plot([], [], "--", color="k", label="fitted line over the steady window (bold)")
        ax.set_xlabel("x1 [m]")
        ax.set_ylabel("x2 less the mean fitted line at its velocity [mm]")
        ax.set_title(f"{rec.folder.name}: mat angle {angle:g}°", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        path = out / f"reduction_{angle:g}deg.png"
        fig.savefig(path, dpi=100)
        plt.close(fig)
        written.append(path)
    return written


RIG_SCENARIO_DESCRIPTION = ("Written by orthocontact identify from the recordings' estimates: the law, "
                            "F_int and the strip's viscosity as identified (identified.json has their "
                            "intervals).")


def write_rig_scenario(data: MeasurementSet, values: dict, out: Path) -> Path | None:
    """rig_scenario.toml: the identified law on the lab's rig (its mass, the
    estimated F_int and strip viscosity) at the velocity with the most slide
    runs, swept over the runs' mat angles: the scenario `orthocontact uq`
    draws bands on, against the runs at that velocity.  None if the law's
    parameters were not all identified."""
    if not {"mu1", "mu2", "eps_ratio"} <= set(values):
        return None
    rig = data.rig
    v, counts = np.unique(data.velocities_of_angles(), return_counts=True)
    velocity = float(v[np.argmax(counts)])
    a = data.angles[:, 0]
    eps2 = values.get("eps2", rig.eps2_nominal_N_m)
    text = f'''name = "{data.folder.name}_identified"
title = "The identified law on the rig of {data.folder.name} at {velocity:g} m/s"
kind = "sweep"
description = "{RIG_SCENARIO_DESCRIPTION}"

[law]
rule = "{rig.rule}"
mu1 = {values["mu1"]!r}
mu2 = {values["mu2"]!r}
eps2 = {float(eps2)!r}
eps_ratio = {values["eps_ratio"]!r}

[geometry]
alpha_offset_deg = {rig.alpha_offset_deg!r}
beta_offset_deg = {rig.beta_offset_deg!r}

[sweep]
start_deg = {float(a.min())!r}
stop_deg = {float(a.max())!r}
step_deg = 2.5

[rig]
mode = "quasistatic"
mass_kg = {rig.mass_kg!r}
g = {rig.g!r}
f_int_N = {float(values.get("f_int", rig.f_int_N))!r}
velocity_m_s = {velocity!r}
mu_strip = {rig.mu_strip!r}
c_strip = {float(values.get("c_strip", rig.c_strip or 0.0))!r}
'''
    path = out / "rig_scenario.toml"
    path.write_text(text)
    return path
