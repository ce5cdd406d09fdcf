"""The pushed block's figures (pushed_outputs draws them): the pressure
under the block at each height, the trajectory angle against the mat angle
with the paper's closed form, and the regimes (full contact, lift-off,
tipping) against mu h / length with theirs."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..closed_forms import FULL_CONTACT, LIFT_OFF, TIPS, contact_fraction, pushed_at_height
from ..experiment import Scenario
from ..output import finish, pyplot, save, swept_label
from ..runs import closed_form_phi_deg_array


def figure_cells(sc: Scenario, runs: list, cells: dict, path: Path) -> None:
    """The pressure under the block at the end of each height's push (its
    first mat angle): cells coloured by normal force, open cells grey,
    slipping ones dotted."""
    plt = pyplot()
    heights = list(cells)
    pad = sc.pad
    L, W, n1, n2 = pad["length_m"] * 1e3, pad["width_m"] * 1e3, pad["n1"], pad["n2"]
    top = max((float(N.max()) for N, _, _ in cells.values() if N is not None), default=1.0) or 1.0
    fig, axes = plt.subplots(1, len(heights), figsize=(2.6 * len(heights) + 1.2, 3.4), squeeze=False)
    x, y = np.linspace(-L / 2, L / 2, n1 + 1), np.linspace(-W / 2, W / 2, n2 + 1)
    xc, yc = np.meshgrid(0.5 * (x[1:] + x[:-1]), 0.5 * (y[1:] + y[:-1]), indexing="ij")
    mesh = None
    for ax, h in zip(axes[0], heights):
        N, S, why = cells[h]
        run = next(r for r in runs if r["height_m"] == h)
        ax.set_title(f"h = {h * 1e3:g} mm: {run['regime']}", fontsize=9, y=1.0)
        ax.set_xlabel("x1 [mm] (push →)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.set_xlim(-L / 2, L / 2)
        ax.set_ylim(-W / 2, W / 2)
        ax.set_aspect("equal")
        if N is None:
            ax.text(0, 0, why, ha="center", va="center", fontsize=7, wrap=True)
            continue
        ax.set_facecolor("0.85")   # open cells are masked: the grey shows
        mesh = ax.pcolormesh(x, y, np.ma.masked_where(S == 0, N).T, cmap="viridis", vmin=0, vmax=top,
                             edgecolors="white", linewidth=0.4)
        slip = S == 2
        ax.plot(xc[slip], yc[slip], ".", color="C3", ms=3)
    axes[0][0].set_ylabel("x2 [mm]", fontsize=8)
    if mesh is not None:
        fig.colorbar(mesh, ax=list(axes[0]), fraction=0.03, pad=0.02).set_label("cell normal force [N]",
                                                                                fontsize=8)
    fig.suptitle(f"{sc.title}: pressure under the block at a = {sc.push['angles_deg'][0]:g}° (grey: open, "
                 "red dot: slipping)", fontsize=9)
    save(fig, path)


def figure_phi(sc: Scenario, runs: list, path: Path) -> None:
    """phi against the mat angle at each height, with the paper's closed form
    (the scenario's) and its measured extremum where the scenario gives it."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    angles = sorted({r["angle_deg"] for r in runs})
    fine = np.linspace(min(angles), max(angles), 181)
    ax.plot(fine, closed_form_phi_deg_array(sc, fine), "-", color="0.3",
            label=f"paper's closed form ({sc.closed_form})")
    for k, h in enumerate(sorted({r["height_m"] for r in runs})):
        mine = [r for r in runs if r["height_m"] == h and r["phi_deg"] is not None]
        tips = [r["angle_deg"] for r in runs if r["height_m"] == h and r["phi_deg"] is None]
        label = f"pad FMU, h = {h * 1e3:g} mm" + (f" (tips at {', '.join(f'{a:g}' for a in tips)}°)"
                                                 if tips else "")
        ax.plot([r["angle_deg"] for r in mine], [r["phi_deg"] for r in mine], "os^vD"[k % 5], ms=6 - k,
                mfc="none", color=f"C{k}", label=label)
    if "extremum_phi_deg" in sc.paper:
        sign = -1.0 if sc.paper.get("phi_sign_differs") else 1.0
        ax.axhline(sign * sc.paper["extremum_phi_deg"], color="C3", ls=":", lw=1,
                   label=f"paper's measured extremum, {sign * sc.paper['extremum_phi_deg']:+g}°")
    ax.set_xlabel(f"{swept_label(sc)} [deg]")
    ax.set_ylabel("trajectory angle φ [deg] (counterclockwise)")
    finish(fig, ax, path, f"{sc.title}: φ at every height")


def figure_regimes(sc: Scenario, runs: list, path: Path) -> None:
    """The pressure's centre e/length and the contact fraction against
    mu h / length, with the closed forms and the thresholds 1/6 and 1/2."""
    plt = pyplot()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4.2))
    x = np.linspace(0, 0.6, 601)
    pad, W = sc.pad, sc.rig.mass_kg * sc.rig.g
    L, Wd, kn = pad["length_m"], pad["width_m"], pad["kn_N_m3"]
    frac = []
    for t in x:   # the closed form's steady pose at e = t length, and its contact
        _, d, phi2 = pushed_at_height(kn, L, Wd, W, t * L)
        frac.append(np.nan if d is None else contact_fraction(L, Wd, d, 0.0, phi2))
    ax.plot(x, np.where(x < 0.5, x, np.nan), "-", color="0.3", label="closed form: e = μh")
    bx.plot(x, frac, "-", color="0.3", label="closed form")
    for a in (ax, bx):
        for t, name in ((1 / 6, "1/6: lift-off"), (0.5, "1/2: tips")):
            a.axvline(t, color="C3", ls=":", lw=1)
            a.text(t, 0.02, f"{name} ", color="C3", fontsize=7, ha="right", transform=a.get_xaxis_transform())
    for k, regime in enumerate((FULL_CONTACT, LIFT_OFF, TIPS)):
        mine = [r for r in runs if r["regime"] == regime]
        xs = [r["mu"] * r["height_m"] / L for r in mine]
        if regime == TIPS:
            ax.plot(xs, [0.5] * len(xs), "x", color=f"C{k}", ms=7, label="pad FMU: tips (no equilibrium)")
            continue
        ax.plot(xs, [r["e_m"] / L for r in mine], "o", mfc="none", color=f"C{k}", label=f"pad FMU: {regime}")
        bx.plot(xs, [r["contact_fraction"] for r in mine], "o", mfc="none", color=f"C{k}",
                label=f"pad FMU: {regime}")
    ax.set_xlabel("μ h / length")
    ax.set_ylabel("centre of pressure e / length")
    bx.set_xlabel("μ h / length")
    bx.set_ylabel("contact fraction")
    bx.grid(alpha=0.3)
    bx.legend(fontsize=8)
    fig.suptitle(f"{sc.title}: full contact, lift-off and tipping", fontsize=10, y=0.995)
    finish(fig, ax, path, "")
