"""Where the FMUs are: a given path, $ORTHOCONTACT_FMU / $ORTHOCONTACT_FMU3,
or the ones installed with the package; their model descriptions (parsed
once per file) and unpacked folders (once per file and process)."""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass
from pathlib import Path

from fmpy import extract, read_model_description

MODEL_IDENTIFIER = "OrthotropicContact"


FMU_ENV = {2: "ORTHOCONTACT_FMU", 3: "ORTHOCONTACT_FMU3"}


FMI_VERSIONS = (2, 3)


RIG_MODEL_IDENTIFIER = "CarriageBlock"


PACKAGE_ROOT = Path(__file__).resolve().parents[1]   # the orthocontact folder


def installed_file(rel, folder: bool = False) -> Path | None:
    """A file (or, with folder, a folder) installed with the package, `rel`
    relative to it: in the package's folder, or (an editable install, whose
    code stays in the source tree) under `orthocontact/` in a site-packages
    folder on sys.path."""
    exists = Path.is_dir if folder else Path.is_file
    here = PACKAGE_ROOT / rel
    if exists(here):
        return here
    for entry in sys.path:
        candidate = Path(entry or ".") / "orthocontact" / rel
        if exists(candidate):
            return candidate
    return None


def _installed(fmi_version: int, model: str = MODEL_IDENTIFIER):
    """The FMU of `model` installed with the package, or None."""
    return installed_file(Path(f"fmi{fmi_version}") / (model + ".fmu"))


def find_fmu(path: str | os.PathLike | None = None, fmi_version: int = 2,
             model: str = MODEL_IDENTIFIER) -> Path:
    """The FMU to use: `path`, else $ORTHOCONTACT_FMU ($ORTHOCONTACT_FMU3 for
    FMI 3.0), else the one installed with the package (regular or editable
    install).  fmi_version: 2 (default) or 3; model: "OrthotropicContact" (the
    contact, default) or "CarriageBlock" (the rig of the experiment).  Raises
    FileNotFoundError with a one-line message saying what to do."""
    if fmi_version not in FMI_VERSIONS:
        raise ValueError(f"fmi_version must be 2 or 3, got {fmi_version!r}")
    env = FMU_ENV[fmi_version] if model == MODEL_IDENTIFIER else None
    for given, where in ((path, "given path"), (os.environ.get(env) if env else None, f"${env}")):
        if given:
            if not Path(given).is_file():
                raise FileNotFoundError(f"FMU not found: {given} ({where})")
            return Path(given)
    installed = _installed(fmi_version, model)
    if installed is not None:
        return installed
    raise FileNotFoundError(
        f"the FMI {fmi_version}.0 {model}.fmu is not installed with the package; run "
        f"`pip install .` (or `pip install -e .`) from the repository, which builds it"
        + (f", or set {env}" if env else ""))


# -- folders that say whether their maker lives ---------------------------------
#
# A command's scratch (its temporary folder of unpacked FMUs, the staging
# folder of its output, an .ssp being zipped) is a locked folder: it holds a
# lock (flock on .lock) for as long as any process of the command lives (a
# forked worker shares it).  SIGKILL runs no cleanup, so a killed command's
# folders stay; their lock is then free, and the next command that makes a
# folder of the same kind in the same place removes them.  The lock file is
# locked before it takes its name (.lock), so a folder whose .lock is free is
# never one being made.  A folder killed before its lock took its name has
# none; its name says whose it was (<prefix><pid>.<start>-...: the maker's
# pid and the kernel's start time of that process), so it is removed once
# that process is gone, and a folder of that prefix with no such name is
# not one of ours and stays.

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
        import shutil
        import time
        for _ in range(20):
            shutil.rmtree(self.path, ignore_errors=True)
            if not self.path.exists():
                break
            time.sleep(0.05)
        if self.fd is not None:
            os.close(self.fd)


def locked_folder(parent, prefix: str) -> LockedFolder:
    """A new folder `prefix` + random in `parent`, holding its lock;
    first removes the abandoned folders of the same prefix there
    (remove_abandoned)."""
    import tempfile
    remove_abandoned(parent, prefix)
    folder = Path(tempfile.mkdtemp(prefix=f"{prefix}{maker_tag(os.getpid())}-", dir=parent))
    making, fd = folder / (LOCK + ".new"), None
    try:
        fd = os.open(making, os.O_CREAT | os.O_EXCL | os.O_RDWR | getattr(os, "O_CLOEXEC", 0), 0o600)
        if _fcntl is not None:
            _fcntl.flock(fd, _fcntl.LOCK_EX | _fcntl.LOCK_NB)
        os.replace(making, folder / LOCK)
    except BaseException:   # a full disk, an interrupt: no folder left
        LockedFolder(folder, fd).remove()
        raise
    return LockedFolder(folder, fd)


