"""Calibrated FMUs out (`orthocontact export`): both contact FMUs with the
identification's estimates as their parameters' start values, in the model
description and in the binary's resources (fmu.start_values), so that an
importer that sets nothing runs the calibrated model; the estimates, their
95 % intervals, the data's digests (each file the identification read in
documentation/calibration.html, their overall digest in the description), the
date and the package version; beside them an SSV
parameter file and an SSP of the rig at one angle built on the calibrated
FMU (experiment.ssp), whose FMUs carry the values too.

The FMUs' axis angles alpha, beta are those of the chosen angle in the
measurement's geometry (alpha = angle + alpha offset, beta = angle + beta
offset), so that the calibrated FMU alone, run in the rig, predicts the
trajectory angle at that mat angle."""
from __future__ import annotations

import dataclasses
import html
import math
from datetime import datetime, timezone
from pathlib import Path

from .. import closed_forms as cf
from .. import plausibility
from ..errors import InputError
from ..experiment import (
    RigSetup,
    Scenario,
    load_rig_toml,
    parameter_values_file,
    require_mat_angles,
    write_ssp,
)
from ..experiment import load_scenario as load
from ..fmu import MODEL_IDENTIFIER, ContactParams, find_fmu, write_with_start_values
from .identified import UNITS, Estimate, IdentifiedFile, NotIdentified
from .identified_file import read_identified

ESTIMATED = ("mu1", "mu2", "eps_ratio", "eps1", "eps2")


@dataclasses.dataclass(frozen=True)
class Calibration:
    """What identified.json says, checked: the law (alpha = beta = 0),
    the 95 % intervals of what was identified, the rig of the data."""
    path: Path
    law: ContactParams
    intervals: dict          # name -> (lo, hi) of each identified parameter
    eps2_identified: bool
    rig: RigSetup            # rig.toml of the data, with the identification's rule and offsets
    c_strip: float           # N s/m, as the identification used it
    data_folder: Path
    digest: str              # SHA-256 over the data files' listing (measurements.data_digest)
    data_files: dict = dataclasses.field(default_factory=dict)   # path under data_folder -> SHA-256
    f_int_N: float = 0.0     # F_int [N] as the identification used it: estimated or rig.toml's
    fit_problems: tuple = ()  # why the fit's estimates cannot be trusted (identified.FitRecord.problems)


def _value(f: IdentifiedFile, name: str) -> float:
    e = f.estimates.get(name)
    if isinstance(e, Estimate):
        return e.value
    why = f" ({name} was not identified: {e.reason})" if isinstance(e, NotIdentified) else ""
    raise InputError(f"{f.path}: {name}.value: expected a finite number > 0, got None{why}")


def load_calibration(path, force: bool = False) -> Calibration:
    """identified.json -> Calibration (read_identified, then calibration_of);
    InputError naming the file and the field (a value that cannot be right
    too, unless `force`: FORCE_OVERRIDE)."""
    return calibration_of(read_identified(path, force=force, override=FORCE_OVERRIDE))


def calibration_of(f: IdentifiedFile) -> Calibration:
    """The calibration an identification read back (read_identified: checked,
    its data found unchanged) gives: mu1, mu2 must be identified; eps1, eps2
    as identified, or eps_ratio with rig.toml's nominal eps2."""
    path, a = f.path, f.assumptions
    mu1, mu2 = _value(f, "mu1"), _value(f, "mu2")
    folder = f.provenance.folder
    rig = dataclasses.replace(load_rig_toml(folder / "rig.toml"), rule=a.rule,
                              alpha_offset_deg=a.alpha_offset_deg, beta_offset_deg=a.beta_offset_deg)
    eps2_identified = isinstance(f.estimates.get("eps2"), Estimate)
    eps2 = _value(f, "eps2") if eps2_identified else rig.eps2_nominal_N_m
    eps1 = _value(f, "eps1") if eps2_identified else _value(f, "eps_ratio") * eps2
    intervals = {n: f.estimates[n].ci95 for n in ESTIMATED if isinstance(f.estimates.get(n), Estimate)}
    c_strip = _value(f, "c_strip") if a.c_strip_N_s_m == "estimated" else a.c_strip_N_s_m
    f_int = _value(f, "f_int") if a.f_int_N == "estimated" else a.f_int_N
    try:
        law = ContactParams(mu1, mu2, eps1, eps2, rule=a.rule)
    except ValueError as e:
        raise InputError(f"{path}: {e}") from None
    return Calibration(path=path, law=law, intervals=intervals, eps2_identified=eps2_identified, rig=rig,
                       c_strip=float(c_strip), data_folder=folder, digest=f.provenance.digest,
                       data_files=f.provenance.files, f_int_N=float(f_int),
                       fit_problems=tuple(f.fit.problems()))


