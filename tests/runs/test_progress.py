"""Progress of many rig runs (orthocontact.runs.progress): a long run says
how far it is within 2 s and stops on Ctrl-C; a line per tenth; a heartbeat
for work of unknown size."""
import os
import signal
import subprocess
import time
from pathlib import Path

from cli_run import CMD, scenario_variant
from cli_run import run_cli as run
from orthocontact.runs.progress import Heartbeat, Progress
from orthocontact.runtime.workers import default_workers
from paths import SCENARIOS


def _aged_with(tmp_path, old, new) -> Path:
    return scenario_variant(SCENARIOS / "mat_aged.toml", old, new, tmp_path / "big.toml")


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


def test_status_lines_say_the_stage_until_the_block_ends(monkeypatch):
    """Work of several stages (a design's search) says what it is doing
    FIRST_S after the start and every HEARTBEAT_S after, and stops with
    its block; nothing where say is None."""
    from orthocontact.runs.progress import status_lines
    said, stage = [], ["building"]
    monkeypatch.setattr(Progress, "FIRST_S", 0.05)
    monkeypatch.setattr(Progress, "HEARTBEAT_S", 0.05)
    with status_lines(said.append, lambda: stage[0]):
        time.sleep(0.3)
    time.sleep(0.1)
    n = len(said)
    assert n >= 2 and all(s.startswith("building (") and s.endswith("s, running)") for s in said)
    time.sleep(0.2)
    assert len(said) == n      # stopped with the block
    with status_lines(None, lambda: "quiet"):
        pass
