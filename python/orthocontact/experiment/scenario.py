"""Scenario files (TOML): parsing and validation.

A scenario says what to simulate and, for the paper's analyses, which
published numbers to compare with.  Every key is checked: an unknown key, a
wrong type or an out-of-range value raises ScenarioError, whose message is
one line naming the file, the key and what was expected.  See
scenarios/README.md for the format."""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

from .. import plausibility
from ..closed_forms.paper import G_STANDARD, isotropic_eps_ratio
from ..fmu.params import RULES, ContactParams
from ..rig.harness import MODES, Rig

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


KINDS = ("sweep", "step_study")


CLOSED_FORMS = ("general", "eq11", "eq25", "eq31", "eq33", "mat")


class ScenarioError(Exception):
    """A bad scenario: str(e) is the one-line message for the user."""

    def __init__(self, path, key: str, expected: str, got=None):
        msg = f"{path}: {key}: expected {expected}"
        if got is not None:
            msg += f", got {got!r}"
        super().__init__(msg)

    @classmethod
    def implausible(cls, path, section: str, message: str) -> "ScenarioError":
        """An error of plausibility.check: '<path>: <section>.<key> = ...'."""
        err = cls.__new__(cls)
        Exception.__init__(err, f"{path}: {section}.{message}")
        return err


_REQ = object()  # marks a required key


# Where the quasi-static rig has settled: over 300 random laws with strip
# terms, |phi - closed form| < 3e-8 deg (99th percentile) with the fit
# starting 10 elastic lengths in, < 1e-3 deg at 5, up to 0.4 deg at 2.
ELASTIC_LENGTHS = 10.0


def _num(lo=None, hi=None, lo_open=False):
    def check(v):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            return "a finite number"
        if lo is not None and (v <= lo if lo_open else v < lo):
            return f"a number {'>' if lo_open else '>='} {lo}"
        if hi is not None and v > hi:
            return f"a number <= {hi}"
        return None
    desc = "a finite number" + (f" {'>' if lo_open else '>='} {lo}" if lo is not None else "") + \
        (f" and <= {hi}" if hi is not None else "")
    check.desc = desc
    return check


def _choice(options):
    def check(v):
        return None if v in options else "one of " + ", ".join(repr(o) for o in options)
    return check


def _str(v):
    return None if isinstance(v, str) else "a string"


def _bool(v):
    return None if isinstance(v, bool) else "true or false"


def _list(item_check, min_len=1):
    def check(v):
        if not isinstance(v, list) or len(v) < min_len:
            return f"a list of at least {min_len} item(s)"
        for x in v:
            why = item_check(x)
            if why:
                return f"a list whose items are {why}"
        return None
    return check


def _eps_ratio(v):
    if v == "isotropic":
        return None
    why = _num(0, lo_open=True)(v)
    return None if why is None else 'a number > 0 or "isotropic"'


# What a comparison with a published number is evidence of (report.md):
# closed-form: the FMU through the harness against the paper's own formula;
# prediction: the model computes it from inputs that do not contain it.
# A number listed in calibrated_on is a round trip: the scenario's parameters
# were derived from it.
EVIDENCE = ("closed-form", "prediction")


PAPER_NUMBERS = ("extremum_angle_deg", "extremum_phi_deg", "max_abs_phi_deg", "drive_0_N",
                 "drive_90_N", "mu1", "mu2", "phi_max_deg")


POS = _num(0, lo_open=True)


NONNEG = _num(0)


ANGLE = _num(-360, 360)


