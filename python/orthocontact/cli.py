"""The `orthocontact` command.

  orthocontact run SCENARIO --out DIR        one scenario file
  orthocontact reproduce --out DIR           every paper scenario + report.md
  orthocontact identify DATA_DIR --out DIR   parameter identification

Exit status: 0 success, 1 a result that does not match the paper (or, with
--strict, any warning: an implausible input, a rig run that is not steady
sliding), 2 bad input (one line on stderr naming the file, option, key or row, and what was
expected), 130 interrupted (Ctrl-C, SIGINT or SIGTERM).  Arguments and the
output folder are checked before any work; the output folder is written all at
once or not at all.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import shutil
import signal
import sys
import tempfile
import time
from pathlib import Path

from .errors import InputError
from .scenarios import ScenarioError, load

__all__ = ["main", "entry", "InputError"]


def check_output_folder(out: Path, option: str = "--out") -> None:
    """Raises InputError, naming the user's path, unless `out` is (or can be
    created as) a writable folder.  Leaves nothing behind."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputError(f"{option} {out}: is a file; expected a folder to write the results into")
    probe = out
    while not probe.exists():
        if probe.parent == probe:
            break
        probe = probe.parent
    if probe != out and not probe.is_dir():
        raise InputError(f"{option} {out}: {probe} is a file, so no folder can be made under it")
    # access() says yes to root everywhere, /proc included: try instead.
    try:
        tempfile.TemporaryDirectory(prefix=".orthocontact-probe-", dir=probe).cleanup()
    except OSError as e:
        raise InputError(f"{option} {out}: {probe} is not writable ({e.strerror})") from None


def check_output_file(out: Path, option: str = "--out") -> None:
    """Raises InputError, naming the user's path, unless a file can be written
    at `out` (in an existing, writable folder)."""
    out = Path(out)
    if out.is_dir():
        raise InputError(f"{option} {out}: is a folder; expected a file name")
    if not out.parent.is_dir():
        raise InputError(f"{option} {out}: the folder {out.parent} does not exist")
    try:
        tempfile.TemporaryDirectory(prefix=".orthocontact-probe-", dir=out.parent).cleanup()
    except OSError as e:
        raise InputError(f"{option} {out}: {out.parent} is not writable ({e.strerror})") from None


@contextlib.contextmanager
def staged_output(out: Path):
    """A scratch folder beside `out`; its files move into `out` only if the
    block completes, so a failure or an interrupt leaves nothing behind: not
    the scratch folder, nor parent folders made for it, nor a half-written `out`."""
    out = Path(out)
    made = []
    for parent in reversed(out.parents):
        if not parent.exists():
            parent.mkdir()
            made.append(parent)
    stage = Path(tempfile.mkdtemp(prefix=f".{out.name}.partial-", dir=out.parent))
    try:
        yield stage
        # An interrupt that a finalizer swallowed ("Exception ignored in
        # __del__") still means the user asked to stop: commit nothing.
        if _interrupted:
            raise KeyboardInterrupt
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        for parent in reversed(made):
            with contextlib.suppress(OSError):
                parent.rmdir()
        raise
    out.mkdir(exist_ok=True)
    for item in stage.iterdir():
        target = out / item.name
        if target.is_dir() and not target.is_symlink():
            shutil.rmtree(target)
        os.replace(item, target)
    shutil.rmtree(stage, ignore_errors=True)


def _fmu_for(sc, args) -> str:
    """The scenario's own FMU if it names one, else the installed FMU of the
    FMI version asked for with --fmi."""
    from .fmu import find_fmu
    return sc.fmu or str(find_fmu(fmi_version=args.fmi))


_warnings: list[str] = []


def warn(line: str) -> None:
    """One warning line on stderr; --strict turns any into exit status 1."""
    _warnings.append(line)
    print(f"orthocontact: warning: {line}", file=sys.stderr, flush=True)


def load_scenario(path):
    """The scenario file, its unusual values said as warnings."""
    sc = load(path)
    for line in sc.warnings:
        warn(line)
    return sc


def _run_scenario(sc, out: Path, workers, fmu_path, master="auto", progress=True, draw=None,
                  dask=None) -> dict:
    from . import report, sweep
    from .fmu import fmi_version_of
    if sc.kind == "sweep":
        res = sweep.run_sweep(sc, workers, progress, fmu_path, master, dask)
        summary = report.sweep_outputs(sc, res, out, draw)
    else:
        res = sweep.run_step_study(sc, workers, progress, fmu_path, master, dask)
        summary = report.step_study_outputs(sc, res, out, draw)
    line = res.warning(sc)
    if line:
        warn(line)
    summary["fmi_version"] = fmi_version_of(fmu_path)
    report.write_json(out / "summary.json", summary)
    return summary


