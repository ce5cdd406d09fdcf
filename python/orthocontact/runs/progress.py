"""Progress of many rig runs on stderr: a bar (a line per 10% when not a
terminal), a heartbeat for work whose run count is not known ahead, and
status lines for work of several stages."""
from __future__ import annotations

import contextlib
import sys
import threading
import time


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
    refinement and recordings, a fit's solves): only the lines at 2 s and
    every 10 s after, with the steps done so far (`unit`: what they are)."""

    def __init__(self, label: str, enabled: bool = True, unit: str = "runs"):
        super().__init__(1 << 62, label, enabled)
        self.unit = unit

    def _show(self, still=False):
        self._said = time.time()
        print(f"{self.label}: {self.done} {self.unit} done ({time.time() - self.t0:.1f}s, running)",
              file=sys.stderr, flush=True)

    def update(self, n: int = 1):
        self.done += n

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


@contextlib.contextmanager
def status_lines(say, text):
    """say(text() with the time so far) Progress.FIRST_S after the start and
    every Progress.HEARTBEAT_S after while the block runs, whatever stage it
    is in (text() says which); nothing where say is None."""
    if say is None:
        yield
        return
    stop, t0 = threading.Event(), time.monotonic()

    def beat():
        wait = Progress.FIRST_S
        while not stop.wait(wait):
            say(f"{text()} ({time.monotonic() - t0:.0f} s, running)")
            wait = Progress.HEARTBEAT_S
    threading.Thread(target=beat, daemon=True, name="status lines").start()
    try:
        yield
    finally:
        stop.set()
