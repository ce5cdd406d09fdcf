"""The subcommands: run, reproduce, identify, sensitivity, uq, ssp, export, design."""
from __future__ import annotations

import contextlib
import json
import time
from pathlib import Path

from ..errors import InputError
from ..experiment import RunOptions, fmu_for, kind_of, require_mat_angles
from ..experiment import load_scenario as read_scenario
from ..output import one_run, staged_output, warn


def load_scenario(path, yes: bool | None = None):
    """The scenario file, its unusual values said as warnings; with `yes`
    given, its size checked (runs.size: refused above the limits unless yes)."""
    from ..runs import check_scenario_size
    sc = read_scenario(path)
    if yes is not None:
        check_scenario_size(sc, yes)
    for line in sc.warnings:
        warn(line)
    return sc


def _run_scenario(sc, out: Path, fmu_path, how) -> dict:
    """The scenario run by its kind (reproduction.kinds) on the FMU the
    command resolved, its warning line said."""
    from ..reproduction import run_scenario
    summary = run_scenario(sc, out, fmu_path, how)
    if summary["checks"]["warning"]:
        warn(summary["checks"]["warning"])
    return summary


def packaged_scenarios() -> Path:
    """The paper's scenario files installed with the package (or, in a source
    tree without an install, the repository's)."""
    from ..fmu import PACKAGE_ROOT, installed_file
    return installed_file("scenarios", folder=True) or PACKAGE_ROOT.parents[1] / "scenarios"


def cmd_run(args) -> int:
    from ..output import FigureDrawer
    sc = load_scenario(args.scenario, args.yes)
    fmu_path = fmu_for(sc, args.fmi)
    with staged_output(args.out, args.cmd, args.force) as stage, _dask_for(args) as dask, \
            FigureDrawer(args.workers or _default_workers()) as draw:
        how = RunOptions(args.workers, args.master, draw=draw, dask=dask)
        summary = _run_scenario(sc, stage, fmu_path, how)
    print(json.dumps({k: summary[k] for k in summary if k in ("scenario", "extremum", "max_deviation_deg",
                                                             "drive_mean_N", "rules", "yaw_deg")}, indent=1))
    print(f"wrote {args.out}/summary.json")
    return 0


def cmd_reproduce(args) -> int:
    from ..output import FigureDrawer, write_json
    from ..reproduction import calibration_rows, paper_rows, reproduction_report
    folder = Path(args.scenarios) if args.scenarios else packaged_scenarios()
    files = sorted(folder.glob("*.toml"))
    if not files:
        raise InputError(f"{folder}: expected scenario files (*.toml), found none")
    scenarios = [load_scenario(f, args.yes) for f in files]  # all validated before anything runs
    from ..reproduction import in_report_order, sensitivity
    from ..runs import Work, check_work, scenario_work
    sens_sc = next((sc for sc in scenarios if sensitivity.takes(sc) and "extremum_phi_deg" in sc.paper),
                   None)   # the rig's hidden assumptions, on it
    planned = sensitivity.plan(sens_sc) if sens_sc is not None else None
    work = sum((scenario_work(sc).named(sc.name) for sc in scenarios), Work())
    if planned is not None:
        work += sensitivity.work(planned).named("sensitivity")
    check_work(str(folder), work, "the scenarios' sweep.step_deg", "their rig.step_s", args.yes)
    taken = {"sensitivity": "the report's sensitivity folder", "report.md": "the report",
             "summary.json": "the report's summary"}
    for sc in scenarios:
        if sc.name in taken:
            raise InputError(f"{sc.path}: name: expected a name of its own, got {sc.name!r}, "
                             f"already {taken[sc.name]} (each scenario is written to --out/<name>/)")
        taken[sc.name] = f"the name of {sc.path}"
    fmus = {sc.name: fmu_for(sc, args.fmi) for sc in scenarios}   # every FMU found before any run
    t0 = time.time()
    runs, rows = [], []
    with staged_output(args.out, args.cmd, args.force) as stage:
        # The figures are drawn in worker processes while the rig runs on.
        with _dask_for(args) as dask, FigureDrawer(args.workers or _default_workers()) as draw:
            # The rig's hidden assumptions, on the calibrated experiment: a
            # job of its own beside the sweeps.
            sens = None
            if sens_sc is not None:
                (stage / "sensitivity").mkdir()
                sens = draw.submit(_sensitivity_job, sens_sc, fmus[sens_sc.name], args.master,
                                   stage / "sensitivity", planned)
            how = RunOptions(args.workers, args.master, draw=draw, dask=dask)
            for sc in in_report_order(scenarios):
                (stage / sc.name).mkdir()
                summary = _run_scenario(sc, stage / sc.name, fmus[sc.name], how)
                runs.append((sc, summary))
                rows += paper_rows(sc, summary)
            sens = sens.result() if sens is not None else None
            if sens is not None and sens["checks"]["warning"]:
                warn(sens["checks"]["warning"])
        rows += calibration_rows()
        write_json(stage / "summary.json", {"rows": rows, "scenarios": {sc.name: s for sc, s in runs}})
        text = reproduction_report(stage, runs, rows, time.time() - t0, sens)
    print(text.split("## Scenarios")[0].rstrip())
    print(f"\nwrote {args.out}/report.md in {time.time() - t0:.1f} s")
    return 0 if all(r["match"] for r in rows) else 1