def packaged_scenarios() -> Path:
    here = Path(__file__).with_name("scenarios")
    if here.is_dir():
        return here
    repo = Path(__file__).resolve().parents[2] / "scenarios"
    return repo


def cmd_run(args) -> int:
    from .figures import FigureDrawer
    sc = load_scenario(args.scenario)
    with staged_output(args.out) as stage, _dask_for(args) as dask, \
            FigureDrawer(args.workers or _default_workers()) as draw:
        summary = _run_scenario(sc, stage, args.workers, _fmu_for(sc, args), args.master, draw=draw,
                                dask=dask)
    print(json.dumps({k: summary[k] for k in summary if k in ("scenario", "extremum", "max_deviation_deg",
                                                             "drive_mean_N", "rules")}, indent=1))
    print(f"wrote {args.out}/summary.json")
    return 0


def cmd_reproduce(args) -> int:
    from . import report
    from .figures import FigureDrawer
    folder = Path(args.scenarios) if args.scenarios else packaged_scenarios()
    files = sorted(folder.glob("*.toml"))
    if not files:
        raise InputError(f"{folder}: expected scenario files (*.toml), found none")
    scenarios = [load_scenario(f) for f in files]  # all validated before anything runs
    t0 = time.time()
    runs, rows = [], []
    with staged_output(args.out) as stage:
        # The figures are drawn in worker processes while the rig runs on.
        with _dask_for(args) as dask, FigureDrawer(args.workers or _default_workers()) as draw:
            # The rig's hidden assumptions, on the calibrated experiment: a
            # job of its own beside the sweeps.
            sens = None
            for sc in scenarios:
                if sc.kind == "sweep" and sc.closed_form == "mat" and "extremum_phi_deg" in sc.paper:
                    (stage / "sensitivity").mkdir()
                    sens = draw.submit(_sensitivity_job, sc, _fmu_for(sc, args), args.master,
                                       stage / "sensitivity")
                    break
            for sc in scenarios:
                (stage / sc.name).mkdir()
                summary = _run_scenario(sc, stage / sc.name, args.workers, _fmu_for(sc, args),
                                        args.master, draw=draw, dask=dask)
                runs.append((sc, summary))
                rows += report.paper_rows(sc, summary)
            sens = sens.result() if sens is not None else None
            if sens is not None and sens["checks"]["warning"]:
                warn(sens["checks"]["warning"])
        rows += report.calibration_rows()
        report.write_json(stage / "summary.json", {"rows": rows, "scenarios": {sc.name: s for sc, s in runs}})
        text = report.reproduction_report(stage, runs, rows, time.time() - t0, sens)
    print(text.split("## Scenarios")[0].rstrip())
    print(f"\nwrote {args.out}/report.md in {time.time() - t0:.1f} s")
    return 0 if all(r["match"] for r in rows) else 1


def cmd_identify(args) -> int:
    from . import identify
    data = identify.load_data(args.data)
    for line in data.warnings:
        warn(line)
    with staged_output(args.out) as stage:
        from .fmu import find_fmu
        result = identify.run(data, stage, validate=not args.no_validate, workers=args.workers,
                              fmu_path=str(find_fmu(fmi_version=args.fmi)))
    print(identify.summary_text(result))
    if result.validation and result.validation.get("warning"):
        warn(result.validation["warning"])
    print(f"wrote {args.out}/identified.json")
    return 0


def _sensitivity_job(sc, fmu_path, master, out) -> dict:
    """sensitivity.run and its files, in one process (a figure worker's)."""
    from . import sensitivity
    res = sensitivity.run(sc, 1, fmu_path, master, progress=False)
    return sensitivity.write_outputs(res, sc, out)


