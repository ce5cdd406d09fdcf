"""The `orthocontact` command.

  orthocontact run SCENARIO --out DIR        one scenario file
  orthocontact reproduce --out DIR           every paper scenario + report.md
  orthocontact identify DATA_DIR --out DIR   parameter identification

Exit status: 0 success, 1 a result that does not match the paper, 2 bad
input (one line on stderr naming the file, the key or row, and what was
expected).  Output folders are written all at once or not at all.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

from .scenarios import ScenarioError, load


class InputError(Exception):
    """Bad user input: str(e) is the one-line message."""


@contextlib.contextmanager
def staged_output(out: Path):
    """A scratch folder beside `out`; its files move into `out` only if the
    block completes, so a failure leaves nothing half-written in `out`."""
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=f".{out.name}.partial-", dir=out.parent))
    try:
        yield stage
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    out.mkdir(parents=True, exist_ok=True)
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


def _run_scenario(sc, out: Path, workers, fmu_path, progress=True) -> dict:
    from . import report, sweep
    from .fmu import fmi_version_of
    if sc.kind == "sweep":
        summary = report.sweep_outputs(sc, sweep.run_sweep(sc, workers, progress, fmu_path), out)
    else:
        summary = report.step_study_outputs(sc, sweep.run_step_study(sc, workers, progress, fmu_path),
                                            out)
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
    sc = load(args.scenario)
    with staged_output(args.out) as stage:
        summary = _run_scenario(sc, stage, args.workers, _fmu_for(sc, args))
    print(json.dumps({k: summary[k] for k in summary if k in ("scenario", "extremum", "max_deviation_deg",
                                                             "drive_mean_N", "rules")}, indent=1))
    print(f"wrote {args.out}/summary.json")
    return 0


def cmd_reproduce(args) -> int:
    from . import report
    folder = Path(args.scenarios) if args.scenarios else packaged_scenarios()
    files = sorted(folder.glob("*.toml"))
    if not files:
        raise InputError(f"{folder}: expected scenario files (*.toml), found none")
    scenarios = [load(f) for f in files]  # all validated before anything runs
    t0 = time.time()
    runs, rows = [], []
    with staged_output(args.out) as stage:
        for sc in scenarios:
            (stage / sc.name).mkdir()
            summary = _run_scenario(sc, stage / sc.name, args.workers, _fmu_for(sc, args))
            runs.append((sc, summary))
            rows += report.paper_rows(sc, summary)
        rows += report.calibration_rows()
        report.write_json(stage / "summary.json", {"rows": rows, "scenarios": {sc.name: s for sc, s in runs}})
        text = report.reproduction_report(stage, runs, rows, time.time() - t0)
    print(text.split("## Scenarios")[0].rstrip())
    print(f"\nwrote {args.out}/report.md")
    return 0 if all(r["match"] for r in rows) else 1


def cmd_identify(args) -> int:
    from . import identify
    data = identify.load_data(args.data)
    with staged_output(args.out) as stage:
        from .fmu import find_fmu
        result = identify.run(data, stage, validate=not args.no_validate, workers=args.workers,
                              fmu_path=str(find_fmu(fmi_version=args.fmi)))
    print(identify.summary_text(result))
    print(f"wrote {args.out}/identified.json")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="orthocontact", description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run", help="run one scenario file")
    r.add_argument("scenario")
    r.add_argument("--out", required=True, type=Path)
    r.add_argument("--workers", type=int, default=None, help="worker processes (default: cores)")
    r.add_argument("--fmi", type=int, choices=(2, 3), default=2,
                   help="FMI version of the contact FMU the harness runs: 2 (default) or 3; "
                        "both give the same results bit for bit")
    r.set_defaults(func=cmd_run)
    p = sub.add_parser("reproduce", help="run every paper scenario and write report.md")
    p.add_argument("--out", required=True, type=Path)
    p.add_argument("--workers", type=int, default=None)
    p.add_argument("--scenarios", default=None, help="folder of scenario files (default: the packaged ones)")
    p.add_argument("--fmi", type=int, choices=(2, 3), default=2,
                   help="FMI version of the contact FMU the harness runs: 2 (default) or 3; "
                        "both give the same results bit for bit")
    p.set_defaults(func=cmd_reproduce)
    i = sub.add_parser("identify", help="identify mu1, mu2, eps ratio and stiffness from measurements")
    i.add_argument("data", type=Path)
    i.add_argument("--out", required=True, type=Path)
    i.add_argument("--workers", type=int, default=None)
    i.add_argument("--no-validate", action="store_true", help="skip the FMU validation runs")
    i.add_argument("--fmi", type=int, choices=(2, 3), default=2,
                   help="FMI version of the contact FMU the harness runs: 2 (default) or 3; "
                        "both give the same results bit for bit")
    i.set_defaults(func=cmd_identify)
    args = ap.parse_args(argv)
    if getattr(args, "workers", None) is not None and args.workers < 1:
        ap.error("--workers must be >= 1")
    try:
        return args.func(args)
    except (ScenarioError, InputError) as e:
        print(f"orthocontact: error: {e}", file=sys.stderr)
        return 2
    except FileNotFoundError as e:  # e.g. the FMU is missing
        print(f"orthocontact: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
