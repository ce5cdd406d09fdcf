"""What an experiment design starts from: the prior (the law's values, the
rig, each kind of run's noise), the runs (a plan.csv's rows: read for
--fixed, written as the plan in a lab's order) and the paper's design a plan
is compared with (the baseline).  Units: N, m, s, deg; a force's noise as a
share of the force or in N."""
from __future__ import annotations

import dataclasses
import math
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

from .. import closed_forms as cf
from .. import plausibility
from ..errors import InputError
from ..experiment import RigSetup
from ..textfiles import read_rows
from .recordings import KINDS, parse_number

PLAN_COLUMNS = ("kind", "mat_angle_deg", "velocity_m_s")
# A ramp is a slow pull through the stick branch (under a millimetre at the
# prior): at the bundled recordings' ramp speed, the carriage's inertia is nil.
RAMP_VELOCITY_M_S = 0.002
# The paper's two carriage velocities (sec. 2.2 and 4.6; Fig. 4) [m/s]: the
# baseline's with a strip, whose viscosity shows only as a change with velocity.
PAPER_VELOCITIES = (0.125, 0.244)


@dataclass(frozen=True)
class Run:
    """One run of a plan: its kind (carriage, slide, ramp), mat angle [deg]
    and carriage velocity [m/s]."""
    kind: str
    mat_angle_deg: float
    velocity_m_s: float


@dataclass(frozen=True)
class Noise:
    """Each run's standard deviation: a driving force's (a slide's or a
    carriage run's) as a share of the force (force_rel) or, from an
    identification, in N (force_N); a trajectory angle's [deg], at a velocity
    [m/s] where angle_by_velocity ((m/s, deg), ...) gives one; a ramp
    sample's force [N]."""
    force_rel: float | None = 0.01
    force_N: float | None = None
    angle_deg: float = 1.0
    angle_by_velocity: tuple = ()
    ramp_N: float = 0.05

    def force_sd(self, force_N: float) -> float:
        """The noise [N] of a measured driving force of force_N [N]."""
        return self.force_rel * force_N if self.force_rel is not None else self.force_N

    def angle_sd(self, velocity_m_s: float) -> float:
        """The noise [deg] of a trajectory angle measured at velocity_m_s."""
        for v, sd in self.angle_by_velocity:
            if math.isclose(v, velocity_m_s, rel_tol=1e-9):
                return sd
        return self.angle_deg

    def as_json(self) -> dict:
        return {"force_relative": self.force_rel, "force_N": self.force_N, "angle_deg": self.angle_deg,
                "angle_deg_by_velocity": {repr(v): sd for v, sd in self.angle_by_velocity} or None,
                "ramp_N": self.ramp_N}


@dataclass(frozen=True)
class Prior:
    """The point a design is optimal at: the rig (its c_strip None where the
    strip's viscosity is designed, a number where it is known, 0 without a
    strip), the values of mu1, mu2, eps_ratio, eps2 [N/m], c_strip [N s/m]
    and f_int [N], the noise, and where they come from."""
    rig: RigSetup
    values: dict
    noise: Noise
    source: str

    @property
    def strip(self) -> bool:
        """The strip's viscosity is a parameter of the design."""
        return self.rig.c_strip is None

    @property
    def rate_dependent(self) -> bool:
        """A run's velocity matters: through the strip's viscosity c v (the
        law itself is rate-independent)."""
        return self.strip or (self.rig.c_strip or 0.0) > 0

    def peak_angle_deg(self) -> float:
        """The mat angle [deg] of the largest |phi| without a strip (the
        paper's calibration point: eq. 37-39), to 0.1 deg."""
        r = cf.mat_ratio(self.values["eps_ratio"], self.values["mu1"], self.values["mu2"])
        return round(math.degrees(cf.mat_extremum(r)[0]), 1)


