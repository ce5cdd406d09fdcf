"""Scenario files (TOML): parsing and validation.

A scenario says what to simulate and, for the paper's analyses, which
published numbers to compare with.  Every key is checked: an unknown key, a
wrong type or an out-of-range value raises ScenarioError, whose message is
one line naming the file, the key and what was expected.  The format:
docs/reference/file-formats.md, "Scenario files"."""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

from ..closed_forms import FORMS
from ..closed_forms.paper import isotropic_eps_ratio
from ..errors import InputError
from ..fmu.params import RULES, ContactParams
from ..fmu.patch import GEOMETRY, geometry_problem, geometry_range
from ..rig.harness import Rig
from ..textfiles import read_toml
from .geometry import AxisGeometry
from .keys import (ANGLE_DEG, NON_NEGATIVE, POSITIVE, REQUIRED, AnyOf, boolean, choice, file_name,
                   list_of, number, read_table, rig_spec, text)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


KINDS = ("sweep", "step_study", "twist", "towed_block")
# The kinds that run a planar body on the ContactPatch FMU (rig.planar), with
# the patch described by a [patch] table.
PATCH_KINDS = ("twist", "towed_block")


class ScenarioError(InputError):
    """A bad scenario (an InputError): str(e) is the one-line message for the user.
    ScenarioError(path, key, expected[, got]), or ScenarioError(message) with
    a message that names the file already (experiment.keys)."""

    def __init__(self, path, key: str | None = None, expected: str | None = None, got=None):
        msg = str(path) if key is None else f"{path}: {key}: expected {expected}"
        if got is not None:
            msg += f", got {got!r}"
        super().__init__(msg)


# Where the quasi-static rig has settled: over 300 random laws with strip
# terms, |phi - closed form| < 3e-8 deg (99th percentile) with the fit
# starting 10 elastic lengths in, < 1e-3 deg at 5, up to 0.4 deg at 2.
ELASTIC_LENGTHS = 10.0


# eps1/eps2, or "isotropic" (mu2/mu1: straight motion)
EPS_RATIO = AnyOf((POSITIVE, choice(("isotropic",))), 'a number > 0 or "isotropic"')


# What a comparison with a published number is evidence of (report.md):
# closed-form: the FMU through the harness against the paper's own formula;
# prediction: the model computes it from inputs that do not contain it.
# A number listed in calibrated_on is a round trip: the scenario's parameters
# were derived from it.
EVIDENCE = ("closed-form", "prediction")


PAPER_NUMBERS = ("extremum_angle_deg", "extremum_phi_deg", "max_abs_phi_deg", "drive_0_N",
                 "drive_90_N", "mu1", "mu2", "phi_max_deg")


SCHEMA = {
    "": {"name": (file_name, REQUIRED), "title": (text, ""), "kind": (choice(KINDS), REQUIRED),
         "fmu": (text, None), "description": (text, "")},
    "law": {"rule": (choice(tuple(RULES)), "coupled"), "mu1": (POSITIVE, REQUIRED),
            "mu2": (POSITIVE, REQUIRED), "eps1": (POSITIVE, None), "eps2": (POSITIVE, REQUIRED),
            "eps_ratio": (EPS_RATIO, None)},
    "geometry": {"alpha_offset_deg": (ANGLE_DEG, 0.0), "beta_offset_deg": (ANGLE_DEG, 0.0),
                 "closed_form": (choice(tuple(FORMS)), "general")},
    "sweep": {"start_deg": (ANGLE_DEG, 0.0), "stop_deg": (ANGLE_DEG, 90.0),
              "step_deg": (POSITIVE, 1.0), "refine_extremum": (boolean, True),
              "trajectory_angles_deg": (list_of(ANGLE_DEG), [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0])},
    "study": {"angle_deg": (ANGLE_DEG, REQUIRED),
              "rules": (list_of(choice(tuple(RULES)), unique=True), REQUIRED),
              "steps_s": (list_of(POSITIVE, unique=True), REQUIRED)},
    "patch": {"length_m": (POSITIVE, REQUIRED), "width_m": (POSITIVE, REQUIRED),
              "n1": (number(*geometry_range("n1")), 8), "n2": (number(*geometry_range("n2")), 8)},
    "twist": {"angle_deg": (number(0, 360, lo_open=True), REQUIRED), "rate_deg_s": (POSITIVE, 10.0),
              "step_s": (number(0, 0.1, lo_open=True), 1e-3),
              "rules": (list_of(choice(("associated", "coupled")), unique=True), ["associated", "coupled"])},
    "tow": {"pin_m": (POSITIVE, REQUIRED), "duration_s": (POSITIVE, 20.0),
            "step_s": (number(0, 0.1, lo_open=True), 5e-3),
            "angles_deg": (list_of(ANGLE_DEG, unique=True), [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0]),
            "rules": (list_of(choice(("associated", "coupled")), unique=True), ["associated", "coupled"])},
    "rig": rig_spec(),   # the rig's keys with Rig's defaults (rig.harness)
    "paper": {"extremum_angle_deg": (ANGLE_DEG, None), "extremum_phi_deg": (ANGLE_DEG, None),
              "phi_sign_differs": (boolean, False), "max_abs_phi_deg": (NON_NEGATIVE, None),
              "drive_0_N": (POSITIVE, None), "drive_90_N": (POSITIVE, None), "mu1": (POSITIVE, None),
              "mu2": (POSITIVE, None), "phi_max_deg": (NON_NEGATIVE, None), "eps_ratio": (POSITIVE, None),
              "source": (text, ""), "evidence": (choice(EVIDENCE), "prediction"),
              "calibrated_on": (list_of(choice(PAPER_NUMBERS), min_len=0), [])},
}


