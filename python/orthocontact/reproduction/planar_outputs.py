"""The scenario kinds of a planar body on the ContactPatch FMU (rig.planar):
`twist` (the torque against the angle, with the grid's elastic slope and
full-slip plateau) and `towed_block` (the yaw against time and its steady
value against the mat angle, with the closed form and the paper's phi
beside it).  Each run checks itself against its closed form, as the rig's
sweeps do: summary.json's "checks" says ok or gives the warning line.

Files (in the folder given): twist.csv, twist.png, twist_cells.csv,
twist_cells.png (every cell's state at a few instants of the twist);
towed_block.csv, yaw_vs_time.csv, yaw_vs_angle.png, yaw_vs_time.png;
summary.json.

The cells' states are an FMI 3.0 array (cellState).  A twist run on an FMI
2.0 FMU takes them from the same twist on the installed FMI 3.0 ContactPatch
FMU, and only if that run's torque, slip fraction and state equal its own at
every step (the two builds compute the same bits); else there is no cells
figure and summary.json's "cells" says why.  The kinds' runners (their piece
"run", experiment.kinds) are here; their part of the report is
patch_report's."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..closed_forms import cell_centres, of_law, steady_phi_deg
from ..experiment import SCHEMA, RunOptions, Scenario, ScenarioError, part
from ..fmu import PATCH_MODEL, PatchGeometry
from ..output import draw_here, write_csv, write_json
from ..rig import planar
from .fmi3_twin import fmi3_twin
from .planar_figures import figure_cells, figure_twist, figure_yaw_angle, figure_yaw_time

# The towed block's steady yaw: after tow.duration_s the transient is far
# below this (tests/rig/test_planar.py: 1e-9 rad after 20 s); a larger
# deviation means the run has not settled.
YAW_TOL_DEG = 1e-5
# The twist's plateau is reached to the elastic lag (rig.planar): past five
# times the angle at which the innermost cell slides, within l / r_mean.
PLATEAU_FROM = 5.0
# The largest angle a twist may turn (twist.angle_deg's range) [deg].
TWIST_ANGLE_MAX_DEG = SCHEMA["twist"]["angle_deg"][0].hi


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
    offsets), writes twist.csv and twist.png; returns the summary.  A check
    the twist does not reach (the plateau starting past its end angle) is
    "not checked", with the angle it needs, not a failure."""
    body, tw = body_of(sc), sc.twist
    rows, runs, checks, cells, said = [], {}, [], {}, []
    version = _version(fmu_path)
    for rule in tw["rules"]:
        p = sc.params_at(0.0, rule)
        res = planar.twist(p, body, math.radians(tw["rate_deg_s"]), math.radians(tw["angle_deg"]),
                           tw["step_s"], fmu_path=fmu_path, fmi_version=version, cells=version == 3)
        states, where = cell_states_of(p, body, tw, res)
        said.append(where)
        if states is not None:
            cells[rule] = (res, states)
        check, plateau, k = twist_check(rule, p, body, res)
        checks.append(check)
        runs[rule] = (res, plateau, k)
        rows += [(rule, math.degrees(t), float(m), float(c), float(f), int(s))
                 for t, m, c, f, s in zip(res.theta, res.Mz, plateau, res.slip_fraction,
                                          res.contact_state)]
    write_csv(out / "twist.csv", ["rule", "theta_deg", "Mz_N_m", "Mz_full_slip_N_m", "slip_fraction",
                                  "contact_state"], rows)
    (draw or draw_here)(figure_twist, sc, runs, out / "twist.png")
    if len(cells) == len(tw["rules"]):
        cell_rows = _cell_rows(body.patch, cells)
        write_csv(out / "twist_cells.csv", ["rule", "instant", "step", "theta_deg", "i", "j", "x1_m",
                                            "x2_m", "cell_state"], cell_rows)
        (draw or draw_here)(figure_cells, sc, body.patch, cell_rows, out / "twist_cells.png")
        cells_summary = {"from": said[0], "files": ["twist_cells.csv", "twist_cells.png"]}
    else:
        cells_summary = {"from": None, "why": next(w for r, w in zip(tw["rules"], said) if r not in cells)}
    warning = twist_warning(sc.name, checks)
    summary = {**sc.head(), "normal_N": body.normal_N,
               "patch": sc.patch, "rules": {c["rule"]: c for c in checks}, "cells": cells_summary,
               "checks": {"ok": warning is None, "warning": warning,
                          "not_checked": [c["rule"] for c in checks if not c["plateau_checked"]]},
               "angle_convention": "theta counterclockwise about the normal; Mz the surface's moment "
                                   "on the body"}
    write_json(out / "summary.json", summary)
    return summary


