"""Scenario files (TOML): parsing and validation.

A scenario says what to simulate and, for the paper's analyses, which
published numbers to compare with.  Every key is checked: an unknown key, a
wrong type or an out-of-range value is a problem of the file, one line
naming the file, the key and what was expected; load() names every problem
of the file in one ScenarioError (errors.Problems), stopping early only
where the rest would mean nothing (not TOML, no known kind).  The tables
every scenario has are here; those of each kind are its row's
(experiment.kinds).  The format: docs/reference/file-formats.md,
"Scenario files"."""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

from ..closed_forms import FORMS, isotropic_eps_ratio
from ..errors import InputError, Problems
from ..fmu import LAW, RULES, ContactParams, check_parameter
from ..plausibility import ELASTIC_LENGTHS
from ..rig import Rig
from ..textfiles import read_toml
from .geometry import AxisGeometry
from .keys import (
    ANGLE_DEG,
    NON_NEGATIVE,
    POSITIVE,
    REQUIRED,
    AnyOf,
    boolean,
    choice,
    file_name,
    list_of,
    read_table,
    rig_spec,
    text,
)
from .kinds import KINDS

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


LAW_ROWS = {row.name: row for row in LAW}


class ScenarioError(InputError):
    """A bad scenario (an InputError): str(e) is the message for the user,
    one line per problem.  ScenarioError(path, key, expected[, got]), or
    ScenarioError(message) with a message that names the file already
    (experiment.keys)."""

    def __init__(self, path, key: str | None = None, expected: str | None = None, got=None):
        msg = str(path) if key is None else f"{path}: {key}: expected {expected}"
        if got is not None:
            msg += f", got {got!r}"
        super().__init__(msg)


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


# The tables of every scenario; then each kind's own (experiment.kinds).
COMMON = {
    "": {"name": (file_name, REQUIRED), "title": (text, ""), "kind": (choice(KINDS), REQUIRED),
         "fmu": (text, None), "description": (text, "")},
    "law": {"rule": (choice(tuple(RULES)), "coupled"), "mu1": (POSITIVE, REQUIRED),
            "mu2": (POSITIVE, REQUIRED), "eps1": (POSITIVE, None), "eps2": (POSITIVE, REQUIRED),
            "eps_ratio": (EPS_RATIO, None)},
    "geometry": {"alpha_offset_deg": (ANGLE_DEG, 0.0), "beta_offset_deg": (ANGLE_DEG, 0.0),
                 "closed_form": (choice(tuple(FORMS)), "general")},
    "rig": rig_spec(),   # the rig's keys with Rig's defaults (rig.harness)
    "paper": {"extremum_angle_deg": (ANGLE_DEG, None), "extremum_phi_deg": (ANGLE_DEG, None),
              "phi_sign_differs": (boolean, False), "max_abs_phi_deg": (NON_NEGATIVE, None),
              "drive_0_N": (POSITIVE, None), "drive_90_N": (POSITIVE, None), "mu1": (POSITIVE, None),
              "mu2": (POSITIVE, None), "phi_max_deg": (NON_NEGATIVE, None), "eps_ratio": (POSITIVE, None),
              "source": (text, ""), "evidence": (choice(EVIDENCE), "prediction"),
              "calibrated_on": (list_of(choice(PAPER_NUMBERS), min_len=0), [])},
}
SCHEMA = {**COMMON, **{t: spec for k in KINDS.values() for t, spec in k.tables.items()}}


class KindTable:
    """A kind's table of a scenario as its attribute (sc.sweep is
    sc.tables["sweep"]; {} where its kind has none)."""

    def __set_name__(self, owner, name):
        self.name = name

    def __get__(self, sc, owner=None):
        return self if sc is None else sc.tables.get(self.name, {})

    def __set__(self, sc, value):
        sc.tables[self.name] = value


@dataclass
class Scenario:
    path: Path
    name: str
    title: str
    kind: str                     # a name in experiment.kinds.KINDS
    description: str
    law: ContactParams            # alpha, beta are 0 here; see params_at
    geometry: AxisGeometry        # the axes' offsets from the mat angle [deg]
    closed_form: str
    rig: Rig
    tables: dict = field(default_factory=dict)    # its kind's own tables: {table: {key: value}}
    paper: dict = field(default_factory=dict)
    fmu: str | None = None
    warnings: list = field(default_factory=list)   # one line each: unusual values

    sweep = KindTable()
    study = KindTable()
    patch = KindTable()           # a body on the patch: the contact rectangle
    twist = KindTable()
    tow = KindTable()
    pad = KindTable()             # a body on the pad: the rectangle on its foundation
    push = KindTable()
    roll = KindTable()            # a pad that rolls: its load, speed and creepages

    def head(self) -> dict:
        """summary.json's first keys: which scenario, its title and kind."""
        return {"scenario": self.name, "title": self.title, "kind": self.kind}

    def params_at(self, angle_deg: float, rule: str | None = None) -> ContactParams:
        """The law's parameters with the mat angle [deg] set."""
        return self.geometry.params_at(self.law, angle_deg, rule)

    def angle_count(self) -> int:
        """len(sweep_angles()), without making the list; a step so small that
        the count is past 2^53 (or overflows) counts as 2^53 + 1, for the size
        check (runs.size) to refuse it naming sweep.step_deg."""
        s = self.sweep
        steps = (s["stop_deg"] - s["start_deg"]) / s["step_deg"] + 1e-9
        return int(math.floor(min(steps, 2.0**53))) + 1

    def sweep_angles(self) -> list[float]:
        s = self.sweep
        return [s["start_deg"] + k * s["step_deg"] for k in range(self.angle_count())]


