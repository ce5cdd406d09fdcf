"""Parameter identification with casadi: friction coefficients, stiffness
ratio and absolute stiffness from measured forces, trajectory angles and a
pre-sliding ramp, with Gauss-Newton standard errors and 95% intervals.

The job, by layer: measurements (data and files) -> estimators (the paper's
formulas and the joint fit) -> uncertainty (statistics) -> here (the whole
identification, its validation on the FMU) -> identified_file (identified.json:
its typed form, writer and reader) and report (figure, Markdown, summary).  Units: N, m, deg."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import plausibility
from ..errors import InputError
from ..experiment import RigSetup
from ..fmu import ContactParams
from . import identified
from .estimators import JointFit, eq1, eq40_fit, identifiability, joint_fit, max_rule, start_values
from .identified import REPORTED
from .identified_file import fit_record, identified_file_of, write_identified
from .measurements import MeasurementSet, data_files, load_data, write_measurements
from .statistics import res_stats

# The whole job here; its parts importable from here as before.
__all__ = ["Identification", "identify", "run", "load_folder", "validate_with_fmu", "simulate_measurements",
           "MeasurementSet", "RigSetup", "load_data", "write_measurements", "JointFit", "joint_fit",
           "identifiability", "eq1", "eq40_fit", "max_rule", "REPORTED", "summary_text"]


def validate_with_fmu(data: MeasurementSet, values: dict, workers=None, fmu_path=None) -> dict:
    """Simulates the identified parameters in the rig harness with the FMU at
    the data's mat angles and velocities (and the ramp), strip terms
    included (the estimated c_strip where it was fitted), and returns the
    residuals data - simulation and the runs' self-checks (rig_checks):
    "warning" holds the user's line if a run was not steady sliding."""
    from ..rig import check_runs, run, warning_line
    from ..runs import run_many
    from ..runtime import default_workers
    rig = data.rig
    if "f_int" in values:
        rig = dataclasses.replace(rig, f_int_N=values["f_int"])
    mu1, mu2 = values.get("mu1"), values.get("mu2")
    if mu1 is None:
        return {"skipped": "mu1, mu2 not identified: nothing to simulate"}
    ratio = values.get("eps_ratio", 1.0)
    eps2 = values.get("eps2", rig.eps2_nominal_N_m)
    law = ContactParams(mu1, mu2, ratio * eps2, eps2)
    c_strip = values.get("c_strip", rig.c_strip or 0.0)
    fv = data.velocities_of_forces()
    points = validation_points(data)
    tasks = [(rig.params_at(law, a), rig.harness(c_strip=c_strip, velocity_m_s=v)) for a, v in points]
    sims = run_many(tasks, workers or default_workers(), fmu_path, "validation", progress=False)
    sim = dict(zip(points, sims))
    checks = check_runs(tasks, sims)
    out = {"rig_mode": rig.mode, "eps_used": {"eps1": ratio * eps2, "eps2": eps2,
                                               "eps2_identified": "eps2" in values},
           "c_strip_used_N_s_m": c_strip,
           "checks": {"ok": bool(checks.ok.all()),
                      "not_steady": [{"alpha_deg": a, "velocity_m_s": v, "check": st}
                                     for (a, v), st, ok in zip(points, checks.status(), checks.ok)
                                     if not ok]}}
    line = warning_line("identification's validation runs", [a for a, _ in points], checks,
                        [f.phi_deg for f in sims], tasks)
    if line:
        out["warning"] = line
    if data.forces is not None:
        res = data.forces[:, 1] - np.array([sim[(float(a), float(v))][1]
                                            for a, v in zip(data.forces[:, 0], fv)])
        out["forces_N"] = res_stats(res)
    if data.angles is not None:
        res = data.angles[:, 1] - np.array([sim[(float(a), float(v))][0] for a, v in
                                            zip(data.angles[:, 0], data.velocities_of_angles())])
        out["angles_deg"] = res_stats(res)
    if data.ramp is not None:
        r = run(rig.params_at(law, rig.ramp_angle_deg), ramp_rig(data.ramp, rig, c_strip))
        x = np.concatenate([[0.0], r.x1])
        F = np.concatenate([[rig.f_int_N], r.drive])
        res = data.ramp[:, 1] - np.interp(data.ramp[:, 0], x, F)
        out["ramp_N"] = res_stats(res)
    return out


