"""Worker processes that behave (orthocontact.runtime.processes): no worker
outlives the main process, whatever signal ends it; a pool forks with the
stop signals held, even where other threads would take them."""
import contextlib
import os
import random
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from cli_run import CMD, scenario_variant
from orthocontact.runtime.processes import process_pool, signals_held, stop_pool
from orthocontact.runtime.workers import worker_bound
from paths import SCENARIOS
from procs import alive, children, descendants


def _aged_with(tmp_path, old, new) -> Path:
    return scenario_variant(SCENARIOS / "mat_aged.toml", old, new, tmp_path / "big.toml")


# -- workers end with the main process, whatever ends it ------------------------------

def _kill_all(pids):
    for k in pids:
        with contextlib.suppress(OSError):
            os.kill(k, signal.SIGKILL)


def _alive_within(pids, seconds):
    """The pids still alive (not zombies) after up to `seconds`."""
    t0 = time.monotonic()
    left = [k for k in pids if alive(k)]
    while left and time.monotonic() - t0 < seconds:
        time.sleep(0.1)
        left = [k for k in left if alive(k)]
    return left


@pytest.mark.parametrize("when", ["figure workers forked", "sweep running"])
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL, signal.SIGINT],
                         ids=["SIGTERM", "SIGKILL", "SIGINT"])
def test_no_worker_outlives_the_main_process_at_the_most_workers(tmp_path, sig, when):
    """`run` at the largest --workers it accepts; the signal goes to the main
    process only (as `timeout` or a job runner sends it): as soon as the
    figure workers exist (a signal held while they fork used to leave them
    all) or while the sweep's workers run.  10 s later none is alive."""
    n = worker_bound().most
    big = _aged_with(tmp_path, "step_s = 2.0e-4", "step_s = 2.0e-5")  # ~10x longer runs
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    proc = subprocess.Popen(CMD + ["run", str(big), "--out", "out", "--yes", "--workers", str(n)],
                            cwd=tmp_path, env=dict(os.environ, TMPDIR=str(tmp)),
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    want = n if when == "figure workers forked" else 2 * n  # N figure workers, then N rig workers
    kids = []
    try:
        t0 = time.monotonic()
        while len(kids) < want and proc.poll() is None and time.monotonic() - t0 < 90:
            kids = descendants(proc.pid)
            time.sleep(0.005 if want == n else 0.1)
        assert len(kids) >= want, f"{len(kids)} of {want} workers started"
        if when == "sweep running":
            time.sleep(0.5)
            kids = descendants(proc.pid)
        os.kill(proc.pid, sig)
        proc.wait(timeout=30)
        left = _alive_within(kids, 10.0)
    finally:
        _kill_all([proc.pid] + descendants(proc.pid) + kids)
        proc.wait(timeout=10)
    assert left == [], f"{len(left)} of {len(kids)} workers alive 10 s after {sig.name} to the main process"
    if sig != signal.SIGKILL:
        assert proc.returncode == 130, proc.stderr.read()
        assert os.listdir(tmp) == []  # the unpacked FMUs, the workers' too


# -- signals held: also where another thread would take them -------------------------

def _handler_noting(seen):
    def handler(signum, frame):
        seen.append(signum)
        raise KeyboardInterrupt
    return handler


def test_a_signal_waits_for_the_end_of_the_held_block_with_another_thread(tmp_path):
    """The kernel gives a signal sent to the process to a thread that does
    not block it (a progress bar's), and Python then runs the handler in the
    main thread between any two steps: blocking it in the main thread did
    not hold it.  Now the handler runs once, after the block."""
    seen, old = [], signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGINT, _handler_noting(seen))
    stop = threading.Event()
    other = threading.Thread(target=stop.wait, daemon=True)
    other.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            with signals_held():
                os.kill(os.getpid(), signal.SIGINT)
                t0 = time.monotonic()
                while time.monotonic() - t0 < 0.2:   # steps during which the handler used to run
                    pass
                assert seen == []
        assert seen == [signal.SIGINT]
        with pytest.raises(KeyboardInterrupt):   # after the block: at once, as before
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.1)
        assert seen == [signal.SIGINT] * 2
    finally:
        stop.set()
        signal.signal(signal.SIGINT, old)


def test_a_pool_interrupted_while_it_forks_leaves_no_worker_and_swallows_nothing():
    """SIGINT at random moments while a pool forks its workers, another
    thread running (measured before: of 200, 10 interrupts reported as
    ignored inside fork's hooks and 51 workers the pool did not list, so
    stop_pool never stopped them; now none)."""
    seen, old = [], signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, _handler_noting(seen))
    unraisable, sys.unraisablehook = sys.unraisablehook, lambda u: seen.append("ignored")
    stop = threading.Event()
    threading.Thread(target=stop.wait, daemon=True).start()
    rng = random.Random(1)
    try:
        for _ in range(30):
            ex = process_pool(2)
            timer = threading.Timer(rng.uniform(0, 0.004), os.kill, (os.getpid(), signal.SIGINT))
            raised = False
            try:
                timer.start()
                ex.submit(int)
                time.sleep(0.05)   # the signal comes by now at the latest
            except KeyboardInterrupt:
                raised = True
            listed = set((ex._processes or {}).keys())
            kids = set(children(os.getpid()))
            stop_pool(ex)
            timer.join()
            assert raised and "ignored" not in seen
            time.sleep(0.02)
            assert [k for k in kids - listed if alive(k)] == []
    finally:
        stop.set()
        signal.signal(signal.SIGINT, old)
        sys.unraisablehook = unraisable
