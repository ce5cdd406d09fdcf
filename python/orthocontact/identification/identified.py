"""The identification's result as identified.json holds it, typed:
IdentifiedFile and its parts (estimates, covariance, points, data, assumptions,
the reduction's summary), and its JSON object (IdentifiedFile.as_json).
identify builds it (job.Identification.identified_file); identified_file
writes and reads it.  Units: as each field's name or its parameter says
(mu1, mu2, eps_ratio, l1_l2_ratio [-]; eps1, eps2 [N/m]; c_strip [N s/m];
f_int [N])."""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

SCHEMA_VERSION = 2    # identified.schema.json's; the reader refuses another (2: the fit's record)

# Always in the file, each a value or the reason why not; the others when fitted.
REPORTED = ("mu1", "mu2", "eps_ratio", "eps1", "eps2")
FITTED_TOO = ("c_strip", "f_int", "l1_l2_ratio")
SHA256_OF = ("the listing `sha256sum` prints for data.files, in that (sorted) order: "
             "cd FOLDER && sha256sum FILE... | sha256sum")


# The unit of each estimate ("-": dimensionless), with every value the
# terminal summary, identified.md and the exported FMU's documentation give.
UNITS = {"mu1": "-", "mu2": "-", "eps_ratio": "-", "l1_l2_ratio": "-", "eps1": "N/m", "eps2": "N/m",
         "c_strip": "N s/m", "f_int": "N"}


def reported_names(estimates) -> list:
    """The parameters a summary lists, of those in `estimates` (names): the
    five, l1/l2 when angles alone were fitted, the strip's viscosity and
    F_int when they were estimated."""
    return list(REPORTED) + [n for n in ("l1_l2_ratio", "c_strip", "f_int") if n in estimates]


@dataclass(frozen=True)
class Estimate:
    """A fitted parameter in its unit: value, standard error, 95 % interval
    (low, high) and the Welch-Satterthwaite degrees of freedom of the
    interval (math.inf: the noise was known; None: not computed)."""
    value: float
    stderr: float
    ci95: tuple
    dof: float | None = None
    unit: str | None = None      # said in the file for c_strip, f_int
    note: str | None = None


@dataclass(frozen=True)
class NotIdentified:
    """A parameter the data do not determine, and why."""
    reason: str


@dataclass(frozen=True)
class Covariance:
    """The Gauss-Newton covariance of the named estimates (values in their
    units; matrix in the products of their units)."""
    parameters: tuple
    values: tuple
    matrix: tuple    # rows


@dataclass(frozen=True)
class Points:
    """The measured points the fit took: angles [[mat angle deg, phi deg
    counterclockwise]], the carriage velocity [m/s] of each angle (raw
    recordings), forces [[mat angle deg, N]]; None where the data had none."""
    angles: tuple | None
    angle_velocities: tuple | None
    forces: tuple | None


@dataclass(frozen=True)
class DataRecord:
    """The data the identification read: the folder as given and resolved,
    how many values of each kind, every file with its SHA-256 and one
    digest over them (measurements.data_digest)."""
    folder: str
    absolute_folder: str
    forces: int
    angles: int
    ramp: int
    files: dict          # path under folder (POSIX) -> SHA-256
    sha256: str


@dataclass(frozen=True)
class Assumptions:
    """What the fit took as known (rig.toml): the rule, the axes' offsets
    [deg], mass [kg], g [m/s^2], F_int [N] and the strip's viscosity
    [N s/m] (or "estimated": see the estimates f_int, c_strip), the ramp's
    mat angle [deg], the strip's friction [-]."""
    rule: str
    alpha_offset_deg: float
    beta_offset_deg: float
    mass_kg: float
    g: float
    f_int_N: float | str
    ramp_angle_deg: float
    mu_strip: float
    c_strip_N_s_m: float | str
    phi_convention: str
    ci: str


@dataclass(frozen=True)
class ReductionSummary:
    """What the reduction of raw recordings did (the whole table is
    reduction.csv): runs of each kind, those left out and flagged, and the
    files it wrote beside identified.json."""
    runs: dict            # kind (slide, carriage, ramp) -> count
    left_out: tuple
    flagged: dict         # run -> its flags
    table: str
    figures: tuple
    scenario: str | None


