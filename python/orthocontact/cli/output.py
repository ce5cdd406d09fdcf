"""Where a command's results go: output paths checked before any work, a
staging folder committed only when everything is written, the folder's
manifest (output.manifest: a new run removes its predecessor's files, never
another's), and the warning lines that --strict counts."""
from __future__ import annotations

import contextlib
import errno
import os
import shutil
import sys
import tempfile
from pathlib import Path

from ..errors import InputError
from ..output.manifest import new_manifest, read_manifest, remove_earlier, write_manifest
from .interrupts import hold_interrupts, interrupted, results_written


# What the system answers a write it refuses: permission, a read-only file
# system, a full disk or quota, an I/O error.
REFUSALS = (errno.EACCES, errno.EPERM, errno.EROFS, errno.ENOSPC, errno.EDQUOT, errno.EIO)


def check_output_folder(out: Path, option: str = "--out") -> None:
    """Raises InputError, naming the user's path, unless `out` is (or can be
    created as) a writable folder; OSError naming the folder where the system
    refuses the write (REFUSALS: the command's exit 74).  Leaves nothing behind."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputError(f"{option} {out}: is a file; expected a folder to write the results into")
    probe = out
    while not probe.exists():
        if probe.parent == probe:
            break
        probe = probe.parent
    if probe != out and not probe.is_dir():
        raise InputError(f"{option} {out}: {probe} is a file, so no folder can be made under it")
    # access() says yes to root everywhere, /proc included: try instead.
    try:
        tempfile.TemporaryDirectory(prefix=".orthocontact-probe-", dir=probe).cleanup()
    except OSError as e:
        if e.errno in REFUSALS:   # the system's refusal: its own exit status (cli.main)
            raise OSError(e.errno, e.strerror, str(probe)) from None
        raise InputError(f"{option} {out}: {probe} is not writable ({e.strerror})") from None
    if out.is_dir():
        read_manifest(out)   # its list decides what the run removes: a bad one is refused now


def check_output_file(out: Path, option: str = "--out") -> None:
    """Raises InputError, naming the user's path, unless a file can be written
    at `out` (in an existing, writable folder); OSError as check_output_folder."""
    out = Path(out)
    if out.is_dir():
        raise InputError(f"{option} {out}: is a folder; expected a file name")
    if not out.parent.is_dir():
        raise InputError(f"{option} {out}: the folder {out.parent} does not exist")
    try:
        tempfile.TemporaryDirectory(prefix=".orthocontact-probe-", dir=out.parent).cleanup()
    except OSError as e:
        if e.errno in REFUSALS:   # the system's refusal: its own exit status (cli.main)
            raise OSError(e.errno, e.strerror, str(out.parent)) from None
        raise InputError(f"{option} {out}: {out.parent} is not writable ({e.strerror})") from None


@contextlib.contextmanager
def staged_output(out: Path, command: str | None = None):
    """A scratch folder beside `out`; its files move into `out` only if the
    block completes, so a failure or an interrupt leaves nothing behind: not
    the scratch folder, nor parent folders made for it, nor a half-written `out`.
    On success `out` is this run's (commit_run): the files an earlier run's
    manifest lists are replaced or removed, the user's own stay."""
    from ..fmu.files import locked_folder
    out = Path(out)
    made = []
    for parent in reversed(out.parents):
        if not parent.exists():
            parent.mkdir()
            made.append(parent)
    # Beside `out`, or in it where `out` is a file system of its own (a
    # mount point, a container's volume): a file moves by renaming only
    # within one file system.
    inside = out.is_dir() and out.stat().st_dev != out.parent.stat().st_dev
    # A locked folder (fmu.files): this run's while it lives; one a killed
    # run left there (SIGKILL cleans nothing) goes with the next run into `out`.
    held = None
    try:
        held = locked_folder(out if inside else out.parent, f".{out.name}.partial-")
        stage = held.path / "files"
        stage.mkdir()
        yield stage
        hold_interrupts()  # one arriving during the commit must not cut it in half
        # An interrupt that a finalizer swallowed ("Exception ignored in
        # __del__") still means the user asked to stop: commit nothing.
        if interrupted():
            raise KeyboardInterrupt
    except BaseException:
        if held is not None:
            held.remove()
        for parent in reversed(made):
            with contextlib.suppress(OSError):
                parent.rmdir()
        raise
    try:
        commit_run(stage, out, command)
    finally:   # a commit the system refused (disk full) leaves no scratch folder either
        held.remove()
    results_written(out)


def commit_run(stage: Path, out: Path, command: str | None) -> None:
    """Moves the run's files from `stage` into `out`, removes what the
    folder's earlier manifest lists and this run did not write, and writes
    this run's manifest last (a reader that finds it finds its files)."""
    from .. import __version__
    earlier = read_manifest(out) if out.is_dir() else None
    run = new_manifest(stage, command, __version__)
    _move_into(stage, out)
    if earlier is not None:
        kept = remove_earlier(out, earlier, run.files)
        if kept:
            warn(f"{out}: kept {', '.join(kept)} of {earlier.describe()}: changed since that run "
                 "wrote them, so they are taken as yours; they are not this run's outputs")
    write_manifest(out, run)


def _move_into(src: Path, dst: Path) -> None:
    """Every file under `src` to the same place under `dst`, replacing only
    the files written: what else the user keeps in `dst` (and in its
    subfolders, e.g. reproduce's <out>/<scenario>/) stays."""
    dst.mkdir(exist_ok=True)
    for item in src.iterdir():
        target = dst / item.name
        if item.is_dir() and target.is_dir() and not target.is_symlink():
            _move_into(item, target)
            continue
        if target.is_dir() and not target.is_symlink():
            shutil.rmtree(target)  # a folder where this command writes a file
        os.replace(item, target)


_warnings: list[str] = []


def warnings_said() -> int:
    """How many warnings this command has printed."""
    return len(_warnings)


def forget_warnings() -> None:
    _warnings.clear()


def warn(line: str) -> None:
    """One warning line on stderr; --strict turns any into exit status 1."""
    _warnings.append(line)
    print(f"orthocontact: warning: {line}", file=sys.stderr, flush=True)
