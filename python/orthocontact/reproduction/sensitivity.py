"""How the rig's unmeasured assumptions move the experiment's numbers.

The paper assumes a frictionless Teflon strip between carriage and block and
never measures it, and it calibrates on a peak angle "measured for the
velocity 12.5 cm/s" while stating that all experiments ran at 24.4 cm/s.  For
a mat scenario (the aged mat) this module computes

* the peak |phi| [deg] against the strip's Coulomb friction mu_strip at both
  velocities: from the steady closed form (closed_forms.
  steady_tan_phi_with_strip_array) and from the rig itself over the
  scenario's travel (the compiled master, on whole degrees about the closed
  form's peak);
* the eps1/eps2 that the paper's calibration would return from its measured
  peak (11.5 deg) if the strip had that friction: the identified ratio is
  conditional on it;
* for a viscous strip c_strip [N s/m] (force c_strip * lateral velocity): the
  ratio calibrated on 11.5 deg at 0.125 m/s, and the peak that ratio then
  gives at 0.244 m/s, i.e. how far the two velocities drift apart.  The law
  is rate-independent: only such a rig term makes the angle depend on speed.

Its files and figures (write_outputs) and its section of the reproduction
report (report_lines) are here too."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .. import closed_forms as cf
from ..errors import InputError
from ..experiment import Scenario, kind_of
from ..rig import check_runs, warning_line

MU_STRIPS = (0.0, 0.025, 0.05, 0.075, 0.1, 0.15, 0.2)


VELOCITIES = (0.125, 0.244)          # m/s: the calibration's and the stated one


C_STRIPS = (0.0, 5.0, 10.0, 20.0, 40.0)


CALIBRATION_VELOCITY = 0.125


RIG_STEP_S = 4e-3  # the implicit rules' angle does not depend on the step (docs/benchmarks.md)


GRID = np.arange(0.0, 90.0 + 1e-9, 0.25)


RIG_SPAN_DEG = 3  # the rig's angles: whole degrees within this of the closed form's peak


def phi_closed_deg(sc: Scenario, angles_deg, mu_strip=0.0, c_strip=0.0, velocity=None,
                   eps_ratio=None) -> np.ndarray:
    """Steady phi [deg, counterclockwise] at the scenario's angles with the
    strip terms, optionally with another eps1/eps2."""
    law = sc.law if eps_ratio is None else sc.law.replace(eps1=eps_ratio * sc.law.eps2)
    alpha, beta = sc.geometry.axes(np.asarray(angles_deg, dtype=float))
    v = sc.rig.velocity_m_s if velocity is None else velocity
    t = cf.of_law(cf.steady_tan_phi_with_strip_array, law, alpha, beta, mu_strip, c_strip, v,
                  sc.rig.normal_force)
    return np.degrees(np.arctan(t))


def peak_closed(sc: Scenario, **kw) -> tuple[float, float]:
    """(phi [deg], angle [deg]) where |phi| is largest: a 0.25 deg grid and a
    parabola through the three points about the largest."""
    phi = phi_closed_deg(sc, GRID, **kw)
    k = int(np.argmax(np.abs(phi)))
    if 0 < k < len(GRID) - 1:
        y0, y1, y2 = np.abs(phi[k - 1:k + 2])
        den = y0 - 2 * y1 + y2
        if den < 0:
            u = 0.5 * (y0 - y2) / den
            a = GRID[k] + u * (GRID[1] - GRID[0])
            return float(np.copysign(y1 - 0.25 * (y0 - y2) * u, phi[k])), float(a)
    return float(phi[k]), float(GRID[k])


def ratio_for_peak(sc: Scenario, target_deg: float, **kw) -> float | None:
    """The eps1/eps2 whose peak |phi| is target_deg with these rig terms (on
    the scenario's side of the isotropic ratio mu2/mu1), or None if no
    ratio reaches it.  Regula falsi (Illinois) in log(ratio)."""
    iso = sc.law.mu2 / sc.law.mu1
    side = -1.0 if sc.law.eps1 / sc.law.eps2 < iso else 1.0

    def f(x):  # x = log(ratio / iso) * side >= 0
        return abs(peak_closed(sc, eps_ratio=iso * math.exp(side * x), **kw)[0]) - target_deg

    a, fa = 0.0, -target_deg
    b = 0.5
    fb = f(b)
    while fb < 0:
        a, fa = b, fb
        b *= 2
        if b > 8:  # the ratio 3000x away from isotropy: out of reach
            return None
        fb = f(b)
    side_kept = 0
    for _ in range(60):
        x = b - fb * (b - a) / (fb - fa)
        fx = f(x)
        if abs(fx) < 1e-10:
            a = b = x
            break
        if (fx < 0) == (fa < 0):
            a, fa = x, fx
            if side_kept == -1:
                fb *= 0.5
            side_kept = -1
        else:
            b, fb = x, fx
            if side_kept == 1:
                fa *= 0.5
            side_kept = 1
        if abs(b - a) < 1e-13:
            break
    x = 0.5 * (a + b)
    return iso * math.exp(side * x) if abs(f(x)) < 1e-6 else None


@dataclass
class Sensitivity:
    scenario: str
    measured_peak_deg: float
    strip_rows: list      # mu_strip, velocity, peak (closed form, rig), ratio for the measured peak
    viscous_rows: list    # c_strip, ratio calibrated at 0.125 m/s, peaks at both velocities
    rig_step_s: float
    seconds: float
    checks: dict          # rig_checks of the rig's runs: counts and the warning line


@dataclass(frozen=True)
class Plan:
    """The rig runs of a sensitivity study, known before any runs: the
    viscous rows' calibrated ratios, the (kind, mu_strip, velocity, c_strip,
    ratio) combinations, each one's (first task, angles [deg]) and closed-form
    peak, and the tasks (params, rig) in order."""
    measured: float
    viscous: list
    combos: list
    spans: list
    closed: list
    tasks: list


def takes(sc: Scenario) -> bool:
    """Whether the study takes the scenario: a sweep of mat angles on the
    carriage rig (experiment.kinds) with the experiment's geometry."""
    return sc.closed_form == "mat" and kind_of(sc).mat_angles


