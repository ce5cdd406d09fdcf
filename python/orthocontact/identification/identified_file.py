"""identified.json read back (by export and uq): the one place that says
what a file that is not identify's output gets, that checks it is the file
its identify run wrote (output.manifest), and that the data it names are
still the bytes the identification read (check_data)."""
from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

from .. import plausibility
from ..errors import InputError
from ..output.manifest import written_by
from ..textfiles import read_text
from .measurements import changed_files, data_digest


def read_identified(path, force: bool = False, override: str = "") -> dict:
    """The JSON object of identified.json; InputError naming the file.  Its
    values with a unit pass the plausibility gate (plausible_identified): one
    that cannot be right is refused (`override`: what lets it through, named
    in the message) unless `force`."""
    path = Path(path)
    try:   # a BOM, CRLF, an unreadable file: textfiles
        d = json.loads(read_text(path, "identified.json written by `orthocontact identify`"))
    except ValueError as e:
        raise InputError(f"{path}: expected JSON written by `orthocontact identify` ({e})") from None
    if not isinstance(d, dict):
        raise InputError(f"{path}: expected a JSON object written by `orthocontact identify`")
    written_by(path)   # in an output folder: as its run wrote it
    errors, _ = plausibility.split(plausible_identified(path, d))
    if errors and not force:
        raise InputError(f"{errors[0]}; refused" + (f" ({override})" if override else ""))
    return d


# identified.json's values with a unit: field -> key of plausibility.QUANTITIES
IDENTIFIED = {"mu1": "mu1", "mu2": "mu2", "eps_ratio": "eps_ratio", "eps1": "eps1", "eps2": "eps2",
              "c_strip": "c_strip", "f_int": "f_int_N"}
ASSUMED = {"mass_kg": "mass_kg", "g": "g", "f_int_N": "f_int_N", "c_strip_N_s_m": "c_strip",
           "mu_strip": "mu_strip"}


def plausible_identified(path, d: dict) -> list:
    """The plausibility Findings of identified.json `d`'s numbers with a unit:
    each estimate's value, the covariance's values (what uq draws around) and
    the assumptions (mass, g, F_int, strip terms).  Fields that are absent,
    not numbers, or outside the quantity's domain (not finite; below 0, or 0
    where 0 is not allowed) are left to the readers that need them, whose
    message says what the field must be."""
    def number(v, key):
        q = plausibility.QUANTITIES[key]
        return (isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
                and (v > 0 or (v == 0 and q.zero_allowed)))
    found = []
    for name, key in IDENTIFIED.items():
        entry = d.get(name)
        if isinstance(entry, dict) and number(entry.get("value"), key):
            found += plausibility.findings({key: entry["value"]},
                                           f"{path}: " + ("" if name == key else f"{name}.value: "))
    cov = d.get("covariance")
    if isinstance(cov, dict) and isinstance(cov.get("parameters"), list) and isinstance(cov.get("values"), list):
        for name, v in zip(cov["parameters"], cov["values"]):
            if name in IDENTIFIED and number(v, IDENTIFIED[name]):
                found += plausibility.findings({IDENTIFIED[name]: v}, f"{path}: covariance.values: ")
    a = d.get("assumptions")
    if isinstance(a, dict):
        for name, key in ASSUMED.items():
            if number(a.get(name), key):
                found += plausibility.findings({key: a[name]}, f"{path}: assumptions."
                                               + ("" if name == key else f"{name}: "))
    return found


@dataclass(frozen=True)
class DataProvenance:
    """The data an identification read, found and checked unchanged."""
    folder: Path      # the data folder as found now
    files: dict       # path under folder (POSIX) -> SHA-256, as identify recorded them
    digest: str       # SHA-256 of their sha256sum listing (measurements.data_digest)


NAMED = 12   # changed files named in the one line; the rest counted


def check_data(path, d: dict) -> DataProvenance:
    """The data folder identified.json `d` (read from `path`) names, found
    as given, relative to the file's folder, or by its absolute path, and
    every file the identification read in it as it was then; InputError
    naming identified.json and the files that changed or are missing."""
    path = Path(path)
    data = d.get("data") if isinstance(d.get("data"), dict) else {}
    folder = data.get("folder")
    if not isinstance(folder, str) or not folder:
        raise InputError(f"{path}: data.folder: expected the measurement folder's path")
    files, stated = data.get("files"), data.get("sha256")
    if not isinstance(files, dict) or not files or not all(
            isinstance(k, str) and isinstance(v, str) for k, v in files.items()):
        raise InputError(f"{path}: data.files: expected the SHA-256 of every file the identification "
                         "read (`orthocontact identify` writes them; run it again)")
    if stated != data_digest(files):
        raise InputError(f"{path}: data.sha256: expected the digest of data.files' listing "
                         f"({data_digest(files)[:12]}...), got {str(stated)[:12]}...: the file was edited")
    absolute = data.get("absolute_folder")
    found = None
    for candidate in (Path(folder), path.parent / folder) + ((Path(absolute),) if absolute else ()):
        if (candidate / "rig.toml").is_file():
            found = candidate
            break
    if found is None:
        raise InputError(f"{path}: data.folder: {folder} not found (relative to the working folder or "
                         f"to {path.parent}): the calibration names the data it came from")
    changed = changed_files(found, files)
    if changed:
        named = ", ".join(changed[:NAMED]) + (f" and {len(changed) - NAMED} more" if len(changed) > NAMED
                                              else "")
        raise InputError(f"{path}: data.files: {len(changed)} of the {len(files)} files the "
                         f"identification read in {found} changed since: {named} "
                         f"(identified on data sha256 {stated[:12]}...; identify again)")
    return DataProvenance(found, dict(files), stated)
