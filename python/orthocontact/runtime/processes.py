"""Worker processes that behave: they ignore Ctrl-C (the main process
decides), end when their parent ends whatever ended it, and are forked by a
pool that holds the stop signals while it forks, so that none is left
unlisted; stop_pool ends such a pool at once."""
from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context

from .temp import temp_folder
from .workers import check_workers

STOP_SIGNALS = {signal.SIGINT, signal.SIGTERM}


@contextlib.contextmanager
def signals_held():
    """SIGINT and SIGTERM held while the block runs: one that arrives
    meanwhile reaches its handler when the block ends, so a step that must
    not be cut (a fork and its record, a folder made and kept, a library
    loaded between two chdir calls) completes first.  Blocking the signals
    in this thread (pthread_sigmask) is not enough: the kernel hands a
    signal sent to the process to any thread that does not block it (a
    progress bar's, a pool's), and Python then runs the handler in the main
    thread between any two steps.  So, in the main thread, the handlers
    themselves wait too (a stand-in notes the signal and calls the handler
    after the block); the mask still holds it from a process forked here."""
    held = {}      # signal -> its handler, while a stand-in takes its place
    arrived = []   # signals noted while held
    holding = [True]

    def stand_in(signum, frame):
        if holding[0]:
            arrived.append(signum)
        else:   # the block has ended: at once, as without the stand-in
            held[signum](signum, frame)

    if threading.current_thread() is threading.main_thread():
        for s in STOP_SIGNALS:
            handler = signal.getsignal(s)
            if callable(handler):   # a Python handler (SIG_IGN, SIG_DFL: the mask holds those)
                held[s] = handler
                signal.signal(s, stand_in)
    old = signal.pthread_sigmask(signal.SIG_BLOCK, STOP_SIGNALS) if hasattr(signal, "pthread_sigmask") \
        else None
    try:
        yield
    finally:
        holding[0] = False
        if old is not None:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)
        for s, handler in held.items():
            signal.signal(s, handler)
        for s in dict.fromkeys(arrived):
            held[s](s, None)


def worker_signals():
    # The main process decides about interrupts: Ctrl-C reaches the whole
    # process group, and a worker must not die with its own traceback.
    # A forked worker starts with these signals held (process_pool): what
    # arrived meanwhile is delivered now, to these dispositions.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, STOP_SIGNALS)


def stop_pool(ex: ProcessPoolExecutor) -> None:
    """Ends the pool now: queued tasks are cancelled and the worker processes
    terminated (shutdown(wait=True) would first run every queued task)."""
    procs = list((getattr(ex, "_processes", None) or {}).values())
    ex.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        if p.is_alive():
            p.terminate()
    for p in procs:
        p.join(timeout=5)
        if p.is_alive():
            p.kill()
            p.join(timeout=5)


# -- workers that end with their parent ------------------------------------------

_PR_SET_PDEATHSIG = 1  # linux/prctl.h

PARENT_POLL_S = 0.5  # how often a worker without PR_SET_PDEATHSIG looks for its parent [s]


def end_with_parent(parent_pid: int, forked_by_main_thread: bool) -> None:
    """Makes this worker process end when its parent `parent_pid` ends,
    however it ends (SIGKILL included, which runs no cleanup in the parent).
    On Linux the kernel does it (PR_SET_PDEATHSIG), but it fires when the
    *thread* that forked this process ends: used only when that was the
    parent's main thread, which lives as long as the process.  Otherwise
    (spawned, forked from another thread, not Linux) a thread here looks for
    the parent every PARENT_POLL_S.  A parent that ended before this ran is
    found at once."""
    armed = False
    if sys.platform.startswith("linux") and forked_by_main_thread:
        import ctypes
        libc = ctypes.CDLL(None, use_errno=True)
        armed = libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0) == 0
    if not armed:
        threading.Thread(target=_watch_parent, args=(parent_pid,), daemon=True,
                         name="orthocontact parent watch").start()
    if os.getppid() != parent_pid:  # the parent ended before the kernel was told
        os._exit(1)


def _watch_parent(parent_pid: int) -> None:
    while os.getppid() == parent_pid:
        time.sleep(PARENT_POLL_S)
    os._exit(1)


_forked_by_main_thread = False  # set just before a pool forks; the worker sees the value at its fork


def _start_worker(parent_pid, initializer, initargs):
    worker_signals()
    end_with_parent(parent_pid, _forked_by_main_thread)
    if initializer is not None:
        initializer(*initargs)


class _SignalSafePool(ProcessPoolExecutor):
    """A pool whose submit holds SIGINT and SIGTERM while it runs.  submit
    forks the workers and records them; a signal landing in between would
    be raised inside Python's at-fork hooks (logging's lock release among
    them), reported as ignored, or leave a worker the pool does not know of
    and so never stops.  Held, it arrives once submit has returned; a forked
    worker inherits the hold until its initializer has set its dispositions
    (worker_signals)."""

    def submit(self, fn, /, *args, **kwargs):
        global _forked_by_main_thread
        _forked_by_main_thread = threading.current_thread() is threading.main_thread()
        with signals_held():
            return super().submit(fn, *args, **kwargs)


def process_pool(workers: int, initializer=None, *initargs) -> ProcessPoolExecutor:
    """`workers` worker processes (at most worker_bound: ValueError above
    it): forked where that exists (they start in milliseconds; each creates
    its own FMU instance after the fork, so no FMU state is shared), spawned
    elsewhere.  Each worker ignores Ctrl-C (worker_signals), ends with this
    process (end_with_parent), then runs initializer(*initargs); its
    temporary files go into the command's temporary folder, which this
    process removes."""
    check_workers(workers)
    temp_folder()  # made before the fork, so the workers inherit it and do not make their own
    method = "fork" if sys.platform.startswith("linux") else "spawn"
    return _SignalSafePool(max_workers=workers, mp_context=get_context(method), initializer=_start_worker,
                           initargs=(os.getpid(), initializer, initargs))
