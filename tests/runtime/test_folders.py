"""Folders that say whether their maker lives (orthocontact.runtime.folders):
a folder is removed by the next one of its kind once no process of its
maker lives, whenever a SIGKILL cut its making, and never while it lives."""
import fcntl
import os
import subprocess
import sys

import pytest

from cli_run import CMD
from orthocontact.runtime.folders import LOCK, locked_folder, maker_tag, remove_abandoned
from orthocontact.runtime.temp import TEMP_PREFIX


def test_only_abandoned_folders_are_removed(tmp_path):
    """A folder whose lock is free is abandoned at once (its lock file is
    locked before it takes its name, so it is never one being made); one
    whose lock is held, one being made (no .lock yet) and one without a
    lock file are left."""
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
        assert sorted(remove_abandoned(tmp_path, TEMP_PREFIX)) == sorted([made["abandoned"], killed])
    finally:
        os.close(fd)
    assert sorted(os.listdir(tmp_path)) == sorted([f"{TEMP_PREFIX}being-made", f"{TEMP_PREFIX}in-use",
                                                  f"{TEMP_PREFIX}not-ours", making.name, "other"])


def test_a_locked_folder_is_held_while_its_maker_lives(tmp_path):
    """locked_folder's lock, seen from another process: held while the
    folder's maker lives, free once it is killed; the next folder of the
    kind made there removes it, and only folders of its own prefix."""
    code = ("import sys, time; from orthocontact.runtime.folders import locked_folder; "
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


# -- a SIGKILL at any point of locked_folder leaves a folder the next one removes -----

DIE_AT = """
import fcntl, os, signal, sys
from orthocontact.runtime import folders
point, real = sys.argv[2], {"open": os.open, "flock": fcntl.flock, "replace": os.replace}
die = lambda: os.kill(os.getpid(), signal.SIGKILL)
def at(name, cut):
    def call(*a, **k):
        if cut(*a):
            die()
        return real[name](*a, **k)
    return call
os.open = at("open", lambda path, *a: point == "made" and str(path).endswith(".lock.new"))
fcntl.flock = at("flock", lambda *a: point == "lock file made")
os.replace = at("replace", lambda *a: point == "locked")
folders.locked_folder(sys.argv[1], ".out.partial-")
die()   # named: the folder is complete, its lock held until now
"""


@pytest.mark.parametrize("point", ["made", "lock file made", "locked", "named"])
@pytest.mark.parametrize("reaped", [True, False], ids=["reaped", "zombie"])
def test_a_folder_killed_at_any_point_of_its_making_goes_with_the_next(tmp_path, point, reaped):
    """SIGKILL right after mkdtemp (an empty folder), after .lock.new is
    made, after it is locked, after it took its name: the next
    remove_abandoned of the kind removes it, also while the killed process
    is a zombie its parent has not reaped yet (it holds no lock then, and a
    folder judged by its name's maker used to stay until the reaping)."""
    proc = subprocess.Popen([sys.executable, "-c", DIE_AT, str(tmp_path), point])
    try:
        if reaped:
            proc.wait(timeout=30)
        else:
            while (maker_tag(proc.pid) or "").startswith(f"{proc.pid}."):   # until it is a zombie
                pass
        left = list(tmp_path.iterdir())
        assert len(left) == 1 and left[0].name.startswith(f".out.partial-{proc.pid}."), left
        assert [p.name for p in left[0].iterdir()] == {"made": [], "lock file made": [LOCK + ".new"],
                                                       "locked": [LOCK + ".new"], "named": [LOCK]}[point]
        assert remove_abandoned(tmp_path, ".out.partial-") == left
        assert list(tmp_path.iterdir()) == []
    finally:
        proc.kill()
        proc.wait(timeout=30)
    assert proc.returncode == -9


def test_a_prefix_with_pattern_characters_finds_its_own_folders(tmp_path):
    """--out 'run[1]': its staging folders' prefix `.run[1].partial-` is a
    glob pattern that matched none of them (a killed run's stayed)."""
    prefix = ".run[1].partial-"
    mine = locked_folder(tmp_path, prefix)
    abandoned = tmp_path / f"{prefix}x"
    abandoned.mkdir()
    (abandoned / LOCK).write_text("")
    decoy = tmp_path / ".run1.partial-x"   # what the pattern matched
    decoy.mkdir()
    (decoy / LOCK).write_text("")
    assert remove_abandoned(tmp_path, prefix) == [abandoned]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([mine.path.name, decoy.name])
    mine.remove()
