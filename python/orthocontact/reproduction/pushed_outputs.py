"""The scenario kind of the paper's block pushed at a height on the
ContactPad FMU (rig.pushed): `pushed_block`, a quasi-static push at each
height and mat angle, each run against its closed forms
(closed_forms.pad.pushed_at_height: the regime, full contact while mu h <=
length/6, lift-off beyond, tipping past mu h = length/2, and the steady
pose; closed_forms.paper: the trajectory angle, which the height does not
change).  summary.json's "checks" says ok or gives the warning line.

Files (in the folder given): pushed_block.csv (a row a run), push_paths.csv
(each run's path), pressure_cells.csv and pressure_cells.png (the pressure
under the block at the end of the push, each cell coloured by its normal
force, open or slipping, at the first mat angle of each height),
phi_vs_angle.png (the trajectory angle against the mat angle at each
height, with the paper's closed form and measured extremum), regimes.png
(the pressure's centre and the contact against mu h / length, with the
thresholds 1/6 and 1/2), the figures drawn by pushed_figures; summary.json.

The cells' normal forces and states are FMI 3.0 arrays: a push on an FMI
2.0 FMU takes them from the same push on the installed FMI 3.0 ContactPad
FMU, and only if that push's record equals its own at every step."""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..closed_forms import (
    TIPS,
    contact_fraction,
    of_law,
    pushed_at_height,
    steady_drive_force,
    steady_phi_deg,
)
from ..experiment import RunOptions, Scenario, ScenarioError, part
from ..fmu import PAD_MODEL, Foundation, PatchGeometry, fmi_version_of
from ..output import draw_here, write_csv, write_json
from ..plausibility import ELASTIC_LENGTHS
from ..rig import pushed
from .fmi3_twin import fmi3_twin
from .pushed_figures import figure_cells, figure_phi, figure_regimes

# A settled push's trajectory angle is the closed form's to the transient
# left after ELASTIC_LENGTHS elastic lengths (measured: < 1e-4 deg); its
# pose the closed form's (a relative 1e-6: the friction within 1e-6 of the
# limit).  Regimes within THRESHOLD_MARGIN of a threshold are not compared.
PHI_TOL_DEG = 1e-3
POSE_TOL = 1e-6
THRESHOLD_MARGIN = 1e-6


def friction_along_x1(params) -> float:
    """mu [-]: the law's steady push over the weight with the block free
    laterally, 1/sqrt(F11) (closed_forms.paper.steady_drive_force)."""
    return steady_drive_force(params.mu1, params.mu2, params.beta, 0.0, 1.0, 1.0)


def block_of(sc: Scenario, height_m: float) -> pushed.PushedBlock:
    """The scenario's block (the rig's mass and g) on its pad, pushed at height_m [m]."""
    p = sc.pad
    geometry = PatchGeometry(float(p["length_m"]), float(p["width_m"]), int(p["n1"]), int(p["n2"]))
    return pushed.PushedBlock(sc.rig.mass_kg, sc.rig.g, geometry, Foundation(float(p["kn_N_m3"])),
                              float(height_m))


def expected(sc: Scenario, angle_deg: float, height_m: float) -> dict:
    """The closed forms of a push: mu, e = mu h, the regime, the steady pose
    (d, phi2) and contact fraction (None where it tips)."""
    b = block_of(sc, height_m)
    mu = friction_along_x1(sc.params_at(angle_deg))
    e = mu * height_m
    regime, d, phi2 = pushed_at_height(b.foundation.kn, b.pad.length, b.pad.width, b.weight, e)
    frac = None if d is None else contact_fraction(b.pad.length, b.pad.width, d, 0.0, phi2)
    near = min(abs(e / b.pad.length - t) for t in (1 / 6, 1 / 2)) < THRESHOLD_MARGIN
    return {"mu": mu, "e_m": e, "regime": regime, "d_m": d, "phi2_rad": phi2, "contact_fraction": frac,
            "near_threshold": near}