SCHEMA = {
    "": {"name": (_str, _REQ), "title": (_str, ""), "kind": (_choice(KINDS), _REQ),
         "fmu": (_str, None), "description": (_str, "")},
    "law": {"rule": (_choice(tuple(RULES)), "coupled"), "mu1": (POS, _REQ), "mu2": (POS, _REQ),
            "eps1": (POS, None), "eps2": (POS, _REQ), "eps_ratio": (_eps_ratio, None)},
    "geometry": {"alpha_offset_deg": (ANGLE, 0.0), "beta_offset_deg": (ANGLE, 0.0),
                 "closed_form": (_choice(CLOSED_FORMS), "general")},
    "sweep": {"start_deg": (ANGLE, 0.0), "stop_deg": (ANGLE, 90.0),
              "step_deg": (_num(0, lo_open=True), 1.0), "refine_extremum": (_bool, True),
              "trajectory_angles_deg": (_list(ANGLE), [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0])},
    "study": {"angle_deg": (ANGLE, _REQ), "rules": (_list(_choice(tuple(RULES))), _REQ),
              "steps_s": (_list(POS), _REQ)},
    "rig": {"mode": (_choice(MODES), "quasistatic"), "mass_kg": (POS, 1.875), "g": (POS, G_STANDARD),
            "f_int_N": (NONNEG, 5.0), "velocity_m_s": (POS, 0.244), "travel_m": (POS, 0.5),
            "mu_strip": (NONNEG, 0.0), "c_strip": (NONNEG, 0.0),
            "step_s": (_num(0, 0.1, lo_open=True), 2e-4),
            "fit_from": (_num(0, 0.95), 0.5)},
    "paper": {"extremum_angle_deg": (ANGLE, None), "extremum_phi_deg": (ANGLE, None),
              "phi_sign_differs": (_bool, False), "max_abs_phi_deg": (NONNEG, None),
              "drive_0_N": (POS, None), "drive_90_N": (POS, None), "mu1": (POS, None),
              "mu2": (POS, None), "phi_max_deg": (NONNEG, None), "eps_ratio": (POS, None),
              "source": (_str, ""), "evidence": (_choice(EVIDENCE), "prediction"),
              "calibrated_on": (_list(_choice(PAPER_NUMBERS), min_len=0), [])},
}


SECTION_FOR_KIND = {"sweep": {"sweep"}, "step_study": {"study"}}


@dataclass
class Scenario:
    path: Path
    name: str
    title: str
    kind: str
    description: str
    law: ContactParams            # alpha, beta are the offsets here; see params_at
    alpha_offset: float           # rad
    beta_offset: float            # rad
    closed_form: str
    rig: Rig
    sweep: dict = field(default_factory=dict)
    study: dict = field(default_factory=dict)
    paper: dict = field(default_factory=dict)
    fmu: str | None = None
    warnings: list = field(default_factory=list)   # one line each: unusual values

    def params_at(self, angle_deg: float, rule: str | None = None) -> ContactParams:
        """The law's parameters with the swept angle [deg] set."""
        a = math.radians(angle_deg)
        return self.law.replace(alpha=a + self.alpha_offset, beta=a + self.beta_offset,
                                rule=rule or self.law.rule)

    def sweep_angles(self) -> list[float]:
        s = self.sweep
        n = int(math.floor((s["stop_deg"] - s["start_deg"]) / s["step_deg"] + 1e-9))
        return [s["start_deg"] + k * s["step_deg"] for k in range(n + 1)]


def _section(path, data: dict, name: str) -> dict:
    spec = SCHEMA[name]
    where = (name + ".") if name else ""
    for key in data:
        if key not in spec:
            raise ScenarioError(path, where + key, "one of the known keys " + ", ".join(sorted(spec)),
                                None)
    out = {}
    for key, (check, default) in spec.items():
        if key in data:
            why = check(data[key])
            if why:
                raise ScenarioError(path, where + key, why, data[key])
            out[key] = data[key]
        elif default is _REQ:
            raise ScenarioError(path, where + key, "a value (the key is required)")
        else:
            out[key] = default
    return out


