"""One temporary folder per command (orthocontact.runtime.temp): unpacked
FMUs that no way of ending a command leaves in the temp folder; a killed
command's folder goes with the next command."""
import os
import signal
import subprocess
import time

import pytest

from cli_run import CMD
from orthocontact.runtime.temp import TEMP_PREFIX
from paths import SCENARIOS


@pytest.mark.parametrize("at", ["case3", "mat_aged", "mat_new", "step_study"])
def test_ctrl_c_on_reproduce_leaves_no_unpacked_fmu(tmp_path, at):
    """Ctrl-C (SIGINT to the process group) at several moments, when the
    sweep of scenario `at` starts: the figure workers run the sensitivity job
    meanwhile, which unpacks the FMU in a worker (that one used to stay)."""
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    proc = subprocess.Popen(CMD + ["reproduce", "--out", "out", "--workers", "2"], cwd=tmp_path,
                            env=dict(os.environ, TMPDIR=str(tmp)), stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)
    for line in proc.stderr:
        if line.startswith(f"{at}: "):
            break
    os.killpg(proc.pid, signal.SIGINT)
    err = proc.communicate(timeout=60)[1]
    assert proc.returncode == 130, err
    assert os.listdir(tmp) == []


def test_a_killed_commands_folder_goes_with_the_next_command(tmp_path):
    """SIGKILL runs no cleanup: the command's folder stays while its lock
    says so, and the next command removes it once its lock is free (no
    process of the killed command is left)."""
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    env = dict(os.environ, TMPDIR=str(tmp))
    proc = subprocess.Popen(CMD + ["run", str(SCENARIOS / "mat_aged.toml"), "--out", "out", "--workers", "2"],
                            cwd=tmp_path, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True)
    assert proc.stderr.readline().startswith("mat_aged:")   # its sweep runs
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait(timeout=30)
    left = [p for p in tmp.iterdir() if p.name.startswith(TEMP_PREFIX)]
    assert len(left) == 1 and any(left[0].rglob("*.so")), left
    time.sleep(1.0)  # its workers end with it
    p = subprocess.run(CMD + ["run", str(SCENARIOS / "case4.toml"), "--out", "out2", "--workers", "2"],
                       cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert os.listdir(tmp) == []