def validation_points(data: MeasurementSet) -> list[tuple[float, float]]:
    """The validation's sliding runs: each distinct (mat angle [deg],
    velocity [m/s]) of the measured forces and angles, sorted."""
    points = [] if data.forces is None else [(float(a), float(v)) for a, v in
                                             zip(data.forces[:, 0], data.velocities_of_forces())]
    if data.angles is not None:
        points += [(float(a), float(v)) for a, v in zip(data.angles[:, 0], data.velocities_of_angles())]
    return sorted(set(points))


def ramp_rig(ramp: np.ndarray, rig: RigSetup, c_strip: float = 0.0):
    """The validation's ramp run over the data's ramp (rows x1 [m], force
    [N]): 1 % beyond its largest x1, in steps fine enough (4000 over it at
    least) for a comparison that interpolates the simulation at the data's x1."""
    xmax = float(ramp[:, 0].max())
    return rig.harness(c_strip=c_strip, travel_m=max(xmax * 1.01, 1e-6),
                       step_s=min(rig.step_s, xmax / rig.velocity_m_s / 4000))


def validation_work(data: MeasurementSet):
    """Every rig run validate_with_fmu makes, known before the fit, for the
    work estimate (runs.size.Work): none when mu1, mu2 will not be
    identified (no driving forces: identifiability), else a run at each
    validation point and one over the ramp."""
    from ..runs import Work, steps_per_run
    work = Work()
    if "mu1" not in identifiability(data)[0]:
        return work
    rig = data.rig
    by_velocity: dict = {}
    for _, v in validation_points(data):
        by_velocity[v] = by_velocity.get(v, 0) + 1
    for v, n in sorted(by_velocity.items()):
        work = work.plus("validation runs", n, steps_per_run(rig.travel_m, v, rig.step_s))
    if data.ramp is not None:
        r = ramp_rig(data.ramp, rig)
        work = work.plus("validation ramp run", 1, steps_per_run(r.travel_m, r.velocity_m_s, r.step_s))
    return work


@dataclass
class Identification:
    data: MeasurementSet
    fit: JointFit
    eq1: dict | None
    max_rule: dict | None
    eq40: dict | None
    validation: dict | None
    start: dict
    warnings: tuple = ()     # one line each: identified values that are unusual (plausible_values)

    def identified_file(self, reduction: identified.ReductionSummary | None = None
                        ) -> identified.IdentifiedFile:
        """The result as identified.json holds it (identified_file_of), with
        the reduction's summary when the data were raw recordings."""
        return identified_file_of(self, reduction)

    def fit_record(self) -> identified.FitRecord:
        return fit_record(self.fit)

    def as_json(self) -> dict:
        """identified.json's object (IdentifiedFile.as_json)."""
        return self.identified_file().as_json()


# The identified values the gate judges, by their key in plausibility.QUANTITIES.
GATED = {"mu1": "mu1", "mu2": "mu2", "eps_ratio": "eps_ratio", "eps1": "eps1", "eps2": "eps2",
         "c_strip": "c_strip", "f_int": "f_int_N"}


def plausible_values(data: MeasurementSet, values: dict) -> list[str]:
    """The identified values through the one gate (orthocontact.plausibility)
    and the elastic length mu N / eps they give against the data's rig
    travel: raises InputError (one line, the reason) for a value that cannot
    be right, before anything is written; returns warning lines."""
    rig = data.rig
    where = f"{data.folder}: identified "
    also = []
    if "mu1" in values and "mu2" in values and ("eps2" in values or "eps_ratio" in values):
        eps2 = values.get("eps2", rig.eps2_nominal_N_m)
        eps1 = values.get("eps1", values.get("eps_ratio", 1.0) * eps2)
        slip = ("rig.toml's eps2_nominal_N_m in N/mm?" if "eps2" not in values else
                "ramp.csv's x1_m in mm?" if data.ramp is not None else "the ramp runs' positions in mm?")
        also.append(plausibility.elastic_length_check(values["mu1"], values["mu2"], eps1, eps2,
                                                      rig.normal_force, rig.travel_m, where, slip))
    return plausibility.gate({GATED[k]: v for k, v in values.items() if k in GATED}, where, also,
                             "refused: identified.json not written")


