"""Where a command's results go: output paths checked before any work, a
staging folder committed only when everything is written, and the warning
lines that --strict counts."""
from __future__ import annotations

import contextlib
import os
import shutil
import sys
import tempfile
from pathlib import Path

from ..errors import InputError
from .interrupts import interrupted


def check_output_folder(out: Path, option: str = "--out") -> None:
    """Raises InputError, naming the user's path, unless `out` is (or can be
    created as) a writable folder.  Leaves nothing behind."""
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
        raise InputError(f"{option} {out}: {probe} is not writable ({e.strerror})") from None


def check_output_file(out: Path, option: str = "--out") -> None:
    """Raises InputError, naming the user's path, unless a file can be written
    at `out` (in an existing, writable folder)."""
    out = Path(out)
    if out.is_dir():
        raise InputError(f"{option} {out}: is a folder; expected a file name")
    if not out.parent.is_dir():
        raise InputError(f"{option} {out}: the folder {out.parent} does not exist")
    try:
        tempfile.TemporaryDirectory(prefix=".orthocontact-probe-", dir=out.parent).cleanup()
    except OSError as e:
        raise InputError(f"{option} {out}: {out.parent} is not writable ({e.strerror})") from None


@contextlib.contextmanager
def staged_output(out: Path):
    """A scratch folder beside `out`; its files move into `out` only if the
    block completes, so a failure or an interrupt leaves nothing behind: not
    the scratch folder, nor parent folders made for it, nor a half-written `out`."""
    out = Path(out)
    made = []
    for parent in reversed(out.parents):
        if not parent.exists():
            parent.mkdir()
            made.append(parent)
    stage = Path(tempfile.mkdtemp(prefix=f".{out.name}.partial-", dir=out.parent))
    try:
        yield stage
        # An interrupt that a finalizer swallowed ("Exception ignored in
        # __del__") still means the user asked to stop: commit nothing.
        if interrupted():
            raise KeyboardInterrupt
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        for parent in reversed(made):
            with contextlib.suppress(OSError):
                parent.rmdir()
        raise
    _move_into(stage, out)
    shutil.rmtree(stage, ignore_errors=True)


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