def plan(sc: Scenario) -> Plan:
    """What run() will run for a mat scenario (closed forms only, no rig
    run); InputError for another scenario."""
    if not takes(sc):
        raise InputError(f"{sc.path}: geometry.closed_form: expected \"mat\" (the experiment's "
                         "geometry) for a sensitivity study")
    measured = abs(sc.paper.get("extremum_phi_deg", sc.paper.get("phi_max_deg", 11.5)))
    lo = sc.sweep["start_deg"]  # not sweep_angles(): a fine sweep's list is large and unused here
    hi = lo + (sc.angle_count() - 1) * sc.sweep["step_deg"]
    rig0 = replace(sc.rig, step_s=RIG_STEP_S)
    viscous = []
    for c in C_STRIPS:
        r = ratio_for_peak(sc, measured, c_strip=c, velocity=CALIBRATION_VELOCITY)
        viscous.append({"c_strip_N_s_m": c, "eps_ratio": r})
    combos = [("strip", mu, v, 0.0, None) for mu in MU_STRIPS for v in VELOCITIES]
    combos += [("viscous", 0.0, v, row["c_strip_N_s_m"], row["eps_ratio"]) for row in viscous
               for v in VELOCITIES if row["eps_ratio"] is not None]
    # The rig runs on whole degrees about the closed form's peak: the peak of
    # the curve it settles to, at a tenth of the cost of the whole sweep.
    tasks, spans, closed = [], [], []
    for _, mu, v, c, ratio in combos:
        s = sc if ratio is None else replace(sc, law=sc.law.replace(eps1=ratio * sc.law.eps2))
        rig = replace(rig0, mu_strip=mu, c_strip=c, velocity_m_s=v)
        cl = peak_closed(sc, mu_strip=mu, c_strip=c, velocity=v, eps_ratio=ratio)
        angles = [a for a in (round(cl[1]) + k for k in range(-RIG_SPAN_DEG, RIG_SPAN_DEG + 1))
                  if lo <= a <= hi]
        spans.append((len(tasks), angles))
        closed.append(cl)
        tasks += [(s.params_at(a), rig) for a in angles]
    return Plan(measured, viscous, combos, spans, closed, tasks)


def work(p: Plan):
    """The plan's rig runs for the work estimate (runs.size.Work): how
    many at each velocity, and each one's steps (the scenario's travel at
    RIG_STEP_S)."""
    from ..runs import Work, steps_per_run
    w = Work()
    for v in VELOCITIES:
        rigs = [r for _, r in p.tasks if r.velocity_m_s == v]
        if rigs:
            w = w.plus(f"at {v:g} m/s", len(rigs), steps_per_run(rigs[0].travel_m, v, rigs[0].step_s))
    return w


