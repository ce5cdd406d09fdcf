"""The scenario kind of a pad that rolls (the ContactPad FMU's input vr):
`rolling`, a wheel's or a belt roller's contact on the textured mat as a
flat-track tyre tester drives it.  The pad is pressed flat by roll.load_N
(d = load / (kn A): full contact, uniform pressure), its surface passes
through at vr along its axis 1, and the body creeps at a steady creepage:
u1 = xi vr t (longitudinal) or u2 = eta vr t (lateral), each creepage of
roll.creepages held for roll.rolled_lengths pad lengths (the material in
the pad all replaced: steady), at each mat angle under each rule.  The step
is roll.courant cells of passage (h = courant length / (n1 vr)).

Checked against the brush's closed forms (closed_forms.brush) where the
texture's axes are the pad's (both tensors diagonal: a mat angle that puts
alpha and beta on 0 or 90 deg), with eps and mu those of the creepage's
axis: full adhesion -eps L xi / 2 up to the slip onset, partial slip
beyond.  Elsewhere no closed form exists, and the runs show what no
isotropic brush has: a lateral force from a pure longitudinal creepage.

Files (in the folder given): rolling.csv (a row a creepage of a run: the
forces over Fn and the closed form where it holds), rolling_cells.csv (each
cell's state at the end of each longitudinal creepage under the first
rule: an FMI 2.0 run, which has no arrays, takes them from the same run on
the installed FMI 3.0 FMU if its rows equal the run's bit for bit),
force_creepage.png, lateral_force.png, zones.png (rolling_figures);
summary.json."""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..closed_forms import adhesion_tensor, friction_tensor, slip_onset, steady_force
from ..experiment import RunOptions, Scenario, part, roll_steps
from ..fmu import PAD_MODEL, Foundation, PadFMU, PatchGeometry, fmi_version_of
from ..output import draw_here, write_csv, write_json
from .fmi3_twin import fmi3_twin
from .rolling_figures import figure_force_creepage, figure_lateral, figure_zones

DIRECTIONS = ("longitudinal", "lateral")
# The grid's brush meets the continuum's closed form to within this share of
# mu Fn (a first-order error in the cell size: about 1/n1 of the force at the
# slip onset, measured in tests/reproduction/test_rolling_outputs.py), times
# 1/n1; at most CLOSED_FORM_TOL_MAX.
CLOSED_FORM_PER_CELL = 1.0
CLOSED_FORM_TOL_MAX = 0.05
# Fn's relative deviation from the load that rounding leaves (kn A d).
FN_TOL = 1e-12
# A tensor whose off-diagonal entry is below this share of its diagonal is on the pad's axes.
ON_AXES = 1e-12


@dataclass(frozen=True)
class RollingPad:
    """The scenario's pad and its drive: geometry, foundation, the approach
    d_m [m] that presses it by load_N [N] in full contact, vr [m/s], the
    step h_s [s] and the steps a creepage is held for."""
    geometry: PatchGeometry
    foundation: Foundation
    load_N: float
    d_m: float
    vr: float
    h_s: float
    steps: int


def pad_of(sc: Scenario) -> RollingPad:
    """The scenario's pad, pressed flat by its load, rolling at its speed."""
    p, r = sc.pad, sc.roll
    g = PatchGeometry(float(p["length_m"]), float(p["width_m"]), int(p["n1"]), int(p["n2"]))
    kn = float(p["kn_N_m3"])
    h = r["courant"] * g.length / (g.n1 * r["vr_m_s"])
    return RollingPad(g, Foundation(kn), r["load_N"], r["load_N"] / (kn * g.length * g.width),
                      r["vr_m_s"], h, roll_steps(r, g.n1))


def axis_law(params, axis: int) -> tuple[float, float] | None:
    """(eps [N/m], mu [-]) along the pad's axis (0: X1, 1: X2) where both
    tensors are diagonal in the pad's frame; None where they are not (no
    closed form: a creepage along one axis deflects along both)."""
    B = adhesion_tensor(params.eps1, params.eps2, params.alpha)
    F = friction_tensor(params.mu1, params.mu2, params.beta)
    if abs(B[0, 1]) > ON_AXES * B.trace() or abs(F[0, 1]) > ON_AXES * F.trace():
        return None
    return float(B[axis, axis]), 1.0 / math.sqrt(F[axis, axis])