def cmd_identify(args) -> int:
    from ..identification import job as identify
    data, recordings = identify.load_folder(args.data)
    for line in data.warnings:
        warn(line)
    if not args.no_validate:   # the fit runs no rig; its validation does
        from ..runs import check_work
        check_work(str(args.data), identify.validation_work(data), "the data's points", "rig.toml's step_s",
                   args.yes, remedy="raise rig.toml's step_s (steps per run), or pass --no-validate (no "
                                    "validation runs) or --yes to run them anyway")
    with staged_output(args.out, args.cmd, args.force) as stage:
        from ..fmu import find_fmu
        result = identify.run(data, stage, validate=not args.no_validate, workers=args.workers,
                              fmu_path=str(find_fmu(fmi_version=args.fmi)), recordings=recordings,
                              force=args.force)
    print(identify.summary_text(result))
    for line in result.warnings:
        warn(line)
    if result.validation and result.validation.get("warning"):
        warn(result.validation["warning"])
    print(f"wrote {args.out}/identified.json")
    return 0


def _sensitivity_job(sc, fmu_path, master, out, planned) -> dict:
    """sensitivity.run of the planned runs and its files, in one process (a
    figure worker's)."""
    from ..reproduction import sensitivity
    res = sensitivity.run(sc, 1, fmu_path, master, progress=False, planned=planned)
    return sensitivity.write_outputs(res, sc, out)


def cmd_sensitivity(args) -> int:
    from ..output import FigureDrawer
    from ..reproduction import sensitivity
    from ..runs import check_work
    sc = load_scenario(args.scenario)
    planned = sensitivity.plan(sc)
    check_work(str(sc.path), sensitivity.work(planned), "its runs", "rig.travel_m", args.yes,
               remedy="lower rig.travel_m (steps per run, at the study's 4 ms step), or pass --yes to "
                      "run it anyway")
    with staged_output(args.out, args.cmd, args.force) as stage, _dask_for(args) as dask, \
            FigureDrawer(1) as draw:
        res = sensitivity.run(sc, args.workers or _default_workers(), fmu_for(sc, args.fmi), args.master,
                              dask=dask, planned=planned)
        summary = sensitivity.write_outputs(res, sc, stage, draw)
    if res.checks["warning"]:
        warn(res.checks["warning"])
    for r in summary["strip"]:
        if r["velocity_m_s"] == sensitivity.VELOCITIES[-1]:
            ratio = r["eps_ratio_for_measured_peak"]
            print(f"mu_strip {r['mu_strip']:<6g} peak |phi| {abs(r['peak_phi_rig_deg']):6.2f} deg (rig), "
                  f"{abs(r['peak_phi_closed_deg']):6.2f} deg (closed form); eps1/eps2 for the measured "
                  f"{summary['measured_peak_deg']:g} deg: "
                  + ("not reachable" if ratio is None else f"{ratio:.4f}"))
    print(f"wrote {args.out}/sensitivity.json, sensitivity_strip.csv, sensitivity_velocity.csv, "
          "sensitivity_strip.png, sensitivity_velocity.png")
    return 0


def cmd_uq(args) -> int:
    from .. import uq
    from ..fmu import find_fmu
    from ..runs import check_uq_size
    from ..uq import read_source
    est, source = read_source(args.identification)
    one_run(args.identification, args.scenario)   # the law and the rig of one identify run
    sc = load_scenario(args.scenario)
    uq.check_geometry(sc, est)  # before any work
    # every run uq makes: the draws and the step check at the scenario's own step
    check_uq_size(sc, args.yes, args.samples, uq.uq_step(sc, args.step_s), "--samples",
                  "--step-s or rig.travel_m")
    fmu_path = find_fmu(fmi_version=2, model=kind_of(sc).model)   # the compiled master's: FMI 2.0
    with staged_output(args.out, args.cmd, args.force) as stage:
        res = uq.propagate(est, sc, args.samples, args.seed, fmu_path,
                           scheduler=None if args.scheduler == "none" else args.scheduler,
                           workers=args.workers or _default_workers(), step_s=args.step_s,
                           chunk_runs=args.chunk_runs)
        summary = uq.write_outputs(res, est, sc, args.seed, stage, source)
    if summary["checks"]["warning"]:
        warn(summary["checks"]["warning"])
    line = uq.step_warning(summary["step_check"])
    if line:
        warn(line)
    w = summary["widest_band"]
    print(f"{summary['runs']} rig runs ({summary['samples']} parameter sets x "
          f"{len(summary['bands'])} angles) in {summary['seconds']:.1f} s on {summary['engine']}")
    print(f"widest 95 % band of phi: {w['width_deg']:.3f} deg at {w['angle_deg']:g} deg; "
          f"{100 * summary['accepted_fraction']:.1f} % of the draws physical")
    print(f"wrote {args.out}/uq.json, uq_bands.csv, samples.csv, uq.png")
    return 0


