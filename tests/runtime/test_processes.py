"""Worker processes that behave (orthocontact.runtime.processes): no worker
outlives the main process, whatever signal ends it."""
import contextlib
import os
import signal
import subprocess
import time
from pathlib import Path

import pytest
from cli_run import CMD, scenario_variant
from procs import alive, descendants

from orthocontact.runtime.processes import process_pool, stop_pool
from orthocontact.runtime.workers import worker_bound

ROOT = Path(__file__).resolve().parents[2]
SCEN = ROOT / "scenarios"


def _aged_with(tmp_path, old, new) -> Path:
    return scenario_variant(SCEN / "mat_aged.toml", old, new, tmp_path / "big.toml")


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

