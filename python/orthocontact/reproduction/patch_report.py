"""The report's section on the contact patch: the runs of the scenario kinds
of a body on the patch (reproduction.planar_outputs: twist, towed_block)
against their closed forms, each kind's part of the report
(experiment.kinds.ReportPart) registered here.  The patch is this project's
extension of the paper's law, not a number the paper prints: its checks are
not rows of the paper's table and not in the headline's counts; a failed
check is its warning line, as in `orthocontact run`."""
from __future__ import annotations

from ..experiment import ReportPart, Scenario, Section, register


def extension_section(title: str, what: str, guide: str, json_key: str) -> Section:
    """The section of one of this project's extensions of the paper's law
    (the patch, the pad): `what` it is, its `guide` in docs/, and that its
    checks are not the paper's."""
    intro = (f"Not the paper's: {what}, each run against its own closed forms ({guide} in the "
             "repository). Its checks are not rows of the paper's table above and not in its counts.")
    return Section(title, (intro, ""), json_key=json_key)


PATCH = extension_section("The contact patch", "the law over an area (the ContactPatch FMU, n1 × n2 "
                          "cells, each the point law with its own slip) under a block",
                          "docs/guides/contact-patch.md", "contact_patch")


def twist_json(sc: Scenario, s: dict) -> dict:
    """report.json's entry of a twist: its checks and the numbers the
    section shows."""
    return {"kind": s["kind"], "checks": s["checks"], "rules": s["rules"], "cells": s.get("cells")}


def towed_json(sc: Scenario, s: dict) -> dict:
    """report.json's entry of a towed block: its checks and the numbers the
    section shows."""
    return {"kind": s["kind"], "checks": s["checks"], "tows": s["tows"],
            "max_deviation_deg": s["max_deviation_deg"]}


def check_line(s: dict) -> str:
    """The run's check: ok, or its warning line as `orthocontact run` prints it."""
    return "Check: ok." if s["checks"]["ok"] else f"Check: **warning**: {s['checks']['warning']}"


def rectangle_mm(p: dict) -> str:
    """"L × W mm" of a patch's or pad's table (length_m, width_m)."""
    return f"{p['length_m'] * 1e3:g} × {p['width_m'] * 1e3:g} mm"


def link(sc: Scenario, name: str, text: str | None = None) -> str:
    """A Markdown link to the file `name` of the scenario's folder, its text
    the path unless `text` is given."""
    return f"[{text or f'{sc.name}/{name}'}]({sc.name}/{name})"


def figures_line(sc: Scenario, figures: list, data: tuple) -> str:
    """"Figures: ...; data: ...." from the figures' links and the names of
    the data files in the scenario's folder."""
    return f"Figures: {', '.join(figures)}; data: {', '.join(link(sc, name) for name in data)}."


def twist_lines(sc: Scenario, s: dict) -> list[str]:
    """A twist's lines in the section: its slope and plateau against their closed forms."""
    p = s["patch"]
    lines = [f"### {sc.title}", "",
             f"Turned about the centre of a {rectangle_mm(p)} patch of "
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
                     f"{r['theta_end_deg']:.4g} | {-r['Mz_end_N_m']:.6g} | "
                     f"{-r['Mz_full_slip_end_N_m']:.6g} | "
                     + ("not checked: the twist stops before it" if plateau is None else f"{plateau:.1e}")
                     + f" ({r['plateau_tolerance']:.1e}, past {r['plateau_from_deg']:.3g}°) |")
    lines += ["", check_line(s), ""]
    cells = s.get("cells") or {}
    figures, data = [link(sc, "twist.png", "torque against angle")], ("twist.csv",)
    if cells.get("from"):
        figures.append(f"{link(sc, 'twist_cells.png', 'the cells in stick and slip')} "
                       f"(their states: {cells['from']})")
        data += ("twist_cells.csv",)
    lines.append(figures_line(sc, figures, data))
    if not cells.get("from"):
        lines.append(f"No figure of the cells: {cells.get('why', 'no cell states')}.")
    return lines + [""]


def towed_lines(sc: Scenario, s: dict) -> list[str]:
    """A towed block's lines in the section: its steady yaw against its closed form."""
    lines = [f"### {sc.title}", "",
             f"A {rectangle_mm(s['patch'])} patch pressed with "
             f"{s['normal_N']:.4g} N, towed along X1 through a pin ahead of its centre. Its steady yaw "
             "(counterclockwise from the motion) against its closed form, the direction of the law's "
             "steady sliding force, and against the paper's φ: the yaw is −φ with the mat turned back "
             "by the yaw, not −φ at the same mat angle (φ's closed form, in its frame: force along X1, "
             "counterclockwise):", "",
             "| mat angle [deg] | rule | steady yaw [deg] | closed form [deg] | deviation [deg] | "
             "−φ, mat turned by the yaw [deg] | φ at the mat angle [deg] |",
             "|---|---|---|---|---|---|---|"]
    for t in sorted(s["tows"], key=lambda t: (t["angle_deg"], t["rule"])):
        lines.append(f"| {t['angle_deg']:g} | {t['rule']} | {t['yaw_deg']:+.4f} | "
                     f"{t['yaw_closed_deg']:+.4f} | "
                     f"{t['deviation_deg']:.1e} | {t['minus_phi_turned_by_yaw_deg']:+.4f} | "
                     f"{t['phi_deg']:+.4f} |")
    lines += ["", f"{check_line(s)} Largest deviation {s['max_deviation_deg']:.1e}° (tolerance "
              f"{s['checks']['tolerance_deg']:g}°).", "",
              figures_line(sc, [link(sc, "yaw_vs_angle.png", "steady yaw against mat angle, with φ"),
                                link(sc, "yaw_vs_time.png", "yaw against time")],
                           ("towed_block.csv", "yaw_vs_time.csv")), ""]
    return lines


register("twist", "report", ReportPart(PATCH, twist_lines, twist_json))
register("towed_block", "report", ReportPart(PATCH, towed_lines, towed_json))