def _dask_for(args):
    """The Dask cluster the command's sweeps run on (--scheduler), or None."""
    if getattr(args, "scheduler", None) in (None, "none"):
        return contextlib.nullcontext(None)
    if args.master == "fmpy" or getattr(args, "fmi", 2) == 3:
        raise InputError("--scheduler runs the compiled master on the workers: it takes FMI 2.0 "
                         "FMUs and --master auto or c")
    from ..runs import DaskRunner
    return DaskRunner(args.scheduler, args.workers or _default_workers())


def _default_workers() -> int:
    from ..runtime import default_workers
    return default_workers()


def cmd_ssp(args) -> int:
    from ..experiment import write_ssp
    sc = load_scenario(args.scenario)
    require_mat_angles(sc, "an SSP", args.scenario)
    from ..rig import system_settling_warning
    line = system_settling_warning(f"{sc.name} at {args.angle:g} deg", sc.params_at(args.angle), sc.rig)
    if line:
        warn(line)
    path = write_ssp(sc, args.angle, args.out)
    print(f"wrote {path}: rig + contact at {args.angle:g} deg "
          f"(run it with libcosim: CosimExecution.from_ssp_file)")
    return 0


def cmd_export(args) -> int:
    from ..identification import export_calibration, load_calibration, plausible_calibration, rig_scenario
    cal = load_calibration(args.identification, force=args.force)
    sc = rig_scenario(cal, args.scenario)
    # the last gate: what it would warn about is refused too, unless --force
    forced = plausible_calibration(cal, sc, args.angle, args.scenario, force=args.force)
    one_run(args.identification, args.scenario)
    for f in forced:
        what = "a value that cannot be right" if f.level == "error" else "an unusual value"
        warn(f"--force: exporting {what} (said in the FMUs' documentation/calibration.html and "
             f"description): {f.line}")
    with staged_output(args.out, args.cmd, args.force) as stage:
        res = export_calibration(cal, stage, args.angle, sc, forced)
    from ..rig import system_settling_warning
    line = system_settling_warning(f"{res['ssp'].name}", res["ssp_params"], res["ssp_rig"])
    if line:
        warn(line)
    v = res["values"]
    print(f"calibrated: mu1 = {v['mu1']:.6g}, mu2 = {v['mu2']:.6g}, eps1 = {v['eps1']:.6g} N/m, "
          f"eps2 = {v['eps2']:.6g} N/m{'' if cal.eps2_identified else ' (nominal: not identified)'}, "
          f"{cal.law.rule} rule; data sha256 {res['digest'][:12]}...")
    print(f"predicted trajectory angle at {args.angle:g} deg: {res['predicted_phi_deg']:.4f} deg")
    print(f"wrote {args.out}/fmi2/OrthotropicContact.fmu, fmi3/OrthotropicContact.fmu, calibration.ssv, "
          f"{res['ssp'].name}")
    return 0


def cmd_design(args) -> int:
    from ..identification import (
        design,
        design_output,
        noise_of,
        paper_prior,
        prior_from_identified,
        read_plan,
        stderr_say,
    )
    noise = (args.sigma_force, args.sigma_angle, args.sigma_ramp)
    prior = prior_from_identified(args.prior, not args.no_strip, noise) if args.prior else \
        paper_prior(not args.no_strip, noise_of(*noise))
    velocities = design.velocities_of(prior, args.velocity_min, args.velocity_max, args.velocity_step)
    fixed = tuple(read_plan(args.fixed)) if args.fixed else ()
    space = design.Space(design.angles_of(prior, args.angle_step), velocities, args.runs, args.ramp_samples,
                         args.carriage_runs, fixed)
    result = design.plan(prior, space, args.criterion, say=stderr_say)
    for line in result.warnings:
        warn(line)
    with staged_output(args.out, args.cmd, args.force) as stage:
        design_output.write_outputs(result, stage)
    print(design_output.summary_text(result))
    print(f"wrote {args.out}/plan.csv, design.json, design.md, design.png")
    return 0