def twist_check(rule: str, p, body, res) -> tuple:
    """A twist run against its closed forms: its first step's slope against
    the grid's torsional stiffness k [N m/rad], stuck at that step, and
    the torque past PLATEAU_FROM times the angle where the innermost cell
    slides against the full-slip plateau.  Returns (the check, the plateau
    at each step [N m], k)."""
    g = body.patch
    r_mean = (g.length + g.width) / 4.0
    r_min = innermost_radius(g)
    k = planar.twist_stiffness(p, g)
    slope = float(-res.Mz[0] / res.theta[0])
    # a grid of one cell has none off the centre: no cell moves, no torque (k = 0, plateau 0)
    onset = _elastic_length(p, body) / r_min if r_min else 0.0
    past = res.theta >= PLATEAU_FROM * onset
    plateau = planar.twist_plateau(p, body, res.theta)
    tol = _elastic_length(p, body) / r_mean
    rel = relative_error(res.Mz[past], plateau[past])
    stuck_first = bool(res.contact_state[0] == 1)
    check = {
        "rule": rule, "k_N_m_rad": k, "slope_N_m_rad": slope,
        "slope_relative_error": float(relative_error(slope, k)),
        # the first step's theta is the first-order term's bound (rig.planar)
        "slope_tolerance": 3 * float(res.theta[0]), "stuck_at_first_step": stuck_first,
        "plateau_from_deg": math.degrees(PLATEAU_FROM * onset),
        "plateau_max_relative_error": float(rel.max()) if rel.size else None,
        "plateau_tolerance": tol, "theta_end_deg": math.degrees(res.theta[-1]),
        "Mz_end_N_m": float(res.Mz[-1]), "Mz_full_slip_end_N_m": float(plateau[-1])}
    check["plateau_checked"] = bool(rel.size)
    check["ok"] = bool(stuck_first and check["slope_relative_error"] <= check["slope_tolerance"]
                       and (not rel.size or rel.max() <= tol))
    return check, plateau, k


@part("twist", "run")
def run_twist(sc: Scenario, out: Path, fmu_path, how: RunOptions) -> dict:
    """The kind's runner: twist_outputs (a run in this process)."""
    return twist_outputs(sc, out, fmu_path, how.draw)


@part("towed_block", "run")
def run_towed(sc: Scenario, out: Path, fmu_path, how: RunOptions) -> dict:
    """The kind's runner: towed_outputs (runs in this process)."""
    return towed_outputs(sc, out, fmu_path, how.draw)


def innermost_radius(g: PatchGeometry) -> float:
    """The radius [m] of the patch's innermost cell off its centre (the
    first to slide as the patch turns); 0 for a single cell, which sits on
    the centre and never moves."""
    x, y = cell_centres(g.length, g.width, g.n1, g.n2)
    r = np.hypot(x, y)
    return float(r[r > 0].min()) if (r > 0).any() else 0.0


