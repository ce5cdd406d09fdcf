"""Every text file a user hands the tool is read here: scenarios, rig.toml,
the reduced data and raw recordings' CSVs, identified.json.  One reader, so
that what a lab's files meet is met once for every format: a byte-order
mark, Windows line ends, a file that is not UTF-8, an OS error, each one
line naming the file; and one record of what was read, so that a result can
name the exact bytes it came from (provenance: `files_read`).

What a spreadsheet in another locale writes is read, not guessed at:
  - a CSV whose header line is separated by semicolons (or tabs) and has no
    comma is read with that separator, and a number with a decimal comma in
    it (0,5; -1,25e-3) is read as with a point (0.5): Excel writes this where
    the decimal separator is a comma;
  - what stays ambiguous is refused with one line saying what was seen and
    what to do: a decimal comma in a comma-separated file (a row with more
    cells than the header, or a quoted "0,5"), a thousands separator
    (1.234,5, or 1.234 beside decimal commas), a decimal comma in a TOML
    file (mass_kg = 1,875)."""
from __future__ import annotations

import contextlib
import csv
import hashlib
import re
import sys
from dataclasses import dataclass
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

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
    finally:   # by identity: two logs that read the same files are equal dicts
        del _logs[next(i for i, x in enumerate(_logs) if x is log)]


def paths_being_read() -> list[Path]:
    """Every file read inside the files_read() blocks open now (a command's:
    cli.main records what it reads, so that its output folder can be held to
    hold none of it)."""
    return sorted({entry.path for log in _logs for entry in log.values()})


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


SEPARATOR_NAMES = {",": "commas", ";": "semicolons", "\t": "tabs"}
# A number written with a decimal comma: 0,5  -1,25  ,5  3,0e-4 (no other comma, no point).
DECIMAL_COMMA = re.compile(r"^[+-]?(\d+,\d*|,\d+)([eE][+-]?\d+)?$")
# A number with both separators: 1.234,5 or 1,234.5 (a thousands separator).
THOUSANDS = re.compile(r"^[+-]?\d{1,3}([.,]\d{3})+[.,]\d*([eE][+-]?\d+)?$")
# Two points with no line break between: in cells joined by line breaks, a
# cell THOUSANDS matches with points (1.234.5; it holds digits and separators only).
TWO_POINTS = re.compile(r"\.[^\n]*\.")
POINT_NUMBER = re.compile(r"^[+-]?(\d+\.\d*|\.\d+)([eE][+-]?\d+)?$")
PLAIN_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")
# A TOML line `key = 1,875`: invalid TOML that a decimal comma explains.
TOML_DECIMAL_COMMA = re.compile(r"^\s*([A-Za-z0-9_.\"-]+)\s*=\s*([+-]?\d+,\d+([eE][+-]?\d+)?)\s*(#.*)?$")


def separator_of(header: str) -> str:
    """The CSV's separator, from its header line: a comma if it has one,
    else a semicolon or a tab if it has one, else a comma."""
    if "," in header:
        return ","
    for sep in (";", "\t"):
        if sep in header:
            return sep
    return ","


def read_rows(path, what: str) -> list[tuple[int, list[str]]]:
    """A CSV file as (line number, cells) rows, the header first: cells
    stripped, blank rows and rows starting with # dropped, the file read by
    read_text (UTF-8, BOM, line ends).  A semicolon- or tab-separated file
    (the header decides) has its decimal commas read as points; what cannot
    be read unambiguously is an InputError naming the line and what to do
    (module docstring)."""
    path = Path(path)
    lines = read_text(path, what).split("\n")
    header = next((ln for ln in lines if ln.strip() and not ln.lstrip().startswith("#")), "")
    sep = separator_of(header)
    reader = csv.reader(lines, delimiter=sep)
    rows = []
    line = 1
    for cells in reader:
        first, line = line, reader.line_num + 1   # a quoted cell may span lines
        cells = [c.strip() for c in cells]
        if not any(cells) or cells[0].startswith("#"):
            continue
        rows.append((first, cells))
    return _decimal_commas(path, rows, sep) if sep != "," else _comma_file(path, rows)


def _comma_file(path: Path, rows):
    """A comma-separated file's rows, after refusing the decimal commas it may hold."""
    if not rows:
        return rows
    width = len(rows[0][1])
    for line, cells in rows[1:]:
        used = len(cells)
        while used and not cells[used - 1]:
            used -= 1     # trailing empty cells ("1,2,") say nothing
        if used > width:
            hint = ""
            numbers = [bool(PLAIN_NUMBER.match(c)) for c in cells[:used]]
            if any(a and b for a, b in zip(numbers, numbers[1:])):   # 0,5 split in two
                hint = (": decimal commas such as 0,5? In a comma-separated file write 0.5 "
                        "(or save the file separated by semicolons, which is read with decimal commas)")
            raise InputError(f"{path}: line {line}: {used} cells ({','.join(cells[:used])}) where the "
                             f"header names {width} columns{hint}")
        joined = "\n".join(cells[:used])
        if "," not in joined and not TWO_POINTS.search(joined):
            continue   # both patterns need a comma or a cell's second point
        for c in cells[:used]:
            if DECIMAL_COMMA.match(c) or THOUSANDS.match(c):
                raise InputError(f"{path}: line {line}: {c!r}: a decimal comma (or a thousands "
                                 "separator) in a comma-separated file; write numbers with a "
                                 "decimal point and no thousands separator (0.5, 1234.5)")
    return rows


def _decimal_commas(path: Path, rows, sep: str):
    """A semicolon/tab-separated file's rows with its decimal commas read as
    points; a thousands separator, or points beside decimal commas, refused."""
    comma_at = point_at = None
    for line, cells in rows[1:]:
        for c in cells:
            if THOUSANDS.match(c) and "." in c and "," in c:
                raise InputError(f"{path}: line {line}: {c!r}: a number with a thousands separator; "
                                 "write numbers without one (e.g. 1234,5)")
            if comma_at is None and DECIMAL_COMMA.match(c):
                comma_at = (line, c)
            if point_at is None and POINT_NUMBER.match(c):
                point_at = (line, c)
    if comma_at and point_at:
        raise InputError(f"{path}: line {point_at[0]}: {point_at[1]!r} beside decimal commas such as "
                         f"{comma_at[1]!r} (line {comma_at[0]}) in a file separated by "
                         f"{SEPARATOR_NAMES[sep]}: a thousands separator, or a decimal point? write "
                         "every number with the same decimal separator and no thousands separator")
    if not comma_at:
        return rows
    return [(line, [c.replace(",", ".") if DECIMAL_COMMA.match(c) else c for c in cells])
            for line, cells in rows]


def read_toml(path, what: str) -> dict:
    """A TOML file (read_text), parsed; a decimal comma (key = 1,875) is an
    InputError naming the line; any other syntax error is tomllib's
    TOMLDecodeError, for the caller to name in its own terms."""
    text = read_text(path, what)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        for n, ln in enumerate(text.split("\n"), 1):
            m = TOML_DECIMAL_COMMA.match(ln)
            if m:
                raise InputError(f"{Path(path)}: line {n}: {m[1]} = {m[2]}: a decimal comma; TOML "
                                 f"numbers take a decimal point ({m[1]} = {m[2].replace(',', '.')})"
                                 ) from None
        raise
