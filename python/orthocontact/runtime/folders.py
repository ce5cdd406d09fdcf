"""Folders that say whether their maker lives.

A command's scratch (its temporary folder of unpacked FMUs, the staging
folder of its output, an .ssp being zipped) is a locked folder: it holds a
lock (flock on .lock) for as long as any process of the command lives (a
forked worker shares it).  SIGKILL runs no cleanup, so a killed command's
folders stay; their lock is then free, and the next command that makes a
folder of the same kind in the same place removes them.  The lock file is
locked before it takes its name (.lock), so a folder whose .lock is free is
never one being made.  A folder killed before its lock took its name has
none; its name says whose it was (<prefix><pid>.<start>-...: the maker's
pid and the kernel's start time of that process), so it is removed once
that process is gone (or a zombie: killed, not yet reaped), and a folder of
that prefix with no such name is not one of ours and stays."""
from __future__ import annotations

import glob
import os
import shutil
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

try:
    import fcntl as _fcntl
except ImportError:  # Windows: no flock, so no judging of other commands' folders
    _fcntl = None

LOCK = ".lock"


@dataclass(frozen=True)
class LockedFolder:
    """A folder that holds its lock while the process that made it (and
    the processes forked from it) live."""
    path: Path
    fd: int | None   # the lock's file descriptor (None without flock)

    def remove(self) -> None:
        """Removes the folder and everything in it, then releases the lock.
        A file that appears while the tree is removed (a process of ours
        ending as it writes) makes a folder non-empty: removed again, for up
        to a second; what is still left goes with the next command (its
        maker is gone by then)."""
        for _ in range(20):
            shutil.rmtree(self.path, ignore_errors=True)
            if not self.path.exists():
                break
            time.sleep(0.05)
        if self.fd is not None:
            os.close(self.fd)


def locked_folder(parent, prefix: str) -> LockedFolder:
    """A new folder `prefix` + random in `parent`, holding its lock, by its
    absolute path; first removes the abandoned folders of the same prefix
    there (remove_abandoned)."""
    parent = Path(parent).absolute()   # its removal must not depend on the working folder then
    remove_abandoned(parent, prefix)
    folder = Path(tempfile.mkdtemp(prefix=f"{prefix}{maker_tag(os.getpid())}-", dir=parent))
    making, fd = folder / (LOCK + ".new"), None
    try:
        fd = os.open(making, os.O_CREAT | os.O_EXCL | os.O_RDWR | getattr(os, "O_CLOEXEC", 0), 0o600)
        if _fcntl is not None:
            _fcntl.flock(fd, _fcntl.LOCK_EX | _fcntl.LOCK_NB)
        os.replace(making, folder / LOCK)
        return LockedFolder(folder, fd)
    except BaseException:   # a full disk, an interrupt: no folder left
        LockedFolder(folder, fd).remove()
        raise


def maker_tag(pid: int) -> str | None:
    """`<pid>.<start>`: the process and the kernel's clock ticks at its
    start (/proc/<pid>/stat's 22nd field), which no later process of that
    pid shares; None if the process does not exist or has ended (a zombie
    its parent has not reaped: its files are closed, its locks free), or,
    off Linux, `<pid>.0`."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            stat = fh.read()
    except FileNotFoundError:
        return None
    except OSError:
        return f"{pid}.0"
    # the name (field 2) is in parentheses and may hold spaces: count after it
    fields = stat[stat.rindex(b')') + 2:].split()
    if fields[0] in (b"Z", b"X") and _threads(pid) <= 1:
        return None   # ended, not yet reaped: its files are closed (with threads: once the last ends)
    return f"{pid}.{int(fields[19])}"


def _threads(pid: int) -> int:
    """The threads of process `pid` that have not ended (0 if it is gone)."""
    try:
        return len(os.listdir(f"/proc/{pid}/task"))
    except OSError:
        return 0


def _maker_gone(name: str, prefix: str) -> bool:
    """Whether the folder `name` (of `prefix`) was made by a process that no
    longer lives; False for a name that does not say its maker."""
    tag = name[len(prefix):].split("-", 1)[0]
    pid, _, start = tag.partition(".")
    if not (pid.isdigit() and start.isdigit()) or start == "0":
        return False
    return maker_tag(int(pid)) != tag


def remove_abandoned(parent, prefix: str) -> list[Path]:
    """Removes the folders `prefix`* in `parent` whose lock is free: their
    command was killed, no process of theirs lives; and those without a lock
    file whose name says their maker is gone (killed before the lock took its
    name).  Any other folder without a lock file is not judged (not one of
    ours, or one being made), nor any where the system has no flock
    (Windows).  Returns those removed."""
    gone = []
    if _fcntl is None:
        return gone
    # escaped: an --out named like a pattern (`run[1]`) still finds its own
    for folder in Path(parent).glob(glob.escape(prefix) + "*"):
        try:
            if folder.is_symlink() or not folder.is_dir() or folder.stat().st_uid != os.getuid():
                continue
            fd = os.open(folder / LOCK, os.O_RDWR | os.O_CLOEXEC | os.O_NOFOLLOW)
        except FileNotFoundError:
            if _maker_gone(folder.name, prefix):   # killed before its lock took its name
                shutil.rmtree(folder, ignore_errors=True)
                gone.append(folder)
            continue  # otherwise not one of ours, or being made right now
        except OSError:
            continue  # not one of ours, or being removed right now
        try:
            _fcntl.flock(fd, _fcntl.LOCK_EX | _fcntl.LOCK_NB)
        except OSError:
            continue  # in use
        finally:
            os.close(fd)
        shutil.rmtree(folder, ignore_errors=True)
        gone.append(folder)
    return gone
