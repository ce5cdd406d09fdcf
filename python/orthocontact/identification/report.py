"""What identification writes for people: the fit figure, identified.md and
the terminal summary, each from an identify.Identification `res` (identify
imports this module, not the reverse)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import closed_forms as cf
from .estimators import reported_names


def fit_figure(res, path: Path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    d, v, rig = res.data, res.fit.values, res.data.rig
    panels = [p for p, have in (("forces", d.forces is not None), ("angles", d.angles is not None),
                                ("ramp", d.ramp is not None)) if have]
    fig, axes = plt.subplots(1, len(panels), figsize=(5 * len(panels), 4), squeeze=False)
    grid = np.linspace(0, 90, 181)

    def phi_curve(eps_ratio):
        return [math.degrees(math.atan(cf.steady_tan_phi(v["mu1"], v["mu2"], eps_ratio, 1.0,
                                                         *rig.axes(a), rig.rule))) for a in grid]
    for ax, p in zip(axes[0], panels):
        if p == "forces":
            ax.plot(d.forces[:, 0], d.forces[:, 1], "o", ms=4, label="data")
            if "mu1" in v:
                ax.plot(grid, [cf.steady_drive_force(v["mu1"], v["mu2"], rig.axes(a)[1], rig.f_int_N,
                                                     rig.mass_kg, rig.g) for a in grid], "-",
                        label=f"fit: μ1={v['mu1']:.4f}, μ2={v['mu2']:.4f}")
            ax.set_ylabel("driving force [N]")
        elif p == "angles":
            ax.plot(d.angles[:, 0], d.angles[:, 1], "o", ms=4, label="data")
            if "eps_ratio" in v:
                ax.plot(grid, phi_curve(v["eps_ratio"]), "-", label=f"joint fit: ε1/ε2={v['eps_ratio']:.4f}")
            for key, style, lab in (("max_rule", ":", "maximum rule"), ("eq41", "--", "eq. (41)")):
                src = res.max_rule if key == "max_rule" else (res.eq40 or {}).get("eq41")
                if src and "eps_ratio" in src and "mu1" in v and math.isfinite(src["eps_ratio"]):
                    ax.plot(grid, phi_curve(src["eps_ratio"]), style, label=f"{lab}: ε1/ε2={src['eps_ratio']:.4f}")
            ax.set_ylabel("trajectory angle φ [deg] (counterclockwise)")
        else:
            ax.plot(d.ramp[:, 0] * 1e3, d.ramp[:, 1], "o", ms=3, label="data")
            if "eps2" in v:
                al, be = rig.axes(rig.ramp_angle_deg)
                k = cf.stick_stiffness_x1(v.get("eps_ratio", 1.0) * v["eps2"], v["eps2"], al)
                top = cf.steady_drive_force(v["mu1"], v["mu2"], be, 0.0, rig.mass_kg, rig.g) \
                    if "mu1" in v else float(np.max(d.ramp[:, 1]) - rig.f_int_N)
                xs = np.linspace(0, d.ramp[:, 0].max(), 200)
                ax.plot(xs * 1e3, rig.f_int_N + np.minimum(k * xs, top), "-", label=f"fit: k={k:.4g} N/m")
            ax.set_xlabel("travel x1 [mm]")
            ax.set_ylabel("driving force [N]")
        if p != "ramp":
            ax.set_xlabel("orientation angle [deg]")
        ax.grid(alpha=0.3)
        # below the panel: inside, it covered data points
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.22))
    fig.suptitle(f"orthocontact identify: {d.folder.name}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def summary_text(res) -> str:
    j = res.as_json()
    lines = []
    for n in reported_names(j):
        e = j[n]
        if "value" in e:
            lines.append(f"{n:>9} = {e['value']:.6g} ± {e['stderr']:.2g}  (95%: {e['ci95'][0]:.6g} .. {e['ci95'][1]:.6g})")
        else:
            lines.append(f"{n:>9}: not identifiable: {e['reason']}")
    if j["max_rule"]:
        lines.append(f"maximum rule: l1/l2 = {j['max_rule']['l1_l2_ratio']:.4f}"
                     + (f", eps1/eps2 = {j['max_rule']['eps_ratio']:.4f}" if "eps_ratio" in j["max_rule"] else ""))
    if j["eq40"]:
        lines.append(f"eq. (40) least squares: l1/l2 = {j['eq40']['l1_l2_ratio']:.4f}; "
                     f"eq. (41) closed form: l1/l2 = {j['eq41']['l1_l2_ratio']:.4f} (not the minimiser)")
    return "\n".join(lines)


def markdown_text(res) -> str:
    j = res.as_json()
    L = [f"# Identification: {res.data.folder.name}", "",
         f"Data: {j['data']['forces']} forces, {j['data']['angles']} angles, {j['data']['ramp']} ramp points. "
         f"Rule {j['assumptions']['rule']}, alpha = angle {j['assumptions']['alpha_offset_deg']:+g}°, "
         f"beta = angle {j['assumptions']['beta_offset_deg']:+g}°.", "",
         "| parameter | value | std. error | 95% interval |", "|---|---|---|---|"]
    for n in reported_names(j):
        e = j[n]
        if "value" in e:
            L.append(f"| {n} | {e['value']:.6g} | {e['stderr']:.3g} | {e['ci95'][0]:.6g} … {e['ci95'][1]:.6g} |")
        else:
            L.append(f"| {n} | not identifiable | – | {e['reason']} |")
    L.append("")
    if j["eq1"]:
        L.append(f"- eq. (1) from the forces at the friction axes: μ1 = {j['eq1']['mu1']:.4f}, μ2 = {j['eq1']['mu2']:.4f}")
    if j["max_rule"]:
        mr = j["max_rule"]
        L.append(f"- maximum rule (eq. 29, 37–39): φ_ext = {mr['phi_ext_deg']:.3f}° → l1/l2 = {mr['l1_l2_ratio']:.4f}"
                 + (f", ε1/ε2 = {mr['eps_ratio']:.4f}" if "eps_ratio" in mr else ""))
    if j["eq40"]:
        L.append(f"- eq. (40) by IPOPT: l1/l2 = {j['eq40']['l1_l2_ratio']:.4f} (objective {j['eq40']['objective']:.3e}); "
                 f"the paper's eq. (41): l1/l2 = {j['eq41']['l1_l2_ratio']:.4f} (objective {j['eq41']['objective']:.3e}) — not the minimiser")
    L.append("- noise estimated from the residuals: " + ", ".join(
        f"{k} {v:.3g}" for k, v in j["noise_estimate"].items() if not isinstance(v, dict)))
    v = j["validation_fmu"]
    if v and "skipped" not in v:
        parts = [f"{k} rms {v[k]['rms']:.3g}" for k in ("forces_N", "angles_deg", "ramp_N") if k in v]
        L.append(f"- validation with the FMU in the rig harness ({v['rig_mode']}): " + ", ".join(parts))
    L += ["", "![data and fit](fit.png)", ""]
    return "\n".join(L)


def reduction_markdown(j: dict) -> str:
    """identified.md's lines on the runs (raw recordings): the noise model's
    two parts per data group, and what the reduction left out or flagged."""
    tau = lambda t: (", ".join(f"{t_:.3g} at {v} m/s" for v, t_ in t.items()) if isinstance(t, dict)
                     else f"{t:.3g}")
    r = j["reduction"]
    return "\n".join([
        "## Runs", "",
        "- run-to-run scatter (between runs) / within-run error (rms): " + "; ".join(
            f"{k} {tau(m['between_runs'])} / {m['within_run_rms']:.2g}" for k, m in j["noise_model"].items()),
        f"- runs: {r['runs']['slide']} slide, {r['runs']['carriage']} carriage, {r['runs']['ramp']} ramp; "
        f"left out: {', '.join(r['left_out']) or 'none'}; flagged: "
        f"{', '.join(f'{k} ({chr(32).join(v)})' for k, v in r['flagged'].items()) or 'none'}",
        "- the reduction per run: reduction.csv; the paths per mat angle: "
        + ", ".join(f"![{f}]({f})" for f in r["figures"]), ""])
