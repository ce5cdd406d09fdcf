"""The report's section on the contact patch: the runs of the scenario kinds
twist and towed_block (reproduction.planar_outputs) against their closed
forms.  The patch is this project's extension of the paper's law, not a
number the paper prints: its checks are not rows of the paper's table and
not in the headline's counts; a failed check is its warning line, as in
`orthocontact run`."""
from __future__ import annotations

from ..experiment.scenario import PATCH_KINDS, Scenario

INTRO = ("Not the paper's: the law over an area (the ContactPatch FMU, n1 × n2 cells, each the point "
         "law with its own slip) under a block, each run against its own closed forms "
         "(docs/guides/contact-patch.md in the repository). Its checks are not rows of the paper's "
         "table above and not in its counts.")


def patch_runs(runs: list[tuple[Scenario, dict]]) -> list[tuple[Scenario, dict]]:
    """The runs of the kinds of a body on the patch, in order."""
    return [(sc, s) for sc, s in runs if sc.kind in PATCH_KINDS]


def patch_json(runs: list[tuple[Scenario, dict]]) -> dict:
    """report.json's "contact_patch": each patch scenario's checks and the
    numbers the section shows."""
    out = {}
    for sc, s in patch_runs(runs):
        entry = {"kind": sc.kind, "checks": s["checks"]}
        if sc.kind == "twist":
            entry["rules"] = s["rules"]
            entry["cells"] = s.get("cells")
        else:
            entry["tows"] = s["tows"]
            entry["max_deviation_deg"] = s["max_deviation_deg"]
        out[sc.name] = entry
    return out


def _check_line(s: dict) -> str:
    return "Check: ok." if s["checks"]["ok"] else f"Check: **warning**: {s['checks']['warning']}"


def _patch_size(s: dict) -> str:
    """"L × W mm" of a run's patch."""
    p = s["patch"]
    return f"{p['length_m'] * 1e3:g} × {p['width_m'] * 1e3:g} mm"


def _twist(sc: Scenario, s: dict) -> list[str]:
    p = s["patch"]
    lines = [f"### {sc.title}", "",
             f"Turned about the centre of a {_patch_size(s)} patch of "
             f"{p['n1']} × {p['n2']} cells pressed with {s['normal_N']:.4g} N. While every cell sticks "
             "the torque follows the grid's torsional stiffness k (the slope −Mz/θ of the first step); "
             "once every cell slides it follows the full-slip plateau of the grid's closed form, reached "
             "as the elastic lag fades (its tolerance is that lag over the mean radius):", "",
             "| rule | slope −Mz/θ [N·m/rad] | k, closed form | relative error (tolerance) | "
             "θ at the end [deg] | −Mz there [N·m] | plateau, closed form | largest relative error "
             "past the plateau's start (tolerance) |",
             "|---|---|---|---|---|---|---|---|"]
    for rule, r in s["rules"].items():
        plateau = r["plateau_max_relative_error"]
        lines.append(f"| {rule} | {r['slope_N_m_rad']:.6g} | {r['k_N_m_rad']:.6g} | "
                     f"{r['slope_relative_error']:.1e} ({r['slope_tolerance']:.1e}) | "
                     f"{r['theta_end_deg']:.4g} | {-r['Mz_end_N_m']:.6g} | {-r['Mz_full_slip_end_N_m']:.6g} | "
                     + ("not checked: the twist stops before it" if plateau is None else f"{plateau:.1e}")
                     + f" ({r['plateau_tolerance']:.1e}, past {r['plateau_from_deg']:.3g}°) |")
    lines += ["", _check_line(s), ""]
    figures = f"[torque against angle]({sc.name}/twist.png)"
    cells = s.get("cells") or {}
    if cells.get("from"):
        figures += f", [the cells in stick and slip]({sc.name}/twist_cells.png) (their states: {cells['from']})"
    data = f"[{sc.name}/twist.csv]({sc.name}/twist.csv)"
    if cells.get("from"):
        data += f", [{sc.name}/twist_cells.csv]({sc.name}/twist_cells.csv)"
    lines.append(f"Figures: {figures}; data: {data}.")
    if not cells.get("from"):
        lines.append(f"No figure of the cells: {cells.get('why', 'no cell states')}.")
    return lines + [""]


def _towed(sc: Scenario, s: dict) -> list[str]:
    lines = [f"### {sc.title}", "",
             f"A {_patch_size(s)} patch pressed with "
             f"{s['normal_N']:.4g} N, towed along X1 through a pin ahead of its centre. Its steady yaw "
             "(counterclockwise from the motion) against its closed form, the direction of the law's "
             "steady sliding force, and against the paper's φ: the yaw is −φ with the mat turned back "
             "by the yaw, not −φ at the same mat angle (φ's closed form, in its frame: force along X1, "
             "counterclockwise):", "",
             "| mat angle [deg] | rule | steady yaw [deg] | closed form [deg] | deviation [deg] | "
             "−φ, mat turned by the yaw [deg] | φ at the mat angle [deg] |",
             "|---|---|---|---|---|---|---|"]
    for t in sorted(s["tows"], key=lambda t: (t["angle_deg"], t["rule"])):
        lines.append(f"| {t['angle_deg']:g} | {t['rule']} | {t['yaw_deg']:+.4f} | {t['yaw_closed_deg']:+.4f} | "
                     f"{t['deviation_deg']:.1e} | {t['minus_phi_turned_by_yaw_deg']:+.4f} | "
                     f"{t['phi_deg']:+.4f} |")
    lines += ["", f"{_check_line(s)} Largest deviation {s['max_deviation_deg']:.1e}° (tolerance "
              f"{s['checks']['tolerance_deg']:g}°).", "",
              f"Figures: [steady yaw against mat angle, with φ]({sc.name}/yaw_vs_angle.png), "
              f"[yaw against time]({sc.name}/yaw_vs_time.png); data: "
              f"[{sc.name}/towed_block.csv]({sc.name}/towed_block.csv), "
              f"[{sc.name}/yaw_vs_time.csv]({sc.name}/yaw_vs_time.csv).", ""]
    return lines


def patch_section(runs: list[tuple[Scenario, dict]]) -> list[str]:
    """report.md's lines of the section "The contact patch" ([] without a
    patch scenario)."""
    mine = patch_runs(runs)
    if not mine:
        return []
    lines = ["## The contact patch", "", INTRO, ""]
    for sc, s in sorted(mine, key=lambda r: PATCH_KINDS.index(r[0].kind)):   # the twist first
        lines += _twist(sc, s) if sc.kind == "twist" else _towed(sc, s)
    return lines
