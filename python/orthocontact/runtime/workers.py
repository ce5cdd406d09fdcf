"""How many worker processes this machine takes: the fewer of a few per
usable core (CPU affinity, a cgroup's quota) and what the available memory
holds; every command's --workers and every pool pass check_workers."""
from __future__ import annotations

import os
from dataclasses import dataclass

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