def identify(data: MeasurementSet, validate: bool = True, workers=None,
             fmu_path=None, force: bool = False) -> Identification:
    """The fit, the paper's formulas beside it and the FMU's validation; a
    fit that did not converge is refused unless `force`, and the fitted
    values pass the plausibility gate before the validation runs
    (InputError: nothing is written).  A group the fitted law does not
    describe (lack_of_fit) is a warning here and refused by export."""
    from ..runs import Heartbeat
    start = start_values(data)
    beat = Heartbeat("joint fit", unit="solves")   # a line at 2 s and every 10 s while it runs
    try:
        fit = joint_fit(data, start, beat.update)
    finally:
        beat.close()
    if not fit.converged and not force:
        raise InputError(f"{data.folder}: {fit_record(fit).problems()[0]}; refused: identified.json not "
                         "written (`orthocontact identify --force` writes it, marked not converged, and "
                         "export refuses it)")
    warnings = plausible_values(data, fit.values)
    warnings += [f"{data.folder}: {t.line()}; `orthocontact export` refuses this fit"
                 for t in sorted(fit.lack_of_fit.values(), key=lambda t: t.p_value) if t.rejected]
    held = fit.solves[-1].get("at_bound", []) if fit.solves else []
    warnings += [f"{data.folder}: {n} is held at its lower bound (0: the data ask for less); its "
                 "interval assumes an interior minimum and is not meaningful" for n in held]
    mu1, mu2 = fit.values.get("mu1"), fit.values.get("mu2")
    mr = max_rule(data, mu1, mu2)
    e40 = eq40_fit(data, mu1, mu2)
    val = validate_with_fmu(data, fit.values, workers, fmu_path) if validate else None
    return Identification(data, fit, eq1(data), mr, e40, val, start, tuple(warnings))


def load_folder(folder):
    """(MeasurementSet, the raw recordings and their reduction or None) of a
    measurement folder: raw recordings if it has a runs.csv, reduced data
    otherwise; the set's `files` are those read, with their SHA-256.
    Raises InputError (one line)."""
    from ..textfiles import files_read
    from .recordings import is_recordings, load_recordings
    with files_read() as read:
        if not is_recordings(folder):
            data, recordings = load_data(folder), None
        else:
            from .reduction import reduce_recordings
            from .reduction_output import to_measurements
            rec = load_recordings(folder)
            red = reduce_recordings(rec)
            data, recordings = to_measurements(rec, red), (rec, red)
    return dataclasses.replace(data, files=data_files(folder, read)), recordings


def run(data: MeasurementSet, out: Path, validate: bool = True, workers=None,
        fmu_path=None, recordings=None, force: bool = False) -> Identification:
    """identify() and write identified.json, fit.png, identified.md into
    out; with recordings (load_folder's second value) also the reduction's
    table and figures."""
    from .report import fit_figure, markdown_text
    res = identify(data, validate, workers, fmu_path, force)
    summary = None
    if recordings is not None:
        from .reduction_output import reduction_summary, write_figures, write_rig_scenario, write_table
        rec, red = recordings
        write_table(red, out)
        figures = write_figures(rec, red, out)
        scenario = write_rig_scenario(data, res.fit.values, out)
        summary = reduction_summary(red, figures, scenario)
    result = res.identified_file(summary)
    write_identified(out / "identified.json", result)
    fit_figure(res, out / "fit.png")
    md = markdown_text(res)
    if summary is not None:
        from .report import reduction_markdown
        md += "\n" + reduction_markdown(result.noise_model, summary)
    (out / "identified.md").write_text(md)
    return res


def simulate_measurements(truth: ContactParams, rig: RigSetup, force_angles, angle_angles,
                          ramp_max_x1_m: float | None = None, workers=1) -> dict:
    """Noise-free measurements made by the FMU in the rig harness (quasistatic
    mode: the steady state without inertial transients): mean driving forces
    and fitted trajectory angles at the given mat angles [deg], and the
    start of a pull at rig.ramp_angle_deg up to ramp_max_x1_m [m].
    truth.alpha/beta are ignored: the rig's geometry sets them per angle."""
    from ..rig import run
    from ..runs import run_many
    h = rig.harness(mode="quasistatic", step_s=1e-3, travel_m=0.2)
    angles = sorted(set(force_angles) | set(angle_angles))
    sims = dict(zip(angles, run_many([(rig.params_at(truth, a), h) for a in angles], workers, None,
                                     "synthesize", progress=False)))
    out = {"forces": np.array([[a, sims[a][1]] for a in force_angles]),
           "angles": np.array([[a, sims[a][0]] for a in angle_angles])}
    if ramp_max_x1_m:
        steps = 400
        r = run(rig.params_at(truth, rig.ramp_angle_deg),
                rig.harness(mode="quasistatic", travel_m=ramp_max_x1_m,
                            step_s=ramp_max_x1_m / rig.velocity_m_s / steps))
        out["ramp"] = np.column_stack([r.x1, r.drive])
    return out


def summary_text(res: Identification) -> str:
    """The terminal summary of an identification (report.summary_text)."""
    from .report import summary_text as text
    return text(res)
