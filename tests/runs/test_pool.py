"""Worker processes and progress (orthocontact.runs.pool): a long run says how
far it is within 2 s and stops on Ctrl-C; --workers is bounded by the machine,
and no worker outlives the main process, whatever signal ends it."""
import contextlib
import os
import signal
import subprocess
import time
from pathlib import Path

import pytest
from cli_run import CMD, leftovers, one_error_line, run_cli as run, scenario_variant
from procs import alive, descendants

from orthocontact.cli.parser import build_parser
from orthocontact.runs.pool import (WORKERS_PER_CORE, Heartbeat, Progress, default_workers, process_pool,
                                    worker_bound)

ROOT = Path(__file__).resolve().parents[2]
SCEN = ROOT / "scenarios"



def _aged_with(tmp_path, old, new) -> Path:
    return scenario_variant(SCEN / "mat_aged.toml", old, new, tmp_path / "big.toml")


# -- huge work: said before it starts, and progress while it runs ---------------------

def test_a_long_run_says_how_far_it_is_within_2_s_and_stops_on_ctrl_c(tmp_path):
    big = _aged_with(tmp_path, "step_s = 2.0e-4", "step_s = 1e-9")
    proc = subprocess.Popen(CMD + ["run", str(big), "--out", "out", "--yes", "--workers", "2"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    t0 = time.monotonic()
    started = None
    try:
        for line in proc.stderr:
            if ": warning: " in line:
                continue
            if started is None:
                started = time.monotonic()
            assert line.startswith("mat_aged: 0/91"), line  # no run of 2e9 steps has finished
            break
        first = time.monotonic() - t0
    finally:
        os.killpg(proc.pid, signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    assert first < 6.0  # the interpreter's start (~1-2 s) and the 2 s of the first line
    assert proc.returncode == 130 and err.strip().splitlines()[-1].startswith("orthocontact: interrupted")


def test_the_sweeps_refinement_and_recordings_say_they_are_running(tmp_path):
    """After the sweep's last run, the extremum's refinement and the recorded
    trajectories are more runs: a line within 2 s of them too."""
    sc = _aged_with(tmp_path, "step_deg = 1.0", "step_deg = 45.0")
    sc.write_text(sc.read_text().replace("step_s = 2.0e-4", "step_s = 5.0e-7"))  # seconds a run
    p = run(["run", sc, "--out", tmp_path / "out", "--workers", "2"], tmp_path, timeout=300)
    assert p.returncode == 0, p.stderr
    assert "mat_aged extremum and trajectories: " in p.stderr and "runs done" in p.stderr


def test_progress_says_each_tenth_once_and_the_end(capsys):
    p = Progress(20, "sweep case5", enabled=True)
    try:
        for _ in range(20):
            p.update()
    finally:
        p.close()
    lines = capsys.readouterr().err.splitlines()   # not a terminal: the first run, then a line per 10 %
    assert [x.split(" (")[0] for x in lines] == [f"sweep case5: {n}/20" for n in (1, 2, 4, 6, 8, 10, 12,
                                                                                 14, 16, 18, 20)]
    assert lines[0].startswith("sweep case5: 1/20 (5%, ")
    assert lines[-1].startswith("sweep case5: 20/20 (100%, ")
    quiet = Progress(5, "q", enabled=False)
    quiet.update(5)
    assert capsys.readouterr().err == "" and quiet.done == 5


def test_a_heartbeat_counts_runs_and_speaks_only_when_due(capsys):
    with Heartbeat("refine", enabled=False) as h:
        h.update(3)
        h.update()
    assert h.done == 4 and capsys.readouterr().err == ""
    assert 1 <= default_workers() <= 8


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
    proc = subprocess.Popen(CMD + ["run", str(SCEN / "case4.toml"), "--out", "out", "--workers", "1000"],
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
    p = subprocess.run(CMD + ["run", str(SCEN / "case4.toml"), "--out", "out", "--workers", "5"], cwd=tmp_path,
                       capture_output=True, text=True, timeout=60, preexec_fn=one_core)
    one_error_line(p, "at most 4 worker processes", "on its 1 core", "got 5")
    with pytest.raises(ValueError, match="at most"):
        process_pool(worker_bound().most + 1)  # the Python API's pools pass the same check


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