def cmd_sensitivity(args) -> int:
    from . import sensitivity
    from .figures import FigureDrawer
    sc = load_scenario(args.scenario)
    with staged_output(args.out) as stage, _dask_for(args) as dask, \
            FigureDrawer(1) as draw:
        res = sensitivity.run(sc, args.workers or _default_workers(), _fmu_for(sc, args), args.master,
                              dask=dask)
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
    from . import uq
    est = uq.load_estimates(args.identification)
    sc = load_scenario(args.scenario)
    uq.check_geometry(sc, est)  # before any work
    with staged_output(args.out) as stage:
        res = uq.propagate(est, sc, args.samples, args.seed, None,
                           scheduler=None if args.scheduler == "none" else args.scheduler,
                           workers=args.workers or _default_workers(), step_s=args.step_s,
                           chunk_runs=args.chunk_runs)
        summary = uq.write_outputs(res, est, sc, args.seed, stage)
    if summary["checks"]["warning"]:
        warn(summary["checks"]["warning"])
    chk = summary["step_check"]
    if not chk["max_abs_difference_deg"] <= uq.STEP_CHECK_WARN_DEG:
        print(f"orthocontact: warning: at the estimates, phi at the uq step {chk['uq_step_s']:g} s "
              f"differs from the scenario's step {chk['scenario_step_s']:g} s by "
              f"{chk['max_abs_difference_deg']:.3g} deg; choose --step-s", file=sys.stderr)
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
    from .cluster import DaskRunner
    return DaskRunner(args.scheduler, args.workers or _default_workers())


def _default_workers() -> int:
    from .sweep import default_workers
    return default_workers()


def _positive_int(what):
    def parse(text):
        try:
            n = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a whole number of {what} >= 1, got {text!r}")
        if n < 1:
            raise argparse.ArgumentTypeError(f"expected a whole number of {what} >= 1, got {n}")
        return n
    return parse


def _positive_float(text):
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number > 0, got {text!r}")
    if not (x > 0 and x < float("inf")):
        raise argparse.ArgumentTypeError(f"expected a finite number > 0, got {text}")
    return x


def cmd_ssp(args) -> int:
    from .ssp import write_ssp
    sc = load_scenario(args.scenario)
    if sc.kind != "sweep":
        raise InputError(f"{args.scenario}: kind: expected a sweep scenario for an SSP, got {sc.kind!r}")
    path = write_ssp(sc, args.angle, args.out)
    print(f"wrote {path}: rig + contact at {args.angle:g} deg "
          f"(run it with libcosim: CosimExecution.from_ssp_file)")
    return 0


_workers = _positive_int("worker processes")


def _version_text() -> str:
    from . import __version__
    from .fmu import find_fmu, fmi_version_of
    lines = [f"orthocontact {__version__}"]
    for v in (2, 3):
        try:
            path = find_fmu(fmi_version=v)
            lines.append(f"  FMI {fmi_version_of(path)}.0 FMU: {path}")
        except (FileNotFoundError, OSError, ValueError) as e:
            lines.append(f"  FMI {v}.0 FMU: not found ({e})")
    return "\n".join(lines)


