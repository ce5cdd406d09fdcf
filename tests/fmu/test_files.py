"""Where the FMUs are (orthocontact.fmu.files): the version asked for, a
given path or environment variable, their model descriptions; unpacked FMUs
that no way of ending a command leaves in the temp folder."""
import fcntl
import os
import signal
import subprocess
import sys
import tempfile
import time

import pytest
from cli_run import CMD, SCENARIOS as SCEN

from orthocontact.fmu.files import (LOCK, TEMP_PREFIX, find_fmu, fmi_version_of, locked_folder, maker_tag,
                                    remove_abandoned)


def test_find_fmu_picks_the_version():
    assert fmi_version_of(find_fmu()) == 2
    assert fmi_version_of(find_fmu(fmi_version=2)) == 2
    assert fmi_version_of(find_fmu(fmi_version=3)) == 3
    with pytest.raises(ValueError, match="2 or 3"):
        find_fmu(fmi_version=1)


# -- unpacked FMUs: in one folder per command, gone whatever ends the command ----------

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
    time.sleep(1.0)  # its workers end with it
    p = subprocess.run(CMD + ["run", str(SCEN / "case4.toml"), "--out", "out2", "--workers", "2"], cwd=tmp_path,
                       env=env, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert os.listdir(tmp) == []


def test_only_abandoned_folders_are_removed(tmp_path, monkeypatch):
    """A folder whose lock is free is abandoned at once (its lock file is
    locked before it takes its name, so it is never one being made); one
    whose lock is held, one being made (no .lock yet) and one without a
    lock file are left."""
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    made = {}
    for name in ("abandoned", "in-use", "being-made"):
        folder = tmp_path / f"{TEMP_PREFIX}{name}"
        folder.mkdir()
        (folder / (LOCK if name != "being-made" else LOCK + ".new")).write_text("")
        made[name] = folder
    (tmp_path / f"{TEMP_PREFIX}not-ours").mkdir()  # no lock file: not a command's folder
    (tmp_path / "other").mkdir()
    # killed before its lock took its name: its name says its maker, now gone
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    killed = tmp_path / f"{TEMP_PREFIX}{dead.pid}.12345-abc"
    killed.mkdir()
    (killed / (LOCK + ".new")).write_text("")
    # being made by a live process (this one): left
    making = tmp_path / f"{TEMP_PREFIX}{maker_tag(os.getpid())}-def"
    making.mkdir()
    fd = os.open(made["in-use"] / LOCK, os.O_RDWR)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)  # as a live command holds it
        assert sorted(remove_abandoned()) == sorted([made["abandoned"], killed])
    finally:
        os.close(fd)
    assert sorted(os.listdir(tmp_path)) == sorted([f"{TEMP_PREFIX}being-made", f"{TEMP_PREFIX}in-use",
                                                  f"{TEMP_PREFIX}not-ours", making.name, "other"])


def test_a_locked_folder_is_held_while_its_maker_lives(tmp_path):
    """locked_folder's lock, seen from another process: held while the
    folder's maker lives, free once it is killed; the next folder of the
    kind made there removes it, and only folders of its own prefix."""
    code = ("import sys, time; from orthocontact.fmu.files import locked_folder; "
            "print(locked_folder(sys.argv[1], '.out.partial-').path, flush=True); time.sleep(60)")
    proc = subprocess.Popen([CMD[0], "-c", code, str(tmp_path)], stdout=subprocess.PIPE, text=True)
    try:
        theirs = tmp_path / os.path.basename(proc.stdout.readline().strip())
        other = tmp_path / f"{TEMP_PREFIX}x"
        other.mkdir()
        (other / LOCK).write_text("")   # free, but of another prefix
        mine = locked_folder(tmp_path, ".out.partial-")
        assert theirs.is_dir() and (theirs / LOCK).is_file() and mine.path.is_dir()
    finally:
        proc.kill()
        proc.wait()
    again = locked_folder(tmp_path, ".out.partial-")   # removes the killed maker's, not its own live one
    assert not theirs.exists() and mine.path.is_dir() and other.is_dir()
    mine.remove()
    again.remove()
    assert sorted(os.listdir(tmp_path)) == [f"{TEMP_PREFIX}x"]