def refuse_large_tilts(sc: Scenario) -> None:
    """One ScenarioError line for a height whose steady push the pad holds
    only with a tilt beyond rig.pushed.MAX_TILT_RAD (mu h just below
    length/2): its equilibrium exists but is outside the small tilts the
    pad models."""
    for h in sc.push["heights_m"]:
        for a in sc.push["angles_deg"]:
            x = expected(sc, a, h)
            if x["phi2_rad"] is not None and abs(x["phi2_rad"]) > pushed.MAX_TILT_RAD:
                L = sc.pad["length_m"]
                raise ScenarioError(
                    sc.path, "push.heights_m",
                    f"heights whose push the pad holds with small tilts: at {h:g} m and mat angle {a:g} "
                    f"deg the centre of pressure moves by mu h = {x['e_m']:.4g} m, {x['e_m'] / L:.4f} of the "
                    f"length, and holding it takes a tilt of {math.degrees(x['phi2_rad']):.3g} deg (more "
                    f"than {math.degrees(pushed.MAX_TILT_RAD):g}); lower it, or raise it past mu h = "
                    f"length/2 ({L / (2 * x['mu']):.4g} m) to see the block tip", h)


def elastic_length(sc: Scenario, want: dict) -> float:
    """How far [m] the most loaded cell trails its path in the steady push
    (want: expected's): max(mu) N_c / min(eps w), N_c its normal force, kn
    times the largest approach over its area share w; the push settles
    within ELASTIC_LENGTHS of them."""
    law, pad = sc.law, sc.pad
    L = pad["length_m"]
    if want["d_m"] is None:
        return math.nan
    peak = want["d_m"] + abs(want["phi2_rad"]) * L / 2     # the leading edge's approach
    area = L * pad["width_m"]
    return max(law.mu1, law.mu2) * pad["kn_N_m3"] * peak * area / min(law.eps1, law.eps2)


def off_closed_form(name: str, value, want, tol: float, unit: str) -> str | None:
    """The phrase for a value off its closed form by more than tol, or one
    that is not a finite number (it cannot be checked, so it is not ok); None
    if within tol.  The difference is printed, not the two values alone: they
    can agree to every digit shown."""
    if value is None or want is None or not (math.isfinite(value) and math.isfinite(want)):
        return f"{name} {value} {unit} cannot be checked against the closed form's {want} {unit}"
    if abs(value - want) <= tol:
        return None
    return (f"{name} {value:.6g} {unit}, closed form {want:.6g} {unit}: off by {value - want:.3g}, "
            f"more than {tol:.3g}")


def _check(run: dict, want: dict, settled: bool) -> list[str]:
    """What is off a run's closed forms, one phrase each: its regime, and
    once settled (the friction at its limit) its angle and pose; a value
    that is not a number is off (off_closed_form)."""
    off = []
    if not want["near_threshold"] and run["regime"] != want["regime"]:
        off.append(f"regime {run['regime']} where the closed form has {want['regime']}")
    if run["regime"] == TIPS or want["regime"] == TIPS or not settled:
        return off
    L = run["length_m"]
    d_tol = POSE_TOL * max(abs(want["d_m"]), abs(want["phi2_rad"]) * L)
    phi2_tol = POSE_TOL * max(abs(want["phi2_rad"]), want["d_m"] / L)
    found = [off_closed_form("phi", run["phi_deg"], run["phi_closed_deg"], PHI_TOL_DEG, "deg"),
             off_closed_form("d", run["d_m"], want["d_m"], d_tol, "m"),
             off_closed_form("phi2", run["phi2_rad"], want["phi2_rad"], phi2_tol, "rad")]
    return off + [x for x in found if x is not None]


