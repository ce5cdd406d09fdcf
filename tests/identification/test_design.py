"""Experiment design (identification.design, `orthocontact design`):
the plan against the paper's points, its predicted standard errors against
an independent Fisher matrix (closed forms by finite differences: no
casadi, no fit model) and against the spread of the joint fit over noisy
rig runs (Monte Carlo), sequential design, a prior from an identification,
the strip and the ramp, and bad input through the command line."""
import json
import math
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

from cli_run import one_error_line, run_cli
from orthocontact import closed_forms as cf
from orthocontact.identification import design, design_inputs
from orthocontact.identification.estimators import joint_fit, start_values
from orthocontact.identification.job import simulate_measurements
from orthocontact.identification.measurements import MeasurementSet

ACCEPTANCE = ["design", "--runs", "5", "--sigma-force", "0.01", "--sigma-angle", "1.0", "--no-strip"]
M_KG, G, F_INT = 1.875, 9.806, 5.0
AGED = {"mu1": 0.408, "mu2": 0.625, "eps_ratio": 1.251}


def independent_sd(angles_deg, sigma_rel=0.01, sigma_deg=1.0, theta=AGED) -> dict:
    """sqrt(diag M^-1) of slide runs at `angles_deg` for (mu1, mu2,
    eps_ratio): the force F_int + m g / sqrt(cos^2/mu1^2 + sin^2/mu2^2)
    (the friction ellipse), the angle of the mat's closed form tan phi =
    (r^2 - 1) t / (r^2 + t^2), r = (eps1/eps2)(mu1/mu2), both
    differentiated by central differences."""
    names = list(theta)

    def model(values, a):
        t = math.radians(a)
        f11 = math.cos(t) ** 2 / values[0] ** 2 + math.sin(t) ** 2 / values[1] ** 2
        force = F_INT + M_KG * G / math.sqrt(f11)
        r = cf.mat_ratio(values[2], values[0], values[1])
        return np.array([force, math.degrees(math.atan(cf.mat_tan_phi(r, t)))])
    x = np.array([theta[n] for n in names])
    M = np.zeros((3, 3))
    for a in angles_deg:
        J = np.zeros((2, 3))
        for k in range(3):
            h = np.zeros(3)
            h[k] = 1e-6 * x[k]
            J[:, k] = (model(x + h, a) - model(x - h, a)) / (2 * h[k])
        w = np.diag(1 / np.array([sigma_rel * model(x, a)[0], sigma_deg]) ** 2)
        M += J.T @ w @ J
    return dict(zip(names, np.sqrt(np.diag(np.linalg.inv(M)))))


@pytest.fixture(scope="module")
def acceptance(tmp_path_factory):
    """The acceptance command, run once: (its process, its output folder)."""
    cwd = tmp_path_factory.mktemp("design")
    p = run_cli(ACCEPTANCE + ["--out", "D"], cwd)
    assert p.returncode == 0, p.stderr
    return p, cwd / "D"


def plan_angles(folder) -> list:
    rows = (folder / "plan.csv").read_text().splitlines()
    assert rows[0] == "kind,mat_angle_deg,velocity_m_s"
    return [float(r.split(",")[1]) for r in rows[1:]]


def test_five_d_optimal_runs_beat_the_papers_points_by_at_least_1_3(acceptance):
    p, out = acceptance
    d = json.loads((out / "design.json").read_text())
    assert sorted(plan_angles(out)) == [29, 29, 29, 90, 90]
    assert d["criterion"] == "D" and d["parameters"] == ["mu1", "mu2", "eps_ratio"]
    assert d["efficiency"] >= 1.30 and d["efficiency"] == pytest.approx(1.403, abs=0.002)
    assert d["predicted_sd"]["eps_ratio"] == pytest.approx(0.0234, abs=2e-4)
    assert d["baseline"]["predicted_sd"]["eps_ratio"] == pytest.approx(0.0290, abs=2e-4)
    assert [(r["mat_angle_deg"], r["runs"]) for r in d["baseline"]["runs"]] == [(0, 2), (39.2, 1), (90, 2)]
    eq = d["equivalence_theorem"]
    assert eq["holds"] and 1.0 <= eq["max_sensitivity_ratio"] <= 1 + eq["tolerance"]
    assert "D-efficiency against the baseline: 1.403" in p.stdout
    assert (out / "design.png").stat().st_size > 10_000 and "| slide | 29 | 0.244 | 3 |" in \
        (out / "design.md").read_text()


def test_predicted_sd_agree_with_an_independent_fisher_matrix(acceptance):
    _, out = acceptance
    d = json.loads((out / "design.json").read_text())
    for sd, angles in ((d["predicted_sd"], plan_angles(out)),
                       (d["baseline"]["predicted_sd"], [0, 0, 39.2, 90, 90])):
        truth = independent_sd(angles)
        for name, value in truth.items():
            assert sd[name] == pytest.approx(value, rel=0.10)
            assert sd[name] == pytest.approx(value, rel=1e-5)   # in fact the same to the differences' error


