"""Benchmark (not a test): rig runs per second of the compiled master and of
the fmpy master, one process each, on the aged mat's dynamic rig (0.5 m at
0.244 m/s, 0.2 ms steps: 10,246 steps a run) and on Case 5's quasi-static rig.
Target: the C master >= 20x the fmpy one.

    .venv/bin/python benchmarks/bench_masters.py [--runs N]
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

from orthocontact.experiment.scenario import load
from orthocontact.fmu.contact import ContactFMU
from orthocontact.fmu.files import find_fmu
from orthocontact.rig.compiled import CMaster
from orthocontact.rig.harness import run

SCEN = Path(__file__).resolve().parents[1] / "scenarios"


def rate(fn, n):
    best = 0.0
    for _ in range(3):  # the least disturbed of three
        t0 = time.perf_counter()
        fn(n)
        best = max(best, n / (time.perf_counter() - t0))
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=4, help="fmpy runs per timing (C: 10x as many)")
    args = ap.parse_args()
    cm = CMaster(find_fmu())
    f = ContactFMU(instance_name="bench")
    print(f"{'scenario':10s} {'steps/run':>9s} {'fmpy runs/s':>12s} {'C runs/s':>10s} {'C / fmpy':>9s}")
    for name in ("mat_aged", "case5"):
        sc = load(SCEN / f"{name}.toml")
        tasks = [(sc.params_at(a), sc.rig) for a in (10.0, 39.2, 70.0)]
        steps = int(sc.rig.travel_m / (sc.rig.velocity_m_s * sc.rig.step_s) + 0.5)

        def fmpy_runs(n, tasks=tasks):   # this scenario's, bound now
            for i in range(n):
                p, r = tasks[i % len(tasks)]
                run(p, r, fmu=f, record_every=1 << 30)

        def c_runs(n, tasks=tasks):
            cm.run([tasks[i % len(tasks)] for i in range(n)])
        a, b = rate(fmpy_runs, args.runs), rate(c_runs, 10 * args.runs)
        print(f"{name:10s} {steps:9d} {a:12.2f} {b:10.1f} {b / a:9.1f}x   (target >= 20x)")


if __name__ == "__main__":
    main()