def closed_form_tol(pad: RollingPad) -> float:
    """The check's tolerance as a share of mu Fn (CLOSED_FORM_PER_CELL)."""
    return min(CLOSED_FORM_TOL_MAX, CLOSED_FORM_PER_CELL / pad.geometry.n1)


def roll(params, pad: RollingPad, direction: str, creepages, fmu_path, version: int) -> tuple[list, list]:
    """One run: the pad rolling through each creepage in turn, each held for
    pad.steps steps.  (rows: (creepage, T1, T2, Mz, Fn, slipFraction) at
    the end of each; states: each cell's state there under a longitudinal
    creepage, FMI 3.0, else [])."""
    axis = DIRECTIONS.index(direction)
    rows, states = [], []
    u = [0.0, 0.0]
    with PadFMU(fmu_path, "rolling", version) as f:
        f.initialize(params, pad.geometry, pad.foundation, (0.0, 0.0, 0.0, pad.d_m, 0.0, 0.0), vr=pad.vr)
        for xi in creepages:
            for _ in range(pad.steps):
                u[axis] += xi * pad.vr * pad.h_s
                f.set_inputs(u[0], u[1], 0.0, pad.d_m, vr=pad.vr)
                f.do_step(pad.h_s)
            out = f.outputs()
            rows.append((xi, out["T1"], out["T2"], out["Mz"], out["Fn"], out["slipFraction"]))
            if version == 3 and direction == "longitudinal":
                states.append(np.array(f.cell_states(), dtype=int))
    return rows, states


def rolling_outputs(sc: Scenario, out: Path, fmu_path, draw=None) -> dict:
    """Runs every rule, mat angle and direction, writes the files and the
    figures; returns the summary."""
    pad, r = pad_of(sc), sc.roll
    version = fmi_version_of(fmu_path)
    rows, cells, cells_from, worst = [], {}, {}, {}
    for rule in r["rules"]:
        for a in r["angles_deg"]:
            params = sc.params_at(a, rule)
            for direction in DIRECTIONS:
                got, states = roll(params, pad, direction, r["creepages"], fmu_path, version)
                if direction == "longitudinal" and rule == r["rules"][0]:   # the zones figure's
                    cells[(rule, a)], cells_from[f"{rule} {a:g}"] = \
                        cells_of(params, pad, r["creepages"], got, states, version)
                law = axis_law(params, DIRECTIONS.index(direction))
                rows += [creepage_row(rule, a, direction, law, pad, one) for one in got]
                offs = [row["off_closed_form_over_mu_Fn"] for row in rows[-len(got):]]
                if law is not None:   # numpy's max: a NaN stays, to fail the check
                    worst[(rule, a, direction)] = float(np.max(offs))
    write_tables(out, pad, rows, cells, r["creepages"])
    draw = draw or draw_here
    draw(figure_force_creepage, sc, rows, out / "force_creepage.png")
    draw(figure_lateral, sc, rows, out / "lateral_force.png")
    draw(figure_zones, sc, cells, r["creepages"], out / "zones.png")
    summary = rolling_summary(sc, pad, rows, worst, cells_from)
    write_json(out / "summary.json", summary)
    return summary


def cells_of(params, pad: RollingPad, creepages, rows: list, states: list, version: int) -> tuple:
    """(the cells' states at the end of each longitudinal creepage, where
    they come from), or (None, why not): the run's own (FMI 3.0), else those
    of the same run on the installed FMI 3.0 FMU (fmi3_twin)."""
    if version == 3:
        return states, "this run (FMI 3.0: cellState)"
    again, why = fmi3_twin(PAD_MODEL, lambda twin: roll(params, pad, "longitudinal", creepages, twin, 3),
                           lambda again: again[0] == rows, "rolls", " at the end of every creepage")
    return (None if again is None else again[1]), why


