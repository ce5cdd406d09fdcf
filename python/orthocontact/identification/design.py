"""Experiment design: which runs of the carriage/block rig tell the most
about the law's parameters (orthocontact design).

Every candidate run becomes a row of a MeasurementSet (a slide run: one
driving force and one trajectory angle at its mat angle and velocity; a ramp
sample: one (x1, force) row on the stick branch; a carriage run: one F_int),
and the joint fit's own model (fit_model, the parameters estimators.
identifiability frees) gives its sensitivities at the prior: the Jacobian of
the residuals, negated, is d model / d parameter.  With each run's noise
(design_inputs.Noise) its Fisher information is I = J' Sigma^-1 J; the
design's is M = sum over its runs, its Gauss-Newton covariance M^-1, and the
predicted standard error of each parameter sqrt(diag M^-1), in its unit.
design_search finds the optimum.  Units: N, m, s, deg."""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import closed_forms as cf
from .. import plausibility
from ..errors import InputError
from ..runs import status_lines
from . import fit_model
from .design_inputs import PAPER_VELOCITIES, RAMP_VELOCITY_M_S, Prior, Run, baseline_runs, grouped, lab_order
from .design_search import Equivalence, Problem, Status, approximate, exact
from .estimators import identifiability
from .measurements import MeasurementSet

# The ramp's candidate samples: at these shares of the sliding force, below
# the fit's stick branch (90 %, fit_model.stick_mask) by more than a sample's noise.
RAMP_SHARES = tuple(round(0.05 * k, 2) for k in range(1, 18))
SLIDE, RAMP = 0, 1
# Parameters a design plans for, in the order reported; F_int is nuisance.
DESIGNED = ("mu1", "mu2", "eps_ratio", "eps2", "c_strip")
ALWAYS = DESIGNED[:3]   # in every rig's fit


@dataclass(frozen=True)
class Space:
    """The design space: the slide runs' mat angles [deg] and velocities
    [m/s], how many slide runs, ramp samples and carriage runs to plan, and
    the runs already made."""
    angles_deg: tuple
    velocities_m_s: tuple
    slides: int
    ramp_samples: int = 0
    carriage_runs: int = 0
    fixed: tuple = ()


@dataclass(frozen=True)
class Candidates:
    """Every run a design may choose and each one's information per run,
    in the design's units (each parameter by its prior value: `unit`).
    names: the model's parameters; designed: the indices of those planned
    for; run_kind: SLIDE or RAMP per candidate, with its run, a ramp sample's
    x1 [m] (nan for slides) and its model value (driving force [N], phi
    [deg]; a ramp sample: force [N], nan); slide_info: the information of
    a slide run at each (mat angle [deg], velocity [m/s]) the design
    names (the grid's, the runs already made, the baseline's); carriage:
    a carriage run's (zero where F_int is known)."""
    names: tuple
    designed: tuple
    unit: np.ndarray
    runs: tuple
    run_kind: np.ndarray
    x1_m: np.ndarray
    model: np.ndarray
    info: np.ndarray
    slide_info: dict
    carriage: np.ndarray
    warnings: tuple = ()

    def covariance(self, M) -> np.ndarray:
        """M^-1 in the parameters' own units."""
        return np.linalg.inv(M) * np.outer(self.unit, self.unit)

    def sd(self, M) -> dict:
        """The predicted standard error of each parameter [its unit]."""
        return {n: math.sqrt(v) for n, v in zip(self.names, np.diag(self.covariance(M)))}

    def information_of(self, runs) -> np.ndarray:
        """M of slide and carriage runs (Run), in the design's units."""
        M = np.zeros((len(self.names),) * 2)
        for r in runs:
            M = M + (self.carriage if r.kind == "carriage" else
                     self.slide_info[(float(r.mat_angle_deg), float(r.velocity_m_s))])
        return M


def ramp_positions(prior: Prior) -> np.ndarray:
    """x1 [m] of the ramp's candidate samples: RAMP_SHARES of the sliding
    force on the stick branch F_int + k x1 at the prior."""
    rig, v = prior.rig, prior.values
    alpha, beta = rig.axes(rig.ramp_angle_deg)
    plateau = cf.steady_drive_force(v["mu1"], v["mu2"], beta, 0.0, rig.mass_kg, rig.g)
    return np.array(RAMP_SHARES) * plateau / stick_stiffness(prior)


