"""Where a uq result's law came from: the identified.json it drew from, named
in uq.json as export's FMUs name theirs: the file's path and the SHA-256 of
the bytes read, the `identify` run that wrote it (its output folder's
manifest, output.manifest) and the digest of the data that run identified
on (identified.json's data.sha256, the data found unchanged)."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..identification import read_identified
from ..output import written_by
from ..textfiles import files_read
from .estimates import Estimates, estimates_of


@dataclass(frozen=True)
class Source:
    """The identified.json a uq run drew from, as it was read."""
    path: str                     # as given on the command line
    sha256: str                   # of the file's bytes as read (hex)
    identify_run_id: str | None   # the run that wrote it; None: a file no manifest lists (the user's own)
    data_sha256: str              # the identification's data digest (data.sha256)

    def as_json(self) -> dict:
        return {"path": self.path, "sha256": self.sha256, "identify_run_id": self.identify_run_id,
                "data_sha256": self.data_sha256}


def read_source(path) -> tuple[Estimates, Source]:
    """What uq draws from (estimates_of, read_identified: every field
    checked, its data unchanged) and where it came from; InputError as
    read_identified."""
    path = Path(path)
    with files_read() as read:
        f = read_identified(path)
    sha = read[str(path)].sha256
    run = written_by(path)
    # The run's id names these bytes only if its manifest lists them.
    run_id = run.run_id if run is not None and run.files.get(path.name) == sha else None
    digest = f.provenance.digest if f.provenance is not None else f.data.sha256
    return estimates_of(f), Source(str(path), sha, run_id, digest)
