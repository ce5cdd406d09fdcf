"""What `orthocontact design` writes: plan.csv (the runs, in a lab's
order), design.json (the criterion, predicted standard errors, the
baseline, the efficiency, the equivalence-theorem check), design.png (the
sensitivity function against mat angle, the chosen runs marked),
design.md (for people) and the terminal's summary.  Units: N, m, s, deg."""
from __future__ import annotations

from collections import Counter
from pathlib import Path

import numpy as np

from ..output import finish, pyplot, write_csv, write_json
from .design import RAMP, SLIDE, Design
from .design_inputs import PLAN_COLUMNS, grouped, plan_rows
from .design_search import group_ratios

RIG_KEYS = ("mass_kg", "g", "f_int_N", "velocity_m_s", "rule", "alpha_offset_deg", "beta_offset_deg",
            "ramp_angle_deg", "mu_strip", "c_strip")
UNITS = {"mu1": "-", "mu2": "-", "eps_ratio": "-", "eps2": "N/m", "c_strip": "N s/m", "f_int": "N"}


def criterion_text(d: Design) -> str:
    """What the criterion optimises, in words."""
    names = ", ".join(d.designed)
    nuisance = [n for n in d.candidates.names if n not in d.designed]
    tail = f" ({', '.join(nuisance)} estimated alongside: nuisance)" if nuisance else ""
    if d.criterion == "D":
        return (f"D-optimal for {names}: the largest det M" if not nuisance else
                f"D-optimal for {names}: the smallest det of their covariance{tail}")
    return (f"A-optimal: the smallest sum of the relative variances (sd / prior value)^2 of {names}"
            f"{tail}")


def efficiency_text(d: Design) -> str:
    p = len(d.designed)
    if d.criterion == "A":
        return "tr C_baseline / tr C, C the designed parameters' covariance relative to the prior values"
    if p == len(d.candidates.names):
        return f"(det M / det M_baseline)^(1/p), p = {p}"
    return f"(det C_baseline / det C)^(1/s), C the covariance of the s = {p} designed parameters"


def runs_json(runs) -> list:
    return [{"kind": r.kind, "mat_angle_deg": r.mat_angle_deg, "velocity_m_s": r.velocity_m_s, "runs": n}
            for r, n in grouped(list(runs))]


def equivalence_json(d: Design) -> dict:
    e = d.equivalence
    return {"max_sensitivity_ratio": e.max_ratio, "tolerance": e.tolerance, "holds": e.holds,
            "iterations": e.iterations,
            "statement": "at the approximate optimum (the multiplicative algorithm's weights), each "
                         "candidate's sensitivity d_c = tr(I_c dCriterion/dM) over the design's average "
                         "sum w_c d_c is at most 1 + tolerance in every group of runs (slides, ramp "
                         "samples); for D with nothing fixed, max_c tr(M^-1 I_c) / p <= 1, M per run"}


def design_json(d: Design) -> dict:
    """design.json's object."""
    c, prior, space = d.candidates, d.prior, d.space
    sd, base = d.sd(d.M), d.baseline
    support = [{"kind": c.runs[i].kind, "mat_angle_deg": c.runs[i].mat_angle_deg,
                "velocity_m_s": c.runs[i].velocity_m_s, "x1_m": None if c.run_kind[i] == SLIDE else c.x1_m[i],
                "weight": float(d.weights[i])} for i in np.argsort(-d.weights) if d.weights[i] >= 1e-3]
    nuisance = {n: v for n, v in c.sd(d.M).items() if n not in sd}
    rig = prior.rig
    return {
        "criterion": d.criterion, "criterion_text": criterion_text(d), "parameters": d.designed,
        "predicted_sd": sd, "nuisance_sd": nuisance or None,
        "plan": runs_json(d.runs()), "ramp_samples_x1_m": d.ramp_x1_m() or None,
        "baseline": {"description": base.description, "runs": runs_json(base.runs),
                     "ramp_samples_x1_m": list(base.ramp_x1_m) or None,
                     "predicted_sd": None if base.M is None else d.sd(base.M)},
        "efficiency": d.efficiency(), "efficiency_definition": efficiency_text(d),
        "equivalence_theorem": equivalence_json(d),
        "approximate": {"support": support, "plan_efficiency": d.problem.efficiency(d.M, d.M_approximate),
                        "note": "the plan's efficiency against the approximate optimum (at most 1)"},
        "prior": {"source": prior.source, "values": {n: prior.values[n] for n in c.names},
                  "noise": prior.noise.as_json(),
                  "rig": {k: getattr(rig, k) for k in RIG_KEYS}},
        "space": {"mat_angles_deg": [float(a) for a in space.angles_deg],
                  "velocities_m_s": [float(v) for v in space.velocities_m_s], "slide_runs": space.slides,
                  "ramp_samples": space.ramp_samples, "carriage_runs": space.carriage_runs,
                  "fixed_runs": runs_json(space.fixed) or None},
        "warnings": list(d.warnings)}


def sensitivity_curves(d: Design) -> tuple[np.ndarray, np.ndarray]:
    """Each candidate's sensitivity over its group's average, at the
    approximate optimum and at the plan (design_search.group_ratios)."""
    p = d.problem
    plan_weights = d.counts / np.asarray(p.budget, float)[p.group]
    return (group_ratios(p, d.weights, p.sensitivity(d.M_approximate)),
            group_ratios(p, plan_weights, p.sensitivity(d.M)))