def stick_stiffness(prior: Prior) -> float:
    """dF/dx1 [N/m] of the ramp's stick branch at the prior."""
    v, alpha = prior.values, prior.rig.axes(prior.rig.ramp_angle_deg)[0]
    return cf.stick_stiffness_x1(v["eps_ratio"] * v["eps2"], v["eps2"], alpha)


def slide_points(space: Space, also: list) -> list:
    """(mat angle [deg], velocity [m/s]) of every candidate slide run, then
    of the slides already made and of `also` (Run), each once."""
    grid = [(float(a), float(v)) for v in space.velocities_m_s for a in space.angles_deg]
    named = [(float(r.mat_angle_deg), float(r.velocity_m_s)) for r in list(space.fixed) + list(also)
             if r.kind == "slide"]
    return list(dict.fromkeys(grid + named))


def measurement_set(prior: Prior, points: list, ramp_x1: np.ndarray, carriage: bool) -> MeasurementSet:
    """The rows the model is evaluated at: a force and an angle at each
    point, the ramp's samples, one carriage run; their values are the
    prior's (no strip: the closed forms) where the fit's model reads them
    (its stick branch); elsewhere only the residuals' Jacobian is used."""
    rig, v = prior.rig, prior.values
    a = np.array([p[0] for p in points])
    vel = np.array([p[1] for p in points])
    F = [v["f_int"] + cf.steady_drive_force(v["mu1"], v["mu2"], rig.axes(x)[1], 0.0, rig.mass_kg, rig.g)
         for x in a]
    ramp = None if not len(ramp_x1) else \
        np.column_stack([ramp_x1, v["f_int"] + stick_stiffness(prior) * ramp_x1])
    return MeasurementSet(Path("design"), rig, forces=np.column_stack([a, F]),
                          angles=np.column_stack([a, np.zeros_like(a)]), ramp=ramp, angle_velocities=vel,
                          force_velocities=vel, carriage=np.array([[v["f_int"], 0.0]]) if carriage else None)


def sensitivities(prior: Prior, data: MeasurementSet) -> tuple[list, dict, dict]:
    """(the fit's free parameters, {group: d model / d parameter, rows in the
    group's order, columns in its unit}, {group: model values}) at the
    prior, from fit_model's residuals r = data - model."""
    free, why = identifiability(data)
    start = dict(prior.values)
    model = fit_model.build(data, start, free)
    r, J = model.evaluate(model.x_of(start))
    G = -J / model.scale
    data_values = {"forces": data.forces[:, 1], "angles": data.angles[:, 1],
                   "ramp": None if data.ramp is None else data.ramp[model.stick, 1],
                   "carriage": None if data.carriage is None else data.carriage[:, 0]}
    rows = model.split(np.arange(len(r)))
    return (free, {g: G[i] for g, i in rows.items()},
            {g: data_values[g] - r[i] for g, i in rows.items()})


def outer(g: np.ndarray, sd: np.ndarray) -> np.ndarray:
    """sum over rows of g g' / sd^2: (n, p), (n,) -> (n, p, p) per row."""
    return np.einsum("ni,nj->nij", g, g) / (np.asarray(sd, float) ** 2)[:, None, None]