class _Version(argparse.Action):
    def __init__(self, option_strings, dest, **kw):
        super().__init__(option_strings, dest, nargs=0, help=kw.get("help"))

    def __call__(self, parser, namespace, values, option_string=None):
        print(_version_text())
        parser.exit(0)


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="orthocontact",
        description="The coupled orthotropic adhesion-friction contact law (Konyukhov & "
                    "Schweizerhof 2007) as FMI 2.0/3.0 FMUs: run the paper's carriage/block rig "
                    "on scenario files, reproduce the paper, identify parameters from "
                    "measurements.",
        epilog="Exit status: 0 success, 1 a result that does not match the paper (or, with "
               "--strict, any warning), 2 bad input "
               "(one line naming the file or option), 130 interrupted.  Angles in scenario and "
               "data files are in degrees, counterclockwise from the driving axis X1.")
    ap.add_argument("--version", action=_Version, help="print the package version and the "
                    "installed FMUs (FMI 2.0 and 3.0), then exit")
    sub = ap.add_subparsers(dest="cmd", required=True, metavar="COMMAND")

    def strict(p):
        p.add_argument("--strict", action="store_true",
                       help="exit with status 1 if any warning was printed (an implausible input, a "
                            "rig run that is not steady sliding); the results are written all the same")

    def common(p, out_help, scheduler=True):
        p.add_argument("--out", required=True, type=Path, metavar="DIR", help=out_help)
        p.add_argument("--workers", type=_workers, default=None, metavar="N",
                       help="worker processes for sweeps (default: the number of cores, at most 8)")
        p.add_argument("--fmi", type=int, choices=(2, 3), default=2,
                       help="FMI version of the contact FMU the harness runs: 2 (default) or 3; "
                            "both give the same results bit for bit")
        p.add_argument("--master", choices=("auto", "c", "fmpy"), default="auto",
                       help="who runs the rig loop: c, the compiled master (FMI 2.0 FMUs, about "
                            "25-55x faster), fmpy, the Python harness, or auto (default: c where "
                            "it applies); both give the same angles")
        strict(p)
        if scheduler:
            p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                           help="run the sweeps on Dask: local (a LocalCluster of --workers "
                                "processes) or tcp://HOST:PORT (an existing scheduler); default: "
                                "local processes, which start faster for sweeps of this size")

    r = sub.add_parser("run", help="run one scenario file (a sweep over the mat/axis angle in "
                                   "degrees, or a step-size study)",
                       description="Run one scenario file and write summary.json, CSV tables, "
                                   "PNG figures into DIR.")
    r.add_argument("scenario", metavar="SCENARIO", help="scenario file (TOML; format in "
                   "scenarios/README.md); angles in degrees, forces in N, lengths in m")
    common(r, "output folder: created if missing, files replaced; written only when the run "
              "completes")
    r.set_defaults(func=cmd_run)
    p = sub.add_parser("reproduce", help="run every paper scenario and write report.md",
                       description="Run every scenario of the paper and write report.md beside "
                                   "one folder per scenario into DIR.")
    common(p, "output folder for report.md, summary.json and one folder per scenario; written "
              "only when everything completes")
    p.add_argument("--scenarios", default=None, metavar="FOLDER",
                   help="folder of scenario files (*.toml; default: the packaged ones)")
    p.set_defaults(func=cmd_reproduce)
    i = sub.add_parser("identify", help="identify mu1, mu2, the stiffness ratio and the absolute "
                                        "stiffness [N/m] from measurements",
                       description="Identify the law's parameters from a measurement folder (mu1, "
                                   "mu2 [-], eps1/eps2 [-], eps1, eps2 [N/m]) and write "
                                   "identified.json, identified.md, fit.png into DIR.")
    i.add_argument("data", type=Path, metavar="DATA_DIR",
                   help="measurement folder: rig.toml and any of forces.csv (alpha_deg,force_N), "
                        "angles.csv (alpha_deg,phi_deg), ramp.csv (x1_m,force_N); angles in "
                        "degrees, forces in N, travel in m")
    common(i, "output folder: created if missing; written only when the fit completes", scheduler=False)
    i.add_argument("--no-validate", action="store_true",
                   help="skip the validation runs of the identified parameters on the FMU")
    i.set_defaults(func=cmd_identify)
    s = sub.add_parser("ssp", help="write the experiment at one angle as an SSP 1.0 package "
                                   "(rig FMU + contact FMU) for any SSP-capable simulator",
                       description="Write SystemStructure.ssd and both FMI 2.0 FMUs (CarriageBlock, "
                                   "OrthotropicContact) with the scenario's parameters as an .ssp.")
    s.add_argument("scenario", metavar="SCENARIO", help="sweep scenario file (TOML); angles in "
                   "degrees, forces in N, lengths in m")
    s.add_argument("--angle", type=float, required=True, metavar="DEG",
                   help="the swept angle [deg] (the mat angle for the experiment's scenarios)")
    s.add_argument("--out", type=Path, required=True, metavar="FILE.ssp",
                   help="the package to write (replaced if it exists)")
    s.set_defaults(func=cmd_ssp)
    v = sub.add_parser("sensitivity", help="how the rig's unmeasured strip friction and viscosity, "
                                           "and the velocity, move the peak angle and the identified "
                                           "eps1/eps2",
                       description="For a mat scenario: the peak |phi| [deg] against the Teflon "
                                   "strip's friction mu_strip (0-0.2) at 0.125 and 0.244 m/s (rig and "
                                   "closed form), the eps1/eps2 the paper's calibration would return "
                                   "for each, and for a viscous strip c_strip [N s/m] the peak at "
                                   "0.244 m/s after calibrating at 0.125 m/s; CSV, JSON, PNG into DIR.")
    v.add_argument("scenario", metavar="SCENARIO", help="a sweep scenario with the experiment's "
                   "geometry (closed_form = \"mat\"), e.g. scenarios/mat_aged.toml")
    common(v, "output folder: created if missing; written only when everything completes")
    v.set_defaults(func=cmd_sensitivity)
    u = sub.add_parser("uq", help="propagate an identification's uncertainty to the predicted "
                                  "trajectory angle over a scenario's angles (Dask)",
                       description="Draw parameter sets from identified.json's estimates and "
                                   "covariance (only mu, eps > 0), run the rig over the scenario's "
                                   "angles for each (compiled master, on Dask), and write the "
                                   "predictive bands of phi [deg] and of the driving force [N] "
                                   "(median, 2.5 and 97.5 %) as uq_bands.csv, uq.json, uq.png, "
                                   "and the drawn sets as samples.csv.")
    u.add_argument("identification", type=Path, metavar="IDENTIFICATION.json",
                   help="identified.json written by `orthocontact identify`")
    u.add_argument("--scenario", required=True, type=Path, metavar="SCENARIO",
                   help="sweep scenario file (TOML) giving the rig and the angles [deg]; its rule "
                        "must be the identification's")
    u.add_argument("--samples", required=True, type=_positive_int("parameter sets"), metavar="N",
                   help="parameter sets to draw; rig runs = N x the scenario's angles")
    u.add_argument("--out", required=True, type=Path, metavar="DIR",
                   help="output folder: created if missing; written only when all runs complete")
    u.add_argument("--seed", type=int, default=0, metavar="S",
                   help="seed of the draws (default 0): the same seed gives the same files, "
                        "serial or on any cluster")
    u.add_argument("--scheduler", default="local", metavar="ADDRESS",
                   help="where the runs go: local (default: a Dask LocalCluster, --workers "
                        "processes), tcp://HOST:PORT (an existing Dask scheduler), or none (this "
                        "process, no Dask)")
    u.add_argument("--workers", type=_workers, default=None, metavar="N",
                   help="worker processes of the local cluster (default: the number of cores, at "
                        "most 8)")
    u.add_argument("--step-s", type=_positive_float, default=None, metavar="SECONDS",
                   help="communication step of the rig [s] (default: 0.004 for the implicit rules, "
                        "step-size independent; the scenario's for eq20); checked against the "
                        "scenario's step at the estimates")
    u.add_argument("--chunk-runs", type=_positive_int("runs"), default=1000, metavar="RUNS",
                   help="rig runs per task sent to a worker (default 1000)")
    strict(u)
    u.set_defaults(func=cmd_uq)
    return ap


