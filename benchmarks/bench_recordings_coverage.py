"""Benchmark (not a test): from raw recordings to intervals — do the 95 %
intervals of `identify` on a lab's raw recordings cover the truth 95 % of
the time?

Each replicate is a fresh set of synthetic recordings (tools/make_recordings.py:
the independent reference simulator tools/rig_reference.py for the physics,
then per run the tracker's and force sensor's noise, drift, rate and start
time, the mat's run-to-run variation), written to disk in the folder format,
read, validated, reduced and fitted exactly as `orthocontact identify` does.
Design: 7 mat angles x (6 runs at 0.244 m/s + 4 at 0.125 m/s), 5 carriage
runs, 3 ramp runs, as the bundled scenarios/example_recordings; truth the
aged mat with eps2 = 1e4 N/m, F_int = 5 N, c_strip = 10 N s/m.

Beside it, what the intervals would be without the between-run part of the
noise model (weights 1/se^2 of the within-run errors alone, as if every run
were as precise as its own line fit): their coverage of eps_ratio.

    .venv/bin/python benchmarks/bench_recordings_coverage.py [--replicates 200] [--small] [--seed 1000]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))

import make_recordings as mr  # noqa: E402

PARAMS = ("mu1", "mu2", "eps_ratio", "eps1", "eps2", "f_int", "c_strip")


def designs(small: bool):
    if small:
        return mr.Truth(c_strip=0.0), mr.Design(angles_deg=[0, 30, 60, 90], velocities={0.244: 5},
                                                carriage_runs=3, ramp_runs=2)
    return mr.Truth(), mr.Design()


def truth_values(t: mr.Truth) -> dict:
    return {"mu1": t.mu1, "mu2": t.mu2, "eps_ratio": t.eps_ratio, "eps1": t.eps1, "eps2": t.eps2,
            "f_int": t.f_int_N, "c_strip": t.c_strip}


def replicate(args):
    """(fit values, ci95, stderr, noise model) of one fresh set of recordings."""
    seed, small, paths, ramp = args
    from orthocontact.identification.estimators import joint_fit, start_values
    from orthocontact.identification.job import load_folder
    truth, design = designs(small)
    runs = mr.make_runs(truth, mr.Sensors(), design, np.random.default_rng(seed), paths, ramp)
    with tempfile.TemporaryDirectory() as d:
        mr.write_folder(Path(d), truth, runs)
        data, _ = load_folder(d)
    fit = joint_fit(data, start_values(data))
    out = {k: (fit.values[k], fit.ci95[k][0], fit.ci95[k][1], fit.stderr[k], fit.param_dof[k])
           for k in PARAMS if k in fit.values}
    # Without the between-run part the angles' noise would be the within-run
    # error alone; eps_ratio rests on the angles, so its stderr would shrink
    # by that ratio of noise levels (an approximation: the forces' share of
    # its information is left as is).
    naive = None
    if data.angle_se is not None:
        se_phi = float(np.sqrt(np.mean(data.angle_se ** 2)))
        tau = fit.between_runs.get("angles")
        tau = float(np.sqrt(np.mean(np.square(list(tau.values()))))) if isinstance(tau, dict) else tau
        naive = fit.stderr["eps_ratio"] * se_phi / math.hypot(tau, se_phi)
    return out, naive


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--replicates", type=int, default=200)
    ap.add_argument("--small", action="store_true", help="the test's design: 4 angles x 5 runs, one velocity")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--seed", type=int, default=1000, help="the first replicate's seed")
    ap.add_argument("--out", type=Path, default=None, help="write recordings_coverage.json here")
    args = ap.parse_args()
    t0 = time.time()
    truth, design = designs(args.small)
    paths = mr.steady_paths(truth, design.angles_deg, list(design.velocities), design.settle_m)
    ramp = mr.ramp_path(truth, design.ramp_travel_m)
    tv = truth_values(truth)
    n = args.replicates
    half = 1.96 * math.sqrt(0.95 * 0.05 / n)
    print(f"{n} replicates of raw recordings ({'small' if args.small else 'bundled'} design); a true 95 % "
          f"coverage lands in {95 - 100 * half:.1f}-{95 + 100 * half:.1f} % (binomial 95 %)", flush=True)
    with ProcessPoolExecutor(args.workers) as ex:
        res = list(ex.map(replicate, [(args.seed + i, args.small, paths, ramp) for i in range(n)],
                          chunksize=2))
    rows = {}
    for k in PARAMS:
        got = [r[0][k] for r in res if k in r[0]]
        if not got:
            continue
        v = np.array(got)
        cover = float(np.mean((v[:, 1] <= tv[k]) & (tv[k] <= v[:, 2])))
        sd = float(v[:, 0].std(ddof=1))
        bias, bias_se = v[:, 0].mean() / tv[k] - 1, sd / math.sqrt(len(v)) / abs(tv[k])
        rows[k] = {"coverage": cover, "truth": tv[k], "mean_estimate": float(v[:, 0].mean()),
                   "relative_bias": float(bias), "relative_bias_se": float(bias_se),
                   "sd_of_estimates": sd, "mean_stderr": float(v[:, 3].mean()),
                   "rms_stderr_over_sd": float(np.sqrt(np.mean(v[:, 3] ** 2)) / sd),
                   "median_dof": float(np.median(v[:, 4]))}
        print(f"{k:>9}: coverage {100 * cover:5.1f} %   truth {tv[k]:.6g}   mean {v[:, 0].mean():.6g} "
              f"({100 * bias:+.3f} +- {100 * bias_se:.3f} %)   sd {sd:.3g}   mean stderr {v[:, 3].mean():.3g}"
              f"   rms stderr / sd {rows[k]['rms_stderr_over_sd']:.2f}   median dof {np.median(v[:, 4]):.3g}",
              flush=True)
    naive = [r[1] for r in res if r[1] is not None]
    if naive:
        est = np.array([r[0]["eps_ratio"][0] for r in res if r[1] is not None])
        cov = float(np.mean(np.abs(est - tv["eps_ratio"]) <= 1.96 * np.array(naive)))
        rows["eps_ratio_within_run_errors_only"] = {"coverage": cov}
        print(f"eps_ratio with the within-run errors alone as its noise: coverage {100 * cov:.1f} %")
    print(f"{time.time() - t0:.0f} s")
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "recordings_coverage.json").write_text(json.dumps(
            {"replicates": n, "first_seed": args.seed, "design": "small" if args.small else "bundled",
             "results": rows, "seconds": round(time.time() - t0, 1)}, indent=2) + "\n")


if __name__ == "__main__":
    main()