SECTION_FOR_KIND = {"sweep": {"sweep"}, "step_study": {"study"}, "twist": {"patch", "twist"},
                    "towed_block": {"patch", "tow"}}


@dataclass
class Scenario:
    path: Path
    name: str
    title: str
    kind: str
    description: str
    law: ContactParams            # alpha, beta are 0 here; see params_at
    geometry: AxisGeometry        # the axes' offsets from the mat angle [deg]
    closed_form: str
    rig: Rig
    sweep: dict = field(default_factory=dict)
    study: dict = field(default_factory=dict)
    patch: dict = field(default_factory=dict)     # kinds in PATCH_KINDS: the contact rectangle
    twist: dict = field(default_factory=dict)
    tow: dict = field(default_factory=dict)
    paper: dict = field(default_factory=dict)
    fmu: str | None = None
    warnings: list = field(default_factory=list)   # one line each: unusual values

    def params_at(self, angle_deg: float, rule: str | None = None) -> ContactParams:
        """The law's parameters with the mat angle [deg] set."""
        return self.geometry.params_at(self.law, angle_deg, rule)

    def angle_count(self) -> int:
        """len(sweep_angles()), without making the list."""
        s = self.sweep
        return int(math.floor((s["stop_deg"] - s["start_deg"]) / s["step_deg"] + 1e-9)) + 1

    def sweep_angles(self) -> list[float]:
        s = self.sweep
        return [s["start_deg"] + k * s["step_deg"] for k in range(self.angle_count())]