# The paper's aged mat on its rig (sec. 2, 4.6; experiment.rig_setup's geometry),
# with the strip viscosity of tools/make_recordings.py's synthetic truth.
PAPER = {"mu1": 0.408, "mu2": 0.625, "eps_ratio": 1.251, "eps2": 1e4, "c_strip": 10.0, "f_int": 5.0}
PAPER_RIG = RigSetup(mass_kg=1.875, g=9.806, f_int_N=5.0)


def paper_prior(strip: bool, noise: Noise) -> Prior:
    """The paper's aged mat and rig; with the strip's viscosity designed
    (10 N s/m) or without a strip."""
    values = dict(PAPER, c_strip=PAPER["c_strip"] if strip else 0.0)
    rig = dataclasses.replace(PAPER_RIG, c_strip=None if strip else 0.0)
    where = "with a strip of 10 N s/m" if strip else "no strip"
    return Prior(rig, values, noise, f"the paper's aged mat and rig ({where})")


DEFAULT_NOISE = Noise()


def noise_of(sigma_force: float | None, sigma_angle: float | None, sigma_ramp: float,
             prior_noise: dict | None = None) -> Noise:
    """The design's noise: each option where given, else an identification's
    noise estimate (identified.json's noise_estimate: forces_N, angles_deg,
    angles_deg_by_velocity) where it has one, else DEFAULT_NOISE (1 % of the
    force, 1 deg)."""
    p = prior_noise or {}
    if sigma_force is None and "forces_N" in p:
        force = {"force_rel": None, "force_N": float(p["forces_N"])}
    else:
        force = {"force_rel": DEFAULT_NOISE.force_rel if sigma_force is None else sigma_force}
    if sigma_angle is None and "angles_deg" in p:
        by_velocity = tuple(sorted((float(v), float(sd)) for v, sd in
                                   (p.get("angles_deg_by_velocity") or {}).items()))
        angle = {"angle_deg": float(p["angles_deg"]), "angle_by_velocity": by_velocity}
    else:
        angle = {"angle_deg": DEFAULT_NOISE.angle_deg if sigma_angle is None else sigma_angle}
    return Noise(**force, **angle, ramp_N=sigma_ramp)


def prior_from_identified(path, strip: bool, noise_options: tuple) -> Prior:
    """The prior of an identification (identified.json, read and checked by
    identified_file.read_identified): its estimates (eps2 the rig's nominal
    1e4 N/m where not identified; F_int and c_strip the assumptions' where
    not estimated), its rig (the assumptions; the velocity its angles were
    measured at most) and its noise estimate, unless noise_options
    (sigma_force, sigma_angle, sigma_ramp: noise_of) say otherwise.
    strip False: no strip, whatever the prior's c_strip."""
    from .identified_file import read_identified
    f = read_identified(path)
    missing = [n for n in ("mu1", "mu2", "eps_ratio") if f.value(n) is None]
    if missing:
        raise InputError(f"{path}: {missing[0]}: expected an estimate (a design is optimal at values of mu1, "
                         f"mu2, eps_ratio), got none: {f.estimates[missing[0]].reason}")
    a = f.assumptions
    c_estimated = f.value("c_strip")
    c_known = None if c_estimated is not None else float(a.c_strip_N_s_m)
    if not strip:
        c_estimated, c_known = None, 0.0
    values = {n: f.value(n) for n in ("mu1", "mu2", "eps_ratio")}
    values.update(eps2=f.value("eps2") or PAPER_RIG.eps2_nominal_N_m,
                  f_int=f.value("f_int") or float(a.f_int_N),
                  c_strip=c_estimated if c_estimated is not None else c_known)
    velocities = Counter(f.points.angle_velocities or ())
    rig = RigSetup(mass_kg=a.mass_kg, g=a.g, f_int_N=values["f_int"], rule=a.rule,
                   alpha_offset_deg=a.alpha_offset_deg, beta_offset_deg=a.beta_offset_deg,
                   ramp_angle_deg=a.ramp_angle_deg, mu_strip=a.mu_strip, c_strip=c_known,
                   velocity_m_s=velocities.most_common(1)[0][0] if velocities else PAPER_RIG.velocity_m_s)
    return Prior(rig, values, noise_of(*noise_options, prior_noise=f.noise_estimate), str(path))


