"""Results for machines: CSV tables and JSON files.  A leaf module, so that
every layer that writes results (identification, reports) can use it without
importing another layer."""
from __future__ import annotations

import csv
import json
from pathlib import Path


def write_csv(path: Path, header: list[str], rows) -> None:
    """A CSV table; floats with 12 significant digits."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for r in rows:
            w.writerow([f"{x:.12g}" if isinstance(x, float) else x for x in r])


def write_json(path: Path, data) -> None:
    """Indented JSON with a final newline."""
    path.write_text(json.dumps(data, indent=2, sort_keys=False) + "\n")
