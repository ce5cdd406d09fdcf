"""A command's interrupts: Ctrl-C, SIGINT and SIGTERM end a command as interrupted
(exit 130, nothing written), even when the signal lands in a finalizer; once
the command has begun to commit its results, an interrupt is noted, not
raised, so that a complete output folder is reported as written (exit 0 or
the command's own status), never as "nothing written"."""
from __future__ import annotations

import contextlib
import logging
import signal
import sys

_interrupted = False
_held = False       # the commit has begun: an interrupt no longer raises
_written = None     # the output folder the command committed, once it has


def _interrupt(signum, frame):
    # Remembered as well as raised: Python turns a KeyboardInterrupt raised
    # inside a finalizer into a warning and runs on, and the run must still
    # end as interrupted.
    global _interrupted
    _interrupted = True
    if not _held:
        raise KeyboardInterrupt


def install_signal_handlers():
    global _interrupted, _held, _written
    _interrupted, _held, _written = False, False, None
    with contextlib.suppress(ValueError):  # not in the main thread: leave them
        # SIGTERM (a job runner, an IDE's stop button) ends a run like Ctrl-C.
        signal.signal(signal.SIGINT, _interrupt)
        signal.signal(signal.SIGTERM, _interrupt)


def interrupted() -> bool:
    """Whether an interrupt arrived since install_signal_handlers."""
    return _interrupted


def hold_interrupts() -> None:
    """From here on an interrupt is noted, not raised: the command is about
    to commit its results, and a commit cut in half would leave a folder of
    two runs.  Call it before the last interrupted() check ahead of the
    commit, so that an earlier interrupt still stops the command."""
    global _held
    _held = True


def results_written(out) -> None:
    """The command's results are all in `out`: an interrupt after this does
    not make it 'interrupted; nothing written'."""
    global _written
    _written = out


def written():
    """The output folder the command committed, or None."""
    return _written


def quiet_interrupts(unraisable):
    """sys.unraisablehook of the command: an interrupt raised inside a
    finalizer is already remembered (_interrupt) and ends the run as
    interrupted; its traceback would only bury the one line the user gets."""
    if issubclass(unraisable.exc_type, KeyboardInterrupt) and _interrupted:
        return
    sys.__unraisablehook__(unraisable)


def quiet_leftovers() -> None:
    """After an interrupt: a Dask cluster cut off while it started leaves
    tasks whose errors its event loop logs as the interpreter ends ("Task
    exception was never retrieved ... Nanny failed to start"); the command
    has ended and said so, and those tracebacks would only bury its line."""
    for name in ("asyncio", "distributed", "tornado"):
        logging.getLogger(name).disabled = True