def load(path) -> Scenario:
    """Reads and validates a scenario file; raises one ScenarioError naming
    every problem of the file, one line each (in the order the readers
    below find them)."""
    path = Path(path)
    f = ScenarioFile(path, parsed(path))
    top, row = f.top()
    law = f.table("law") if "law" in f.tables else {}
    geo, rig = f.table("geometry"), f.table("rig")
    paper = {k: v for k, v in f.table("paper").items() if v is not None}
    own = f.kind_tables(row)
    eps1 = f.eps1(law)
    fmu = f.fmu(top.get("fmu"), row)
    f.check_travel(row, law, eps1, rig)
    contact, geometry = f.law_on_axes(law, eps1, geo)
    f.problems.raise_any()
    return Scenario(
        path=path, name=top["name"], title=top["title"] or top["name"], kind=top["kind"],
        description=top["description"], law=contact, geometry=geometry, closed_form=geo["closed_form"],
        rig=Rig(**rig), tables=own, paper=paper, fmu=fmu, warnings=f.warnings)


def parsed(path: Path) -> dict:
    """The file's TOML; ScenarioError (one line) if it cannot be read or is not TOML."""
    try:
        return read_toml(path, "a scenario file (TOML)")   # a BOM, CRLF, a decimal comma: textfiles
    except InputError as e:
        raise ScenarioError(str(e)) from None
    except tomllib.TOMLDecodeError as e:
        raise ScenarioError(path, "(syntax)", f"valid TOML ({e})") from None


