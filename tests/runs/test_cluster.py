"""Runs on Dask (orthocontact.runs.cluster): a Dask run leaves nothing in
the temp folder, sweeps on Dask give the local results, a local cluster
listens on 127.0.0.1 only and none of its processes outlives the command."""
import contextlib
import ipaddress
import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

from cli_run import CMD, busy_dashboard_port, scenario_variant
from cli_run import run_cli as run
from orthocontact.errors import InputError
from orthocontact.runs.cluster import check_address
from orthocontact.runtime.workers import worker_bound
from paths import SCENARIOS
from procs import alive, descendants

# -- Ctrl-C on a Dask command -------------------------------------------------------

def test_a_dask_run_leaves_nothing_in_the_temp_folder(tmp_path):
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    env = dict(os.environ, TMPDIR=str(tmp))
    port = busy_dashboard_port()
    try:
        p = run(["run", SCENARIOS / "case4.toml", "--out", tmp_path / "out", "--scheduler", "local",
                 "--workers", "2"], tmp_path, env=env)
    finally:
        if port is not None:
            port.close()
    assert p.returncode == 0, p.stderr
    assert "Warning" not in p.stderr and "Traceback" not in p.stderr, p.stderr
    assert sorted(os.listdir(tmp)) == []
    p = run(["run", SCENARIOS / "case4.toml", "--out", tmp_path / "out2"], tmp_path, env=env)
    assert p.returncode == 0 and sorted(os.listdir(tmp)) == []


def test_sweeps_on_dask_give_the_local_results(tmp_path):
    a = subprocess.run(CMD + ["run", str(SCENARIOS / "case5.toml"), "--out", str(tmp_path / "a")],
                       capture_output=True, text=True, timeout=300)
    b = subprocess.run(CMD + ["run", str(SCENARIOS / "case5.toml"), "--out", str(tmp_path / "b"),
                              "--scheduler", "local", "--workers", "2"],
                       capture_output=True, text=True, timeout=300)
    assert a.returncode == 0 and b.returncode == 0, b.stderr
    for name in ("sweep.csv", "trajectories.csv"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()


def test_a_scheduler_is_local_or_an_address():
    for ok in ("local", "tcp://10.0.0.5:8786", "tls://h:1", "inproc://x", "ucx://h:2"):
        check_address(ok)
    for bad in ("127.0.0.1:8786", "none", "Local", ""):
        with pytest.raises(InputError) as e:
            check_address(bad)
        assert str(e.value) == (f"--scheduler {bad}: expected 'local' or a scheduler address such as "
                                "tcp://HOST:PORT")


# -- a local cluster: this machine only, and no process outlives the command --------

def _listening(pid) -> set:
    """(address, port) of every TCP socket process `pid` listens on, from
    its open files and the kernel's socket tables (/proc)."""
    inodes = set()
    for fd in Path(f"/proc/{pid}/fd").iterdir():
        with contextlib.suppress(OSError):
            target = os.readlink(fd)
            if target.startswith("socket:["):
                inodes.add(target[8:-1])
    out = set()
    for table in ("tcp", "tcp6"):
        with contextlib.suppress(OSError):
            for line in Path(f"/proc/{pid}/net/{table}").read_text().splitlines()[1:]:
                f = line.split()
                if f[3] == "0A" and f[9] in inodes:  # 0A: LISTEN
                    addr, port = f[1].split(":")
                    raw = bytes.fromhex(addr)
                    # the kernel prints each 32-bit word in host (little-endian) order
                    raw = b"".join(raw[i:i + 4][::-1] for i in range(0, len(raw), 4))
                    out.add((str(ipaddress.ip_address(raw)), int(port, 16)))
    return out


def _dask_run(tmp_path, workers):
    sc = scenario_variant(SCENARIOS / "mat_aged.toml", "step_s = 2.0e-4", "step_s = 2.0e-5",
                          tmp_path / "big.toml")
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    proc = subprocess.Popen(CMD + ["run", str(sc), "--out", "out", "--yes", "--workers", str(workers),
                                   "--scheduler", "local"], cwd=tmp_path,
                            env=dict(os.environ, TMPDIR=str(tmp)),
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    line = ""
    t0 = time.monotonic()
    while not line.startswith("mat_aged:") and time.monotonic() - t0 < 120:  # the workers run chunks
        line = proc.stderr.readline()
        assert line or proc.poll() is None, "the run ended before its first progress line"
    return proc, tmp


def test_a_local_cluster_listens_on_the_loopback_interface_only(tmp_path):
    proc, _ = _dask_run(tmp_path, 2)
    try:
        procs = [proc.pid] + descendants(proc.pid)   # the scheduler (in the command), workers, nannies
        sockets = {s for pid in procs for s in _listening(pid)}
    finally:
        os.kill(proc.pid, signal.SIGINT)
        proc.communicate(timeout=60)
    assert len(sockets) >= 4, sockets  # the scheduler, its HTTP server, each worker's
    assert {a for a, _ in sockets} == {"127.0.0.1"}, sockets


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL], ids=["SIGTERM", "SIGKILL"])
def test_no_dask_process_outlives_the_command(tmp_path, sig):
    """The signal to the main process only, at the most --workers accepted,
    while the workers run chunks."""
    proc, tmp = _dask_run(tmp_path, worker_bound().most)
    kids = descendants(proc.pid)
    try:
        os.kill(proc.pid, sig)
        proc.wait(timeout=60)
        t0 = time.monotonic()
        left = [k for k in kids if alive(k)]
        while left and time.monotonic() - t0 < 10:
            time.sleep(0.1)
            left = [k for k in left if alive(k)]
    finally:
        for k in [proc.pid] + kids:
            with contextlib.suppress(OSError):
                os.kill(k, signal.SIGKILL)
        proc.wait(timeout=10)
    assert len(kids) > worker_bound().most  # the Dask workers and the figure workers
    assert left == [], f"{len(left)} of {len(kids)} processes alive 10 s after {sig.name}"
    if sig == signal.SIGTERM:
        assert proc.returncode == 130
        assert os.listdir(tmp) == []