_interrupted = False


def _interrupt(signum, frame):
    # Remembered as well as raised: Python turns a KeyboardInterrupt raised
    # inside a finalizer into a warning and runs on, and the run must still
    # end as interrupted.
    global _interrupted
    _interrupted = True
    raise KeyboardInterrupt


def _install_signal_handlers():
    global _interrupted
    _interrupted = False
    with contextlib.suppress(ValueError):  # not in the main thread: leave them
        # SIGTERM (a job runner, an IDE's stop button) ends a run like Ctrl-C.
        signal.signal(signal.SIGINT, _interrupt)
        signal.signal(signal.SIGTERM, _interrupt)


def _quiet_interrupts(unraisable):
    """sys.unraisablehook of the command: an interrupt raised inside a
    finalizer is already remembered (_interrupt) and ends the run as
    interrupted; its traceback would only bury the one line the user gets."""
    if issubclass(unraisable.exc_type, KeyboardInterrupt) and _interrupted:
        return
    sys.__unraisablehook__(unraisable)


def main(argv=None) -> int:
    """Runs the command line `argv` (default: sys.argv[1:]); returns the exit status."""
    args = build_parser().parse_args(argv)
    _install_signal_handlers()
    _warnings.clear()
    out = getattr(args, "out", None)
    try:
        if getattr(args, "master", None) == "c" and getattr(args, "fmi", 2) == 3:
            raise InputError("--master c runs FMI 2.0 FMUs; with --fmi 3 use --master fmpy "
                             "(or auto)")
        if getattr(args, "scheduler", None) not in (None, "none"):
            from .cluster import check_address
            check_address(args.scheduler)
        if out is not None and args.cmd == "ssp":
            check_output_file(out)
        elif out is not None:
            check_output_folder(out)
        status = args.func(args)
        if _interrupted:
            raise KeyboardInterrupt
        if status == 0 and _warnings and getattr(args, "strict", False):
            print(f"orthocontact: --strict: {len(_warnings)} warning(s); exit status 1", file=sys.stderr)
            return 1
        return status
    except KeyboardInterrupt:
        print(f"orthocontact: interrupted; nothing written to {out}", file=sys.stderr)
        return 130
    except (ScenarioError, InputError) as e:
        print(f"orthocontact: error: {e}", file=sys.stderr)
        return 2
    except FileNotFoundError as e:  # e.g. the FMU is missing
        print(f"orthocontact: error: {e}", file=sys.stderr)
        return 2


def entry() -> None:
    """The console command: main(), then the exit.  An interrupted run leaves
    at once with 130: its workers are already stopped and its output removed,
    and the interpreter's shutdown would restore the default signal handlers,
    so that a second Ctrl-C during it would end the process by the signal
    instead of with the status documented above."""
    sys.unraisablehook = _quiet_interrupts
    status = main()
    if status == 130:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(130)
    sys.exit(status)


if __name__ == "__main__":
    entry()