def pushed_outputs(sc: Scenario, out: Path, fmu_path, draw=None) -> dict:
    """Runs the push at each height and mat angle, writes the files and the
    figures; returns the summary."""
    refuse_large_tilts(sc)
    pu = sc.push
    version = fmi_version_of(fmu_path)
    runs, paths, cells, off, unsettled = [], [], {}, [], []
    for h in pu["heights_m"]:
        for i, a in enumerate(pu["angles_deg"]):
            one = push_at(sc, h, a, version, fmu_path, first=i == 0)
            if i == 0:
                cells[h] = one.cells
            if not one.settled:
                unsettled.append(one.run)
            off += [f"h = {h:g} m, a = {a:g} deg: {x}" for x in one.problems]
            runs.append(one.run)
            res = one.res
            paths += [(h, a, float(x1), float(x2), float(d), float(ph), float(f)) for x1, x2, d, ph, f in
                      zip(res.x1, res.x2, res.d, res.phi2, res.contact_fraction)]
    write_tables(out, runs, paths, cells)
    draw = draw or draw_here
    draw(figure_cells, sc, runs, cells, out / "pressure_cells.png")
    draw(figure_phi, sc, runs, out / "phi_vs_angle.png")
    draw(figure_regimes, sc, runs, out / "regimes.png")
    summary = push_summary(sc, runs, cells, push_warning(sc, off, unsettled), unsettled)
    write_json(out / "summary.json", summary)
    return summary


@dataclass
class Push:
    """One push of the scenario: its row (pushed_block.csv, summary.json's
    runs), what is off its closed forms, whether it settled before its fit,
    the result, and its cells (the first angle of a height only: cells_of)."""
    run: dict
    problems: list
    settled: bool
    res: pushed.PushResult
    cells: tuple | None


def push_at(sc: Scenario, h: float, a: float, version: int, fmu_path, first: bool) -> Push:
    """The push at height h [m] and mat angle a [deg], checked against its
    closed forms (_check); ScenarioError naming push.step_m if a step of it
    cannot be solved."""
    pu = sc.push
    p = sc.params_at(a)
    b = block_of(sc, h)
    cells = None
    try:
        res = pushed.push(p, b, pu["travel_m"], pu["step_m"], version, fmu_path, cells=first and version == 3)
        if first:
            cells = cells_of(p, b, pu, res)
    except pushed.PushNotSolved as e:
        raise ScenarioError(f"{sc.path}: push.step_m: the push at mat angle {a:g} deg could not be "
                            f"solved ({e}); a smaller push.step_m may help") from None
    want = expected(sc, a, h)
    solved = len(res.x1) > 0   # a push that tips at its first step has no step solved
    last = -1
    run = {"height_m": h, "angle_deg": a, "length_m": b.pad.length, "regime": res.regime,
           "regime_closed": want["regime"], "mu": want["mu"], "e_closed_m": want["e_m"],
           "tipped_at_m": res.tipped_at_m,
           "phi_deg": math.degrees(math.atan(res.trajectory_tan_phi(pushed.FIT_FROM))),
           "phi_closed_deg": of_law(steady_phi_deg, p, p.alpha, p.beta),
           "d_m": float(res.d[last]) if solved else None, "d_closed_m": want["d_m"],
           "phi2_rad": float(res.phi2[last]) if solved else None,
           "phi2_closed_rad": want["phi2_rad"],
           "e_m": float(-res.M2[last] / res.Fn[last]) if solved else None,
           "contact_fraction": float(res.contact_fraction[last]) if solved else None,
           "contact_fraction_closed": want["contact_fraction"],
           "newton_iterations": int(res.iterations.sum())}
    if res.regime == TIPS or not math.isfinite(run["phi_deg"]):
        run["phi_deg"] = None
    run["elastic_length_m"] = elastic_length(sc, want)
    settled = not pushed.FIT_FROM * pu["travel_m"] < ELASTIC_LENGTHS * run["elastic_length_m"]
    run["phi_checked"] = settled and run["phi_deg"] is not None
    problems = _check(run, want, settled)
    run["ok"] = not problems
    return Push(run, problems, settled, res, cells)


