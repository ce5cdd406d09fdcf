"""Results for machines: CSV tables and JSON files.  A leaf module, so that
every layer that writes results (identification, reports) can use it without
importing another layer."""
from __future__ import annotations

import csv
import json
import math
from pathlib import Path


def write_csv(path: Path, header: list[str], rows) -> None:
    """A CSV table; floats with 12 significant digits."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for r in rows:
            w.writerow([f"{x:.12g}" if isinstance(x, float) else x for x in r])


def write_json(path: Path, data) -> None:
    """Indented JSON with a final newline.  JSON has no NaN or infinity:
    a number that is not finite (a quantity a run could not give) is
    written as null, so that every reader of JSON reads the file."""
    path.write_text(json.dumps(_finite_or_null(data), indent=2, sort_keys=False, allow_nan=False) + "\n")


def _finite_or_null(x):
    if isinstance(x, float):
        return x if math.isfinite(x) else None
    if isinstance(x, dict):
        return {k: _finite_or_null(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_finite_or_null(v) for v in x]
    return x