def creepage_row(rule: str, a: float, direction: str, law, pad: RollingPad, one: tuple) -> dict:
    """rolling.csv's row of a creepage's end: the forces over Fn, and where
    the texture's axes are the pad's (law: eps, mu along the creepage) the
    brush's closed form, its slip onset and the run's deviation [mu Fn]."""
    xi, T1, T2, Mz, Fn, slip = one
    closed = onset = off = None
    if law is not None:
        eps, mu = law
        closed = steady_force(eps, mu, Fn, pad.geometry.length, xi)
        onset = slip_onset(eps, mu, Fn, pad.geometry.length)
        off = abs((T1, T2)[DIRECTIONS.index(direction)] - closed) / (mu * Fn)
    return {"rule": rule, "angle_deg": a, "direction": direction, "creepage": xi, "T1_over_Fn": T1 / Fn,
            "T2_over_Fn": T2 / Fn, "Mz_N_m": Mz, "Fn_N": Fn, "slip_fraction": slip,
            "closed_form_over_Fn": None if closed is None else closed / Fn, "slip_onset": onset,
            "off_closed_form_over_mu_Fn": off}


def write_tables(out: Path, pad: RollingPad, rows: list, cells: dict, creepages) -> None:
    """rolling.csv and rolling_cells.csv (each cell's centre in the pad's frame [m])."""
    names = list(rows[0]) if rows else []
    write_csv(out / "rolling.csv", names, [[row[n] for n in names] for row in rows])
    g = pad.geometry
    cell_rows = [(rule, a, xi, i, j, (i + 0.5) * g.length / g.n1 - g.length / 2,
                  (j + 0.5) * g.width / g.n2 - g.width / 2, int(s[i, j]))
                 for (rule, a), states in cells.items() if states is not None
                 for xi, s in zip(creepages, states)
                 for i in range(g.n1) for j in range(g.n2)]
    write_csv(out / "rolling_cells.csv", ["rule", "angle_deg", "creepage", "i", "j", "x1_m", "x2_m",
                                          "state"], cell_rows)


def rolling_summary(sc: Scenario, pad: RollingPad, rows: list, worst: dict, cells_from: dict) -> dict:
    """summary.json: the pad, its drive, every row, the checks where a
    closed form holds, and the largest lateral force a pure longitudinal
    creepage makes at each mat angle."""
    tol = closed_form_tol(pad)
    bad = {k: v for k, v in worst.items() if not v <= tol}   # a NaN is off, never ok
    # flat and in full contact the foundation carries the load exactly (Fn = kn A d)
    fn_off = float(np.max([abs(row["Fn_N"] / pad.load_N - 1.0) for row in rows], initial=0.0))
    warning = None
    if not fn_off <= FN_TOL:
        warning = (f"{sc.name}: the pad carries Fn {fn_off:.3g} of the load off roll.load_N = {pad.load_N:g} "
                   "N, which a flat pad in full contact carries exactly")
    elif bad:
        (rule, a, direction), off = max(bad.items(), key=lambda kv: kv[1])
        warning = (f"{sc.name}: the {rule} pad rolling at mat angle {a:g} deg under {direction} creepage "
                   f"is {off:.3g} mu Fn off the brush's closed form (tolerance {tol:.3g} mu Fn at "
                   f"{pad.geometry.n1} cells along the rolling axis): not steady, or not the brush")
    lateral = {}
    for row in rows:
        if row["direction"] == "longitudinal":
            key = f"{row['rule']} {row['angle_deg']:g}"
            lateral[key] = max(lateral.get(key, 0.0), abs(row["T2_over_Fn"]))
    return {**sc.head(), "pad": sc.pad, "roll": sc.roll, "d_m": pad.d_m, "h_s": pad.h_s,
            "steps_per_creepage": pad.steps, "cells": cells_from, "rows": rows,
            "lateral_from_longitudinal_max_over_Fn": lateral,
            "checks": {"ok": warning is None, "tolerance_over_mu_Fn": tol, "warning": warning,
                       "Fn_off_load": fn_off,
                       "worst_over_mu_Fn": {f"{r} {a:g} {d}": v for (r, a, d), v in worst.items()}}}


@part("rolling", "run")
def run_rolling(sc: Scenario, out: Path, fmu_path, how: RunOptions) -> dict:
    """The kind's runner: rolling_outputs (runs in this process)."""
    return rolling_outputs(sc, out, fmu_path, how.draw)