def write_tables(out: Path, runs: list, paths: list, cells: dict) -> None:
    """pushed_block.csv (a row a push), push_paths.csv (a row a step) and
    pressure_cells.csv (the cells at each height's first push's end)."""
    columns = ["height_m", "angle_deg", "regime", "regime_closed", "mu", "e_m", "e_closed_m", "tipped_at_m",
               "phi_deg", "phi_closed_deg", "d_m", "d_closed_m", "phi2_rad", "phi2_closed_rad",
               "contact_fraction", "contact_fraction_closed"]
    write_csv(out / "pushed_block.csv", columns, [[r[c] for c in columns] for r in runs])
    write_csv(out / "push_paths.csv", ["height_m", "angle_deg", "x1_m", "x2_m", "d_m", "phi2_rad",
                                       "contact_fraction"], paths)
    cell_rows = [(h, i, j, float(N[i, j]), int(S[i, j])) for h, (N, S, _) in cells.items()
                 if N is not None for i in range(N.shape[0]) for j in range(N.shape[1])]
    write_csv(out / "pressure_cells.csv", ["height_m", "i", "j", "normal_N", "cell_state"], cell_rows)


def push_warning(sc: Scenario, off: list, unsettled: list) -> str | None:
    """The one warning line: what is off the closed forms, else the pushes
    whose angle and pose were not checked (not settled before the fit)."""
    if off:
        return f"{sc.name}: the push is off its closed forms: " + "; ".join(off)
    if unsettled:
        worst = max(r["elastic_length_m"] for r in unsettled)
        start = pushed.FIT_FROM * sc.push["travel_m"]
        return (f"{sc.name}: the trajectory angle and the pose were not checked at {len(unsettled)} "
                f"pushes: the fit starts at {start:g} m, within {ELASTIC_LENGTHS:g} elastic lengths "
                f"of the most loaded cell (up to {worst:.3g} m) of the start; push further "
                f"(push.travel_m >= {2 * ELASTIC_LENGTHS * worst:.3g} m)")
    return None


def push_summary(sc: Scenario, runs: list, cells: dict, warning: str | None, unsettled: list) -> dict:
    """summary.json: the runs, the thresholds at each angle, the cells' source and the checks."""
    L = sc.pad["length_m"]
    return {**sc.head(), "rule": sc.law.rule, "weight_N": sc.rig.mass_kg * sc.rig.g, "pad": sc.pad,
            "runs": runs,
            "thresholds": {f"{a:g}": {"mu": friction_along_x1(sc.params_at(a)),
                                      "lift_off_height_m": L / (6 * friction_along_x1(sc.params_at(a))),
                                      "tipping_height_m": L / (2 * friction_along_x1(sc.params_at(a)))}
                           for a in sc.push["angles_deg"]},
            "cells": {f"{h:g}": why for h, (_, _, why) in cells.items()},
            "checks": {"ok": warning is None, "warning": warning, "phi_unchecked": len(unsettled)},
            "angle_convention": "phi the trajectory's angle from X1, counterclockwise; e the centre of "
                                "pressure's shift toward the leading edge (+X1)"}


def cells_of(params, block, pu, res) -> tuple:
    """(the cells' normal forces and states at the push's end, where they
    come from), or (None, None, why not): res's own (FMI 3.0), else those of
    the same push on the installed FMI 3.0 ContactPad FMU if its record
    equals res's."""
    if res.cell_normal is not None or res.regime == TIPS:
        return res.cell_normal, res.cell_state, ("this run (FMI 3.0: cellFn, cellState)"
                                                 if res.regime != TIPS else "the block tipped")
    again, why = fmi3_twin(
        PAD_MODEL, lambda twin: pushed.push(params, block, pu["travel_m"], pu["step_m"], 3, twin, cells=True),
        lambda again: all(np.array_equal(getattr(res, k), getattr(again, k))
                          for k in ("x1", "x2", "d", "phi2", "T1")), "push")
    return (None, None, why) if again is None else (again.cell_normal, again.cell_state, why)


@part("pushed_block", "run")
def run_pushed(sc: Scenario, out: Path, fmu_path, how: RunOptions) -> dict:
    """The kind's runner: pushed_outputs (runs in this process)."""
    return pushed_outputs(sc, out, fmu_path, how.draw)
