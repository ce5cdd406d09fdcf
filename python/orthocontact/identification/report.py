"""What identification writes for people: the fit figure, identified.md and
the terminal summary, each from a job.Identification `res` (job imports
this module, not the reverse)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import closed_forms as cf
from ..experiment import RigSetup
from .identified import UNITS, Estimate, ReductionSummary, reported_names

# The one name of the angle the mat (the law's axes) is turned by: every figure, message and help text.
SWEPT_ANGLE = "mat angle"


@dataclass(frozen=True)
class FittedModel:
    """The model the joint fit fitted (estimators._joint_fit_once), for
    drawing: with the strip's Coulomb friction and viscosity whenever the fit
    had them, each steady state from closed_forms at the carriage velocity
    [m/s] it is drawn for; F_int [N] as fitted or from rig.toml."""
    rig: RigSetup
    values: dict

    @property
    def f_int(self) -> float:
        return self.values.get("f_int", self.rig.f_int_N)

    @property
    def c_strip(self) -> float:
        return self.values.get("c_strip", self.rig.c_strip or 0.0)

    @property
    def with_strip(self) -> bool:
        return "eps_ratio" in self.values and (self.rig.mu_strip > 0 or self.c_strip > 0)

    def _strip_state(self, angles_deg, velocity):
        v, rig = self.values, self.rig
        al, be = rig.axes(np.asarray(angles_deg, dtype=float))
        # eps enters the direction of sliding only through eps1/eps2
        return cf.steady_strip_state_array(v["mu1"], v["mu2"], v["eps_ratio"], 1.0, al, be, rig.rule,
                                           rig.mu_strip, self.c_strip, velocity, rig.normal_force)

    def forces(self, angles_deg, velocity) -> np.ndarray | None:
        """Driving force [N] of steady sliding at the mat angles [deg]."""
        v, rig = self.values, self.rig
        if "mu1" not in v:
            return None
        if self.with_strip:
            return self.f_int + self._strip_state(angles_deg, velocity)[1]
        _, be = rig.axes(np.asarray(angles_deg, dtype=float))
        return cf.steady_drive_force(v["mu1"], v["mu2"], be, self.f_int, rig.mass_kg, rig.g)

    def angles(self, angles_deg, velocity) -> np.ndarray | None:
        """Steady trajectory angle phi [deg] at the mat angles [deg]."""
        v, rig = self.values, self.rig
        al, be = rig.axes(np.asarray(angles_deg, dtype=float))
        if self.with_strip:
            tp = self._strip_state(angles_deg, velocity)[0]
        elif "eps_ratio" in v and "mu1" in v:
            tp = cf.steady_tan_phi(v["mu1"], v["mu2"], v["eps_ratio"], 1.0, al, be, rig.rule)
        elif "l1_l2_ratio" in v:
            tp = cf.eq25_tan_phi(v["l1_l2_ratio"], 1.0, al)
        else:
            return None
        return np.degrees(np.arctan(tp))

    def label(self, panel: str) -> str:
        """The fitted values a panel's curve shows (legend text)."""
        v = self.values
        if panel == "forces":
            return f": μ1={v['mu1']:.4f}, μ2={v['mu2']:.4f}" if "mu1" in v else ""
        if "eps_ratio" in v:
            return f": ε1/ε2={v['eps_ratio']:.4f}"
        return f": l1/l2={v['l1_l2_ratio']:.4f}" if "l1_l2_ratio" in v else ""

    def describe(self) -> str:
        """The fitted model's terms, one phrase."""
        if not self.with_strip:
            return "the fitted model: no strip"
        return (f"the fitted model: strip μ={self.rig.mu_strip:g}, "
                f"c_strip={self.c_strip:.3g} N s/m" + (" (fitted)" if "c_strip" in self.values else ""))