def candidates(prior: Prior, space: Space, also: list = ()) -> Candidates:
    """The candidates of `space` at `prior`, each with its information, and
    that of the runs already made and of `also` (the baseline's runs)."""
    points = slide_points(space, also)
    ramp_x1 = ramp_positions(prior) if space.ramp_samples else np.zeros(0)
    carriage = space.carriage_runs > 0 or any(r.kind == "carriage" for r in list(space.fixed) + list(also))
    data = measurement_set(prior, points, ramp_x1, carriage)
    names, G, model = sensitivities(prior, data)
    lost = [n for n in ALWAYS if n not in names]
    if lost:
        raise InputError(f"expected a rig whose runs determine {', '.join(lost)} (sliding rule "
                         f"{prior.rig.rule}: {identifiability(data)[1].get(lost[0], '')})")
    unit = np.array([abs(prior.values[n]) if prior.values.get(n) else 1.0 for n in names])
    noise, p = prior.noise, len(names)
    slide_info = (outer(G["forces"] * unit, [noise.force_sd(F) for F in model["forces"]])
                  + outer(G["angles"] * unit, [noise.angle_sd(v) for _, v in points]))
    n_grid = len(space.angles_deg) * len(space.velocities_m_s)
    runs = [Run("slide", a, v) for a, v in points[:n_grid]]
    info, kind, x1 = [slide_info[:n_grid]], [SLIDE] * n_grid, [math.nan] * n_grid
    values = list(zip(model["forces"], model["angles"]))[:n_grid]
    if space.ramp_samples:
        info.append(outer(G["ramp"] * unit, np.full(len(ramp_x1), noise.ramp_N)))
        runs += [Run("ramp", prior.rig.ramp_angle_deg, RAMP_VELOCITY_M_S)] * len(ramp_x1)
        kind, x1 = kind + [RAMP] * len(ramp_x1), x1 + list(ramp_x1)
        values += [(F, math.nan) for F in model["ramp"]]
    carriage_info = np.zeros((p, p)) if not carriage else \
        outer(G["carriage"] * unit, [noise.force_sd(prior.values["f_int"])])[0]
    warnings = () if not any(r.kind == "ramp" for r in space.fixed) else (
        "--fixed: its ramp runs are not counted: a ramp's information depends on where its samples "
        "lie on the stick branch, which a plan does not hold (plan them with --ramp-samples)",)
    return Candidates(tuple(names), tuple(i for i, n in enumerate(names) if n in DESIGNED), unit,
                      tuple(runs), np.array(kind), np.array(x1), np.array(values), np.concatenate(info),
                      dict(zip(points, slide_info)), carriage_info, warnings)


@dataclass(frozen=True)
class Baseline:
    """The paper's design at the same budget (design_inputs.baseline_runs),
    beside the runs already made and the carriage runs: its runs, its ramp
    samples' x1 [m] (spread evenly over the candidates), its information
    (None where singular) and what it is, in words."""
    runs: tuple
    ramp_x1_m: tuple
    M: np.ndarray | None
    description: str


@dataclass(frozen=True)
class Design:
    """A planned design: the prior and space it is for, the candidates, the
    exact design (runs of each candidate), the approximate optimum (weights)
    with its equivalence check, the information of both, the baseline."""
    criterion: str
    prior: Prior
    space: Space
    candidates: Candidates
    counts: np.ndarray
    weights: np.ndarray
    equivalence: Equivalence
    M: np.ndarray
    M_approximate: np.ndarray
    baseline: Baseline
    problem: Problem
    warnings: tuple = ()

    @property
    def designed(self) -> list:
        return [self.candidates.names[i] for i in self.candidates.designed]

    def runs(self) -> list[Run]:
        """The new runs, in lab order: the carriage runs, the slides, one
        ramp run if ramp samples are planned."""
        c, v = self.candidates, self.prior.rig.velocity_m_s
        slides = [r for r, n, k in zip(c.runs, self.counts, c.run_kind) if k == SLIDE for _ in range(n)]
        ramp = [Run("ramp", self.prior.rig.ramp_angle_deg, RAMP_VELOCITY_M_S)] * (self.space.ramp_samples > 0)
        return lab_order([Run("carriage", 0.0, v)] * self.space.carriage_runs + slides + ramp)

    def ramp_x1_m(self) -> list:
        """x1 [m] of each planned ramp sample, ascending."""
        c = self.candidates
        return [float(x) for x, n, k in zip(c.x1_m, self.counts, c.run_kind) if k == RAMP for _ in range(n)]

    def sd(self, M) -> dict:
        """The designed parameters' predicted standard errors [their units] at M."""
        sd = self.candidates.sd(M)
        return {n: sd[n] for n in DESIGNED if n in sd}

    def efficiency(self) -> float | None:
        """The plan against the baseline (design_search.Problem.efficiency)."""
        return None if self.baseline.M is None else self.problem.efficiency(self.M, self.baseline.M)