def load(path) -> Scenario:
    """Reads and validates a scenario file; raises ScenarioError."""
    path = Path(path)
    try:
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise ScenarioError(path, "(file)", "an existing scenario file") from None
    except (OSError, UnicodeDecodeError) as e:
        raise ScenarioError(path, "(file)", f"a readable UTF-8 file ({e})") from None
    except tomllib.TOMLDecodeError as e:
        raise ScenarioError(path, "(syntax)", f"valid TOML ({e})") from None

    tables = {k for k, v in raw.items() if isinstance(v, dict)}
    for t in tables:
        if t not in SCHEMA:
            raise ScenarioError(path, t, "a known table: " + ", ".join(sorted(k for k in SCHEMA if k)))
    top = _section(path, {k: v for k, v in raw.items() if k not in tables}, "")
    needed = SECTION_FOR_KIND[top["kind"]]
    for t in ("sweep", "study"):
        if t in tables and t not in needed:
            raise ScenarioError(path, t, f"no [{t}] table in a scenario of kind {top['kind']!r}")
    for t in needed:
        if t not in tables:
            raise ScenarioError(path, t, f"a [{t}] table for kind {top['kind']!r}")
    if "law" not in tables:
        raise ScenarioError(path, "law", "a [law] table")
    law = _section(path, raw["law"], "law")
    geo = _section(path, raw.get("geometry", {}), "geometry")
    rig = _section(path, raw.get("rig", {}), "rig")
    paper = {k: v for k, v in _section(path, raw.get("paper", {}), "paper").items() if v is not None}
    sweep = _section(path, raw["sweep"], "sweep") if "sweep" in needed else {}
    study = _section(path, raw["study"], "study") if "study" in needed else {}
    if sweep and sweep["stop_deg"] < sweep["start_deg"]:
        raise ScenarioError(path, "sweep.stop_deg", f"a value >= sweep.start_deg = {sweep['start_deg']}",
                            sweep["stop_deg"])

    warnings = _plausibility(path, {"law": law, "rig": rig, "geometry": geo, "sweep": sweep,
                                    "study": study})

    if law["eps1"] is not None and law["eps_ratio"] is not None:
        raise ScenarioError(path, "law.eps_ratio", "either law.eps1 or law.eps_ratio, not both")
    if law["eps1"] is None and law["eps_ratio"] is None:
        raise ScenarioError(path, "law.eps1", "law.eps1 [N/m] or law.eps_ratio (eps1/eps2)")
    eps1 = law["eps1"]
    if eps1 is None:
        ratio = law["eps_ratio"]
        if ratio == "isotropic":
            ratio = isotropic_eps_ratio(law["mu1"], law["mu2"])
        eps1 = ratio * law["eps2"]

    fmu = top["fmu"]
    if fmu is not None:
        fmu_path = (path.parent / fmu) if not Path(fmu).is_absolute() else Path(fmu)
        if not fmu_path.is_file():
            raise ScenarioError(path, "fmu", "the path of an existing .fmu file", fmu)
        fmu = str(fmu_path)

    rig_given = raw.get("rig", {})
    if "travel_m" not in rig_given:
        # The default rig must settle for the scenario's law: the quasi-static
        # rig's transient dies out over a few elastic lengths mu N / eps.
        elastic = max(law["mu1"], law["mu2"]) * rig["mass_kg"] * rig["g"] / min(eps1, law["eps2"])
        fit_start = rig["fit_from"] * rig["travel_m"]
        if rig["mode"] == "quasistatic" and fit_start < ELASTIC_LENGTHS * elastic:
            raise ScenarioError(path, "rig.travel_m", (
                f"a travel for this law: the default {rig['travel_m']:g} m starts the fit at "
                f"{fit_start:g} m, within {ELASTIC_LENGTHS:g} elastic lengths max(mu) N / min(eps) = "
                f"{elastic:.3g} m of the start, where the block has not settled; set rig.travel_m >= "
                f"{ELASTIC_LENGTHS * elastic / rig['fit_from']:.3g}"))
    return Scenario(
        path=path, name=top["name"], title=top["title"] or top["name"], kind=top["kind"],
        description=top["description"],
        law=ContactParams(law["mu1"], law["mu2"], float(eps1), float(law["eps2"]), 0.0, 0.0, law["rule"]),
        alpha_offset=math.radians(geo["alpha_offset_deg"]),
        beta_offset=math.radians(geo["beta_offset_deg"]), closed_form=geo["closed_form"],
        rig=Rig(mass_kg=rig["mass_kg"], g=rig["g"], f_int_N=rig["f_int_N"],
                velocity_m_s=rig["velocity_m_s"], travel_m=rig["travel_m"], mu_strip=rig["mu_strip"],
                c_strip=rig["c_strip"],
                mode=rig["mode"], step_s=rig["step_s"], fit_from=rig["fit_from"]),
        sweep=sweep, study=study, paper=paper, fmu=fmu, warnings=warnings)


def _plausibility(path, sections: dict) -> list[str]:
    """Raises ScenarioError for a value that cannot be right for this kind
    of rig and law; returns the warnings for unusual ones (plausibility)."""
    warnings = []
    for name, values in sections.items():
        for key, value in values.items():
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                continue
            found = plausibility.check(key, value)
            if found is None and key.endswith("_deg") and key != "step_deg":
                found = plausibility.check_angle_deg(key, value)
            if found is None:
                continue
            level, message = found
            if level == "error":
                raise ScenarioError.implausible(path, name, message)
            warnings.append(f"{path}: {name}.{message}")
    return warnings
