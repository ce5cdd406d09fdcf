"""Every text file a user hands the tool is read here: scenarios, rig.toml,
the reduced data and raw recordings' CSVs, identified.json.  One reader, so
that what a lab's files meet is met once for every format: a byte-order
mark, Windows line ends, a file that is not UTF-8, an OS error, each one
line naming the file; and one record of what was read, so that a result can
name the exact bytes it came from (provenance: `files_read`)."""
from __future__ import annotations

import contextlib
import hashlib
from dataclasses import dataclass
from pathlib import Path

from .errors import InputError

BOM = "\ufeff"


@dataclass(frozen=True)
class FileRead:
    """A file as it was read: its path as given and the SHA-256 of its bytes."""
    path: Path
    sha256: str


_logs: list[dict] = []   # open files_read() records, innermost last


@contextlib.contextmanager
def files_read():
    """Records every file read through this module inside the block:
    yields a dict, path as given (str) -> FileRead, filled as files are read."""
    log: dict = {}
    _logs.append(log)
    try:
        yield log
    finally:
        _logs.remove(log)


def sha256_of(path) -> str:
    """The SHA-256 [hex] of the file's bytes; InputError (one line) if unreadable."""
    return hashlib.sha256(read_bytes(path, "a file")).hexdigest()


def read_bytes(path, what: str) -> bytes:
    """The file's bytes, recorded in every open files_read(); InputError
    naming the file and `what` was expected there if it cannot be read."""
    path = Path(path)
    try:
        blob = path.read_bytes()
    except FileNotFoundError:
        raise InputError(f"{path}: not found; expected {what}") from None
    except IsADirectoryError:
        raise InputError(f"{path}: is a folder; expected {what}") from None
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror}); expected {what}") from None
    if _logs:
        entry = FileRead(path, hashlib.sha256(blob).hexdigest())
        for log in _logs:
            log[str(path)] = entry
    return blob


def read_text(path, what: str) -> str:
    """The file as text: UTF-8, a leading byte-order mark dropped (Excel's
    "CSV UTF-8" writes one), Windows and old Mac line ends made \\n."""
    blob = read_bytes(path, what)
    try:
        text = blob.decode("utf-8")
    except UnicodeDecodeError as e:
        raise InputError(f"{Path(path)}: byte {e.start}: not UTF-8 text; expected {what} "
                         "(save it as UTF-8, e.g. Excel's \"CSV UTF-8\")") from None
    if text.startswith(BOM):
        text = text[1:]
    return text.replace("\r\n", "\n").replace("\r", "\n")
