"""The `orthocontact` command.

  orthocontact run SCENARIO --out DIR        one scenario file
  orthocontact reproduce --out DIR           every paper scenario + report.md
  orthocontact identify DATA_DIR --out DIR   parameter identification

Exit status: 0 success, 1 a result that does not match the paper (or, with
--strict, any warning: an implausible input, a rig run that is not steady
sliding), 2 bad input (one line on stderr naming the file, option, key or row, and what was
expected), 130 interrupted (Ctrl-C, SIGINT or SIGTERM).  Arguments and the
output folder are checked before any work; the output folder is written all at
once or not at all."""
from __future__ import annotations

import os
import sys

from ..errors import InputError
from ..experiment.scenario import ScenarioError
from .interrupts import install_signal_handlers, interrupted, quiet_interrupts
from .output import check_output_file, check_output_folder, forget_warnings, warnings_said
from .parser import build_parser

__all__ = ["main", "entry", "InputError"]


def main(argv=None) -> int:
    """Runs the command line `argv` (default: sys.argv[1:]); returns the exit status."""
    args = build_parser().parse_args(argv)
    install_signal_handlers()
    forget_warnings()
    out = getattr(args, "out", None)
    try:
        if getattr(args, "master", None) == "c" and getattr(args, "fmi", 2) == 3:
            raise InputError("--master c runs FMI 2.0 FMUs; with --fmi 3 use --master fmpy "
                             "(or auto)")
        if getattr(args, "scheduler", None) not in (None, "none"):
            from ..runs.cluster import check_address
            check_address(args.scheduler)
        if out is not None and args.cmd == "ssp":
            check_output_file(out)
        elif out is not None:
            check_output_folder(out)
        status = args.func(args)
        if interrupted():
            raise KeyboardInterrupt
        if status == 0 and warnings_said() and getattr(args, "strict", False):
            print(f"orthocontact: --strict: {warnings_said()} warning(s); exit status 1", file=sys.stderr)
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
    sys.unraisablehook = quiet_interrupts
    status = main()
    if status == 130:
        from ..fmu.files import remove_unzipped
        remove_unzipped()  # os._exit skips atexit
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(130)
    sys.exit(status)


if __name__ == "__main__":
    entry()
