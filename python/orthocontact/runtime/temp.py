"""One temporary folder per command, and the unzip cache in it.

Every unpacked FMU goes into one folder per command: the first process of
the command makes it and removes it when it ends, whatever its workers
(forked or Dask's) unpacked there.  A worker killed mid-run cannot clean up
after itself, so its files must be somewhere its parent removes.  It is a
locked folder (folders): the next command removes it if the command was
killed."""
from __future__ import annotations

import atexit
import os
import shutil
import tempfile
from pathlib import Path

from .folders import LockedFolder, locked_folder

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
    held = locked_folder(tempfile.gettempdir(), TEMP_PREFIX)
    if not _cleanup_registered:
        _cleanup_registered = True
        from multiprocessing import util
        atexit.register(remove_unzipped)
        # A multiprocessing child (a Dask worker, a spawned pool worker)
        # ends by os._exit, which skips atexit but runs these.
        util.Finalize(None, remove_unzipped, exitpriority=0)
    _temp = (held, os.getpid())
    return held.path


_extracted: dict[Path, tuple[str, int]] = {}  # FMU -> (its unpacked folder, the pid that made it)


def unzipped(path) -> str:
    """One extraction per FMU file and process (instances share it; forked
    workers share the parent's), in the command's temporary folder
    (temp_folder), so no run leaves an unpacked FMU in the temp folder, not
    even one of a worker that was killed."""
    from fmpy import extract
    key = Path(path).resolve()
    if key not in _extracted:
        folder = tempfile.mkdtemp(prefix="fmu-", dir=temp_folder())
        _extracted[key] = (extract(str(key), unzipdir=folder), os.getpid())
    return _extracted[key][0]


def remove_unzipped() -> None:
    """Removes the unpacked FMUs this process made (not those of a parent it
    was forked from, which the parent still uses) and, in the process that
    made it, the command's temporary folder with everything its workers left
    there."""
    global _temp
    for key, (folder, pid) in list(_extracted.items()):
        if pid == os.getpid():
            shutil.rmtree(folder, ignore_errors=True)
            del _extracted[key]
    if _temp is not None and _temp[1] == os.getpid():
        _temp[0].remove()
        _temp = None
