"""Local worker processes for many rig runs: how many this machine takes
(worker_bound), a process pool whose workers ignore Ctrl-C (the main process
decides), end when their parent ends whatever ended it, and can be stopped
at once; and a progress bar on stderr."""
from __future__ import annotations

import os
import signal
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
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


# -- how many workers this machine takes --------------------------------------------

WORKER_MB = 64.0  # memory [MB] of one worker after its runs: 42-58 MB of its own (USS) measured

PROCESSES_PER_WORKER = 2  # --workers N: N rig workers and N figure workers at the same time

WORKERS_PER_CORE = 4  # the runs are single-threaded and CPU-bound: more only share the cores


@dataclass(frozen=True)
class WorkerBound:
    """The most worker processes (--workers) this machine takes: the fewer
    of WORKERS_PER_CORE per usable core and what the available memory holds
    at PROCESSES_PER_WORKER x WORKER_MB per worker."""
    most: int
    cores: int
    by_cores: int
    available_mb: float | None  # None: not known on this system
    by_memory: int | None

    def reason(self) -> str:
        cores = f"{WORKERS_PER_CORE} per core on its {self.cores} core{'s' * (self.cores != 1)}"
        if self.by_memory is None:
            return cores
        memory = (f"memory for {self.by_memory}: {self.available_mb:,.0f} MB available at "
                  f"~{PROCESSES_PER_WORKER * WORKER_MB:.0f} MB per worker")
        return f"{memory}; {cores}" if self.by_memory < self.by_cores else f"{cores}; {memory}"


def _read(path) -> str | None:
    try:
        with open(path) as f:
            return f.read()
    except OSError:
        return None


def usable_cores() -> int:
    """Cores this process may run on: its CPU affinity, and a cgroup's CPU
    quota (a container's --cpus) if one is set."""
    try:
        n = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        n = os.cpu_count() or 1
    quota = (_read("/sys/fs/cgroup/cpu.max") or "").split()
    if len(quota) == 2 and quota[0] != "max":
        n = min(n, max(1, -(-int(quota[0]) // int(quota[1]))))
    return max(1, n)


def available_memory_mb() -> float | None:
    """Memory [MB] that new processes can take without swapping: the
    kernel's MemAvailable, and less if a cgroup's limit leaves less; None
    where neither is known (not Linux)."""
    avail = None
    for line in (_read("/proc/meminfo") or "").splitlines():
        if line.startswith("MemAvailable:"):
            avail = int(line.split()[1]) / 1024.0
    for limit, usage in (("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"),
                         ("/sys/fs/cgroup/memory/memory.limit_in_bytes",
                          "/sys/fs/cgroup/memory/memory.usage_in_bytes")):
        lim, use = _read(limit), _read(usage)
        if lim and use and lim.strip().isdigit() and use.strip().isdigit():
            left = (int(lim) - int(use)) / 2.0 ** 20
            avail = left if avail is None else min(avail, left)
    return None if avail is None else max(0.0, avail)


def worker_bound() -> WorkerBound:
    """The most worker processes this machine takes now, and why."""
    cores = usable_cores()
    by_cores = WORKERS_PER_CORE * cores
    avail = available_memory_mb()
    by_memory = None if avail is None else max(1, int(avail // (PROCESSES_PER_WORKER * WORKER_MB)))
    return WorkerBound(min(by_cores, by_memory or by_cores), cores, by_cores, avail, by_memory)


def check_workers(n: int) -> int:
    """`n` if this machine takes that many worker processes; ValueError (one
    line: the bound and why) if not.  Every command's --workers and every
    pool pass here."""
    bound = worker_bound()
    if n > bound.most:
        raise ValueError(f"expected at most {bound.most} worker processes on this machine "
                         f"({bound.reason()}), got {n}")
    return n


def default_workers() -> int:
    """The number of usable cores, at most 8 (and at most worker_bound)."""
    return max(1, min(usable_cores(), 8, worker_bound().most))


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
        if not hasattr(signal, "pthread_sigmask"):
            return super().submit(fn, *args, **kwargs)
        old = signal.pthread_sigmask(signal.SIG_BLOCK, _STOP_SIGNALS)
        try:
            return super().submit(fn, *args, **kwargs)
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)


def process_pool(workers: int, initializer=None, *initargs) -> ProcessPoolExecutor:
    """`workers` worker processes (at most worker_bound: ValueError above
    it): forked where that exists (they start in milliseconds; each creates
    its own FMU instance after the fork, so no FMU state is shared), spawned
    elsewhere.  Each worker ignores Ctrl-C (worker_signals), ends with this
    process (end_with_parent), then runs initializer(*initargs); its
    temporary files go into the command's temporary folder, which this
    process removes."""
    check_workers(workers)
    from ..fmu.files import temp_folder
    temp_folder()  # made before the fork, so the workers inherit it and do not make their own
    method = "fork" if sys.platform.startswith("linux") else "spawn"
    return _SignalSafePool(max_workers=workers, mp_context=get_context(method), initializer=_start_worker,
                           initargs=(os.getpid(), initializer, initargs))
