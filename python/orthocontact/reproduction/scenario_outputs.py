"""A scenario's results for machines (sweep.csv, trajectories.csv,
step_study.csv, summary.json with its self-checks) and for people (PNG
figures).  Every writer takes the folder to write into; the CLI hands it a
staging folder and moves the files into place only when all are written.
The runners of the kinds sweep and step_study (their piece "run",
experiment.kinds) are here."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import closed_forms as cf
from ..experiment import RunOptions, Scenario, part
from ..output import curve_style, draw_here, finish, pyplot, swept_label, write_csv, write_json
from ..rig import SETTLE_TOL_DEG, STEADY_TOL_DEG
from ..runs import StepStudyResult, SweepResult, closed_form_phi_deg_array, run_step_study, run_sweep

FLAT_DEG = 1e-9  # a closed form below this everywhere is flat: no extremum


def sweep_outputs(sc: Scenario, res: SweepResult, out: Path, draw=None) -> dict:
    """sweep.csv, trajectories.csv, three figures; returns the summary.
    draw(fn, *args) draws a figure (default: here and now; a FigureDrawer
    draws them in worker processes)."""
    write_sweep_tables(sc, res, out)
    closed_ext = _closed_extremum(sc, res)
    # Flat when the paper's closed form is: then there is no extremum to show,
    # however far a short dynamic run has settled.
    flat = abs(closed_ext["phi_deg"]) < FLAT_DEG
    draw = draw or draw_here
    draw(figure_phi, sc, res, out / "phi_vs_angle.png", flat)
    draw(_figure_paths, sc, res, out / "trajectories.png", "x2")
    draw(_figure_paths, sc, res, out / "force_vs_travel.png", "drive")
    summary = sweep_summary(sc, res, closed_ext, flat)
    summary.update(drive_figures(sc, res))
    write_json(out / "summary.json", summary)
    return summary


def write_sweep_tables(sc: Scenario, res: SweepResult, out: Path) -> None:
    """sweep.csv (an angle a row: the axes, phi against the closed form, the
    drive, each half's angle and the check) and trajectories.csv (the
    recorded runs' steps)."""
    rows = []
    ch = res.checks
    for i, (a, phi, c, d) in enumerate(zip(res.angles_deg, res.phi_deg, res.phi_closed_deg,
                                           res.drive_mean_N)):
        p = sc.params_at(a)
        f = res.figures[i]
        rows.append((float(a), math.degrees(p.alpha), math.degrees(p.beta), float(phi), float(c),
                     float(phi - c), float(d), float(f.phi_head_deg), float(f.phi_tail_deg),
                     float(ch.steady_deg[i]), ch.status()[i]))
    write_csv(out / "sweep.csv", ["angle_deg", "alpha_deg", "beta_deg", "phi_deg", "phi_closed_deg",
                                  "deviation_deg", "drive_mean_N", "phi_head_deg", "phi_tail_deg",
                                  "phi_steady_deg", "check"], rows)
    traj_rows = []
    for a, r in res.trajectories.items():
        for i in range(len(r.t)):
            traj_rows.append((a, float(r.t[i]), float(r.x1[i]), float(r.x2[i]), float(r.T1[i]),
                              float(r.T2[i]), float(r.drive[i]), int(r.state[i])))
    write_csv(out / "trajectories.csv", ["angle_deg", "t_s", "x1_m", "x2_m", "T1_N", "T2_N",
                                         "drive_N", "contact_state"], traj_rows)


def sweep_summary(sc: Scenario, res: SweepResult, closed_ext: dict, flat: bool) -> dict:
    """summary.json of a sweep: the extremum (none for a flat curve: the
    closed form zero everywhere), the closed form's, the deviation, the checks."""
    e = res.extremum
    return {
        **sc.head(), "mode": sc.rig.mode,
        "rule": sc.law.rule, "n_angles": int(len(res.angles_deg)), "workers": res.workers,
        "seconds": round(res.seconds, 3),
        "extremum": None if flat else {"angle_deg": e["angle_deg"], "phi_deg": e["phi_deg"],
                                       **({"other_rule": e["other_rule"]} if "other_rule" in e else {}),
                                       "steady_sliding": extremum_is_steady(res)},
        "flat": flat,
        "extremum_refined": bool(e.get("refined", False)) and not flat,
        "grid_extremum": res.grid_extremum,
        "max_abs_phi_deg": float(np.max(np.abs(res.phi_deg))),
        "closed_form": sc.closed_form,
        "closed_form_extremum": closed_ext,
        "max_deviation_deg": res.max_deviation_deg,
        "angle_convention": "counterclockwise from X1; phi = atan(dx2/dx1) of the fitted path",
        "checks": checks_summary(res.checks, res.angles_deg, res.phi_deg, res.warning(sc)),
    }


def drive_figures(sc: Scenario, res: SweepResult) -> dict:
    """The mean drive [N] at 0 and 90 deg where the grid has them; with
    both, and the axes along the mat's, mu1 and mu2 from them (eq. 1)."""
    drives = {}
    for target in (0.0, 90.0):
        hit = np.where(np.abs(res.angles_deg - target) < 1e-9)[0]
        if len(hit):
            drives[f"{target:g}"] = float(res.drive_mean_N[hit[0]])
    if not drives:
        return {}
    found = {"drive_mean_N": drives}
    if math.isclose(sc.geometry.beta_offset_deg % 180.0, 0.0, abs_tol=1e-9) and len(drives) == 2:
        # Sliding along a friction axis at 0 and 90 deg: eq. (1).
        r = sc.rig
        found["mu_from_drive"] = {"mu1": cf.eq1_mu(drives["0"], r.f_int_N, r.mass_kg, r.g),
                                  "mu2": cf.eq1_mu(drives["90"], r.f_int_N, r.mass_kg, r.g)}
    return found


def extremum_is_steady(res: SweepResult) -> bool:
    """Whether the grid's runs about the extremum (within one grid step)
    all passed their checks: a refined extremum between unsettled runs is
    not the law's."""
    a = res.angles_deg
    step = float(np.min(np.diff(a))) if len(a) > 1 else 0.0
    near = np.abs(a - res.extremum["angle_deg"]) <= step + 1e-9
    return bool(np.all(res.checks.ok[near]))


def checks_summary(checks, angles_deg, phi_deg, warning: str | None) -> dict:
    """summary.json's "checks": the tolerances, the flagged angles and the
    warning line (rig_checks)."""
    angles = np.asarray(angles_deg, dtype=float)
    dev = np.abs(np.asarray(phi_deg, dtype=float) - checks.steady_deg)
    return {
        "ok": warning is None,   # eq20 runs are listed below but not warned about (rig_checks)
        "settle_tolerance_deg": SETTLE_TOL_DEG, "steady_tolerance_deg": STEADY_TOL_DEG,
        "unsettled_angles_deg": [float(a) for a in angles[~checks.settled]],
        "off_steady_angles_deg": [float(a) for a in angles[~checks.on_steady]],
        "max_halves_deg": float(np.max(np.abs(checks.halves_deg))) if len(angles) else 0.0,
        "max_steady_deviation_deg": float(np.nanmax(dev)) if np.any(np.isfinite(dev)) else None,
        "warning": warning,
    }


def figure_phi(sc: Scenario, res: SweepResult, path: Path, flat: bool) -> None:
    """phi_vs_angle.png: the rig's steady angles [deg] over the mat angle
    [deg] with the closed form; `flat` (a flat closed form) shows them on a
    scale of degrees, not of their rounding, and no extremum."""
    plt = pyplot()
    fine = np.linspace(res.angles_deg[0], res.angles_deg[-1], 721)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(fine, closed_form_phi_deg_array(sc, fine), "-", color="0.3",
            label=f"closed form ({sc.closed_form})")
    ax.plot(res.angles_deg, res.phi_deg, "o", ms=3.5, color="C0", label=f"rig + FMU ({sc.rig.mode})")
    bad = ~res.checks.ok
    if bad.any():
        ax.plot(res.angles_deg[bad], res.phi_deg[bad], "x", ms=8, mew=1.6, color="C3",
                label=f"not steady sliding ({int(bad.sum())}): see summary.json")
    e = res.extremum
    if not flat:
        ax.plot([e["angle_deg"]], [e["phi_deg"]], "*", ms=12, color="C3",
                label=f"extremum {e['phi_deg']:.2f}° at {e['angle_deg']:.2f}°"
                      + ("" if extremum_is_steady(res) else " (not steady sliding)"))
    if flat:
        # Autoscaled, rounding of 1e-10 deg would look like a curve.
        top = float(np.nanmax(np.abs(res.phi_deg)))
        ax.set_ylim(-1.0, 1.0)
        ax.text(0.02, 0.04, f"flat: |φ| ≤ {top:.1g}° at every angle (rounding)", transform=ax.transAxes,
                fontsize=8)
    ax.set_xlabel(f"{swept_label(sc)} [deg]")
    ax.set_ylabel("trajectory angle φ [deg] (counterclockwise)")
    finish(fig, ax, path, sc.title)


def _figure_paths(sc: Scenario, res: SweepResult, path: Path, what: str) -> None:
    """The recorded runs: the block's path (what = "x2") or the driving
    force (what = "drive") over the travel."""
    plt = pyplot()
    legend_title = swept_label(sc).replace("mat angle a: ", "a, with ")
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for i, (a, r) in enumerate(res.trajectories.items()):
        y = r.x2 * 1e3 if what == "x2" else r.drive
        ax.plot(r.x1 * 1e3, y, label=f"a = {a:g}°", **curve_style(i, len(r.x1), len(res.trajectories)))
    if what == "x2":
        ax.set_xlabel("x1 [mm] (driving direction)")
        ax.set_ylabel("x2 [mm]")
        ax.set_aspect("equal", adjustable="datalim")
        title = f"{sc.title}: block trajectories"
    else:
        ax.set_xlabel("travel x1 [mm]")
        ax.set_ylabel("driving force (sensor) [N]")
        title = f"{sc.title}: driving force"
    finish(fig, ax, path, title, legend_title, outside=True)


def _closed_extremum(sc: Scenario, res: SweepResult) -> dict:
    fine = np.linspace(res.angles_deg[0], res.angles_deg[-1], 90001)
    vals = closed_form_phi_deg_array(sc, fine)
    k = int(np.argmax(np.abs(vals)))
    return {"angle_deg": float(fine[k]), "phi_deg": float(vals[k])}


@part("sweep", "run")
def run_sweep_scenario(sc: Scenario, out: Path, fmu_path, how: RunOptions) -> dict:
    """The sweep (runs.sweep) and its outputs: the kind's runner."""
    res = run_sweep(sc, how.workers, how.progress, fmu_path, how.master, how.dask)
    return sweep_outputs(sc, res, out, how.draw)


@part("step_study", "run")
def run_step_study_scenario(sc: Scenario, out: Path, fmu_path, how: RunOptions) -> dict:
    """The step study (runs.sweep) and its outputs: the kind's runner."""
    res = run_step_study(sc, how.workers, how.progress, fmu_path, how.master, how.dask)
    return step_study_outputs(sc, res, out, how.draw)


def step_study_outputs(sc: Scenario, res: StepStudyResult, out: Path, draw=None) -> dict:
    write_csv(out / "step_study.csv", ["rule", "step_s", "phi_deg", "phi_closed_deg", "deviation_deg",
                                       "drive_mean_N", "check"],
              [(r["rule"], r["step_s"], r["phi_deg"], r["phi_closed_deg"], r["deviation_deg"],
                r["drive_mean_N"], r["check"]) for r in res.rows])
    (draw or draw_here)(figure_step_study, sc, res, out / "step_study.png")
    rules = list(dict.fromkeys(r["rule"] for r in res.rows))
    per_rule = {}
    for rule in rules:
        rs = [r for r in res.rows if r["rule"] == rule]
        phis = [r["phi_deg"] for r in rs]
        per_rule[rule] = {"phi_deg": dict((f"{r['step_s']:g}", r["phi_deg"]) for r in rs),
                          "spread_deg": max(phis) - min(phis),
                          "max_deviation_deg": max(abs(r["deviation_deg"]) for r in rs)}
    summary = {**sc.head(), "mode": sc.rig.mode,
               "angle_deg": res.angle_deg, "rules": per_rule, "seconds": round(res.seconds, 3),
               "checks": checks_summary(res.checks, [res.angle_deg] * len(res.rows),
                                        [r["phi_deg"] for r in res.rows], res.warning(sc))}
    write_json(out / "summary.json", summary)
    return summary


def figure_step_study(sc: Scenario, res: StepStudyResult, path: Path) -> None:
    """step_study.png: each rule's angle [deg] over the step [s], with its
    closed form (one line for rules that share it)."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    rules = list(dict.fromkeys(r["rule"] for r in res.rows))
    for i, rule in enumerate(rules):
        rs = [r for r in res.rows if r["rule"] == rule]
        st = curve_style(i, len(rs))
        ax.plot([r["step_s"] for r in rs], [r["phi_deg"] for r in rs], color=st["color"],
                marker=st["marker"], ls="-", label=f"{rule}: FMU in the rig")
        # Rules with the same closed form (eq. 20's is the coupled rule's
        # eq. 25) share one line, named for both: drawn twice, one hid the other.
        same = [r2 for r2 in rules if abs(next(r["phi_closed_deg"] for r in res.rows if r["rule"] == r2)
                                          - rs[0]["phi_closed_deg"]) <= 1e-9]
        if same[0] == rule:
            ax.axhline(rs[0]["phi_closed_deg"], color=st["color"], ls=":", lw=1.2,
                       label=f"{'+'.join(same)}: closed form")
    if any(math.isfinite(r["phi_deg"]) for r in res.rows):
        ax.set_xscale("log")   # (no angle at any step, e.g. a run of too few steps: nothing to scale)
    ax.set_xlabel("communication step [s]")
    ax.set_ylabel("steady trajectory angle φ [deg] (counterclockwise)")
    finish(fig, ax, path, sc.title, "rule (colour)", outside=True)