def monte_carlo(angles, sd, replicates, seed=1):
    """The spread of the joint fit's estimates over noisy copies of the
    rig's noise-free runs (the FMU in the harness) at `angles`, noise
    `sd` (share of F, deg)."""
    rig = design_inputs.paper_prior(False, design_inputs.Noise()).rig
    law = design_inputs.PAPER
    from orthocontact.fmu.params import ContactParams
    truth = ContactParams(law["mu1"], law["mu2"], law["eps_ratio"] * law["eps2"], law["eps2"])
    clean = simulate_measurements(truth, rig, angles, angles)
    rng = np.random.default_rng(seed)
    estimates = []
    for _ in range(replicates):
        forces = clean["forces"].copy()
        forces[:, 1] += rng.normal(0, sd[0] * forces[:, 1])
        phi = clean["angles"].copy()
        phi[:, 1] += rng.normal(0, sd[1], len(phi))
        data = MeasurementSet(folder=Path("mc"), rig=rig, forces=forces, angles=phi)
        fit = joint_fit(data, start_values(data))
        estimates.append([fit.values[n] for n in ("mu1", "mu2", "eps_ratio")])
    return dict(zip(("mu1", "mu2", "eps_ratio"), np.std(estimates, axis=0, ddof=1)))


def test_the_joint_fits_spread_over_noisy_rig_runs_is_the_predicted_sd(acceptance):
    """200 replicates: a spread's own sampling error is 1/sqrt(2 x 199) = 5 %."""
    _, out = acceptance
    d = json.loads((out / "design.json").read_text())
    spread = monte_carlo(plan_angles(out), (0.01, 1.0), 200)
    for name, predicted in d["predicted_sd"].items():
        assert spread[name] == pytest.approx(predicted, rel=0.15), (name, spread[name], predicted)


def run_design(tmp_path, *args):
    p = run_cli(["design", *map(str, args)], tmp_path)
    assert p.returncode == 0, p.stderr
    return json.loads((tmp_path / args[args.index("--out") + 1] / "design.json").read_text())


def test_the_next_runs_given_those_made_complete_the_best_design(tmp_path):
    """Sequential design: 5 runs, then 5 more given those, are as good as
    the best 10 runs planned at once."""
    first = run_design(tmp_path, "--runs", 5, "--no-strip", "--out", "first")
    second = run_design(tmp_path, "--runs", 5, "--no-strip", "--fixed", tmp_path / "first/plan.csv",
                        "--out", "second")
    assert second["space"]["fixed_runs"] == first["plan"]
    assert second["plan"] != first["plan"]
    prior = design_inputs.paper_prior(False, design_inputs.Noise())
    ten = design.plan(prior, design.Space(design.angles_of(prior, 1.0), (0.244,), 10), "D")
    both = design.Space(design.angles_of(prior, 1.0), (0.244,), 5,
                        fixed=tuple(design_inputs.read_plan(tmp_path / "first/plan.csv")))
    seq = design.plan(prior, both, "D")
    assert seq.problem.efficiency(seq.M, ten.M) >= 0.98
    assert second["predicted_sd"] == pytest.approx(seq.sd(seq.M), rel=1e-9)


def test_a_prior_from_an_identification_brings_its_estimates_rig_and_noise(tmp_path, identified):
    d = run_design(tmp_path, "--runs", 5, "--prior", identified, "--out", "o")
    f = json.loads(identified.read_text())
    assert d["prior"]["values"]["mu1"] == f["mu1"]["value"]
    assert d["prior"]["values"]["eps_ratio"] == f["eps_ratio"]["value"]
    assert d["prior"]["noise"]["force_N"] == f["noise_estimate"]["forces_N"]
    assert d["prior"]["noise"]["angle_deg"] == f["noise_estimate"]["angles_deg"]
    assert d["prior"]["source"] == str(identified)
    # the example was identified with c_strip = 0 given: no strip, one velocity
    assert d["parameters"] == ["mu1", "mu2", "eps_ratio"] and d["space"]["velocities_m_s"] == [0.244]
    # an explicit option wins over the prior's noise
    d = run_design(tmp_path, "--runs", 5, "--prior", identified, "--sigma-force", "0.02", "--out", "p")
    assert d["prior"]["noise"]["force_relative"] == 0.02 and d["prior"]["noise"]["force_N"] is None