def maker_tag(pid: int) -> str | None:
    """`<pid>.<start>`: the process and the kernel's clock ticks at its
    start (/proc/<pid>/stat's 22nd field), which no later process of that
    pid shares; None if the process does not exist (or, off Linux, `<pid>.0`)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            stat = fh.read()
    except FileNotFoundError:
        return None
    except OSError:
        return f"{pid}.0"
    # the name (field 2) is in parentheses and may hold spaces: count after it
    return f"{pid}.{int(stat[stat.rindex(b')') + 2:].split()[19])}"


def _maker_gone(name: str, prefix: str) -> bool:
    """Whether the folder `name` (of `prefix`) was made by a process that no
    longer lives; False for a name that does not say its maker."""
    tag = name[len(prefix):].split("-", 1)[0]
    pid, _, start = tag.partition(".")
    if not (pid.isdigit() and start.isdigit()) or start == "0":
        return False
    return maker_tag(int(pid)) != tag


def remove_abandoned(parent=None, prefix: str | None = None) -> list[Path]:
    """Removes the folders `prefix`* in `parent` (default: this command's
    kind, TEMP_PREFIX in the system's temp folder) whose lock is free: their
    command was killed, no process of theirs lives; and those without a lock
    file whose name says their maker is gone (killed before the lock took its
    name).  Any other folder without a lock file is not judged (not one of
    ours, or one being made), nor any where the system has no flock
    (Windows).  Returns those removed."""
    import shutil
    import tempfile
    gone = []
    if _fcntl is None:
        return gone
    parent = Path(tempfile.gettempdir() if parent is None else parent)
    prefix = TEMP_PREFIX if prefix is None else prefix
    for folder in parent.glob(prefix + "*"):
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


# -- one temporary folder per command ----------------------------------------------
#
# Every unpacked FMU goes into one folder per command: the first process of
# the command makes it and removes it when it ends, whatever its workers
# (forked or Dask's) unpacked there.  A worker killed mid-run cannot clean up
# after itself, so its files must be somewhere its parent removes.  It is a
# locked folder: the next command removes it if the command was killed.

TEMP_PREFIX = "orthocontact-"

TEMP_ENV = "ORTHOCONTACT_TEMP"  # a command's folder, given to its spawned workers (Dask's)

_temp: tuple[LockedFolder, int | None] | None = None  # (the folder, pid of its owner or None)

_cleanup_registered = False


def temp_folder() -> Path:
    """This command's temporary folder: $ORTHOCONTACT_TEMP in a worker the
    command started, else one made here under the system's temp folder
    ($TMPDIR), removed when this process ends (remove_unzipped)."""
    global _temp, _cleanup_registered
    if _temp is not None:
        return _temp[0].path
    given = os.environ.get(TEMP_ENV)
    if given and Path(given).is_dir():
        _temp = (LockedFolder(Path(given), None), None)  # its owner removes it
        return _temp[0].path
    import tempfile
    held = locked_folder(tempfile.gettempdir(), TEMP_PREFIX)
    if not _cleanup_registered:
        _cleanup_registered = True
        import atexit
        from multiprocessing import util
        atexit.register(remove_unzipped)
        # A multiprocessing child (a Dask worker, a spawned pool worker)
        # ends by os._exit, which skips atexit but runs these.
        util.Finalize(None, remove_unzipped, exitpriority=0)
    _temp = (held, os.getpid())
    return held.path


_extracted: dict[Path, tuple[str, int]] = {}  # FMU -> (its unpacked folder, the pid that made it)


def unzipped(path: Path) -> str:
    """One extraction per FMU file and process (instances share it; forked
    workers share the parent's), in the command's temporary folder
    (temp_folder), so no run leaves an unpacked FMU in the temp folder, not
    even one of a worker that was killed."""
    import tempfile
    key = path.resolve()
    if key not in _extracted:
        folder = tempfile.mkdtemp(prefix="fmu-", dir=temp_folder())
        _extracted[key] = (extract(str(key), unzipdir=folder), os.getpid())
    return _extracted[key][0]


def remove_unzipped() -> None:
    """Removes the unpacked FMUs this process made (not those of a parent it
    was forked from, which the parent still uses) and, in the process that
    made it, the command's temporary folder with everything its workers left
    there."""
    import shutil
    global _temp
    for key, (folder, pid) in list(_extracted.items()):
        if pid == os.getpid():
            shutil.rmtree(folder, ignore_errors=True)
            del _extracted[key]
    if _temp is not None and _temp[1] == os.getpid():
        _temp[0].remove()
        _temp = None


_descriptions: dict = {}


def model_description(path):
    """fmpy's reading of the FMU's modelDescription.xml, parsed once per
    file version and process (a reproduction asks for it dozens of times)."""
    p = Path(path).resolve()
    st = p.stat()
    key = (p, st.st_mtime_ns, st.st_size)
    if key not in _descriptions:
        _descriptions[key] = read_model_description(str(p))
    return _descriptions[key]


def fmi_version_of(path) -> int:
    """2 or 3: the FMI version of the FMU at `path`."""
    return int(model_description(path).fmiVersion.split(".")[0])