def contact_start_values(cal: Calibration, angle_deg: float) -> dict:
    """The contact FMU's parameters at the mat angle `angle_deg`."""
    try:
        p = cal.rig.params_at(cal.law, angle_deg)
    except ValueError as e:
        raise InputError(f"--angle {angle_deg:g}: {e}") from None
    return p.fmu_values()


def predicted_phi_deg(cal: Calibration, angle_deg: float, rig=None) -> float:
    """The identified model's steady trajectory angle [deg] at `angle_deg`
    in the rig (the data's unless given), strip terms included."""
    rig = rig or cal.rig.harness(c_strip=cal.c_strip)
    p = cal.rig.params_at(cal.law, angle_deg)
    t = cf.of_law(cf.steady_tan_phi_with_strip, p, p.alpha, p.beta, rig.mu_strip, rig.c_strip,
                  rig.velocity_m_s, rig.mass_kg * rig.g)
    return math.degrees(math.atan(t))


def rig_scenario(cal: Calibration, scenario=None) -> Scenario:
    """The calibrated law in a scenario: the given scenario file's rig, or the
    data's rig.toml (its velocity, travel and step; the CarriageBlock FMU
    integrates the block's lateral inertia whatever the rig's mode)."""
    law = cal.law
    offsets = dict(geometry=cal.rig.geometry)
    if scenario is not None:
        sc = load(scenario)
        require_mat_angles(sc, "an SSP", scenario)
        return dataclasses.replace(sc, name=f"calibrated_{sc.name}", law=law, fmu=None, **offsets)
    return Scenario(path=cal.path, name="calibrated",
                    title=f"Calibrated contact on the rig of {cal.data_folder}",
                    kind="sweep", description="", law=law, closed_form="mat",
                    rig=cal.rig.harness(c_strip=cal.c_strip), **offsets)


def _documentation(cal: Calibration, values: dict, angle_deg: float, version: str, date: str,
                   phi_deg: float) -> str:
    rows = []
    for n in ("mu1", "mu2", "eps1", "eps2"):
        ci = cal.intervals.get(n)
        interval = f"{ci[0]:.6g} .. {ci[1]:.6g}" if ci else "not identified"
        rows.append(f"<tr><td>{n}</td><td>{values[n]!r}</td><td>{UNITS[n]}</td><td>{interval}</td></tr>")
    if "eps_ratio" in cal.intervals:
        ci = cal.intervals["eps_ratio"]
        rows.append(f"<tr><td>eps1/eps2</td><td>{values['eps1'] / values['eps2']!r}</td>"
                    f"<td>{UNITS['eps_ratio']}</td>"
                    f"<td>{ci[0]:.6g} .. {ci[1]:.6g}</td></tr>")
    eps2 = ("eps2 was identified (from the stick branch of the pull)." if cal.eps2_identified else
            f"eps2 was <b>not</b> identified: the nominal eps2 = {cal.rig.eps2_nominal_N_m!r} N/m of the "
            f"data's rig.toml (eps2_nominal_N_m) is used and eps1 = eps1/eps2 &times; eps2. The trajectory "
            f"angle depends on the ratio only; forces before sliding depend on the absolute value.")
    e = html.escape
    return f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>OrthotropicContact: calibration</title></head>