def test_with_a_strip_the_runs_go_to_the_extreme_velocities_and_the_ramp_to_its_end():
    prior = design_inputs.paper_prior(True, design_inputs.Noise())
    velocities = design.velocities_of(prior, 0.05, 0.5, 0.15)
    space = design.Space(design.angles_of(prior, 5.0), velocities, 10, ramp_samples=5)
    d = design.plan(prior, space, "D")
    assert d.designed == ["mu1", "mu2", "eps_ratio", "eps2", "c_strip"]
    # on the axes (0, 90 deg) the block slides straight: no lateral speed, no viscous force, any velocity
    off_axes = {r.velocity_m_s for r in d.runs() if r.kind == "slide" and r.mat_angle_deg % 90}
    assert off_axes == {0.05, 0.5}
    # and the plan makes them at the candidate velocity nearest the rig's 0.244 m/s
    assert {r.velocity_m_s for r in d.runs() if r.kind == "slide" and not r.mat_angle_deg % 90} == {0.2}
    # F_int known: eps2 = slope alone, best at the stick branch's end
    assert set(d.ramp_x1_m()) == {max(design.ramp_positions(prior))}
    assert d.equivalence.holds and d.efficiency() > 1.0 and d.warnings == ()
    sd = d.sd(d.M)
    assert sd["eps2"] == pytest.approx(0.05 / math.sqrt(5) / max(design.ramp_positions(prior)), rel=1e-6)


def test_carriage_runs_make_f_int_a_nuisance_parameter():
    prior = design_inputs.paper_prior(False, design_inputs.Noise())
    space = design.Space(design.angles_of(prior, 5.0), (0.244,), 5, ramp_samples=4, carriage_runs=3)
    d = design.plan(prior, space, "D")
    assert "f_int" in d.candidates.names and "f_int" not in d.designed
    assert Counter(r.kind for r in d.runs()) == {"carriage": 3, "slide": 5, "ramp": 1}
    # F_int from the carriage runs (1 % of 5 N each) and from every force and ramp sample
    assert d.candidates.sd(d.M)["f_int"] < 0.05 / math.sqrt(3)


def test_a_criterion_minimises_the_relative_variances(tmp_path):
    prior = design_inputs.paper_prior(False, design_inputs.Noise())
    space = design.Space(design.angles_of(prior, 1.0), (0.244,), 5)
    a, dopt = design.plan(prior, space, "A"), design.plan(prior, space, "D")

    def relative(d):
        return sum((s / prior.values[n]) ** 2 for n, s in d.sd(d.M).items())
    assert relative(a) <= relative(dopt) and a.equivalence.holds
    cli = run_design(tmp_path, "--runs", 5, "--no-strip", "--criterion", "A", "--out", "a")
    assert cli["criterion"] == "A" and cli["predicted_sd"] == pytest.approx(a.sd(a.M), rel=1e-9)


@pytest.mark.parametrize("args, says", [
    (["--runs", "0"], "--runs"),
    (["--runs", "5", "--sigma-force", "-0.01"], "--sigma-force"),
    (["--runs", "5", "--criterion", "E"], "--criterion"),
    (["--runs", "5", "--velocity-min", "0.6"], "--velocity-min 0.6, --velocity-max 0.5"),
    (["--runs", "5", "--velocity-max", "50"], "--velocity-max"),
    (["--runs", "5", "--fixed", "missing.csv"], "missing.csv"),
    (["--runs", "5", "--fixed", "bad.csv"], "bad.csv: line 2: kind"),
    (["--runs", "5", "--prior", "missing.json"], "missing.json"),
    (["--runs", "1", "--no-strip"], "--runs 1: expected enough slide runs"),
    # three numbers for five parameters: refused before the search (a small grid: no progress line)
    (["--runs", "1", "--ramp-samples", "1", "--angle-step", "45", "--velocity-step", "0.4"],
     "--runs 1: expected enough slide runs to determine mu1, mu2, eps_ratio, eps2, c_strip"),
    (["--runs", "5", "--angle-step", "0.001", "--velocity-step", "0.001"], "at most 50000 candidate"),
])
def test_bad_input_is_one_line_and_exit_2(tmp_path, args, says):
    (tmp_path / "bad.csv").write_text("kind,mat_angle_deg,velocity_m_s\nslid,30,0.244\n")
    p = run_cli(["design", *args, "--out", "o"], tmp_path)
    one_error_line(p, says)
    assert not (tmp_path / "o").exists()


def test_a_baseline_that_determines_not_every_parameter_has_no_efficiency(tmp_path):
    """Two runs with a strip: the paper's points (0 and 90 deg) tell nothing
    of eps_ratio; the plan is not 1e15 times better than them, it is the
    only one of the two that determines the parameters."""
    p = run_cli(["design", "--runs", "2", "--angle-step", "5", "--out", "o"], tmp_path)
    assert p.returncode == 0, p.stderr
    assert "baseline: its information is singular at this budget: no efficiency" in p.stdout
    assert json.loads((tmp_path / "o" / "design.json").read_text())["efficiency"] is None