@dataclass(frozen=True)
class FitRecord:
    """How the joint fit ended: converged (every part of `convergence`:
    solver, the last solve met IPOPT's tolerance with no Gauss-Newton step
    left; noise_model, the reweighting settled; strip_regimes, strip_roots:
    the strip's regimes and steady states are those at the solution), each
    solve's status, iterations and step left [standard errors], the
    lack-of-fit test of each group with
    replicates (lack_of_fit.LackOfFit.as_json), and whether identify wrote
    it with --force."""
    converged: bool
    convergence: dict
    reweighting_rounds: int
    solves: tuple
    lack_of_fit: dict
    forced: bool = False

    def problems(self) -> list:
        """One line for each reason the fit's estimates cannot be trusted:
        what did not converge, each group the law does not describe."""
        out = []
        if not self.converged:
            last = self.solves[-1] if self.solves else {}
            parts = ", ".join(k for k, ok in self.convergence.items() if not ok) or "solver"
            step = last.get("step_left_se", math.nan)
            out.append(f"the joint fit did not converge ({parts}; the last solve: {last.get('status')}, "
                       f"{last.get('iterations')} iterations, a step of {step:.2g} standard errors left)")
        rejected = [t for t in self.lack_of_fit.values() if t.get("rejected")]
        # the least likely group first: its cause is the likelier one
        return out + [t["line"] for t in sorted(rejected, key=lambda t: t["p_value"])]

    def as_json(self) -> dict:
        return {"converged": self.converged, "convergence": dict(self.convergence),
                "reweighting_rounds": self.reweighting_rounds, "solves": [dict(s) for s in self.solves],
                "lack_of_fit": {g: dict(t) for g, t in self.lack_of_fit.items()}, "forced": self.forced}


@dataclass(frozen=True)
class IdentifiedFile:
    """identified.json as typed fields.  estimates: every name of REPORTED,
    and those of FITTED_TOO that were fitted; covariance: the law's
    parameters' (what uq draws from), covariance_joint: with F_int and the
    strip when they were fitted.  The paper's formulas beside the fit
    (max_rule, eq40, eq41, eq1), the noise model, the residuals and the FMU's
    validation are the report's, kept as written.  path, provenance: where
    the reader read it and the data it found (not in the file)."""
    estimates: dict
    max_rule: dict | None
    eq40: dict | None
    eq41: dict | None
    eq1: dict | None
    noise_estimate: dict          # group's unit key (forces_N, angles_deg, ...) -> noise; and
    #                               angles_deg_by_velocity: {m/s as text: deg}
    noise_model: dict
    intervals: str
    noise_assumed: tuple          # groups whose noise is the prior, not estimated
    fit_residuals: dict
    dof: int
    covariance: Covariance
    covariance_joint: Covariance | None
    points: Points
    ramp_stick_points: int
    validation_fmu: dict | None
    data: DataRecord
    assumptions: Assumptions
    fit: FitRecord
    reduction: ReductionSummary | None = None
    path: Path | None = dataclasses.field(default=None, compare=False)
    provenance: object = dataclasses.field(default=None, compare=False)   # identified_file.DataProvenance

    def value(self, name: str) -> float | None:
        """The estimate's value, None if it was not identified."""
        e = self.estimates.get(name)
        return e.value if isinstance(e, Estimate) else None

    def as_json(self) -> dict:
        """The file's JSON object (write_identified writes it)."""
        out = {"schema_version": SCHEMA_VERSION}
        for name, e in self.estimates.items():
            if isinstance(e, NotIdentified):
                out[name] = {"identifiable": False, "reason": e.reason}
                continue
            out[name] = {"value": e.value, "stderr": e.stderr, "ci95": list(e.ci95), "dof": _dof_json(e.dof)}
            out[name].update({k: v for k, v in (("unit", e.unit), ("note", e.note)) if v is not None})
        out.update(max_rule=self.max_rule, eq40=self.eq40, eq41=self.eq41, eq1=self.eq1,
                   noise_estimate=self.noise_estimate, noise_model=self.noise_model, intervals=self.intervals)
        if self.noise_assumed:
            out["noise_assumed"] = list(self.noise_assumed)
        out.update(fit=self.fit.as_json(), fit_residuals=self.fit_residuals, dof=self.dof,
                   covariance=_cov_json(self.covariance))
        if self.covariance_joint is not None:
            out["covariance_joint"] = _cov_json(self.covariance_joint)
        p = self.points
        out["points"] = {"angles": _lists(p.angles), "angle_velocities": _lists(p.angle_velocities),
                         "forces": _lists(p.forces)}
        out.update(ramp_stick_points=self.ramp_stick_points, validation_fmu=self.validation_fmu,
                   data={**dataclasses.asdict(self.data), "sha256_of": SHA256_OF},
                   assumptions=dataclasses.asdict(self.assumptions))
        if self.reduction is not None:
            r = self.reduction
            out["reduction"] = {"runs": dict(r.runs), "left_out": list(r.left_out),
                                "flagged": dict(r.flagged), "table": r.table, "figures": list(r.figures),
                                "scenario": r.scenario}
        return out


def _dof_json(nu):
    return None if nu is None else ("inf" if math.isinf(nu) else nu)


def _cov_json(c: Covariance) -> dict:
    return {"parameters": list(c.parameters), "values": list(c.values), "matrix": [list(r) for r in c.matrix]}


def _lists(rows):
    return None if rows is None else [list(r) if isinstance(r, tuple) else r for r in rows]