<body>
<h1>Calibration</h1>
<p>The start values of this FMU's parameters are an identification's estimates: the FMU uses them
when an importer sets nothing (they are in <code>resources/start_values.txt</code> too).</p>
<table border="1"><tr><th>parameter</th><th>start value</th><th>unit</th><th>95 % interval</th></tr>
{chr(10).join(rows)}
</table>
<p>{eps2}</p>
<p>slidingRule = {values['slidingRule']} ({e(cal.law.rule)}), the rule the identification assumed.
alpha = {values['alpha']!r} rad, beta = {values['beta']!r} rad: the axes at the mat angle
{angle_deg:g} deg of the measurement's geometry (alpha = mat angle + {cal.rig.alpha_offset_deg:g} deg,
beta = mat angle + {cal.rig.beta_offset_deg:g} deg); set them for another mat angle.
The identified model predicts a steady trajectory angle of {phi_deg:.4f} deg (counterclockwise)
there on the data's rig (strip: mu_strip = {cal.rig.mu_strip:g}, c_strip = {cal.c_strip:g} N s/m).</p>
<h2>Provenance</h2>
<ul>
<li>identification: <code>{e(str(cal.path))}</code> (<code>orthocontact identify</code>)</li>
<li>data: <code>{e(str(cal.data_folder))}</code>, SHA-256 {cal.digest}
(of the listing <code>sha256sum</code> prints for the {len(cal.data_files)} files below in this order:
<code>cd DATA &amp;&amp; sha256sum FILE... | sha256sum</code>); every file the identification read,
with its SHA-256:
<table border="1"><tr><th>file</th><th>SHA-256</th></tr>
{chr(10).join(f"<tr><td><code>{e(n)}</code></td><td><code>{h}</code></td></tr>"
              for n, h in sorted(cal.data_files.items()))}
</table></li>
<li>intervals: 95 %, Student t with Welch-Satterthwaite degrees of freedom, Gauss-Newton covariance</li>
<li>exported {date} by orthocontact {e(version)}</li>
</ul>
</body></html>
"""


FORCE_OVERRIDE = "`orthocontact export --force` exports it anyway"


def check_angle(angle_deg: float):
    """InputError unless --angle [deg] is a finite number."""
    if not math.isfinite(angle_deg):
        raise InputError(f"--angle: expected a finite angle [deg], got {angle_deg!r}")


def plausible_calibration(cal: Calibration, sc: Scenario, angle_deg: float, scenario=None,
                          force: bool = False) -> list:
    """The last gate (plausibility.last_gate) over every value the export
    writes: the law (mu1, mu2, eps1, eps2, eps1/eps2), the SSP's rig `sc.rig`
    (rig_scenario: mass, g, F_int, velocity, travel, step, strip terms; from
    `scenario`'s file if given, else the data's rig.toml), the axes' angles
    (the offsets, --angle: radians?), the elastic length mu N / eps against
    the data's rig travel and the forces' size against m g (kN?).  A value
    the gate refuses or warns about is refused (InputError, one line naming
    --force) unless `force`; then every finding (plausibility.Finding) is
    returned, for the terminal and the FMUs' documentation and description."""
    check_angle(angle_deg)
    law, rig, data_rig = cal.law, sc.rig, cal.rig
    where = f"{cal.path}: "
    values = {"mu1": law.mu1, "mu2": law.mu2, "eps1": law.eps1, "eps2": law.eps2,
              "eps_ratio": law.eps1 / law.eps2}
    ramp = "ramp.csv's x1_m" if "ramp.csv" in cal.data_files else "the ramp runs' positions"
    slip = (f"eps1, eps2 in N/mm ({ramp} in mm)?" if cal.eps2_identified else
            "rig.toml's eps2_nominal_N_m in N/mm?")
    # a fit that did not converge or a law that does not describe the data: before any single value
    also = [plausibility.Finding("error", f"{where}{line}") for line in cal.fit_problems]
    also += [plausibility.force_unit_check((law.mu1, law.mu2), cal.f_int_N, where, "mu1, mu2"),
            plausibility.elastic_length_check(law.mu1, law.mu2, law.eps1, law.eps2, data_rig.normal_force,
                                              data_rig.travel_m, where, slip)]
    carried = {"mass_kg": rig.mass_kg, "g": rig.g, "f_int_N": rig.f_int_N,
               "velocity_m_s": rig.velocity_m_s, "travel_m": rig.travel_m, "step_s": rig.step_s,
               "mu_strip": rig.mu_strip, "c_strip": rig.c_strip}
    if scenario is not None:
        also += plausibility.findings(carried, f"{scenario}: rig.")
    else:   # the data's rig.toml, with the strip's viscosity as the identification used it
        also += plausibility.findings({"c_strip": carried.pop("c_strip")}, where)
        also += plausibility.findings(carried, f"{cal.data_folder / 'rig.toml'}: ")
    also += plausibility.angle_findings({"alpha_offset_deg": data_rig.alpha_offset_deg,
                                         "beta_offset_deg": data_rig.beta_offset_deg}, f"{where}assumptions.")
    also += plausibility.angle_findings({"--angle": angle_deg})
    return plausibility.last_gate(values, where, also, force, FORCE_OVERRIDE)