def relative_error(value, closed):
    """|value / closed - 1| (arrays alike); where the closed form is 0 (a
    cell on the centre: no torque) it is 0 if value is 0 too, else inf."""
    value, closed = np.asarray(value, dtype=float), np.asarray(closed, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.abs(value - closed) / np.abs(closed)
    return np.where(value == closed, 0.0, np.where(closed == 0, np.inf, rel))


def twist_warning(name: str, checks: list[dict]) -> str | None:
    """The twist's warning line: the rules whose torque is off a closed form
    it checked, and those whose full-slip plateau it did not reach (not
    checked: the angle it needs); None if every check was made and passed."""
    parts = []
    off = [c["rule"] for c in checks if not c["ok"]]
    if off:
        parts.append(f"the twist's torque is off its closed forms under the {', '.join(off)} rule(s) "
                     "(summary.json's checks): turn further (twist.angle_deg) or finer (twist.step_s)")
    late = [c for c in checks if not c["plateau_checked"]]
    if late:
        needs = max(c["plateau_from_deg"] for c in late)
        parts.append(f"the full-slip plateau was not checked under the {', '.join(c['rule'] for c in late)} "
                     f"rule(s): it is reached from {needs:.4g} deg on (five times the angle at which the "
                     f"innermost cell slides), past the twist's end at {late[0]['theta_end_deg']:.4g} deg; "
                     + (f"turn to twist.angle_deg >= {math.ceil(needs * 10) / 10:g} to check it"
                        if needs <= TWIST_ANGLE_MAX_DEG else
                        f"beyond the {TWIST_ANGLE_MAX_DEG:g} deg a twist turns at most: the elastic length "
                        "mu N / eps is long against the innermost cell's radius"))
    return f"{name}: " + "; ".join(parts) if parts else None


def cell_states_of(params, body, tw, res) -> tuple:
    """(the twist's cell states (steps, n1, n2), where they come from), or
    (None, why not): res's own (FMI 3.0), else those of the same twist on the
    installed FMI 3.0 ContactPatch FMU if its record equals res's."""
    if res.cell_state is not None:
        return res.cell_state, "this run (FMI 3.0: cellState)"
    again, why = fmi3_twin(
        PATCH_MODEL, lambda twin: planar.twist(params, body, math.radians(tw["rate_deg_s"]),
                                               math.radians(tw["angle_deg"]), tw["step_s"], fmu_path=twin,
                                               fmi_version=3, cells=True),
        lambda again: all(np.array_equal(getattr(res, k), getattr(again, k))
                          for k in ("theta", "Mz", "slip_fraction", "contact_state")),
        "twist", " at every step in torque, slip fraction and state", differs="torque")
    return (None if again is None else again.cell_state), why


# The instants the cells are shown at: the last step with every cell stuck,
# the first with half the area slipping, the last before every cell slips,
# the first with every cell slipping (those the twist reaches).
INSTANTS = ("every cell sticks", "half the area slips", "the last cells stick", "every cell slips")


def cell_instants(res) -> list[tuple[str, int]]:
    """(name, step index) of the INSTANTS the twist record res reaches, in
    order, each step once."""
    stuck = np.flatnonzero(res.contact_state == 1)
    half = np.flatnonzero(res.slip_fraction >= 0.5)
    full = np.flatnonzero(res.contact_state == 3)
    picks = [stuck[-1] if stuck.size else None, half[0] if half.size else None,
             full[0] - 1 if full.size and full[0] > 0 else None, full[0] if full.size else None]
    out = []
    for name, k in zip(INSTANTS, picks):
        if k is not None and all(int(k) != j for _, j in out):
            out.append((name, int(k)))
    return sorted(out, key=lambda x: x[1])


def _cell_rows(g: PatchGeometry, cells: dict) -> list[tuple]:
    """twist_cells.csv: each cell at each instant, its centre (x1, x2) [m] in
    body coordinates."""
    rows = []
    for rule, (res, states) in cells.items():
        for name, k in cell_instants(res):
            for i in range(g.n1):
                for j in range(g.n2):
                    rows.append((rule, name, k, math.degrees(res.theta[k]), i, j,
                                 (i + 0.5) * g.length / g.n1 - g.length / 2,
                                 (j + 0.5) * g.width / g.n2 - g.width / 2, int(states[k, i, j])))
    return rows


def towed_outputs(sc: Scenario, out: Path, fmu_path, draw=None) -> dict:
    """Runs the towed block at each mat angle under each rule, writes
    towed_block.csv, yaw_vs_time.csv and the two figures; returns the
    summary."""
    body, tw = body_of(sc), sc.tow
    rows, time_rows, records = [], [], {}
    worst = worst_phi = 0.0
    version = _version(fmu_path)
    for rule in tw["rules"]:
        for a in tw["angles_deg"]:
            p = sc.params_at(a, rule)
            try:
                res = planar.towed_block(p, body, sc.rig.velocity_m_s, tw["pin_m"], tw["duration_s"],
                                         tw["step_s"], fmu_path=fmu_path, fmi_version=version)
            except planar.StepNotSolved as e:
                raise ScenarioError(f"{sc.path}: tow.step_s: the {rule} tow at mat angle {a:g} deg could not "
                                    f"be integrated ({e}); a smaller tow.step_s may help") from None
            yaw = math.degrees(res.theta[-1])
            closed = math.degrees(planar.steady_yaw(p))
            phi = of_law(steady_phi_deg, p, p.alpha, p.beta)
            # the paper's phi on the mat turned by the yaw (rig.planar): -phi(a - yaw) on its mat
            shifted = of_law(steady_phi_deg, p, p.alpha - res.theta[-1], p.beta - res.theta[-1])
            worst = max(worst, abs(yaw - closed))
            worst_phi = max(worst_phi, abs(yaw + shifted))   # the paper's phi, read from the motion's side
            rows.append((rule, a, yaw, closed, yaw - closed, phi, -shifted))
            records[(rule, a)] = res
            time_rows += [(rule, a, float(t), math.degrees(th)) for t, th in
                          zip(res.t[::10], res.theta[::10])]
    write_csv(out / "towed_block.csv", ["rule", "angle_deg", "yaw_deg", "yaw_closed_deg", "deviation_deg",
                                        "phi_deg", "minus_phi_turned_by_yaw_deg"], rows)
    write_csv(out / "yaw_vs_time.csv", ["rule", "angle_deg", "t_s", "yaw_deg"], time_rows)
    draw = draw or draw_here
    draw(figure_yaw_angle, sc, rows, out / "yaw_vs_angle.png")
    draw(figure_yaw_time, sc, records, out / "yaw_vs_time.png")
    warning = None
    if worst > YAW_TOL_DEG:
        warning = (f"{sc.name}: the towed block's yaw is {worst:.3g} deg off its steady closed form "
                   f"(tolerance {YAW_TOL_DEG:g} deg): it has not settled; tow longer (tow.duration_s)")
    elif worst_phi > YAW_TOL_DEG:
        warning = (f"{sc.name}: the towed block's yaw is {worst_phi:.3g} deg off -phi with the mat turned "
                   f"back by the yaw (tolerance {YAW_TOL_DEG:g} deg): the steady yaw and the paper's phi "
                   "disagree")
    summary = {**sc.head(), "normal_N": body.normal_N,
               "patch": sc.patch, "max_deviation_deg": worst,
               "max_deviation_from_minus_phi_turned_deg": worst_phi,
               "yaw_deg": {rule: {f"{a:g}": y for r, a, y, *_ in rows if r == rule} for rule in tw["rules"]},
               "tows": [dict(zip(("rule", "angle_deg", "yaw_deg", "yaw_closed_deg", "deviation_deg",
                                  "phi_deg", "minus_phi_turned_by_yaw_deg"), r)) for r in rows],
               "checks": {"ok": warning is None, "tolerance_deg": YAW_TOL_DEG, "warning": warning},
               "angle_convention": "yaw of the block's axis (centre to pin) from the motion (X1), "
                                   "counterclockwise; phi the paper's trajectory angle at the same mat "
                                   "angle (force along X1); minus_phi_turned_by_yaw: -phi with the "
                                   "texture turned back by the yaw (-phi(a - yaw) on the paper's mat), "
                                   "the yaw itself once settled"}
    write_json(out / "summary.json", summary)
    return summary


def _version(fmu_path) -> int:
    from ..fmu import fmi_version_of
    return fmi_version_of(fmu_path)