def velocities_of(prior: Prior, lowest: float, highest: float, step: float) -> tuple:
    """The candidate velocities [m/s]: lowest to highest in about `step`
    steps where a run's velocity matters (the strip's viscosity), else the
    rig's alone (the law is rate-independent)."""
    if not prior.rate_dependent:
        return (prior.rig.velocity_m_s,)
    if not 0 < lowest < highest:
        raise InputError(f"--velocity-min {lowest:g}, --velocity-max {highest:g}: expected the lowest "
                         "below the highest [m/s] (a strip's viscosity shows only as a change with velocity)")
    plausibility.gate({"velocity_m_s": lowest}, "--velocity-min: ")
    plausibility.gate({"velocity_m_s": highest}, "--velocity-max: ")
    n = max(1, int(round((highest - lowest) / step)))
    return tuple(round(x, 9) for x in np.linspace(lowest, highest, n + 1))


def angles_of(prior: Prior, step: float) -> tuple:
    """The candidate mat angles [deg]: 0 to 90 in `step`s (90 included),
    where the axes' offsets are multiples of 90 deg (a mat angle's mirror
    image gives the mirrored trajectory and the same force), else 0 to
    below 180 (the tensors repeat every 180 deg)."""
    rig = prior.rig
    mirrored = all(math.isclose(o / 90.0, round(o / 90.0), abs_tol=1e-12)
                   for o in (rig.alpha_offset_deg, rig.beta_offset_deg))
    angles = np.round(np.arange(0.0, (90.0 if mirrored else 180.0 - 1e-6) + 1e-9, step), 9)
    if mirrored and angles[-1] != 90.0:
        angles = np.append(angles, 90.0)
    return tuple(float(a) for a in angles)


def baseline_of(prior: Prior, space: Space, cand: Candidates, made: list, problem: Problem) -> Baseline:
    """The paper's design at the plan's budget, with the runs already made."""
    velocities = PAPER_VELOCITIES if prior.rate_dependent else (prior.rig.velocity_m_s,)
    paper = baseline_runs(space.slides, prior.peak_angle_deg(), velocities)
    M = cand.information_of(made + paper)
    ramp = np.flatnonzero(cand.run_kind == RAMP)
    spread = [] if not len(ramp) else ramp[np.round(np.linspace(0, len(ramp) - 1,
                                                                space.ramp_samples)).astype(int)]
    for i in spread:
        M = M + cand.info[i]
    points = ", ".join(f"{r.mat_angle_deg:g} deg x{n}" for r, n in grouped(paper)
                       if r.velocity_m_s == velocities[0])
    text = (f"the paper's points (0 and 90 deg for eq. 1, the peak of |phi| at the prior for eq. 39) in "
            f"its proportions 2:1:2: {points} at " + " and at ".join(f"{v:g}" for v in velocities) + " m/s")
    if space.ramp_samples:
        text += f"; {space.ramp_samples} ramp samples spread evenly over the stick branch"
    if space.fixed:
        text += "; with the runs already made"
    if space.carriage_runs:
        text += f"; with the same {space.carriage_runs} carriage runs"
    return Baseline(tuple(paper), tuple(float(cand.x1_m[i]) for i in spread),
                    M if np.isfinite(problem.loss(M)) else None, text)


def made_runs(prior: Prior, space: Space) -> list[Run]:
    """The runs whose information the plan adds to: those already made (but
    ramps: their samples' positions unknown) and the carriage runs."""
    made = [r for r in space.fixed if r.kind != "ramp"]
    return made + [Run("carriage", 0.0, prior.rig.velocity_m_s)] * space.carriage_runs


def problem_of(prior: Prior, space: Space, cand: Candidates, criterion: str) -> Problem:
    """The search's problem: slides and ramp samples, each group its budget."""
    budget = (space.slides,) + ((space.ramp_samples,) if space.ramp_samples else ())
    made = cand.information_of(made_runs(prior, space))
    return Problem(cand.info, cand.run_kind, budget, made, cand.designed, criterion)


def search(problem: Problem, cand: Candidates, velocity_m_s: float, status: Status):
    """(weights, Equivalence, counts): the approximate optimum, then whole runs."""
    weights, equivalence = approximate(problem, status=status)
    status.text = f"whole runs by exchange among {len(cand.runs)} candidates"
    return weights, equivalence, consolidated(cand, exact(problem, weights), velocity_m_s)


# The most candidate slide runs a design takes: the fit model's build costs about 1 ms
# each (16606 with a strip: 22 s in all), so this is a minute or two.
MAX_CANDIDATES = 50_000


