"""The `orthocontact` command.

  orthocontact run SCENARIO --out DIR             one scenario file
  orthocontact reproduce --out DIR                every paper scenario + report.md
  orthocontact identify DATA_DIR --out DIR        parameter identification
  orthocontact export IDENTIFIED --out DIR        calibrated FMUs, SSV and SSP
  orthocontact uq IDENTIFIED --scenario SCENARIO --samples N --out DIR
                                                  the identification's uncertainty
  orthocontact ssp SCENARIO --angle DEG --out FILE.ssp   the experiment as an SSP
  orthocontact sensitivity --out DIR              the rig's unmeasured strip terms
  orthocontact design --runs N --out DIR          plan the lab's runs (experiment design)
(`orthocontact COMMAND --help`: each command's arguments.)

Exit status:
  0    success
  1    a result that does not match the paper (or, with --strict, any
       warning: an implausible input, a rig run that is not steady sliding)
  2    bad input: one line on stderr naming the file, option, key or row, and
       what was expected (a file with several problems: one line each)
  74   (sysexits.h's EX_IOERR) the system refused a read or a write -- the
       disk is full, permission denied, a read-only file system: one line
       naming what failed, the system's reason and the path; the results'
       scratch folder is removed, as on any failure
  130  interrupted (Ctrl-C, SIGINT or SIGTERM) before the output was written
Arguments and the output folder are checked before any work; the output
folder is written all at once or not at all.
A closed standard output (`orthocontact ... | head -1`) is no error: the rest
of the text is dropped and the command ends as it would have.  Python and
numpy warnings never reach the terminal as such: numpy's floating-point ones
(nan, overflow: the results they concern are checked where they are used)
are dropped, any other is one `orthocontact: warning:` line."""
from __future__ import annotations

import os
import re
import sys
import warnings
from pathlib import Path

from ..errors import InputError
from ..output import check_output_file, check_output_folder, check_owner, forget_warnings, warn, warnings_said
from ..runtime import install_signal_handlers, interrupted, quiet_interrupts, quiet_leftovers, written
from ..textfiles import files_read
from .parser import build_parser

__all__ = ["main", "entry", "InputError", "OS_ERROR"]

OS_ERROR = 74   # the system refused a read or a write (sysexits.h: EX_IOERR)
STDOUT = "standard output"
# numpy's floating-point and empty/all-nan reductions' RuntimeWarnings
NUMPY_NOISE = re.compile(r"encountered|Mean of empty slice|Degrees of freedom <= 0")


def main(argv=None) -> int:
    """Runs the command line `argv` (default: sys.argv[1:]); returns the exit status."""
    _warned.clear()
    with warnings.catch_warnings():   # the command's own way of saying them, undone after
        warnings.showwarning = show_warning
        return run_command(argv)


def show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """warnings.showwarning of the command: numpy's floating-point noise
    dropped, any other warning one line (no source line), once per text."""
    text = (str(message).strip().splitlines() or [category.__name__])[0]
    if issubclass(category, RuntimeWarning) and NUMPY_NOISE.search(text):
        return
    if (category, text) in _warned:
        return
    _warned.add((category, text))
    warn(f"{text} ({category.__name__} in {Path(filename).stem})")


_warned: set = set()


def os_error_line(e: OSError, out) -> str:
    """The one line for an error the system raised: what failed, the
    system's reason, the path (the user's --out for a file of the results,
    whose scratch folder's name means nothing to them)."""
    path, results = e.filename, False
    if path == STDOUT:
        return f"orthocontact: error: cannot write the command's text: {e.strerror} ({STDOUT})"
    if out is not None:
        out = Path(out)
        if path is None:   # a write through an open file: the results are the only ones
            path, results = out, True
        else:
            try:
                rel = Path(path).absolute().relative_to(out.absolute().parent).parts
            except ValueError:
                rel = ()
            scratch = f".{out.name}.partial-"
            if rel and (rel[0] == out.name or rel[0].startswith(scratch)):
                # the scratch folder's (beside --out or in it) named as in --out
                path, results = out.joinpath(*(r for r in rel[1:] if not r.startswith(scratch))), True
            elif out.absolute().is_relative_to(Path(path).absolute()):
                results = True   # the folder --out is in (checked before any work)
    what = "cannot write the results" if results else "cannot read or write a file"
    return f"orthocontact: error: {what}: {e.strerror or e} ({path})"