def figure(d: Design, path: Path) -> None:
    """design.png: the sensitivity function of the slide runs against mat
    angle at each velocity shown (the plan's and the lowest and highest),
    the approximate optimum's and the plan's, the chosen runs marked; the
    ramp samples' below it where planned."""
    plt = pyplot()
    c = d.candidates
    approx, planned = sensitivity_curves(d)
    ramp = d.space.ramp_samples > 0
    fig, axes = plt.subplots(2 if ramp else 1, 1, figsize=(7.5, 6.5 if ramp else 4.2), squeeze=False)
    ax = axes[0, 0]
    slides = c.run_kind == SLIDE
    in_plan = {r.velocity_m_s for r, n, k in zip(c.runs, d.counts, c.run_kind) if n and k == SLIDE}
    velocities = sorted(in_plan | {min(d.space.velocities_m_s), max(d.space.velocities_m_s)})
    ax.plot([], [], color="0.3", label="approximate optimum")
    ax.plot([], [], color="0.3", ls="--", label="the plan")
    for k, v in enumerate(velocities):
        at = slides & np.array([r.velocity_m_s == v for r in c.runs])
        angles = np.array([r.mat_angle_deg for r in c.runs])[at]
        ax.plot(angles, approx[at], color=f"C{k}", label=f"{v:g} m/s")
        ax.plot(angles, planned[at], color=f"C{k}", ls="--")
        for i in np.flatnonzero(at & (d.counts > 0)):
            ax.plot(c.runs[i].mat_angle_deg, planned[i], "o", color=f"C{k}", ms=8)
            ax.annotate(f"x{d.counts[i]}", (c.runs[i].mat_angle_deg, planned[i]), textcoords="offset points",
                        xytext=(4, 6), fontsize=9)
    ax.axhline(1.0, color="0.4", lw=0.8)
    ax.set_xlabel("mat angle [deg]")
    ax.set_ylabel("sensitivity / design average")
    ax.set_ylim(bottom=0.0)
    if ramp:
        ramp_axes(axes[1, 0], d, approx, planned)
    fig.subplots_adjust(hspace=0.35)
    finish(fig, ax, path, f"{d.criterion}-optimal {d.space.slides} slide runs: sensitivity function "
                          "(o: the runs chosen; <= 1 at the optimum)")


def ramp_axes(ax, d: Design, approx, planned) -> None:
    c = d.candidates
    at = c.run_kind == RAMP
    ax.plot(1e3 * c.x1_m[at], approx[at], "C0", label="approximate optimum")
    ax.plot(1e3 * c.x1_m[at], planned[at], "C0--", label="the plan")
    for i in np.flatnonzero(at & (d.counts > 0)):
        ax.plot(1e3 * c.x1_m[i], planned[i], "o", color="C0", ms=8)
        ax.annotate(f"x{d.counts[i]}", (1e3 * c.x1_m[i], planned[i]), textcoords="offset points",
                    xytext=(4, 6), fontsize=9)
    ax.axhline(1.0, color="0.4", lw=0.8)
    ax.set_xlabel("ramp sample's travel x1 [mm] (stick branch)")
    ax.set_ylabel("sensitivity / average")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def sd_line(sd: dict) -> str:
    return ", ".join(f"{n} {v:.3g}" + ("" if UNITS[n] == "-" else f" {UNITS[n]}") for n, v in sd.items())


def runs_line(runs) -> str:
    return ", ".join(f"{r.kind} {r.mat_angle_deg:g} deg at {r.velocity_m_s:g} m/s x{n}"
                     for r, n in grouped(list(runs)))


def summary_text(d: Design) -> str:
    """The terminal's summary (and design.md's core)."""
    base, eff = d.baseline, d.efficiency()
    lines = [f"{criterion_text(d)}",
             f"plan ({len(d.runs())} runs): {runs_line(d.runs())}",
             f"predicted sd: {sd_line(d.sd(d.M))}"]
    if d.ramp_x1_m():
        at = sorted(Counter(d.ramp_x1_m()).items())
        lines.append("ramp samples at x1: " + ", ".join(f"{1e3 * x:.3g} mm x{n}" for x, n in at))
    lines.append("baseline: " + base.description)
    if base.M is None:
        lines.append("baseline: its information is singular at this budget: no efficiency")
    else:
        lines += [f"baseline predicted sd: {sd_line(d.sd(base.M))}",
                  f"{d.criterion}-efficiency against the baseline: {eff:.3f} ({efficiency_text(d)})"]
    e = d.equivalence
    verdict = f"<= 1 + {e.tolerance:g}: holds" if e.holds else f"> 1 + {e.tolerance:g}: does not hold"
    lines.append(f"equivalence theorem at the approximate optimum: max sensitivity ratio {e.max_ratio:.5f} "
                 f"({verdict}); the plan's efficiency against it "
                 f"{d.problem.efficiency(d.M, d.M_approximate):.3f}")
    return "\n".join(lines)


def markdown(d: Design) -> str:
    """design.md: the plan and its figures for people."""
    rows = [f"| {r.kind} | {r.mat_angle_deg:g} | {r.velocity_m_s:g} | {n} |" for r, n in grouped(d.runs())]
    lines = summary_text(d).splitlines()
    return "\n".join([
        "# Experiment design", "", f"Prior: {d.prior.source}.", "",
        "| kind | mat angle [deg] | velocity [m/s] | runs |", "|---|---|---|---|", *rows, "",
        *[f"- {line}" for line in lines], "",
        "The design is optimal at the prior: after the first runs, identify and plan the next ones "
        "with `--prior identified.json --fixed` the runs made (sequential design).", "",
        "![the sensitivity function](design.png)", ""])


def write_outputs(d: Design, out: Path) -> None:
    """plan.csv, design.json, design.png, design.md into out."""
    out = Path(out)
    write_csv(out / "plan.csv", list(PLAN_COLUMNS), plan_rows(d.runs()))
    write_json(out / "design.json", design_json(d))
    figure(d, out / "design.png")
    (out / "design.md").write_text(markdown(d))