class ScenarioFile:
    """A scenario file being read: its TOML, the problems found so far and
    the warnings said; a reader a table (or a check across tables) each."""

    def __init__(self, path: Path, raw: dict):
        self.path, self.raw = path, raw
        self.problems = Problems(ScenarioError)
        self.warnings = []
        self.tables = [k for k, v in raw.items() if isinstance(v, dict)]

    def problem(self, key, expected, got=None) -> None:
        self.problems.add(str(ScenarioError(self.path, key, expected, got)))

    def given(self, name: str) -> dict:
        """The table as the file has it ({} where it has none)."""
        return self.raw[name] if name in self.tables else {}

    def table(self, name: str, data=None) -> dict:
        """The table `name` (the file's, or `data`: the top level's keys)
        read against its schema: its values, defaults filled in."""
        if data is None:
            data = self.given(name)
        values, said = read_table(self.path, name + "." if name else "", data, SCHEMA[name], ScenarioError,
                                  self.problems)
        self.warnings.extend(said)
        return values

    def top(self):
        """The top level's keys and the kind's row (None: no known kind, its
        tables unknown); every table known, the kind's present, and [law]."""
        for t in self.tables:
            if t not in SCHEMA:
                self.problem(t, "a known table: " + ", ".join(sorted(k for k in SCHEMA if k)))
        top = self.table("", {k: v for k, v in self.raw.items() if k not in self.tables})
        row = KINDS.get(top.get("kind"))
        if row is not None:
            for t in self.tables:
                if t in SCHEMA and t not in COMMON and t not in row.tables:
                    self.problem(t, f"no [{t}] table in a scenario of kind {row.name!r}")
            for t in row.tables:
                if t not in self.tables:
                    self.problem(t, f"a [{t}] table for kind {row.name!r}")
        if "law" not in self.tables:
            self.problem("law", "a [law] table")
        return top, row

    def kind_tables(self, row) -> dict:
        """The kind's own tables, and its checks across them once all are there."""
        own = {t: self.table(t) for t in row.tables if t in self.tables} if row is not None else {}
        if row is not None and row.check is not None and len(own) == len(row.tables):
            row.check(self.path, own, self.problems)
        return own

    def eps1(self, law: dict):
        """eps1 [N/m]: law.eps1, or law.eps_ratio x law.eps2 ("isotropic":
        mu2/mu1); None where neither or both are given."""
        if "eps1" not in law or "eps_ratio" not in law:
            return None
        if law["eps1"] is not None and law["eps_ratio"] is not None:
            self.problem("law.eps_ratio", "either law.eps1 or law.eps_ratio, not both")
        elif law["eps1"] is None and law["eps_ratio"] is None:
            self.problem("law.eps1", "law.eps1 [N/m] or law.eps_ratio (eps1/eps2)")
        elif law["eps1"] is not None:
            return law["eps1"]
        elif law.keys() >= {"mu1", "mu2", "eps2"}:
            ratio = law["eps_ratio"]
            if ratio == "isotropic":
                ratio = isotropic_eps_ratio(law["mu1"], law["mu2"])
            return ratio * law["eps2"]
        return None

    def fmu(self, fmu, row):
        """The key fmu as a path (beside the file where relative): an existing
        FMU of the kind's model."""
        if fmu is None:
            return None
        fmu_path = (self.path.parent / fmu) if not Path(fmu).is_absolute() else Path(fmu)
        if not fmu_path.is_file():
            self.problem("fmu", "the path of an existing .fmu file", fmu)
        elif row is not None:
            # an FMU of another model would fail later, far from the key that named it
            from ..fmu import model_description
            try:
                model = model_description(fmu_path).coSimulation.modelIdentifier
            except Exception as e:
                model = f"not a readable FMU ({e})"
            if model != row.model:
                article = "an" if row.model[0] in "AEIOU" else "a"
                self.problem("fmu", f"{article} {row.model} FMU for a scenario of kind {row.name!r}",
                             f"{fmu}: {model}")
        return str(fmu_path)

    def check_travel(self, row, law: dict, eps1, rig: dict) -> None:
        """The default rig must settle for the scenario's law: the
        quasi-static rig's transient dies out over a few elastic lengths
        mu N / eps, and its fit must start beyond them."""
        needs = {"mu1", "mu2", "eps2"} <= law.keys() and eps1 is not None and len(rig) == len(SCHEMA["rig"])
        if row is None or not row.carriage or "travel_m" in self.given("rig") or not needs:
            return
        elastic = max(law["mu1"], law["mu2"]) * rig["mass_kg"] * rig["g"] / min(eps1, law["eps2"])
        fit_start = rig["fit_from"] * rig["travel_m"]
        if rig["mode"] == "quasistatic" and fit_start < ELASTIC_LENGTHS * elastic:
            self.problem("rig.travel_m", (
                f"a travel for this law: the default {rig['travel_m']:g} m starts the fit at "
                f"{fit_start:g} m, within {ELASTIC_LENGTHS:g} elastic lengths max(mu) N / min(eps) = "
                f"{elastic:.3g} m of the start, where the block has not settled; set "
                + (f"rig.travel_m >= {ELASTIC_LENGTHS * elastic / rig['fit_from']:.3g}" if rig["fit_from"] > 0
                   else "rig.fit_from > 0 (the fit starts where the path does)")))

    def law_checked(self, law: dict, eps1) -> bool:
        """Whether the law is complete and each parameter within the FMU's
        own range (a positive 1e-320 passes the schema's check)."""
        if eps1 is None or not {"mu1", "mu2", "eps2", "rule"} <= law.keys():
            return False
        refused = set()
        for name, value in (("mu1", law["mu1"]), ("mu2", law["mu2"]), ("eps2", law["eps2"]), ("eps1", eps1)):
            derived = name == "eps1" and law.get("eps1") is None   # eps_ratio x eps2
            if derived and "eps2" in refused:
                continue
            try:
                check_parameter("ContactParams", LAW_ROWS[name], value)
            except ValueError as e:
                refused.add(name)
                self.problems.add(f"{self.path}: law.{'eps_ratio' if derived else name}: "
                                  f"{str(e).split(': ', 1)[1]}")
        return not refused

    def law_on_axes(self, law: dict, eps1, geo: dict):
        """The law's parameters and the axes' geometry, where both are
        complete, and geometry.closed_form held for them; (None, None) else."""
        if not self.law_checked(law, eps1) or len(geo) != len(SCHEMA["geometry"]):
            return None, None
        contact = ContactParams(law["mu1"], law["mu2"], float(eps1), float(law["eps2"]), rule=law["rule"])
        geometry = AxisGeometry(float(geo["alpha_offset_deg"]), float(geo["beta_offset_deg"]))
        refusal = FORMS[geo["closed_form"]].refusal(contact, geometry.beta_minus_alpha_deg)
        if refusal is not None:
            # a warning about the axes (radians in a degree key?) is the likely cause: say it too
            said = "".join(f"; {w[len(str(self.path)) + 2:]}" for w in self.warnings
                           if w.startswith(f"{self.path}: geometry."))
            expected = (f"a closed form that holds for this law and these axes ({geo['closed_form']} needs "
                        f"{refusal}; \"general\" holds for any)")
            self.problems.add(str(ScenarioError(self.path, "geometry.closed_form", expected,
                                                geo["closed_form"])) + said)
        return contact, geometry
