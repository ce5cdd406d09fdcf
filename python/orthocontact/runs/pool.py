"""Local worker processes for many rig runs: a process pool whose workers
ignore Ctrl-C (the main process decides), that can be stopped at once, and a
progress bar on stderr."""
from __future__ import annotations

import os
import signal
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context

_STOP_SIGNALS = {signal.SIGINT, signal.SIGTERM}


def worker_signals():
    # The main process decides about interrupts: Ctrl-C reaches the whole
    # process group, and a worker must not die with its own traceback.
    # A forked worker starts with these signals held (process_pool): what
    # arrived meanwhile is delivered now, to these dispositions.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _STOP_SIGNALS)


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


class Progress:
    """A progress bar on stderr (a line per 10% when not a terminal).  While
    it is open, a line comes at least 2 s after the start and then every
    HEARTBEAT_S even when no run has finished (a single run can be long):
    runs done and the time so far.  close() (or the last update) ends it."""

    FIRST_S, HEARTBEAT_S = 2.0, 10.0

    def __init__(self, total: int, label: str, enabled: bool = True):
        self.total, self.label, self.enabled = total, label, enabled
        self.done, self.t0, self.last_decile = 0, time.time(), -1
        self.tty = sys.stderr.isatty()
        self._said = self.t0 - self.HEARTBEAT_S + self.FIRST_S  # the first line due at 2 s
        self._lock = threading.Lock()
        self._stop = threading.Event()
        if enabled and total > 0:
            threading.Thread(target=self._beat, daemon=True, name=f"progress {label}").start()

    def _beat(self):
        while not self._stop.wait(0.25):
            with self._lock:
                if self.done < self.total and time.time() - self._said >= self.HEARTBEAT_S:
                    self._show(still=True)

    def close(self):
        self._stop.set()

    def _show(self, still=False):
        frac = self.done / self.total
        elapsed = time.time() - self.t0
        self._said = time.time()
        if self.tty:
            bar = "#" * int(30 * frac)
            sys.stderr.write(f"\r{self.label:<22} [{bar:<30}] {self.done}/{self.total} {elapsed:5.1f}s")
            if self.done == self.total:
                sys.stderr.write("\n")
            sys.stderr.flush()
        else:
            print(f"{self.label}: {self.done}/{self.total} ({100 * frac:.0f}%, {elapsed:.1f}s"
                  + (", running)" if still else ")"), file=sys.stderr, flush=True)

    def update(self, n: int = 1):
        self.done += n
        if self.done >= self.total:
            self.close()
        if not self.enabled:
            return
        with self._lock:
            if self.tty:
                self._show()
            elif int(10 * self.done / self.total) > self.last_decile:
                self.last_decile = int(10 * self.done / self.total)
                self._show()


class Heartbeat(Progress):
    """Progress of work whose run count is not known ahead (a sweep's
    refinement and recordings): only the lines at 2 s and every 10 s after,
    with the runs done so far."""

    def __init__(self, label: str, enabled: bool = True):
        super().__init__(1 << 62, label, enabled)

    def _show(self, still=False):
        self._said = time.time()
        print(f"{self.label}: {self.done} runs done ({time.time() - self.t0:.1f}s, running)",
              file=sys.stderr, flush=True)

    def update(self, n: int = 1):
        self.done += n

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def default_workers() -> int:
    return max(1, min(os.cpu_count() or 1, 8))


class _SignalSafePool(ProcessPoolExecutor):
    """A pool whose submit holds SIGINT and SIGTERM while it runs.  submit
    forks the workers and records them; a signal landing in between would
    be raised inside Python's at-fork hooks (logging's lock release among
    them), reported as ignored, or leave a worker the pool does not know of
    and so never stops.  Held, it arrives once submit has returned; a forked
    worker inherits the hold until its initializer has set its dispositions
    (worker_signals)."""

    def submit(self, fn, /, *args, **kwargs):
        if not hasattr(signal, "pthread_sigmask"):
            return super().submit(fn, *args, **kwargs)
        old = signal.pthread_sigmask(signal.SIG_BLOCK, _STOP_SIGNALS)
        try:
            return super().submit(fn, *args, **kwargs)
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)


def process_pool(workers: int, initializer, *initargs) -> ProcessPoolExecutor:
    """Worker processes: forked where that exists (they start in
    milliseconds; each creates its own FMU instance after the fork, so no FMU
    state is shared), spawned elsewhere.  The initializer must call
    worker_signals first."""
    method = "fork" if sys.platform.startswith("linux") else "spawn"
    return _SignalSafePool(max_workers=workers, mp_context=get_context(method), initializer=initializer,
                           initargs=initargs)