def run(sc: Scenario, workers: int = 1, fmu_path=None, master: str = "auto", progress: bool = True,
        dask=None, planned: Plan | None = None) -> Sensitivity:
    """The tables above for a mat scenario; the rig runs over the scenario's
    angles at a 4 ms step (those of `planned`, plan(sc) if not given)."""
    import time

    from ..runs import run_many
    t0 = time.time()
    pl = planned or plan(sc)
    measured, combos, spans, closed, tasks = pl.measured, pl.combos, pl.spans, pl.closed, pl.tasks
    viscous = [dict(row) for row in pl.viscous]   # filled below; the plan stays as planned
    res = run_many(tasks, workers, fmu_path or sc.fmu, f"sensitivity {sc.name}", progress, master, dask)
    checks = check_runs(tasks, res)
    line = warning_line(f"sensitivity {sc.name}", [math.degrees(p.beta) - sc.geometry.beta_offset_deg
                                                   for p, _ in tasks],
                        checks, [r.phi_deg for r in res], tasks)
    strip_rows = []
    peaks = {}
    for (kind, mu, v, c, _ratio), (start, angles), cl in zip(combos, spans, closed):
        phis = np.array([r[0] for r in res[start:start + len(angles)]])
        k = int(np.nanargmax(np.abs(phis)))
        rig_peak = (float(phis[k]), float(angles[k]))
        peaks[(kind, mu, v, c)] = (cl, rig_peak)
        if kind == "strip":
            strip_rows.append({"mu_strip": mu, "velocity_m_s": v, "peak_phi_closed_deg": cl[0],
                               "peak_angle_closed_deg": cl[1], "peak_phi_rig_deg": rig_peak[0],
                               "peak_angle_rig_deg": rig_peak[1]})
    ratios = {mu: ratio_for_peak(sc, measured, mu_strip=mu) for mu in MU_STRIPS}
    for row in strip_rows:
        row["eps_ratio_for_measured_peak"] = ratios[row["mu_strip"]]
    for row in viscous:
        for v in VELOCITIES:
            key = ("viscous", 0.0, v, row["c_strip_N_s_m"])
            if key in peaks:
                (cl, rig_peak) = peaks[key]
                row[f"peak_phi_closed_deg_at_{v:g}"] = cl[0]
                row[f"peak_phi_rig_deg_at_{v:g}"] = rig_peak[0]
    return Sensitivity(sc.name, measured, strip_rows, viscous, RIG_STEP_S, time.time() - t0,
                       {"runs": len(tasks), "not_steady": int((~checks.ok).sum()), "warning": line})


def write_outputs(res: Sensitivity, sc: Scenario, out, draw=None) -> dict:
    """sensitivity_strip.csv, sensitivity_velocity.csv, sensitivity.json and
    two figures into out."""
    from ..output import write_csv, write_json
    keys = ["mu_strip", "velocity_m_s", "peak_phi_closed_deg", "peak_angle_closed_deg",
            "peak_phi_rig_deg", "peak_angle_rig_deg", "eps_ratio_for_measured_peak"]
    write_csv(out / "sensitivity_strip.csv", keys,
              [tuple(float("nan") if r[k] is None else r[k] for k in keys) for r in res.strip_rows])
    vkeys = ["c_strip_N_s_m", "eps_ratio"] + [f"peak_phi_{w}_deg_at_{v:g}" for v in VELOCITIES
                                              for w in ("closed", "rig")]
    write_csv(out / "sensitivity_velocity.csv", vkeys,
              [tuple(float("nan") if r.get(k) is None else r.get(k) for k in vkeys)
               for r in res.viscous_rows])
    summary = {"scenario": res.scenario, "kind": "sensitivity", "measured_peak_deg": res.measured_peak_deg,
               "calibration_velocity_m_s": CALIBRATION_VELOCITY, "rig_step_s": res.rig_step_s,
               "strip": res.strip_rows, "viscous": res.viscous_rows, "seconds": round(res.seconds, 3),
               "checks": res.checks,
               "angle_convention": "counterclockwise (ours)",
               "note": "the paper prints no peak angle at 0.244 m/s (Fig. 4 is a plot), so c_strip is "
                       "not determined by it: the velocity table shows what each c_strip implies"}
    write_json(out / "sensitivity.json", summary)
    (draw or (lambda fn, *a: fn(*a)))(_figures, res, sc, out)
    return summary