def load(path) -> Scenario:
    """Reads and validates a scenario file; raises ScenarioError."""
    path = Path(path)
    try:
        raw = read_toml(path, "a scenario file (TOML)")   # a BOM, CRLF, a decimal comma: textfiles
    except InputError as e:
        raise ScenarioError(str(e)) from None
    except tomllib.TOMLDecodeError as e:
        raise ScenarioError(path, "(syntax)", f"valid TOML ({e})") from None

    tables = {k for k, v in raw.items() if isinstance(v, dict)}
    for t in tables:
        if t not in SCHEMA:
            raise ScenarioError(path, t, "a known table: " + ", ".join(sorted(k for k in SCHEMA if k)))
    warnings = []

    def section(name, data):
        values, said = read_table(path, name + "." if name else "", data, SCHEMA[name], ScenarioError)
        warnings.extend(said)
        return values
    top = section("", {k: v for k, v in raw.items() if k not in tables})
    needed = SECTION_FOR_KIND[top["kind"]]
    for t in ("sweep", "study", "patch", "twist", "tow"):
        if t in tables and t not in needed:
            raise ScenarioError(path, t, f"no [{t}] table in a scenario of kind {top['kind']!r}")
    for t in needed:
        if t not in tables:
            raise ScenarioError(path, t, f"a [{t}] table for kind {top['kind']!r}")
    if "law" not in tables:
        raise ScenarioError(path, "law", "a [law] table")
    law = section("law", raw["law"])
    geo = section("geometry", raw.get("geometry", {}))
    rig = section("rig", raw.get("rig", {}))
    paper = {k: v for k, v in section("paper", raw.get("paper", {})).items() if v is not None}
    sweep = section("sweep", raw["sweep"]) if "sweep" in needed else {}
    study = section("study", raw["study"]) if "study" in needed else {}
    patch = section("patch", raw["patch"]) if "patch" in needed else {}
    for name, key in zip(GEOMETRY, ("length_m", "width_m", "n1", "n2")):   # the FMU's own ranges
        problem = geometry_problem(name, patch[key]) if patch else None
        if problem is not None:
            raise ScenarioError(f"{path}: patch.{key}: {problem}")
    twist = section("twist", raw["twist"]) if "twist" in needed else {}
    tow = section("tow", raw["tow"]) if "tow" in needed else {}
    if sweep and sweep["stop_deg"] < sweep["start_deg"]:
        raise ScenarioError(path, "sweep.stop_deg", f"a value >= sweep.start_deg = {sweep['start_deg']}",
                            sweep["stop_deg"])

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
        if top["kind"] in PATCH_KINDS:
            # a point FMU here would fail later, far from the key that named it
            from ..fmu.files import model_description
            try:
                model = model_description(fmu_path).coSimulation.modelIdentifier
            except Exception as e:
                model = f"not a readable FMU ({e})"
            if model != "ContactPatch":
                raise ScenarioError(path, "fmu", f"a ContactPatch FMU for a scenario of kind "
                                    f"{top['kind']!r}", f"{fmu}: {model}")
        fmu = str(fmu_path)

    rig_given = raw.get("rig", {})
    if "travel_m" not in rig_given:
        # The default rig must settle for the scenario's law: the quasi-static
        # rig's transient dies out over a few elastic lengths mu N / eps.
        elastic = max(law["mu1"], law["mu2"]) * rig["mass_kg"] * rig["g"] / min(eps1, law["eps2"])
        fit_start = rig["fit_from"] * rig["travel_m"]
        if top["kind"] not in PATCH_KINDS and rig["mode"] == "quasistatic" and fit_start < ELASTIC_LENGTHS * elastic:
            raise ScenarioError(path, "rig.travel_m", (
                f"a travel for this law: the default {rig['travel_m']:g} m starts the fit at "
                f"{fit_start:g} m, within {ELASTIC_LENGTHS:g} elastic lengths max(mu) N / min(eps) = "
                f"{elastic:.3g} m of the start, where the block has not settled; set "
                + (f"rig.travel_m >= {ELASTIC_LENGTHS * elastic / rig['fit_from']:.3g}" if rig["fit_from"] > 0
                   else "rig.fit_from > 0 (the fit starts where the path does)")))
    contact = ContactParams(law["mu1"], law["mu2"], float(eps1), float(law["eps2"]), rule=law["rule"])
    geometry = AxisGeometry(float(geo["alpha_offset_deg"]), float(geo["beta_offset_deg"]))
    refusal = FORMS[geo["closed_form"]].refusal(contact, geometry.beta_minus_alpha_deg)
    if refusal is not None:
        # a warning about the axes (radians in a degree key?) is the likely cause: say it too
        said = "".join(f"; {w[len(str(path)) + 2:]}" for w in warnings if w.startswith(f"{path}: geometry."))
        raise ScenarioError(str(ScenarioError(
            path, "geometry.closed_form", f"a closed form that holds for this law and these axes "
            f"({geo['closed_form']} needs {refusal}; \"general\" holds for any)", geo["closed_form"])) + said)
    return Scenario(
        path=path, name=top["name"], title=top["title"] or top["name"], kind=top["kind"],
        description=top["description"], law=contact, geometry=geometry, closed_form=geo["closed_form"],
        rig=Rig(**rig),
        sweep=sweep, study=study, patch=patch, twist=twist, tow=tow, paper=paper, fmu=fmu, warnings=warnings)
