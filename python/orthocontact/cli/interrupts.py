"""Interrupts: Ctrl-C, SIGINT and SIGTERM end a command as interrupted
(exit 130, nothing written), even when the signal lands in a finalizer."""
from __future__ import annotations

import contextlib
import signal
import sys

_interrupted = False


def _interrupt(signum, frame):
    # Remembered as well as raised: Python turns a KeyboardInterrupt raised
    # inside a finalizer into a warning and runs on, and the run must still
    # end as interrupted.
    global _interrupted
    _interrupted = True
    raise KeyboardInterrupt


def install_signal_handlers():
    global _interrupted
    _interrupted = False
    with contextlib.suppress(ValueError):  # not in the main thread: leave them
        # SIGTERM (a job runner, an IDE's stop button) ends a run like Ctrl-C.
        signal.signal(signal.SIGINT, _interrupt)
        signal.signal(signal.SIGTERM, _interrupt)


def interrupted() -> bool:
    """Whether an interrupt arrived since install_signal_handlers."""
    return _interrupted


def quiet_interrupts(unraisable):
    """sys.unraisablehook of the command: an interrupt raised inside a
    finalizer is already remembered (_interrupt) and ends the run as
    interrupted; its traceback would only bury the one line the user gets."""
    if issubclass(unraisable.exc_type, KeyboardInterrupt) and _interrupted:
        return
    sys.__unraisablehook__(unraisable)
