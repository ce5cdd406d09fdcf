"""The report's section on the contact pad: the runs of the scenario kind of
a body on the pad (reproduction.pushed_outputs: pushed_block) against their
closed forms, the kind's part of the report (experiment.kinds.ReportPart)
registered here.  The pad is this project's extension of the paper's law:
its checks are not rows of the paper's table and not in the headline's
counts; a failed check is its warning line, as in `orthocontact run`."""
from __future__ import annotations

from ..experiment import ReportPart, Scenario, register
from .patch_report import check_line, extension_section, figures_line, link, rectangle_mm

PAD = extension_section("The contact pad", "the patch's cells on a Winkler foundation (the ContactPad "
                        "FMU), whose pressure follows the block's pose", "docs/guides/contact-pad.md",
                        "contact_pad")


def pushed_json(sc: Scenario, s: dict) -> dict:
    """report.json's entry of a push at heights: its checks, runs and thresholds."""
    return {"kind": s["kind"], "checks": s["checks"], "runs": s["runs"], "thresholds": s["thresholds"]}


def _number(x, fmt: str) -> str:
    return "—" if x is None else format(x, fmt)


def pushed_lines(sc: Scenario, s: dict) -> list[str]:
    """A push's lines in the section: each run's regime, pressure centre and
    trajectory angle against the closed forms, the thresholds, the figures."""
    p = s["pad"]
    lines = [f"### {sc.title}", "",
             f"The block ({s['weight_N']:.4g} N) on a {rectangle_mm(p)} pad of "
             f"{p['n1']} × {p['n2']} cells on a foundation of {p['kn_N_m3']:.3g} N/m³, pushed along "
             "X1 at a height h above the contact, free to drift laterally, quasi-static. The push's moment "
             "moves the pressure's centre by e = μh toward the leading edge (μ the law's friction along X1 "
             "with the block free laterally): full contact while μh ≤ L/6, the trailing edge lifting "
             "beyond, tipping past μh = L/2. The trajectory angle φ is the point law's at every height "
             "(every pressed cell slides the same way; the law is homogeneous in the normal force).", "",
             "| h [mm] | mat angle [deg] | μh / L | regime (closed form) | e / L | contact fraction "
             "(closed form) | φ [deg] | closed form [deg] |",
             "|---|---|---|---|---|---|---|---|"]
    for r in s["runs"]:
        L = r["length_m"]
        regime = r["regime"] + ("" if r["regime"] == r["regime_closed"] else f" (**{r['regime_closed']}**)")
        if r["regime"] == "tips":
            regime += f" at {r['tipped_at_m'] * 1e3:.3g} mm of travel"
        e = None if r["e_m"] is None or r["regime"] == "tips" else r["e_m"] / L
        lines.append(f"| {r['height_m'] * 1e3:g} | {r['angle_deg']:g} | {r['mu'] * r['height_m'] / L:.4f} | "
                     f"{regime} | {_number(e, '.4f')} | "
                     f"{_number(r['contact_fraction'] if r['regime'] != 'tips' else None, '.4f')} "
                     f"({_number(r['contact_fraction_closed'], '.4f')}) | {_number(r['phi_deg'], '+.4f')} | "
                     f"{r['phi_closed_deg']:+.4f} |")
    heights = ", ".join(f"a = {a}°: lift-off from h = {t['lift_off_height_m'] * 1e3:.4g} mm, tipping from "
                        f"{t['tipping_height_m'] * 1e3:.4g} mm" for a, t in s["thresholds"].items())
    lines += ["", f"Thresholds (closed form): {heights}.", "", check_line(s), "",
              figures_line(sc, [link(sc, "pressure_cells.png", "the pressure under the block"),
                                link(sc, "phi_vs_angle.png", "φ against mat angle at each height"),
                                link(sc, "regimes.png", "full contact, lift-off and tipping")],
                           ("pushed_block.csv", "push_paths.csv", "pressure_cells.csv")), ""]
    return lines


register("pushed_block", "report", ReportPart(PAD, pushed_lines, pushed_json))


def rolling_json(sc: Scenario, s: dict) -> dict:
    """report.json's entry of a rolling pad: its checks and lateral forces."""
    return {"kind": s["kind"], "checks": s["checks"],
            "lateral_from_longitudinal_max_over_Fn": s["lateral_from_longitudinal_max_over_Fn"]}


def rolling_lines(sc: Scenario, s: dict) -> list[str]:
    """A rolling pad's lines in the section: each run's largest deviation
    from the brush's closed form where it holds, and the largest lateral
    force a pure longitudinal creepage makes at each mat angle."""
    p, r = s["pad"], s["roll"]
    lines = [f"### {sc.title}", "",
             f"A {rectangle_mm(p)} pad of {p['n1']} × {p['n2']} cells on a foundation of {p['kn_N_m3']:.3g} "
             f"N/m³, pressed flat by {r['load_N']:g} N, its surface passing through at {r['vr_m_s']:g} m/s "
             f"({r['courant']:g} cell a step), the body creeping longitudinally or laterally at each "
             f"creepage up to {max(r['creepages']):g}, each held for {r['rolled_lengths']:g} pad lengths: "
             "the brush model with the law's orthotropic stiffness and friction in each bristle. Where the "
             "texture's axes are the pad's, the force is the brush's closed form (full adhesion −εLξ/2, "
             "then partial slip); elsewhere a longitudinal creepage also pushes sideways.", "",
             "| rule | mat angle [deg] | longitudinal: off the closed form [μFn] | lateral: off the closed "
             "form [μFn] | largest \\|T2\\|/Fn under longitudinal creepage |",
             "|---|---|---|---|---|"]
    worst = s["checks"]["worst_over_mu_Fn"]
    for rule in r["rules"]:
        for a in r["angles_deg"]:
            off = ["no closed form" if (x := worst.get(f"{rule} {a:g} {d}")) is None else f"{x:.2e}"
                   for d in ("longitudinal", "lateral")]
            lines.append(f"| {rule} | {a:g} | {off[0]} | {off[1]} | "
                         f"{s['lateral_from_longitudinal_max_over_Fn'][f'{rule} {a:g}']:.4f} |")
    lines += ["", f"Tolerance: {s['checks']['tolerance_over_mu_Fn']:.3g} μFn (the grid's first-order error "
              f"at {p['n1']} cells along the rolling axis).", "", check_line(s), "",
              figures_line(sc, [link(sc, "force_creepage.png", "force against creepage"),
                                link(sc, "lateral_force.png", "the lateral force of a longitudinal creepage"),
                                link(sc, "zones.png", "the adhesion and slip zones")],
                           ("rolling.csv", "rolling_cells.csv")), ""]
    return lines


register("rolling", "report", ReportPart(PAD, rolling_lines, rolling_json))