def forced_html(forced) -> str:
    """The documentation's paragraph on what was exported with --force
    (plausible_calibration's findings)."""
    if not forced:
        return ""
    items = "\n".join(f"<li>{f.level}: {html.escape(f.line)}</li>" for f in forced)
    return (f"<p><b>Exported with --force</b>: the plausibility gate (orthocontact.plausibility) refused "
            f"these values (an error: they cannot be right; a warning: they are unusual, a unit slip is "
            f"named where one fits), and they were exported anyway:</p>\n<ul>\n{items}\n</ul>\n")


def forced_note(forced) -> str:
    """The model description's sentence on what was exported with --force."""
    if not forced:
        return ""
    return (f" Exported with --force despite the plausibility gate ({len(forced)} finding(s), also in "
            "documentation/calibration.html): " + " | ".join(f"{f.level}: {f.line}" for f in forced))


def export(cal: Calibration, out: Path, angle_deg: float, sc: Scenario | None = None, forced=()) -> dict:
    """Writes into the folder `out` fmi2/ and fmi3/OrthotropicContact.fmu
    (calibrated), calibration.ssv and rig_<angle>.ssp of the scenario `sc`
    (rig_scenario; default: the data's rig); returns what was written.
    forced: the findings exported with --force (plausible_calibration),
    said in the documentation and the description."""
    from ..version import __version__
    check_angle(angle_deg)
    sc = sc or rig_scenario(cal)
    values = contact_start_values(cal, angle_deg)
    date = datetime.now(timezone.utc).strftime("%Y-%m-%d")
    phi = predicted_phi_deg(cal, angle_deg, sc.rig)
    doc = _documentation(cal, values, angle_deg, __version__, date, phi)
    if forced:   # said before the provenance, where a reader of the values looks
        at = doc.find("<h2>Provenance</h2>") if "<h2>Provenance</h2>" in doc else doc.find("</body>")
        doc = doc[:at] + forced_html(forced) + doc[at:]
    note = (f"Calibrated: mu1 = {values['mu1']:.6g}, mu2 = {values['mu2']:.6g}, eps1 = {values['eps1']:.6g} "
            f"N/m, eps2 = {values['eps2']:.6g} N/m{'' if cal.eps2_identified else ' (nominal)'}, "
            f"{cal.law.rule} rule, axes at {angle_deg:g} deg; data sha256 {cal.digest} "
            f"(of {len(cal.data_files)} files, each in documentation/calibration.html); {date}; "
            f"orthocontact {__version__}; 95 % intervals in documentation/calibration.html.")
    note += forced_note(forced)
    fmus = {}
    for v in (2, 3):
        fmus[v] = write_with_start_values(find_fmu(fmi_version=v),
                                          out / f"fmi{v}" / f"{MODEL_IDENTIFIER}.fmu",
                                          values, documentation={"calibration.html": doc},
                                          description_note=note)
    (out / "calibration.ssv").write_text(parameter_values_file(values, "calibration", note))
    ssp = write_ssp(sc, angle_deg, out / f"rig_{angle_deg:g}.ssp", contact_fmu=fmus[2])
    return {"fmus": fmus, "ssv": out / "calibration.ssv", "ssp": ssp, "values": values,
            "predicted_phi_deg": phi, "digest": cal.digest, "ssp_params": sc.params_at(angle_deg),
            "ssp_rig": sc.rig}
