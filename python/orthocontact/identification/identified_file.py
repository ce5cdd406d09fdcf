"""identified.json, the identification's result as a file (its typed form:
identified.IdentifiedFile): built from an identification part by part
(identified_file_of), the one writer (write_identified, used by identify)
and the one reader (read_identified, used by export and uq; its fields
typed by identified_json.from_json).

The file carries SCHEMA_VERSION, and identified.schema.json beside this
module describes it (a test validates identify's outputs against it).  The
reader refuses a file of another schema version, checks every field it types
(one line naming the file and the field), that the file is the one its
identify run wrote (output.manifest), that its values pass the plausibility
gate, and that the data it names are still the bytes the identification read
(check_data).  Units: as each field's name or its parameter says (mu1, mu2,
eps_ratio, l1_l2_ratio [-]; eps1, eps2 [N/m]; c_strip [N s/m]; f_int [N])."""
from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass
from pathlib import Path

from .. import plausibility
from ..errors import InputError
from ..output import written_by
from ..textfiles import read_text
from . import identified
from .identified import REPORTED
from .identified_json import WRITTEN_BY, from_json, is_number, short_repr
from .measurements import changed_files, data_digest
from .statistics import json_dof, res_stats

SCHEMA = Path(__file__).with_name("identified.schema.json")   # installed with the package


@dataclass(frozen=True)
class DataProvenance:
    """The data an identification read, found and checked unchanged."""
    folder: Path      # the data folder as found now
    files: dict       # path under folder (POSIX) -> SHA-256, as identify recorded them
    digest: str       # SHA-256 of their sha256sum listing (measurements.data_digest)


# The data groups' keys in the file (noise_estimate, noise_model, noise_assumed).
GROUP_KEYS = {"forces": "forces_N", "angles": "angles_deg", "ramp": "ramp_N", "carriage": "carriage_N",
              "stiffness": "stiffness_N_m"}
# The estimates fitted beyond the five when the data determine them: unit and note.
FITTED_NOTES = {
    "c_strip": ("N s/m", "the strip's lateral viscosity, from the angles' change with velocity"),
    "f_int": ("N", "the carriage's internal resistance, from the carriage runs (and every force)"),
    "l1_l2_ratio": (None, "eigenvalue ratio lambda1/lambda2: what angles alone determine")}
INTERVALS = ("ci95 = value * exp(-+ t(0.975, dof) stderr / value), on the log scale (the "
             "delta method's log-normal interval: every parameter is positive by nature, "
             "so its interval stays > 0; for a small stderr / value it is value -+ "
             "t(0.975, dof) stderr); stderr from the Gauss-Newton covariance "
             "with each value weighted by 1/(between_runs^2 + its within-run error^2); dof "
             "the Welch-Satterthwaite degrees of freedom of that variance over its parts: "
             "each group's between-run variance with its between_runs_dof (values less "
             "the parameters it determines), the within-run errors known (inf)")
CI = ("95%, on the log scale, Student t with each parameter's Welch-Satterthwaite "
      "degrees of freedom over the data groups' noise estimates, "
      "Gauss-Newton covariance with per-group noise estimates")


def identified_file_of(ident, reduction: identified.ReductionSummary | None = None
                       ) -> identified.IdentifiedFile:
    """An identification (job.Identification) as identified.json holds it,
    with the reduction's summary when the data were raw recordings."""
    f = ident.fit
    cov, joint = covariances(f)
    return identified.IdentifiedFile(
        estimates=estimates(f), max_rule=ident.max_rule,
        eq40={k: v for k, v in (ident.eq40 or {}).items() if k != "eq41"} or None,
        eq41=(ident.eq40 or {}).get("eq41"), eq1=ident.eq1, noise_estimate=noise_estimate(f),
        noise_model={GROUP_KEYS[g]: {"between_runs": f.between_runs.get(g),
                                     "between_runs_dof": json_dof(f.between_runs_dof.get(g)),
                                     "within_run_rms": f.within_run.get(g),
                                     "values": int(len(f.residuals[g]))}
                     for g in f.sigma},
        intervals=INTERVALS, noise_assumed=tuple(GROUP_KEYS[g] for g in f.sigma_assumed),
        fit_residuals={g: res_stats(x) for g, x in f.residuals.items()}, dof=f.dof,
        covariance=cov, covariance_joint=joint, points=points(ident.data),
        ramp_stick_points=f.stick_points, validation_fmu=ident.validation,
        data=data_record(ident.data), assumptions=assumptions(ident.data.rig, f), fit=fit_record(f),
        reduction=reduction)