def fit_figure(res, path: Path):
    """fit.png: the data beside the model that was fitted (with the strip's
    friction and viscosity and at each velocity measured, as the joint fit
    saw them), the paper's approximations (maximum rule, eq. 41) marked as
    such.  Angles in deg, forces in N, travel in mm."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    d, v, rig = res.data, res.fit.values, res.data.rig
    panels = [p for p, have in (("forces", d.forces is not None), ("angles", d.angles is not None),
                                ("ramp", d.ramp is not None)) if have]
    # constrained layout keeps the suptitle clear of the axes' labels
    fig, axes = plt.subplots(1, len(panels), figsize=(5 * len(panels), 4.6), squeeze=False,
                             layout="constrained")
    grid = np.linspace(0, 90, 181)
    model = FittedModel(rig, v)
    for ax, p in zip(axes[0], panels):
        if p in ("forces", "angles"):
            data_and_model(ax, p, d, model, grid)
        if p == "forces":
            ax.set_ylabel("driving force [N]")
        elif p == "angles":
            paper_approximations(ax, res, grid)
            ax.set_ylabel("trajectory angle φ [deg]\n(counterclockwise)")
        else:
            ramp_panel(ax, d, v, rig, model)
        if p != "ramp":
            ax.set_xlabel(f"{SWEPT_ANGLE} [deg]")
        ax.grid(alpha=0.3)
        # below the panel: inside, it covered data points
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.2))
    fig.suptitle(f"orthocontact identify: {d.folder.name} ({model.describe()})", fontsize=10)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def data_and_model(ax, p: str, d, model: FittedModel, grid) -> None:
    """The forces' or the angles' panel: the data and the fitted model's
    curve at each velocity measured."""
    pts = d.forces if p == "forces" else d.angles
    vel = d.velocities_of_forces() if p == "forces" else d.velocities_of_angles()
    speeds = np.unique(np.round(vel, 9))
    for k, u in enumerate(speeds):
        at = np.isclose(vel, u, rtol=0, atol=1e-9)
        colour = f"C{k}"
        tag = f" at {u:g} m/s" if len(speeds) > 1 else ""
        ax.plot(pts[at, 0], pts[at, 1], "o", ms=4, color=colour, alpha=0.7, label="data" + tag)
        curve = model.forces(grid, u) if p == "forces" else model.angles(grid, u)
        if curve is not None:
            ax.plot(grid, curve, "-", color=colour, label=f"fitted model{tag}{model.label(p)}")


def paper_approximations(ax, res, grid) -> None:
    """On the angles' panel, the paper's steady angle (eq. (10)/(23): no
    strip, no velocity) at the eps1/eps2 of the maximum rule and of eq. (41)."""
    v, rig = res.fit.values, res.data.rig

    def paper_phi(eps_ratio):
        al, be = rig.axes(grid)
        return np.degrees(np.arctan(cf.steady_tan_phi(v["mu1"], v["mu2"], eps_ratio, 1.0, al, be, rig.rule)))
    for key, style, lab in (("max_rule", ":", "the paper's approximation (maximum rule)"),
                            ("eq41", "--", "the paper's eq. (41)")):
        src = res.max_rule if key == "max_rule" else (res.eq40 or {}).get("eq41")
        if src and "eps_ratio" in src and "mu1" in v and math.isfinite(src["eps_ratio"]):
            ax.plot(grid, paper_phi(src["eps_ratio"]), style, color="0.35" if key == "max_rule"
                    else "C3", label=f"{lab}: ε1/ε2={src['eps_ratio']:.4f}")


def ramp_panel(ax, d, v: dict, rig, model: FittedModel) -> None:
    """The ramp's panel: its data and the fitted stick line up to sliding."""
    ax.plot(d.ramp[:, 0] * 1e3, d.ramp[:, 1], "o", ms=3, label="data")
    if "eps2" in v:
        al, be = rig.axes(rig.ramp_angle_deg)
        k = cf.stick_stiffness_x1(v.get("eps_ratio", 1.0) * v["eps2"], v["eps2"], al)
        top = cf.steady_drive_force(v["mu1"], v["mu2"], be, 0.0, rig.mass_kg, rig.g) \
            if "mu1" in v else float(np.max(d.ramp[:, 1]) - model.f_int)
        xs = np.linspace(0, d.ramp[:, 0].max(), 200)
        ax.plot(xs * 1e3, model.f_int + np.minimum(k * xs, top), "-",
                label=f"fitted model: k={k:.4g} N/m")
    ax.set_xlabel("travel x1 [mm]")
    ax.set_ylabel("driving force [N]")


def unit_of(name: str) -> str:
    """The unit of a reported estimate, bracketed: [-], [N/m], [N s/m], [N]."""
    return f"[{UNITS[name]}]"


def summary_text(res) -> str:
    """The terminal summary: each estimate with its unit, standard error and
    95 % interval; the paper's formulas beside them."""
    f = res.identified_file()
    lines = []
    for n in reported_names(f.estimates):
        e = f.estimates[n]
        if isinstance(e, Estimate):
            u = unit_of(n)
            lines.append(f"{n:>9} = {e.value:.6g} ± {e.stderr:.2g} {u}  "
                         f"(95%: {e.ci95[0]:.6g} .. {e.ci95[1]:.6g} {u})")
        else:
            lines.append(f"{n:>9}: not identifiable: {e.reason}")
    if f.max_rule:
        mr = f.max_rule
        lines.append(f"maximum rule (the paper's approximation): phi_ext = {mr['phi_ext_deg']:.3f} deg at "
                     f"{SWEPT_ANGLE} {mr['at_alpha_deg']:g} deg -> l1/l2 = {mr['l1_l2_ratio']:.4f} [-]"
                     + (f", eps1/eps2 = {mr['eps_ratio']:.4f} [-]" if "eps_ratio" in mr else ""))
    if f.eq40:
        lines.append(f"eq. (40) least squares: l1/l2 = {f.eq40['l1_l2_ratio']:.4f} [-]; "
                     f"eq. (41) closed form: l1/l2 = {f.eq41['l1_l2_ratio']:.4f} [-] (not the minimiser)")
    return "\n".join(lines)