def too_few_runs(space: Space, names) -> InputError:
    return InputError(f"--runs {space.slides}: expected enough slide runs to determine "
                      f"{', '.join(names)} (each gives a force and an angle)")


def check_size(space: Space) -> None:
    """Refuses (InputError, before any work) a grid of more than
    MAX_CANDIDATES slide runs (a step that small is usually a typo), and
    runs that give fewer numbers than every fit has parameters."""
    if not space.fixed and 2 * space.slides + space.ramp_samples < len(ALWAYS):
        raise too_few_runs(space, ALWAYS)
    n = len(space.angles_deg) * len(space.velocities_m_s)
    if n > MAX_CANDIDATES:
        raise InputError(f"--angle-step, --velocity-step: expected at most {MAX_CANDIDATES} candidate slide "
                         f"runs (a minute or two), got {len(space.angles_deg)} mat angles x "
                         f"{len(space.velocities_m_s)} velocities = {n}: raise the steps")


def plan(prior: Prior, space: Space, criterion: str, say=None) -> Design:
    """The optimal design of `space` at `prior` by `criterion` (D or A):
    the approximate optimum, then whole runs (design_search.exact);
    `say(text)` is given a progress line as runs.progress.status_lines says."""
    check_size(space)
    velocities = PAPER_VELOCITIES if prior.rate_dependent else (prior.rig.velocity_m_s,)
    n = len(space.angles_deg) * len(space.velocities_m_s)
    status = Status(f"the fit's model at {n} candidate slide runs")
    with status_lines(say, lambda: status.text):
        cand = candidates(prior, space, baseline_runs(space.slides, prior.peak_angle_deg(), velocities))
        problem = problem_of(prior, space, cand, criterion)
        if problem.rank_bound() < len(cand.names):   # no design within the budget determines them
            raise too_few_runs(space, cand.names)
        weights, equivalence, counts = search(problem, cand, prior.rig.velocity_m_s, status)
    M = problem.information(counts)
    if not np.isfinite(problem.loss(M)):
        raise too_few_runs(space, cand.names)
    runs = np.asarray(problem.budget, float)[cand.run_kind]
    baseline = baseline_of(prior, space, cand, made_runs(prior, space), problem)
    return Design(criterion, prior, space, cand, counts, weights, equivalence, M,
                  problem.information(runs * weights), baseline,
                  problem, cand.warnings + tuple(identification_warnings(prior, space, cand, counts)))


def consolidated(cand: Candidates, counts: np.ndarray, velocity_m_s: float) -> np.ndarray:
    """The runs moved, at each mat angle, between velocities whose runs tell
    the same (the same information: on the tensors' axes the block slides
    straight, and the strip's viscosity has no lateral speed to resist)
    onto the one nearest the rig's velocity [m/s]: a plan a lab makes at
    one speed where any would do.  The information is unchanged."""
    counts = counts.copy()
    for i in np.flatnonzero(counts * (cand.run_kind == SLIDE)):
        tol = 1e-12 * np.abs(cand.info[i]).max()
        same = [j for j, r in enumerate(cand.runs) if cand.run_kind[j] == SLIDE
                and r.mat_angle_deg == cand.runs[i].mat_angle_deg
                and np.allclose(cand.info[j], cand.info[i], rtol=1e-9, atol=tol)]
        best = min(same, key=lambda j: (abs(cand.runs[j].velocity_m_s - velocity_m_s),
                                        cand.runs[j].velocity_m_s))
        if best != i:
            counts[best] += counts[i]
            counts[i] = 0
    return counts


def identification_warnings(prior: Prior, space: Space, cand: Candidates, counts) -> list[str]:
    """What `orthocontact identify` would not estimate from the plan and the
    runs already made although the design plans for it (estimators.
    identifiability): the strip's viscosity needs angles at two velocities."""
    runs = [r for r, n in zip(cand.runs, counts) if r.kind == "slide" for _ in range(n)]
    runs += [r for r in space.fixed if r.kind == "slide"]
    data = measurement_set(prior, [(r.mat_angle_deg, r.velocity_m_s) for r in runs], np.zeros(0), False)
    free, why = identifiability(data)
    return [f"the plan cannot give {n} to `orthocontact identify`: {why.get(n, 'not determined')}"
            for n in ("mu1", "mu2", "eps_ratio", "c_strip") if n in cand.names and n not in free]
