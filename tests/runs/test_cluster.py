"""Runs on Dask (orthocontact.runs.cluster): a Dask run leaves nothing in
the temp folder, sweeps on Dask give the local results."""
import os
import subprocess
from pathlib import Path

import pytest
from cli_run import CMD, busy_dashboard_port, run_cli as run

from orthocontact.errors import InputError
from orthocontact.runs.cluster import check_address

ROOT = Path(__file__).resolve().parents[2]
SCEN = ROOT / "scenarios"


# -- Ctrl-C on a Dask command -------------------------------------------------------

def test_a_dask_run_leaves_nothing_in_the_temp_folder(tmp_path):
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    env = dict(os.environ, TMPDIR=str(tmp))
    port = busy_dashboard_port()
    try:
        p = run(["run", SCEN / "case4.toml", "--out", tmp_path / "out", "--scheduler", "local",
                 "--workers", "2"], tmp_path, env=env)
    finally:
        if port is not None:
            port.close()
    assert p.returncode == 0, p.stderr
    assert "Warning" not in p.stderr and "Traceback" not in p.stderr, p.stderr
    assert sorted(os.listdir(tmp)) == []
    p = run(["run", SCEN / "case4.toml", "--out", tmp_path / "out2"], tmp_path, env=env)
    assert p.returncode == 0 and sorted(os.listdir(tmp)) == []


def test_sweeps_on_dask_give_the_local_results(tmp_path):
    a = subprocess.run(CMD + ["run", str(ROOT / "scenarios/case5.toml"), "--out", str(tmp_path / "a")],
                       capture_output=True, text=True, timeout=300)
    b = subprocess.run(CMD + ["run", str(ROOT / "scenarios/case5.toml"), "--out", str(tmp_path / "b"),
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
