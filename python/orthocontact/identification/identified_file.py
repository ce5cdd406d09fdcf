"""identified.json read back (by export and uq): the one place that says
what a file that is not identify's output gets."""
from __future__ import annotations

import json
from pathlib import Path

from ..errors import InputError


def read_identified(path) -> dict:
    """The JSON object of identified.json; InputError naming the file."""
    path = Path(path)
    try:
        d = json.loads(path.read_text())
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})") from None
    except ValueError as e:
        raise InputError(f"{path}: expected JSON written by `orthocontact identify` ({e})") from None
    if not isinstance(d, dict):
        raise InputError(f"{path}: expected a JSON object written by `orthocontact identify`")
    return d