def estimate(f, n: str, unit=None, note=None) -> identified.Estimate:
    """The joint fit f's estimate of n: value, standard error, interval, dof."""
    dof = f.param_dof.get(n)
    return identified.Estimate(value=f.values[n], stderr=f.stderr[n], ci95=tuple(f.ci95[n]),
                               dof=None if dof is None else
                               (math.inf if not math.isfinite(dof) else round(float(dof), 2)),
                               unit=unit, note=note)


def estimates(f) -> dict:
    """The five reported parameters, each estimated or why not, then those
    fitted beyond them (FITTED_NOTES)."""
    out = {n: estimate(f, n) if n in f.values else
           identified.NotIdentified(f.not_identifiable.get(n, "not determined")) for n in REPORTED}
    for n, (unit, note) in FITTED_NOTES.items():
        if n in f.values:
            out[n] = estimate(f, n, unit, note)
    return out


def noise_estimate(f) -> dict:
    """Each data group's noise as fitted; the angles' at each velocity, for uq."""
    noise = {GROUP_KEYS[g]: s for g, s in f.sigma.items()}
    tau = f.between_runs.get("angles")
    if isinstance(tau, dict):   # a measured angle's noise at each velocity, for uq
        noise["angles_deg_by_velocity"] = {v: (t * t + f.within_run["angles"] ** 2) ** 0.5
                                           for v, t in tau.items()}
    return noise


def covariances(f) -> tuple:
    """What uncertainty propagation (orthocontact uq) draws from: the joint
    Gauss-Newton covariance of the fitted parameters.  uq draws the law's
    parameters: their marginal (exact for a normal); the joint one, with
    F_int and the strip, beside it (None where there are no others)."""
    law = [i for i, n in enumerate(f.free) if n not in ("f_int", "c_strip")]
    sym = 0.5 * (f.cov + f.cov.T)
    cov = identified.Covariance(parameters=tuple(f.free[i] for i in law),
                                values=tuple(f.values[f.free[i]] for i in law),
                                matrix=tuple(tuple(float(sym[i, j]) for j in law) for i in law))
    joint = None if len(law) == len(f.free) else identified.Covariance(
        parameters=tuple(f.free), values=tuple(f.values[n] for n in f.free),
        matrix=tuple(tuple(float(c) for c in row) for row in sym))
    return cov, joint


def _rows(a):
    return None if a is None else tuple(tuple(float(x) for x in r) for r in a)


def points(d) -> identified.Points:
    """The measured angles (with their velocities) and forces, to show beside the predictions."""
    return identified.Points(angles=_rows(d.angles),
                             angle_velocities=None if d.angles is None or d.angle_velocities is None
                             else tuple(float(v) for v in d.angle_velocities),
                             forces=_rows(d.forces))


def data_record(d) -> identified.DataRecord:
    """The data the identification read: folder, counts, every file and one digest over them."""
    return identified.DataRecord(folder=str(d.folder), absolute_folder=str(Path(d.folder).resolve()),
                                 forces=0 if d.forces is None else len(d.forces),
                                 angles=0 if d.angles is None else len(d.angles),
                                 ramp=0 if d.ramp is None else len(d.ramp),
                                 files=d.files, sha256=None if d.files is None else data_digest(d.files))


def assumptions(r, f) -> identified.Assumptions:
    """The rig `r` (experiment.RigSetup) and rule the fit f was made on; F_int
    and the strip's viscosity "estimated" where f estimated them."""
    return identified.Assumptions(
        rule=r.rule, alpha_offset_deg=r.alpha_offset_deg, beta_offset_deg=r.beta_offset_deg,
        mass_kg=r.mass_kg, g=r.g, f_int_N="estimated" if "f_int" in f.values else r.f_int_N,
        ramp_angle_deg=r.ramp_angle_deg, mu_strip=r.mu_strip,
        c_strip_N_s_m=("estimated" if "c_strip" in f.values else
                       (r.c_strip if r.c_strip is not None else 0.0)),
        phi_convention="counterclockwise (data converted)" if r.phi_convention == "paper"
        else "counterclockwise",
        ci=CI)


def fit_record(fit) -> identified.FitRecord:
    """How the joint fit ended, as identified.json records it: a fit that
    did not converge is written only by identify --force (identify), so
    `forced` is its not converging."""
    return identified.FitRecord(converged=fit.converged, convergence=dict(fit.convergence),
                                reweighting_rounds=fit.reweighting_rounds, solves=tuple(fit.solves),
                                lack_of_fit={g: t.as_json() for g, t in fit.lack_of_fit.items()},
                                forced=not fit.converged)


def write_identified(path, f: identified.IdentifiedFile) -> Path:
    """Writes identified.json (indented JSON); the one writer."""
    from ..output import write_json
    path = Path(path)
    write_json(path, f.as_json())
    return path