def _figures(res: Sensitivity, sc: Scenario, out) -> None:
    from ..output import finish, pyplot, save
    plt = pyplot()
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 4.5))
    for i, v in enumerate(VELOCITIES):
        rows = [r for r in res.strip_rows if r["velocity_m_s"] == v]
        ax.plot([r["mu_strip"] for r in rows], [abs(r["peak_phi_rig_deg"]) for r in rows],
                "o" if i == 0 else "x", color=f"C{i}", label=f"rig, {v:g} m/s, 0.5 m travel")
    rows = [r for r in res.strip_rows if r["velocity_m_s"] == VELOCITIES[0]]
    mu = [r["mu_strip"] for r in rows]
    ax.plot(mu, [abs(r["peak_phi_closed_deg"]) for r in rows], "-", color="0.3",
            label="steady closed form")
    ax.axhline(res.measured_peak_deg, color="C3", ls=":", label=f"measured {res.measured_peak_deg:g}°")
    ax.set_xlabel("Teflon strip friction μ_strip")
    ax.set_ylabel("peak |φ| [deg]")
    ax.set_title("peak angle with the paper's ε1/ε2", fontsize=10, y=1.0)
    ax.legend(fontsize=8)
    ax2.plot(mu, [np.nan if r["eps_ratio_for_measured_peak"] is None else r["eps_ratio_for_measured_peak"]
                  for r in rows], "s-", color="C2", ms=4)
    ax2.set_xlabel("Teflon strip friction μ_strip")
    ax2.set_ylabel(f"ε1/ε2 calibrated on the measured {res.measured_peak_deg:g}°")
    ax2.set_title("what the calibration would identify", fontsize=10, y=1.0)
    for a in (ax, ax2):
        a.grid(alpha=0.3)
    fig.suptitle(f"{sc.name}: the strip's friction", fontsize=10)
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.12, top=0.88, wspace=0.28)
    save(fig, out / "sensitivity_strip.png")

    fig, ax = plt.subplots(figsize=(8, 4.5))
    c = [r["c_strip_N_s_m"] for r in res.viscous_rows]
    for i, v in enumerate(VELOCITIES):
        ax.plot(c, [abs(r.get(f"peak_phi_rig_deg_at_{v:g}", np.nan)) for r in res.viscous_rows], "o",
                color=f"C{i}", label=f"rig, {v:g} m/s")
        ax.plot(c, [abs(r.get(f"peak_phi_closed_deg_at_{v:g}", np.nan)) for r in res.viscous_rows], "-",
                color=f"C{i}", label=f"closed form, {v:g} m/s")
    ax.set_xlabel("strip's lateral viscosity c_strip [N s/m] (ε1/ε2 calibrated at 0.125 m/s each time)")
    ax.set_ylabel("peak |φ| [deg]")
    finish(fig, ax, out / "sensitivity_velocity.png", f"{sc.name}: velocity through a viscous strip",
            outside=True)


def report_lines(sens: dict) -> list[str]:
    """The study's section of the reproduction report (report.md), from
    its summary (write_outputs)."""
    m = sens["measured_peak_deg"]
    last_v = max(r["velocity_m_s"] for r in sens["strip"])
    lines = ["## The rig's assumptions", "",
             f"The paper assumes a frictionless Teflon strip between carriage and block and measures "
             f"neither its friction μ_strip nor any viscous resistance c_strip. Peak |φ| of "
             f"{sens['scenario']} (rig over the 0.5 m travel, {sens['rig_step_s'] * 1e3:g} ms steps; "
             f"steady closed form beside), and the ε1/ε2 the paper's calibration would return from "
             f"the measured {m:g}° if the strip had that friction:", "",
             "| μ_strip | peak \\|φ\\| rig [deg] | closed form [deg] | ε1/ε2 for the measured peak |",
             "|---|---|---|---|"]
    for r in sens["strip"]:
        if r["velocity_m_s"] == last_v:
            ratio = r["eps_ratio_for_measured_peak"]
            lines.append(f"| {r['mu_strip']:g} | {abs(r['peak_phi_rig_deg']):.2f} | "
                         f"{abs(r['peak_phi_closed_deg']):.2f} | "
                         + ("not reachable" if ratio is None else f"{ratio:.4f}") + " |")
    lines += ["", "The identified ratio is conditional on the strip: with μ_strip = 0.1 the same "
              "measurement means ε1/ε2 ≈ "
              f"{next(r['eps_ratio_for_measured_peak'] for r in sens['strip'] if r['mu_strip'] == 0.1):.3f} "
              "instead of 1.25. The law is rate-independent, so without a rate-dependent rig term "
              "the two velocities give the same angle; with a viscous strip (ε1/ε2 calibrated on "
              f"{m:g}° at {sens['calibration_velocity_m_s']:g} m/s each time):", "",
              "| c_strip [N s/m] | ε1/ε2 | peak \\|φ\\| at 0.125 m/s | at 0.244 m/s (rig) |",
              "|---|---|---|---|"]
    for r in sens["viscous"]:
        if r["eps_ratio"] is None:
            continue
        lines.append(f"| {r['c_strip_N_s_m']:g} | {r['eps_ratio']:.4f} | "
                     f"{abs(r['peak_phi_rig_deg_at_0.125']):.2f} | "
                     f"{abs(r['peak_phi_rig_deg_at_0.244']):.2f} |")
    lines += ["", "The paper prints no peak angle at 0.244 m/s (its Fig. 4 is a plot), so it does "
              "not determine c_strip. Figures: [strip friction](sensitivity/sensitivity_strip.png), "
              "[velocity](sensitivity/sensitivity_velocity.png); data: "
              "[sensitivity.json](sensitivity/sensitivity.json).", ""]
    return lines
