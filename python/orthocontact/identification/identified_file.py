"""identified.json read back (by export and uq): the one place that says
what a file that is not identify's output gets."""
from __future__ import annotations

import json
import math
from pathlib import Path

from .. import plausibility
from ..errors import InputError


def read_identified(path, force: bool = False, override: str = "") -> dict:
    """The JSON object of identified.json; InputError naming the file.  Its
    values with a unit pass the plausibility gate (plausible_identified): one
    that cannot be right is refused (`override`: what lets it through, named
    in the message) unless `force`."""
    path = Path(path)
    try:
        d = json.loads(path.read_text())
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})") from None
    except ValueError as e:
        raise InputError(f"{path}: expected JSON written by `orthocontact identify` ({e})") from None
    if not isinstance(d, dict):
        raise InputError(f"{path}: expected a JSON object written by `orthocontact identify`")
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