# -- the reader ---------------------------------------------------------------------

def read_identified(path, force: bool = False, override: str = "") -> identified.IdentifiedFile:
    """identified.json -> IdentifiedFile, checked: its schema version, every
    field (InputError naming the file and the field), the run that wrote it
    (output.manifest), the plausibility gate (plausible_identified: a value
    that cannot be right is refused, `override` naming what lets it through,
    unless `force`), and the data it names, unchanged (check_data)."""
    path = Path(path)
    try:   # a BOM, CRLF, an unreadable file: textfiles
        d = json.loads(read_text(path, f"identified.json {WRITTEN_BY}"))
    except ValueError as e:
        raise InputError(f"{path}: expected JSON {WRITTEN_BY} ({e})") from None
    if not isinstance(d, dict):
        raise InputError(f"{path}: expected a JSON object {WRITTEN_BY}")
    version = d.get("schema_version")
    if version != identified.SCHEMA_VERSION or isinstance(version, bool):
        raise InputError(f"{path}: schema_version: expected {identified.SCHEMA_VERSION}, got "
                         f"{short_repr(version)} (a file of another version of orthocontact: run "
                         "`orthocontact identify` again)")
    written_by(path)   # in an output folder: as its run wrote it
    f = from_json(path, d)
    errors, _ = plausibility.split(plausible_identified(f))
    if errors and not force:
        raise InputError(f"{errors[0]}; refused" + (f" ({override})" if override else ""))
    return dataclasses.replace(f, provenance=check_data(path, f.data))


# identified.json's values with a unit: estimate -> key of plausibility.QUANTITIES
IDENTIFIED = {"mu1": "mu1", "mu2": "mu2", "eps_ratio": "eps_ratio", "eps1": "eps1", "eps2": "eps2",
              "c_strip": "c_strip", "f_int": "f_int_N"}
ASSUMED = {"mass_kg": "mass_kg", "g": "g", "f_int_N": "f_int_N", "c_strip_N_s_m": "c_strip",
           "mu_strip": "mu_strip"}


def plausible_identified(f: identified.IdentifiedFile) -> list:
    """The plausibility Findings of the file's numbers with a unit: each
    estimate's value, the covariance's values (what uq draws around) and
    the assumptions (mass, g, F_int, strip terms).  Numbers outside the
    quantity's domain (0 where 0 is not allowed) are left to the readers
    that need them, whose message says what the field must be."""
    path = f.path

    def number(v, key):
        q = plausibility.QUANTITIES[key]
        return is_number(v) and (v > 0 or (v == 0 and q.zero_allowed))
    found = []
    for name, key in IDENTIFIED.items():
        v = f.value(name)
        if v is not None and number(v, key):
            found += plausibility.findings({key: v}, f"{path}: " + ("" if name == key else f"{name}.value: "))
    for name, v in zip(f.covariance.parameters, f.covariance.values):
        if name in IDENTIFIED and number(v, IDENTIFIED[name]):
            found += plausibility.findings({IDENTIFIED[name]: v}, f"{path}: covariance.values: ")
    a = f.assumptions
    for name, key in ASSUMED.items():
        v = getattr(a, name)
        if number(v, key):
            found += plausibility.findings({key: v}, f"{path}: assumptions."
                                           + ("" if name == key else f"{name}: "))
    return found


NAMED = 12   # changed files named in the one line; the rest counted


def check_data(path, data: identified.DataRecord) -> DataProvenance:
    """The data folder identified.json (read from `path`) names, found as
    given, relative to the file's folder, or by its absolute path, and every
    file the identification read in it as it was then; InputError naming
    identified.json and the files that changed or are missing."""
    path = Path(path)
    folder, files, stated = data.folder, data.files, data.sha256
    found = None
    for candidate in (Path(folder), path.parent / folder) + (
            (Path(data.absolute_folder),) if data.absolute_folder else ()):
        if (candidate / "rig.toml").is_file():
            found = candidate
            break
    if found is None:
        raise InputError(f"{path}: data.folder: {folder} not found (relative to the working folder or "
                         f"to {path.parent}): the calibration names the data it came from")
    changed = changed_files(found, files)
    if changed:
        named = ", ".join(changed[:NAMED]) + (f" and {len(changed) - NAMED} more" if len(changed) > NAMED
                                              else "")
        raise InputError(f"{path}: data.files: {len(changed)} of the {len(files)} files the "
                         f"identification read in {found} changed since: {named} "
                         f"(identified on data sha256 {stated[:12]}...; identify again)")
    return DataProvenance(found, dict(files), stated)
