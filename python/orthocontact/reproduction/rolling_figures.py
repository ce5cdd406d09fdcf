"""The rolling pad's figures (rolling_outputs draws them): the force against
the creepage at each mat angle with the brush's closed form where it holds,
the lateral force a pure longitudinal creepage makes against the mat angle,
and the adhesion and slip zones in the pad."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..experiment import Scenario
from ..output import curve_style, finish, label, pyplot, save, swept_label

# The zones figure: at most this many creepages (rows), spread over the list.
ZONE_ROWS = 4


def _runs(rows: list, rule: str, direction: str) -> dict:
    """{mat angle: its rows in creepage order} of one rule and direction."""
    out = {}
    for row in rows:
        if row["rule"] == rule and row["direction"] == direction:
            out.setdefault(row["angle_deg"], []).append(row)
    return out


def figure_force_creepage(sc: Scenario, rows: list, path: Path) -> None:
    """T1/Fn against the longitudinal creepage and T2/Fn against the lateral
    one, a panel each per rule, a curve per mat angle; the closed form
    (black, dotted) where the texture's axes are the pad's."""
    plt = pyplot()
    rules = list(sc.roll["rules"])
    fig, axes = plt.subplots(2, len(rules), figsize=(5.2 * len(rules) + 1.8, 7.0), squeeze=False)
    for col, rule in enumerate(rules):
        for row_i, (direction, key) in enumerate((("longitudinal", "T1_over_Fn"), ("lateral", "T2_over_Fn"))):
            ax = axes[row_i][col]
            runs = _runs(rows, rule, direction)
            for i, (a, rs) in enumerate(runs.items()):
                xi = [r["creepage"] for r in rs]
                ax.plot(xi, [-r[key] for r in rs], label=f"{a:g}°", **curve_style(i, len(xi), len(runs)))
                if rs[0]["closed_form_over_Fn"] is not None:
                    ax.plot(xi, [-r["closed_form_over_Fn"] for r in rs], ":", color="black", lw=1)
            ax.set_xlabel(f"{direction} creepage [-]", fontsize=8)
            ax.set_ylabel(f"-{key.split('_')[0]} / Fn [-]", fontsize=8)
            ax.tick_params(labelsize=7)
            label(ax, f"{rule}: {direction} (dotted: the brush's closed form)", swept_label(sc), outside=True,
                  size=9)
    fig.suptitle(f"{sc.title}: force against creepage", fontsize=10)
    fig.subplots_adjust(left=0.08, right=0.85, bottom=0.07, top=0.92, hspace=0.3, wspace=0.45)
    save(fig, path)


def figure_lateral(sc: Scenario, rows: list, path: Path) -> None:
    """T2/Fn against the mat angle under a pure longitudinal creepage, a
    curve per creepage and rule: zero on the texture's axes, where an
    isotropic brush has it everywhere."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    creepages = [x for x in sc.roll["creepages"] if x > 0]
    lines = [(rule, xi) for rule in sc.roll["rules"] for xi in creepages]
    for i, (rule, xi) in enumerate(lines):
        pts = sorted((r["angle_deg"], r["T2_over_Fn"]) for r in rows
                     if r["rule"] == rule and r["direction"] == "longitudinal" and r["creepage"] == xi)
        ax.plot([a for a, _ in pts], [t for _, t in pts], label=f"{rule}, ξ = {xi:g}",
                **curve_style(i, len(pts), len(lines)))
    ax.axhline(0.0, color="black", lw=0.8)
    ax.set_xlabel(swept_label(sc) + " [deg]", fontsize=8)
    ax.set_ylabel("T2 / Fn [-] under longitudinal creepage only", fontsize=8)
    finish(fig, ax, path, f"{sc.title}: the lateral force of a longitudinal creepage", "rule, creepage",
           outside=True)


def zone_creepages(creepages) -> list:
    """Up to ZONE_ROWS of the creepages, spread evenly from the first to the last."""
    spread = np.linspace(0, len(creepages) - 1, min(ZONE_ROWS, len(creepages)))
    picks = np.unique(np.round(spread).astype(int))
    return [creepages[k] for k in picks]


def figure_zones(sc: Scenario, cells: dict, creepages, path: Path) -> None:
    """Each cell's state at the end of a longitudinal creepage (rows) at
    each mat angle (columns), the first rule: sticking (adhesion) light,
    slipping dark; the material enters on the right.  Said in words where
    there are none (an FMI 2.0 run without its FMI 3.0 twin)."""
    plt = pyplot()
    rule = sc.roll["rules"][0]
    angles = list(sc.roll["angles_deg"])
    shown = zone_creepages(list(creepages))
    fig, axes = plt.subplots(len(shown), len(angles), squeeze=False,
                             figsize=(1.3 * len(angles) + 1.0, 1.1 * len(shown) + 1.2))
    L, W = sc.pad["length_m"] * 1e3, sc.pad["width_m"] * 1e3
    n1, n2 = sc.pad["n1"], sc.pad["n2"]
    x, y = np.linspace(-L / 2, L / 2, n1 + 1), np.linspace(-W / 2, W / 2, n2 + 1)
    for r, xi in enumerate(shown):
        for c, a in enumerate(angles):
            ax = axes[r][c]
            ax.set_xticks([])
            ax.set_yticks([])
            states = cells.get((rule, a))
            if c == 0:
                ax.set_ylabel(f"ξ = {xi:g}", fontsize=7)
            if r == 0:
                ax.set_title(f"{a:g}°", fontsize=8)
            if states is None:
                ax.text(0.5, 0.5, "no cell arrays:\nsummary.json's\n\"cells\" says why", ha="center",
                        va="center", fontsize=6, transform=ax.transAxes)
                continue
            S = states[list(creepages).index(xi)]
            ax.pcolormesh(x, y, S.T, cmap="Blues", vmin=0, vmax=2.5)
            ax.set_aspect("equal")
    fig.suptitle(f"{sc.title}: adhesion (light) and slip (dark) zones, {rule} rule, longitudinal "
                 "creepage; material enters on the right", fontsize=8)
    save(fig, path)
