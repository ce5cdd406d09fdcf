"""The planar body's figures (planar_outputs draws them): the twist's
torque, the cells during the twist, and the towed block's yaw against the
mat angle and against time."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..closed_forms import of_law, steady_phi_deg
from ..experiment import Scenario
from ..fmu import PatchGeometry
from ..output import curve_style, finish, pyplot, swept_label
from ..rig import steady_yaw


def figure_twist(sc: Scenario, runs: dict, path: Path) -> None:
    """The torque against the twist angle under each rule, with the full-slip
    plateau and the stick line k theta (log-log where every torque is > 0)."""
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
    lowest = min(float(np.min(-res.Mz)) for res, _, _ in runs.values())
    if lowest > 0:
        # log-log: the stick line has slope 1, the plateau is flat, both readable
        ax.set_xscale("log")
        ax.set_yscale("log")
        from matplotlib.ticker import FormatStrFormatter
        for axis in (ax.xaxis, ax.yaxis):   # plain numbers: short tick labels
            axis.set_major_formatter(FormatStrFormatter("%g"))
            axis.set_minor_formatter(FormatStrFormatter(""))
        ax.set_ylim(lowest / 2, 2 * top)
    # else linear: a torque of 0 (a single cell, on the centre, never moves) has no logarithm
    ax.set_xlabel("body angle θ [deg]")
    ax.set_ylabel("torque to turn the body, −Mz [N·m]")
    finish(fig, ax, path, f"{sc.title}: twist", swept_label(sc) + " at a = 0")


def figure_yaw_angle(sc: Scenario, rows: list, path: Path) -> None:
    """The towed block's steady yaw against the mat angle, with the closed
    form and the paper's phi beside it."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    rules = list(dict.fromkeys(r[0] for r in rows))
    fine = np.linspace(min(r[1] for r in rows), max(r[1] for r in rows), 181)
    for i, rule in enumerate(rules):
        pts = [r for r in rows if r[0] == rule]
        closed = [math.degrees(steady_yaw(sc.params_at(a, rule))) for a in fine]
        phi = [of_law(steady_phi_deg, p, p.alpha, p.beta) for p in (sc.params_at(a, rule) for a in fine)]
        ax.plot(fine, closed, "-", color=f"C{i}", lw=1, label=f"{rule}: yaw, closed form")
        ax.plot([r[1] for r in pts], [r[2] for r in pts], "o", ms=4, color=f"C{i}",
                label=f"{rule}: yaw, patch FMU")
        ax.plot(fine, phi, ":", color=f"C{i}", label=f"{rule}: paper's φ (force along X1)")
    ax.set_xlabel("mat angle a [deg]")
    ax.set_ylabel("angle [deg]")
    finish(fig, ax, path, f"{sc.title}: steady yaw of the towed block", swept_label(sc))


def figure_yaw_time(sc: Scenario, records: dict, path: Path) -> None:
    """The towed block's yaw against time, a curve a rule and mat angle."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for i, ((rule, a), res) in enumerate(records.items()):
        ax.plot(res.t, np.degrees(res.theta), label=f"{rule[:5]}., a = {a:g}°",
                **curve_style(i, len(res.t), len(records)))
    ax.set_xlabel("time [s]")
    ax.set_ylabel("yaw θ [deg]")
    finish(fig, ax, path, f"{sc.title}: yaw against time", swept_label(sc), outside=True)


def figure_cells(sc: Scenario, g: PatchGeometry, rows: list, path: Path) -> None:
    """Every cell's state (open, stick, slip) at the twist's instants, a row
    of panels a rule (rules with the same cells sharing one)."""
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Rectangle
    plt = pyplot()
    # one row of panels per rule, rules whose cells are the same at the
    # same instants sharing one
    shown: dict = {}
    for rule in dict.fromkeys(r[0] for r in rows):
        mine = tuple(r[1:] for r in rows if r[0] == rule)
        shown.setdefault(mine, []).append(rule)
    panels = [(", ".join(rules), *key) for mine, rules in shown.items()
              for key in dict.fromkeys(r[:3] for r in mine)]
    rows = [(", ".join(rules), *r) for mine, rules in shown.items() for r in mine]
    rules = list(dict.fromkeys(p[0] for p in panels))
    ncol = max(sum(p[0] == rule for p in panels) for rule in rules)
    colours = ("0.8", "C0", "C3")   # open, stick, slip
    cmap, norm = ListedColormap(colours), BoundaryNorm([-0.5, 0.5, 1.5, 2.5], 3)
    fig = plt.figure(figsize=(2.4 * ncol + 2.8, 1.6 * len(rules) + 1.2))
    grid = fig.add_gridspec(len(rules) + 1, ncol, height_ratios=[0.02] + [1] * len(rules),
                            hspace=0.75, wspace=0.3)
    x = np.linspace(-g.length / 2, g.length / 2, g.n1 + 1) * 1e3
    y = np.linspace(-g.width / 2, g.width / 2, g.n2 + 1) * 1e3
    for r, rule in enumerate(rules):
        for c, (_, name, k, theta) in enumerate(p for p in panels if p[0] == rule):
            ax = fig.add_subplot(grid[r + 1, c])
            state = np.array([q[8] for q in rows if q[:3] == (rule, name, k)]).reshape(g.n1, g.n2)
            ax.pcolormesh(x, y, state.T, cmap=cmap, norm=norm, edgecolors="white", linewidth=0.5)
            ax.set_aspect("equal")
            ax.set_title(f"{name}\nθ = {theta:.3g}°", fontsize=9, y=1.0)
            ax.tick_params(labelsize=7)
            ax.set_xlabel("x1 [mm]", fontsize=8)
            if c == 0:
                ax.set_ylabel(f"{rule}\nx2 [mm]", fontsize=8)
    # the figure's title and legend on a strip above the panels
    strip = fig.add_subplot(grid[0, :])
    strip.axis("off")
    for colour, what in zip(colours, ("open", "stick", "slip")):
        strip.add_patch(Rectangle((0, 0), 0, 0, facecolor=colour, label=what))
    finish(fig, strip, path, f"{sc.title}: the cells during the twist (body frame, θ counterclockwise)",
           f"α = {sc.geometry.alpha_offset_deg:g}°, β = {sc.geometry.beta_offset_deg:g}°", outside=True)
