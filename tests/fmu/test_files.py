"""Where the FMUs are (orthocontact.fmu.files): the version asked for, a
given path or environment variable, their model descriptions; unpacked FMUs
that no way of ending a command leaves in the temp folder."""
import fcntl
import os
import signal
import subprocess
import tempfile
import time

import pytest
from cli_run import CMD, SCENARIOS as SCEN

from orthocontact.fmu.files import ABANDONED_AFTER_S, TEMP_PREFIX, find_fmu, fmi_version_of, remove_abandoned


def test_find_fmu_picks_the_version():
    assert fmi_version_of(find_fmu()) == 2
    assert fmi_version_of(find_fmu(fmi_version=2)) == 2
    assert fmi_version_of(find_fmu(fmi_version=3)) == 3
    with pytest.raises(ValueError, match="2 or 3"):
        find_fmu(fmi_version=1)


# -- unpacked FMUs: in one folder per command, gone whatever ends the command ----------

def _age(folder, seconds):
    t = time.time() - seconds
    os.utime(folder / ".lock", (t, t))


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
    proc = subprocess.Popen(CMD + ["run", str(SCEN / "mat_aged.toml"), "--out", "out", "--workers", "2"],
                            cwd=tmp_path, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    assert proc.stderr.readline().startswith("mat_aged:")   # its sweep runs
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait(timeout=30)
    left = [p for p in tmp.iterdir() if p.name.startswith(TEMP_PREFIX)]
    assert len(left) == 1 and any(left[0].rglob("*.so")), left
    _age(left[0], 2 * ABANDONED_AFTER_S)
    time.sleep(1.0)  # its workers end with it
    p = subprocess.run(CMD + ["run", str(SCEN / "case4.toml"), "--out", "out2", "--workers", "2"], cwd=tmp_path,
                       env=env, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert os.listdir(tmp) == []


def test_only_abandoned_folders_are_removed(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    made = {}
    for name in ("abandoned", "in-use", "new"):
        folder = tmp_path / f"{TEMP_PREFIX}{name}"
        folder.mkdir()
        (folder / ".lock").write_text("")
        made[name] = folder
    _age(made["abandoned"], 2 * ABANDONED_AFTER_S)
    _age(made["in-use"], 2 * ABANDONED_AFTER_S)
    (tmp_path / f"{TEMP_PREFIX}not-ours").mkdir()  # no lock file: not a command's folder
    (tmp_path / "other").mkdir()
    fd = os.open(made["in-use"] / ".lock", os.O_RDWR)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)  # as a live command holds it
        assert remove_abandoned() == [made["abandoned"]]
    finally:
        os.close(fd)
    assert sorted(os.listdir(tmp_path)) == [f"{TEMP_PREFIX}in-use", f"{TEMP_PREFIX}new",
                                           f"{TEMP_PREFIX}not-ours", "other"]
