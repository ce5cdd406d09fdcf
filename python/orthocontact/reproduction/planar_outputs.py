"""The scenario kinds of a planar body on the ContactPatch FMU (rig.planar):
`twist` (the torque against the angle, with the grid's elastic slope and
full-slip plateau) and `towed_block` (the yaw against time and its steady
value against the mat angle, with the closed form and the paper's phi
beside it).  Each run checks itself against its closed form, as the rig's
sweeps do: summary.json's "checks" says ok or gives the warning line.

Files (in the folder given): twist.csv, twist.png; towed_block.csv,
yaw_vs_time.csv, yaw_vs_angle.png, yaw_vs_time.png; summary.json."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..closed_forms.paper import of_law, steady_phi_deg
from ..experiment.scenario import Scenario
from ..fmu.patch import PatchGeometry
from ..output.figures import curve_style, draw_here, finish, pyplot, swept_label
from ..output.tables import write_csv, write_json
from ..rig import planar

# The towed block's steady yaw: after tow.duration_s the transient is far
# below this (tests/rig/test_planar.py: 1e-9 rad after 20 s); a larger
# deviation means the run has not settled.
YAW_TOL_DEG = 1e-5
# The twist's plateau is reached to the elastic lag (rig.planar): past five
# times the angle at which the innermost cell slides, within l / r_mean.
PLATEAU_FROM = 5.0


def body_of(sc: Scenario) -> planar.PlanarBody:
    """The scenario's block: a uniform block of the rig's mass on its patch,
    pressed by its weight."""
    p = sc.patch
    geometry = PatchGeometry(float(p["length_m"]), float(p["width_m"]), int(p["n1"]), int(p["n2"]))
    return planar.PlanarBody.uniform(sc.rig.mass_kg, geometry, sc.rig.mass_kg * sc.rig.g)


def _elastic_length(params, body) -> float:
    """l = max(mu) N / min(eps) [m]: how far a sliding cell trails its path."""
    return max(params.mu1, params.mu2) * body.normal_N / min(params.eps1, params.eps2)


def twist_outputs(sc: Scenario, out: Path, fmu_path, draw=None) -> dict:
    """Runs the twist test under each rule at mat angle 0 (the axes at their
    offsets), writes twist.csv and twist.png; returns the summary."""
    body, tw = body_of(sc), sc.twist
    g = body.patch
    r_mean = (g.length + g.width) / 4.0
    r_min = math.hypot(g.length / (2 * g.n1), g.width / (2 * g.n2))
    rows, runs, checks = [], {}, []
    for rule in tw["rules"]:
        p = sc.params_at(0.0, rule)
        res = planar.twist(p, body, math.radians(tw["rate_deg_s"]), math.radians(tw["angle_deg"]),
                           tw["step_s"], fmu_path=fmu_path, fmi_version=_version(fmu_path))
        k = planar.twist_stiffness(p, g)
        slope = float(-res.Mz[0] / res.theta[0])
        onset = _elastic_length(p, body) / r_min
        past = res.theta >= PLATEAU_FROM * onset
        plateau = planar.twist_plateau(p, body, res.theta)
        tol = _elastic_length(p, body) / r_mean
        rel = np.abs(res.Mz[past] / plateau[past] - 1) if past.any() else np.array([])
        stuck_first = bool(res.contact_state[0] == 1)
        check = {
            "rule": rule, "k_N_m_rad": k, "slope_N_m_rad": slope,
            "slope_relative_error": abs(slope / k - 1),
            # the first step's theta is the first-order term's bound (rig.planar)
            "slope_tolerance": 3 * float(res.theta[0]), "stuck_at_first_step": stuck_first,
            "plateau_from_deg": math.degrees(PLATEAU_FROM * onset),
            "plateau_max_relative_error": float(rel.max()) if rel.size else None,
            "plateau_tolerance": tol}
        check["ok"] = bool(stuck_first and check["slope_relative_error"] <= check["slope_tolerance"]
                           and rel.size and rel.max() <= tol)
        checks.append(check)
        runs[rule] = (res, plateau, k)
        rows += [(rule, math.degrees(t), float(m), float(c), float(f), int(s))
                 for t, m, c, f, s in zip(res.theta, res.Mz, plateau, res.slip_fraction,
                                          res.contact_state)]
    write_csv(out / "twist.csv", ["rule", "theta_deg", "Mz_N_m", "Mz_full_slip_N_m", "slip_fraction",
                                  "contact_state"], rows)
    (draw or draw_here)(_figure_twist, sc, runs, out / "twist.png")
    bad = [c["rule"] for c in checks if not c["ok"]]
    warning = None if not bad else (
        f"{sc.name}: the twist's torque is off its closed forms under the {', '.join(bad)} rule(s) "
        "(summary.json's checks): turn further (twist.angle_deg) or finer (twist.step_s)")
    summary = {"scenario": sc.name, "title": sc.title, "kind": sc.kind, "normal_N": body.normal_N,
               "patch": sc.patch, "rules": {c["rule"]: c for c in checks},
               "checks": {"ok": warning is None, "warning": warning},
               "angle_convention": "theta counterclockwise about the normal; Mz the surface's moment "
                                   "on the body"}
    write_json(out / "summary.json", summary)
    return summary


def towed_outputs(sc: Scenario, out: Path, fmu_path, draw=None) -> dict:
    """Runs the towed block at each mat angle under each rule, writes
    towed_block.csv, yaw_vs_time.csv and the two figures; returns the
    summary."""
    body, tw = body_of(sc), sc.tow
    rows, time_rows, records = [], [], {}
    worst = 0.0
    for rule in tw["rules"]:
        for a in tw["angles_deg"]:
            p = sc.params_at(a, rule)
            res = planar.towed_block(p, body, sc.rig.velocity_m_s, tw["pin_m"], tw["duration_s"],
                                     tw["step_s"], fmu_path=fmu_path, fmi_version=_version(fmu_path))
            yaw = math.degrees(res.theta[-1])
            closed = math.degrees(planar.steady_yaw(p))
            phi = of_law(steady_phi_deg, p, p.alpha, p.beta)
            worst = max(worst, abs(yaw - closed))
            rows.append((rule, a, yaw, closed, yaw - closed, phi))
            records[(rule, a)] = res
            time_rows += [(rule, a, float(t), math.degrees(th)) for t, th in
                          zip(res.t[::10], res.theta[::10])]
    write_csv(out / "towed_block.csv", ["rule", "angle_deg", "yaw_deg", "yaw_closed_deg", "deviation_deg",
                                        "phi_deg"], rows)
    write_csv(out / "yaw_vs_time.csv", ["rule", "angle_deg", "t_s", "yaw_deg"], time_rows)
    draw = draw or draw_here
    draw(_figure_yaw_angle, sc, rows, out / "yaw_vs_angle.png")
    draw(_figure_yaw_time, sc, records, out / "yaw_vs_time.png")
    warning = None if worst <= YAW_TOL_DEG else (
        f"{sc.name}: the towed block's yaw is {worst:.3g} deg off its steady closed form (tolerance "
        f"{YAW_TOL_DEG:g} deg): it has not settled; tow longer (tow.duration_s)")
    summary = {"scenario": sc.name, "title": sc.title, "kind": sc.kind, "normal_N": body.normal_N,
               "patch": sc.patch, "max_deviation_deg": worst,
               "yaw_deg": {rule: {f"{a:g}": y for r, a, y, *_ in rows if r == rule} for rule in tw["rules"]},
               "checks": {"ok": warning is None, "tolerance_deg": YAW_TOL_DEG, "warning": warning},
               "angle_convention": "yaw of the block's axis (centre to pin) from the motion (X1), "
                                   "counterclockwise; phi the paper's trajectory angle at the same mat "
                                   "angle (force along X1)"}
    write_json(out / "summary.json", summary)
    return summary


def _version(fmu_path) -> int:
    from ..fmu.files import fmi_version_of
    return fmi_version_of(fmu_path)


def _figure_twist(sc: Scenario, runs: dict, path: Path) -> None:
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    top = 0.0
    for i, (rule, (res, plateau, k)) in enumerate(runs.items()):
        th = np.degrees(res.theta)
        ax.plot(th, -res.Mz, color=f"C{i}", label=f"patch FMU, {rule}")
        ax.plot(th, -plateau, "--", color=f"C{i}", lw=1, label=f"full slip (closed form), {rule}")
        top = max(top, float(np.max(-res.Mz)))
        if i == 0:
            ax.plot(th, k * res.theta, ":", color="0.3", label=f"stick: k θ, k = {k:.4g} N·m/rad")
    # log-log: the stick line has slope 1, the plateau is flat, both readable
    ax.set_xscale("log")
    ax.set_yscale("log")
    from matplotlib.ticker import FormatStrFormatter
    for axis in (ax.xaxis, ax.yaxis):   # plain numbers: short tick labels
        axis.set_major_formatter(FormatStrFormatter("%g"))
        axis.set_minor_formatter(FormatStrFormatter(""))
    ax.set_ylim(float(np.min(-runs[next(iter(runs))][0].Mz)) / 2, 2 * top)
    ax.set_xlabel("body angle θ [deg]")
    ax.set_ylabel("torque to turn the body, −Mz [N·m]")
    finish(fig, ax, path, f"{sc.title}: twist", swept_label(sc) + " at a = 0")


def _figure_yaw_angle(sc: Scenario, rows: list, path: Path) -> None:
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    rules = list(dict.fromkeys(r[0] for r in rows))
    fine = np.linspace(min(r[1] for r in rows), max(r[1] for r in rows), 181)
    for i, rule in enumerate(rules):
        pts = [r for r in rows if r[0] == rule]
        closed = [math.degrees(planar.steady_yaw(sc.params_at(a, rule))) for a in fine]
        phi = [of_law(steady_phi_deg, p, p.alpha, p.beta) for p in (sc.params_at(a, rule) for a in fine)]
        ax.plot(fine, closed, "-", color=f"C{i}", lw=1, label=f"{rule}: yaw, closed form")
        ax.plot([r[1] for r in pts], [r[2] for r in pts], "o", ms=4, color=f"C{i}",
                label=f"{rule}: yaw, patch FMU")
        ax.plot(fine, phi, ":", color=f"C{i}", label=f"{rule}: paper's φ (force along X1)")
    ax.set_xlabel("mat angle a [deg]")
    ax.set_ylabel("angle [deg]")
    finish(fig, ax, path, f"{sc.title}: steady yaw of the towed block", swept_label(sc))


def _figure_yaw_time(sc: Scenario, records: dict, path: Path) -> None:
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for i, ((rule, a), res) in enumerate(records.items()):
        ax.plot(res.t, np.degrees(res.theta), label=f"{rule[:5]}., a = {a:g}°",
                **curve_style(i, len(res.t), len(records)))
    ax.set_xlabel("time [s]")
    ax.set_ylabel("yaw θ [deg]")
    finish(fig, ax, path, f"{sc.title}: yaw against time", swept_label(sc), outside=True)
