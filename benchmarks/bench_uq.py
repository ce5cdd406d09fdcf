"""Benchmark (not a test): 10^6 rig runs of uncertainty propagation, through
the command a user runs: `orthocontact uq` on the example identification and
the aged mat (91 angles), on the default Dask LocalCluster (one worker per
core).  Target: <= 30 s on this 2-core machine.

    .venv/bin/python benchmarks/bench_uq.py [--runs 1000000] [--scheduler local]
"""
from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CMD = [sys.executable, "-m", "orthocontact"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=1_000_000)
    ap.add_argument("--scheduler", default="local")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        subprocess.run(CMD + ["identify", str(ROOT / "scenarios/example_identification"), "--out",
                              str(tmp / "id"), "--no-validate"], check=True, capture_output=True)
        angles = 91
        samples = math.ceil(args.runs / angles)
        t0 = time.perf_counter()
        p = subprocess.run(CMD + ["uq", str(tmp / "id/identified.json"), "--scenario",
                                  str(ROOT / "scenarios/mat_aged.toml"), "--samples", str(samples),
                                  "--out", str(tmp / "uq"), "--scheduler", args.scheduler],
                           capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if p.returncode != 0:
            sys.exit(p.stderr)
        d = json.loads((tmp / "uq/uq.json").read_text())
    print(f"uq: {d['runs']:,} rig runs ({d['samples']:,} sets x {angles} angles, step "
          f"{d['step_s']:g} s) on {d['engine']}")
    print(f"    {wall:.1f} s wall including start-up ({d['runs'] / wall:,.0f} runs/s); "
          f"target <= 30 s")
    print(f"    step check at the estimates: |phi(uq step) - phi(scenario step)| <= "
          f"{d['step_check']['max_abs_difference_deg']:.1e} deg")


if __name__ == "__main__":
    main()
