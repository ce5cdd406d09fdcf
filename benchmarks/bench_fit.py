"""The joint fit (casadi/IPOPT, reweighted until its noise model settles)
against scipy.optimize.least_squares (Levenberg-Marquardt on
log-parameters, x_scale='jac') on the same reduced data, interleaved, in
one process.  The peer is a plain weighted least squares with the weights
our fit ends with, its model written here from closed_forms' numpy
functions (not our casadi model): the peer must be straightforward code.
Target: ours <= 2x the peer's time, the same estimates (within 1e-3 of
their standard errors).  Figures only.

The data: noise-free raw recordings at 17 mat angles (5-85 deg) x 2
velocities with the strip's viscosity, made by tools/make_recordings.py
(the independent reference simulator) and reduced by orthocontact's
reduction; and the bundled example_recordings.

    .venv/bin/python benchmarks/bench_fit.py [--repeats 5]
"""
from __future__ import annotations

import argparse
import math
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
import make_recordings as mr  # noqa: E402
from orthocontact import closed_forms as cf  # noqa: E402
from orthocontact.identification import estimators, job  # noqa: E402


def noise_free_set(folder: Path) -> Path:
    quiet = mr.Sensors(tracker_noise_m=0, tracker_drift_m_s=0, force_noise_N=0, force_tare_N=0,
                       force_drift_N_s=0, friction_scatter=0)
    design = mr.Design(angles_deg=list(range(5, 90, 5)), velocities={0.244: 1, 0.125: 1}, carriage_runs=2,
                       ramp_runs=1)
    mr.write_folder(folder, mr.Truth(), mr.make_runs(mr.Truth(), quiet, design, np.random.default_rng(3)))
    return folder


def steady_state(p, rig, angles_deg, c_times_v):
    """(tan phi, push [N]) of steady sliding with the strip's viscosity alone
    (mu_strip = 0: the data here), by Newton on the lateral force from the
    law's angle without the strip."""
    if rig.mu_strip:
        raise SystemExit("bench_fit: the peer handles mu_strip = 0 only")
    al, be = rig.axes(np.asarray(angles_deg, float))
    h = cf.slip_force_tensor(p["mu1"], p["mu2"], p["eps_ratio"], 1.0, al, be, rig.rule)
    f = cf.friction_entries(p["mu1"], p["mu2"], be)
    t = cf.steady_tan_phi(p["mu1"], p["mu2"], p["eps_ratio"], 1.0, al, be, rig.rule)
    for _ in range(50):
        F2 = cf.strip_lateral_force(h, f, t, 0.0, 0.0, c_times_v, rig.normal_force)[0]
        slope = (cf.strip_lateral_force(h, f, t + 1e-7, 0.0, 0.0, c_times_v, rig.normal_force)[0] - F2) / 1e-7
        step = F2 / slope
        t = t - step
        if np.max(np.abs(step)) < 1e-15:
            break
    return t, cf.strip_lateral_force(h, f, t, 0.0, 0.0, c_times_v, rig.normal_force)[1]


def peer_residuals(data, names):
    """r(theta) = data - model of the forces, carriage, angles and
    stiffness, from closed_forms' numpy functions."""
    rig = data.rig
    fa, fv = data.forces[:, 0], data.velocities_of_forces()
    aa, av = data.angles[:, 0], data.velocities_of_angles()

    def residuals(log_theta):
        p = dict(zip(names, np.exp(log_theta)))
        c = p.get("c_strip", rig.c_strip or 0.0)
        f_int = p.get("f_int", rig.f_int_N)
        out = []
        for angles, vel, col in ((fa, fv, 1), (aa, av, 0)):
            model = np.empty(len(angles))
            for v in np.unique(vel):
                m = vel == v
                tan_phi, push = steady_state(p, rig, angles[m], c * v)
                model[m] = f_int + push if col == 1 else np.degrees(np.arctan(tan_phi))
            out.append((data.forces[:, 1] if col == 1 else data.angles[:, 1]) - model)
        if data.carriage is not None:
            out.append(data.carriage[:, 0] - f_int)
        if data.stiffness is not None:
            out.append(data.stiffness[:, 1] - np.array(
                [cf.stick_stiffness_x1(p["eps_ratio"] * p["eps2"], p["eps2"], rig.axes(a)[0])
                 for a in data.stiffness[:, 0]]))
        return np.concatenate(out)
    return residuals


def peer_fit(data, fit, start):
    """scipy's LM with our fit's final weights, from our start values."""
    from scipy.optimize import least_squares
    names = list(fit.free)
    order = ["forces", "angles", "carriage", "stiffness"]
    sd = np.concatenate([fit.weights[g] ** -0.5 for g in order if g in fit.residuals])
    r = peer_residuals(data, names)
    # log-parameters need a start above 0: c_strip starts at 0 (no strip) in ours, at 1 N s/m here
    x0 = np.log([max(start[n], 1.0 if n == "c_strip" else 1e-9) for n in names])
    sol = least_squares(lambda x: r(x) / sd, x0, method="lm", x_scale="jac", xtol=1e-15, ftol=1e-15,
                        gtol=1e-15)
    return dict(zip(names, np.exp(sol.x)))


def bench(folder: Path, repeats: int):
    data, _ = job.load_folder(folder)
    start = estimators.start_values(data)
    ours, peers = [], []
    for _ in range(repeats):     # interleaved: the machine's state is shared by both
        t = time.perf_counter()
        fit = estimators.joint_fit(data, start)
        ours.append(time.perf_counter() - t)
        t = time.perf_counter()
        peer = peer_fit(data, fit, start)
        peers.append(time.perf_counter() - t)
    gap = max(abs(fit.values[n] - peer[n]) / fit.stderr[n] for n in peer)
    o, p = statistics.median(ours), statistics.median(peers)
    print(f"{folder.name}: ours {o:.3f} s ({len(fit.solves)} solves, converged {fit.converged}), "
          f"scipy least_squares {p:.3f} s: {o / p:.2f}x the peer's time (target <= 2x); "
          f"estimates apart by {gap:.1e} standard errors at most")
    if not math.isfinite(gap):
        print("  (a standard error of 0: compare by hand)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        bench(noise_free_set(Path(tmp) / "noise_free_17_angles_strip"), args.repeats)
    bench(ROOT / "scenarios" / "example_recordings", args.repeats)


if __name__ == "__main__":
    main()
