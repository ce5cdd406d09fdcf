"""How many worker processes this machine takes (orthocontact.runtime.workers):
--workers is bounded by the cores and the memory, checked before any work."""
import contextlib
import os
import signal
import subprocess
import time

import pytest

from cli_run import CMD, leftovers, one_error_line
from orthocontact.cli.parser import build_parser
from orthocontact.runtime.processes import process_pool
from orthocontact.runtime.workers import WORKERS_PER_CORE, worker_bound
from paths import SCENARIOS
from procs import descendants


def _kill_all(pids):
    for k in pids:
        with contextlib.suppress(OSError):
            os.kill(k, signal.SIGKILL)


# -- how many workers: the machine's bound, checked before any work -----------------

def _most_children_at_once(proc, timeout=10) -> int:
    """Waits for `proc`; the most processes of it seen alive at one time
    (polled every 5 ms from its start)."""
    most, seen = 0, set()
    t0 = time.monotonic()
    try:
        while proc.poll() is None and time.monotonic() - t0 < timeout:
            now = descendants(proc.pid)
            seen |= set(now)
            most = max(most, len(now))
            time.sleep(0.005)
    finally:
        if proc.poll() is None:  # a run that forks on: stop it and what it started
            _kill_all([proc.pid] + descendants(proc.pid) + list(seen))
        proc.wait(timeout=10)
    return most


def test_workers_above_the_machines_bound_are_one_line_at_once_and_start_nothing(tmp_path):
    bound = worker_bound()
    assert bound.cores == len(os.sched_getaffinity(0))  # independent: this process's cores
    assert bound.by_cores == WORKERS_PER_CORE * bound.cores and bound.most <= bound.by_cores
    t0 = time.monotonic()
    proc = subprocess.Popen(CMD + ["run", str(SCENARIOS / "case4.toml"), "--out", "out", "--workers", "1000"],
                            cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # No worker: at most the one short-lived `ldconfig -p` that fmpy's import
    # runs (ctypes.util.find_library), where a pool forks all its workers at once.
    assert _most_children_at_once(proc) <= 1
    elapsed = time.monotonic() - t0
    p = subprocess.CompletedProcess(proc.args, proc.returncode, proc.stdout.read(), proc.stderr.read())
    one_error_line(p, "--workers", f"at most {bound.most} worker processes", "got 1000",
                   f"{bound.cores} core")
    assert elapsed < 5.0  # the interpreter's start: no fork, no run
    assert leftovers(tmp_path) == []
    # the largest accepted passes the parser (uq's --workers too)
    assert build_parser().parse_args(["run", "s.toml", "--out", "o", "--workers", str(bound.most)]).workers \
        == bound.most
    with pytest.raises(SystemExit):
        build_parser().parse_args(["uq", "i.json", "--scenario", "s", "--samples", "1", "--out", "o",
                                   "--workers", str(bound.most + 1)])


def test_the_bound_follows_the_cores_this_process_may_use(tmp_path):
    """On one core (taskset -c 0), --workers 5 is above 4 per core."""
    def one_core():
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    p = subprocess.run(CMD + ["run", str(SCENARIOS / "case4.toml"), "--out", "out", "--workers", "5"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=60, preexec_fn=one_core)
    one_error_line(p, "at most 4 worker processes", "on its 1 core", "got 5")
    with pytest.raises(ValueError, match="at most"):
        process_pool(worker_bound().most + 1)  # the Python API's pools pass the same check
