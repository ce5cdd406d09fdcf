"""Benchmark (not a test): do the identification's nominal 95 % intervals
cover the truth 95 % of the time?

Data are made by an independent simulator of the rig (tools/rig_reference.py:
the law from its definition in plain Python, no code of the package), once per
truth and noise-free; each replicate adds fresh normal noise (forces 0.05 N,
angles 0.3 deg, ramp 0.02 N) and runs the joint fit.  Three truths: the aged
mat, one with eps1 < eps2 (mu 0.30 / 0.55, eps1/eps2 0.8, eps2 3e4 N/m), and one near
isotropy.  Target: coverage within 92-98 % for every parameter and truth.

    .venv/bin/python benchmarks/bench_coverage.py [--replicates 400] [--out docs]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))

import rig_reference as ref  # noqa: E402
from orthocontact.experiment.rig_setup import RigSetup  # noqa: E402
from orthocontact.identification.estimators import joint_fit, start_values  # noqa: E402
from orthocontact.identification.measurements import MeasurementSet  # noqa: E402

TRUTHS = {
    "aged mat": dict(mu1=0.408, mu2=0.625, eps_ratio=1.251, eps2=1.0e4),
    "eps1/eps2 = 0.8": dict(mu1=0.30, mu2=0.55, eps_ratio=0.8, eps2=3.0e4),
    "near isotropy": dict(mu1=0.40, mu2=0.60, eps_ratio=1.45, eps2=2.0e4),  # isotropic: 1.5
}
NOISE = {"forces": 0.05, "angles": 0.3, "ramp": 0.02}
FA = [0, 15, 30, 45, 60, 75, 90]
AA = list(range(5, 90, 5))
RIG = RigSetup(mass_kg=1.875, f_int_N=5.0)
PARAMS = ("mu1", "mu2", "eps_ratio", "eps1", "eps2")


def noise_free(t: dict) -> dict:
    N = RIG.mass_kg * RIG.g
    eps1 = t["eps_ratio"] * t["eps2"]
    al, be = math.radians(RIG.alpha_offset_deg), math.radians(RIG.beta_offset_deg)
    m = ref.measure(t["mu1"], t["mu2"], eps1, t["eps2"], RIG.rule, al, be, sorted(set(FA) | set(AA)),
                    N, RIG.f_int_N)
    r = ref.ramp(t["mu1"], t["mu2"], eps1, t["eps2"], RIG.rule, al, be, RIG.ramp_angle_deg, N,
                 RIG.f_int_N, 2e-3)
    return {"forces": np.array([[a, m[a][1]] for a in FA * 3]),
            "angles": np.array([[a, m[a][0]] for a in AA * 2]),
            "ramp": np.array(r)[::8]}


def one(args):
    data, seed = args
    rng = np.random.default_rng(seed)
    noisy = {g: v + np.c_[np.zeros(len(v)), rng.normal(0, NOISE[g], len(v))] for g, v in data.items()}
    ms = MeasurementSet(Path("coverage"), RIG, noisy["forces"], noisy["angles"], noisy["ramp"])
    fit = joint_fit(ms, start_values(ms))
    return {k: (fit.values[k], fit.stderr[k], fit.ci95[k][0], fit.ci95[k][1]) for k in PARAMS}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--replicates", type=int, default=400)
    ap.add_argument("--out", type=Path, default=ROOT / "docs")
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--replot", action="store_true",
                    help="only redraw coverage.png from the coverage.json in --out")
    args = ap.parse_args()
    if args.replot:
        summary = json.loads((args.out / "coverage.json").read_text())
        n = summary["replicates"]
        _figure(summary["results"], n, 1.96 * math.sqrt(0.95 * 0.05 / n), args.out / "coverage.png")
        return
    t0 = time.time()
    results = {}
    n = args.replicates
    half = 1.96 * math.sqrt(0.95 * 0.05 / n)
    print(f"{n} replicates per truth; a true 95 % coverage lands in {95 - 100 * half:.1f}-"
          f"{95 + 100 * half:.1f} % (binomial 95 %); target 92-98 %")
    with ProcessPoolExecutor(args.workers) as ex:
        for j, (name, t) in enumerate(TRUTHS.items()):
            truth = dict(t, eps1=t["eps_ratio"] * t["eps2"])
            data = noise_free(t)
            # fresh noise for every replicate of every truth
            fits = list(ex.map(one, [(data, (j, i)) for i in range(n)], chunksize=8))
            row = {}
            for k in PARAMS:
                v = np.array([f[k] for f in fits])
                cover = float(np.mean((v[:, 2] <= truth[k]) & (truth[k] <= v[:, 3])))
                row[k] = {"coverage": cover, "mean_stderr": float(v[:, 1].mean()),
                          "sd_of_estimates": float(v[:, 0].std(ddof=1)),
                          "bias_in_sd": float((v[:, 0].mean() - truth[k]) / v[:, 0].std(ddof=1))}
            results[name] = {"truth": truth, "parameters": row}
            print(f"{name:14s} " + "  ".join(f"{k} {100 * row[k]['coverage']:5.1f}% "
                                            f"(se/sd {row[k]['mean_stderr'] / row[k]['sd_of_estimates']:.2f})"
                                            for k in PARAMS), flush=True)
    args.out.mkdir(parents=True, exist_ok=True)
    summary = {"replicates": n, "noise": NOISE, "design": {"forces_deg": FA, "force_repeats": 3,
                                                          "angles_deg": AA, "angle_repeats": 2,
                                                          "ramp": "0-2 mm, every 8th of 400 steps"},
               "simulator": "tools/rig_reference.py (independent of the package)",
               "results": results, "seconds": round(time.time() - t0, 1)}
    (args.out / "coverage.json").write_text(json.dumps(summary, indent=2) + "\n")
    _figure(results, n, half, args.out / "coverage.png")
    print(f"wrote {args.out / 'coverage.json'}, {args.out / 'coverage.png'} ({time.time() - t0:.0f} s)")


def _figure(results, n, half, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 4.2))
    w = 0.25
    for i, (name, r) in enumerate(results.items()):
        cov = [100 * r["parameters"][k]["coverage"] for k in PARAMS]
        ax.bar(np.arange(len(PARAMS)) + (i - 1) * w, cov, w, label=name, color=f"C{i}")
    ax.axhspan(92, 98, color="C2", alpha=0.12, label="target 92-98 %")
    ax.axhline(95, color="0.3", lw=1, ls="--", label="nominal 95 %")
    ax.set_xticks(np.arange(len(PARAMS)), ["μ1", "μ2", "ε1/ε2", "ε1", "ε2"])
    ax.set_ylim(80, 100)
    ax.set_ylabel("coverage of the 95 % intervals [%]")
    ax.set_title(f"Identification intervals on independent data: {n} replicates per truth",
                 fontsize=10)
    ax.legend(fontsize=8, loc="lower right")
    ax.grid(alpha=0.3, axis="y")
    fig.subplots_adjust(left=0.09, right=0.98, bottom=0.1, top=0.92)
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    main()