def run_command(argv=None) -> int:
    """main() without its warnings' setting."""
    args = build_parser().parse_args(argv)
    install_signal_handlers()
    forget_warnings()
    out = getattr(args, "out", None)
    try:
        if getattr(args, "master", None) == "c" and getattr(args, "fmi", 2) == 3:
            raise InputError("--master c runs FMI 2.0 FMUs; with --fmi 3 use --master fmpy "
                             "(or auto)")
        if getattr(args, "scheduler", None) not in (None, "none"):
            from ..runs import check_address
            check_address(args.scheduler)
        # What the command reads (the paths its arguments name; every file
        # read through textfiles once it runs) its output may not hold.
        reads = [Path(v) for v in (getattr(args, name) for name in getattr(args, "reads", ()))
                 if v is not None]
        if out is not None and args.cmd == "ssp":
            check_output_file(out, reads=reads, force=args.force)
        elif out is not None:
            check_output_folder(out)
            check_owner(out, args.cmd, args.force, reads)
        with files_read():
            status = args.func(args)
        if interrupted() and written() is None:
            raise KeyboardInterrupt
        if interrupted():  # it came after the commit: the results stand
            print(f"orthocontact: interrupted after writing {written()}; the results there are "
                  "complete", file=sys.stderr)
        if status == 0 and warnings_said() and getattr(args, "strict", False):
            print(f"orthocontact: --strict: {warnings_said()} warning(s); exit status 1", file=sys.stderr)
            return 1
        return status
    except KeyboardInterrupt:
        quiet_leftovers()
        print(f"orthocontact: interrupted; nothing written to {out}", file=sys.stderr)
        return 130
    except InputError as e:   # a scenario's (ScenarioError) too: one hierarchy
        for line in e.lines or [""]:   # each problem of a file, one line each
            print(f"orthocontact: error: {line}", file=sys.stderr)
        return 2
    except FileNotFoundError as e:  # e.g. the FMU is missing
        print(f"orthocontact: error: {e}", file=sys.stderr)
        return 2
    except OSError as e:   # disk full, permission denied, a read-only file system
        print(os_error_line(e, out), file=sys.stderr)
        return OS_ERROR


class ClosedPipeSafe:
    """sys.stdout of the command: a reader that went away (`| head -1`) ends
    the text, not the command (the rest goes to the null device, so that no
    BrokenPipeError comes from a print or from the interpreter's last flush);
    any other error writing it names standard output."""

    def __init__(self, stream):
        self._stream = stream

    def write(self, text):
        return self._guard(self._stream.write, text, len(text))

    def flush(self):
        return self._guard(self._stream.flush)

    def _guard(self, fn, *args):
        value = args[1] if len(args) > 1 else None
        try:
            return fn(*args[:1])
        except BrokenPipeError:
            self._drop()
            return value
        except OSError as e:   # said once (main, entry); the rest is dropped
            self._drop()
            raise OSError(e.errno, e.strerror, STDOUT) from None

    def _drop(self):
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, self._stream.fileno())
        os.close(null)

    def __getattr__(self, name):
        return getattr(self._stream, name)


def entry() -> None:
    """The console command: main(), then the exit.  An interrupted run leaves
    at once with 130: its workers are already stopped and its output removed,
    and the interpreter's shutdown would restore the default signal handlers,
    so that a second Ctrl-C during it would end the process by the signal
    instead of with the status documented above."""
    sys.unraisablehook = quiet_interrupts
    sys.stdout = ClosedPipeSafe(sys.stdout)
    try:
        status = main()
    except SystemExit as e:   # argparse's: --help, --version, a bad argument (said already)
        status = e.code if isinstance(e.code, int) else int(e.code is not None)
    except OSError as e:      # writing argparse's --help or --version
        print(os_error_line(e, None), file=sys.stderr)
        status = OS_ERROR
    try:
        sys.stdout.flush()    # here, not at the interpreter's exit, where an error has no line
    except OSError as e:
        print(os_error_line(e, None), file=sys.stderr)
        status = status or OS_ERROR
    if status == 130:
        from ..runtime import remove_unzipped
        remove_unzipped()  # os._exit skips atexit
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(130)
    sys.exit(status)


if __name__ == "__main__":
    entry()
