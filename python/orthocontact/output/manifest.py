"""An output folder's manifest: what one orthocontact command wrote there.

`<out>/.orthocontact-manifest.json` names the command, a run id, the date,
the package version and every file the run wrote (its path under the folder,
subfolders included, and its SHA-256).  With it a command that reads
another's outputs (uq and export read identified.json, uq a
rig_scenario.toml) can tell that they all come from one run and are as that
run wrote them (written_by, one_run); what a new run into the folder does
with it (removes its predecessor's files and nothing else, keeps those
edited since) is the output folder's logic, output.folder."""
from __future__ import annotations

import hashlib
import json
import os
import uuid
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path, PurePosixPath

from ..errors import InputError

MANIFEST = ".orthocontact-manifest.json"


@dataclass(frozen=True)
class Manifest:
    """One run's record of its output folder."""
    command: str | None       # the subcommand: identify, uq, ...
    run_id: str               # unique per run (a UUID's 32 hex digits)
    date: str                 # when it was written, UTC, ISO 8601 to the second
    version: str              # the package's version
    files: dict = field(default_factory=dict)   # POSIX path under the folder -> SHA-256 (hex)

    def describe(self) -> str:
        """`orthocontact CMD` run ID of DATE: how messages name the run."""
        return f"`orthocontact {self.command or '?'}` run {self.run_id[:12]} of {self.date}"

    def as_json(self) -> dict:
        return {"written_by": "orthocontact", "command": self.command, "run_id": self.run_id,
                "date": self.date, "version": self.version,
                "files": {k: self.files[k] for k in sorted(self.files)}}


def file_sha256(path: Path) -> str:
    """The SHA-256 (hex) of the file's bytes."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def file_names(folder: Path) -> list[str]:
    """Every file under `folder` (subfolders included, the manifest left
    out), as its POSIX path under the folder, sorted."""
    folder = Path(folder)
    return [p.relative_to(folder).as_posix() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != MANIFEST]


def listing(folder: Path) -> dict:
    """Every file under `folder` (file_names) -> its SHA-256."""
    return {name: file_sha256(Path(folder) / name) for name in file_names(folder)}


def new_manifest(folder: Path, command: str | None, version: str) -> Manifest:
    """The manifest of a run whose files are those now under `folder`."""
    return Manifest(command, uuid.uuid4().hex, datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
                    version, listing(folder))


def write_manifest(folder: Path, m: Manifest) -> Path:
    """Writes `m` as the folder's manifest, replacing any (atomically)."""
    path = Path(folder) / MANIFEST
    tmp = path.with_name(MANIFEST + ".new")
    tmp.write_text(json.dumps(m.as_json(), indent=2) + "\n")
    os.replace(tmp, path)
    return path


def _safe_relative(name) -> bool:
    """A path the manifest may name: relative, inside the folder, not the manifest."""
    if not isinstance(name, str) or not name or "\\" in name:
        return False
    p = PurePosixPath(name)
    return not p.is_absolute() and ".." not in p.parts and "." not in p.parts and p.name != MANIFEST


def read_manifest(folder: Path) -> Manifest | None:
    """The folder's manifest, or None if it has none; InputError (one line)
    if it is not one orthocontact wrote, since its list decides what a new
    run removes."""
    path = Path(folder) / MANIFEST
    if not path.is_file():
        return None
    why = f"{path}: expected the manifest an orthocontact command writes (remove it if it is not one)"
    try:
        d = json.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})") from None
    except ValueError:
        raise InputError(why) from None
    if not isinstance(d, dict) or d.get("written_by") != "orthocontact":
        raise InputError(why)
    files = d.get("files")
    if not isinstance(files, dict) or not all(_safe_relative(k) and isinstance(v, str)
                                              for k, v in files.items()):
        raise InputError(f"{path}: files: expected paths inside the folder with their SHA-256")
    if not isinstance(d.get("run_id"), str) or not d["run_id"]:
        raise InputError(f"{path}: run_id: expected the run's id")
    return Manifest(d.get("command"), d["run_id"], str(d.get("date")), str(d.get("version")), dict(files))


def written_by(path) -> Manifest | None:
    """The run that wrote `path`, by the manifest in its folder: None if the
    folder has none or does not list the file (a file of the user's own);
    InputError naming the file if the run listed it with other bytes (it
    changed since, or another run's file was put in its place)."""
    path = Path(path)
    m = read_manifest(path.parent)
    if m is None or path.name not in m.files:
        return None
    if not path.is_file():
        return None   # the reader names a missing file itself
    if file_sha256(path) != m.files[path.name]:
        raise InputError(f"{path}: not the file {m.describe()} wrote there (its SHA-256 differs: "
                         "changed since, or a file of another run); run the command again, or copy "
                         "the file out of that folder to use it as it is")
    return m


def one_run(*paths) -> None:
    """Refuses (InputError naming the file) outputs of orthocontact read
    together that come from different runs, or that changed since their run
    wrote them; files no manifest lists are the user's own and pass."""
    seen = []
    for p in paths:
        if p is None:
            continue
        m = written_by(p)
        if m is None:
            continue
        for q, other in seen:
            if other.run_id != m.run_id:
                raise InputError(f"{p}: written by {m.describe()}, but {q} by {other.describe()}: "
                                 "outputs of two runs (e.g. the rig of one data set with the law of "
                                 "another); use the files of one run")
        seen.append((p, m))