def baseline_runs(n: int, peak_deg: float, velocities: tuple) -> list[Run]:
    """The paper's design at n slide runs: its points 0, the peak, 90 deg
    in its proportions 2:1:2 (0, 0, 39.2, 90, 90 deg at 5 runs), n
    apportioned by the largest remainder (ties: the peak first, then 0,
    then 90); with several velocities the same at each, the runs shared
    alike."""
    cells = [(a, v) for v in velocities for a in (peak_deg, 0.0, 90.0)]
    shares = [n * (1.0 if a == peak_deg else 2.0) / (5.0 * len(velocities)) for a, _ in cells]
    counts = [math.floor(s) for s in shares]
    order = sorted(range(len(cells)), key=lambda i: -(shares[i] - counts[i]))
    for i in order[:n - sum(counts)]:
        counts[i] += 1
    return [Run("slide", a, v) for (a, v), k in zip(cells, counts) for _ in range(k)]


def lab_order(runs: list[Run]) -> list[Run]:
    """Runs as a lab makes them: carriage runs first, then the slides
    grouped by mat angle (and velocity), then the ramps."""
    rank = {"carriage": 0, "slide": 1, "ramp": 2}
    return sorted(runs, key=lambda r: (rank[r.kind], r.mat_angle_deg, r.velocity_m_s))


def grouped(runs: list[Run]) -> list[tuple[Run, int]]:
    """(run, how many) of each distinct run, in lab order."""
    counts = Counter(runs)
    return [(r, counts[r]) for r in dict.fromkeys(lab_order(runs))]


def read_plan(path) -> list[Run]:
    """The runs of a plan.csv (or a recording folder's runs.csv: its run
    column is ignored): columns kind, mat_angle_deg, velocity_m_s; InputError
    naming the file, the line and the column."""
    path = Path(path)
    rows = read_rows(path, "a plan.csv with columns " + ",".join(PLAN_COLUMNS))
    if not rows:
        raise InputError(f"{path}: expected a header line with columns {','.join(PLAN_COLUMNS)}")
    line0, header = rows[0]
    header = [h.strip() for h in header]
    missing = [c for c in PLAN_COLUMNS if c not in header]
    if missing:
        raise InputError(f"{path}: line {line0}: expected column {missing[0]!r} "
                         f"(header has {','.join(header)})")
    k, a, v = (header.index(c) for c in PLAN_COLUMNS)
    runs = []
    for line, r in rows[1:]:
        cells = [r[i].strip() if i < len(r) else "" for i in (k, a, v)]
        if cells[0] not in KINDS:
            raise InputError(f"{path}: line {line}: kind: expected one of {', '.join(KINDS)}, "
                             f"got {cells[0]!r}")
        angle, velocity = (parse_number(path, line, c, x) for c, x in zip(PLAN_COLUMNS[1:], cells[1:]))
        if not -180.0 <= angle <= 180.0:
            raise InputError(f"{path}: line {line}: mat_angle_deg: expected an angle in [-180, 180] deg, "
                             f"got {cells[1]}")
        plausibility.gate({"velocity_m_s": velocity}, f"{path}: line {line}: ")
        runs.append(Run(cells[0], angle, velocity))
    if not runs:
        raise InputError(f"{path}: expected at least one run below the header")
    return runs


def plan_rows(runs: list[Run]) -> list[tuple]:
    """plan.csv's rows (kind, mat angle [deg], velocity [m/s]) in lab order."""
    return [(r.kind, float(r.mat_angle_deg), float(r.velocity_m_s)) for r in lab_order(runs)]