def markdown_text(res) -> str:
    """identified.md (its runs' section: reduction_markdown)."""
    f = res.identified_file()
    a = f.assumptions
    L = [f"# Identification: {res.data.folder.name}", "",
         f"Data: {f.data.forces} forces, {f.data.angles} angles, {f.data.ramp} ramp points. "
         f"Rule {a.rule}, alpha = angle {a.alpha_offset_deg:+g}°, "
         f"beta = angle {a.beta_offset_deg:+g}°.", "",
         "| parameter | unit | value | std. error | 95% interval |", "|---|---|---|---|---|"]
    for n in reported_names(f.estimates):
        e = f.estimates[n]
        if isinstance(e, Estimate):
            L.append(f"| {n} | {UNITS[n]} | {e.value:.6g} | {e.stderr:.3g} | "
                     f"{e.ci95[0]:.6g} … {e.ci95[1]:.6g} |")
        else:
            L.append(f"| {n} | {UNITS[n]} | not identifiable | – | – | {e.reason} |")
    L.append("")
    if f.eq1:
        L.append(f"- eq. (1) from the forces at the friction axes: μ1 = {f.eq1['mu1']:.4f} [-], "
                 f"μ2 = {f.eq1['mu2']:.4f} [-]")
    if f.max_rule:
        mr = f.max_rule
        L.append("- maximum rule (eq. 29, 37–39; the paper's approximation): "
                 f"φ_ext = {mr['phi_ext_deg']:.3f}° "
                 f"at {SWEPT_ANGLE} {mr['at_alpha_deg']:g}° → l1/l2 = {mr['l1_l2_ratio']:.4f} [-]"
                 + (f", ε1/ε2 = {mr['eps_ratio']:.4f} [-]" if "eps_ratio" in mr else ""))
    if f.eq40:
        L.append(f"- eq. (40) by IPOPT: l1/l2 = {f.eq40['l1_l2_ratio']:.4f} [-] (objective "
                 f"{f.eq40['objective']:.3e}); the paper's eq. (41): l1/l2 = {f.eq41['l1_l2_ratio']:.4f} [-] "
                 f"(objective {f.eq41['objective']:.3e}) — not the minimiser")
    L.append("- noise estimated from the residuals: " + ", ".join(
        f"{k} {v:.3g}" for k, v in f.noise_estimate.items() if not isinstance(v, dict)))
    v = f.validation_fmu
    if v and "skipped" not in v:
        parts = [f"{k} rms {v[k]['rms']:.3g}" for k in ("forces_N", "angles_deg", "ramp_N") if k in v]
        L.append(f"- validation with the FMU in the rig harness ({v['rig_mode']}): " + ", ".join(parts))
    L += ["", "![data and fit](fit.png)", ""]
    return "\n".join(L)


def reduction_markdown(noise_model: dict, r: ReductionSummary) -> str:
    """identified.md's lines on the runs (raw recordings): the noise model's
    two parts per data group (identified.json's noise_model), and what the
    reduction left out or flagged."""
    def tau(t):
        return (", ".join(f"{t_:.3g} at {v} m/s" for v, t_ in t.items()) if isinstance(t, dict)
                else f"{t:.3g}")
    return "\n".join([
        "## Runs", "",
        "- run-to-run scatter (between runs) / within-run error (rms): " + "; ".join(
            f"{k} {tau(m['between_runs'])} / {m['within_run_rms']:.2g}" for k, m in noise_model.items()),
        f"- runs: {r.runs['slide']} slide, {r.runs['carriage']} carriage, {r.runs['ramp']} ramp; "
        f"left out: {', '.join(r.left_out) or 'none'}; flagged: "
        f"{', '.join(f'{k} ({chr(32).join(v)})' for k, v in r.flagged.items()) or 'none'}",
        "- the reduction per run: reduction.csv; the paths per mat angle: "
        + ", ".join(f"![{f}]({f})" for f in r.figures), ""])
