"""Benchmark (not a test): the wall time of `orthocontact reproduce` (the
README's main command after setup: every bundled scenario, their figures, the
report), three times, with the scenarios and figures it wrote counted.
Target: <= 5 s on this 2-core machine.

    .venv/bin/python benchmarks/bench_reproduce.py [--repeat 3]
"""
from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CMD = [sys.executable, "-m", "orthocontact"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    times, written = [], ""
    for _ in range(args.repeat):
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            p = subprocess.run(CMD + ["reproduce", "--out", str(Path(tmp) / "results")],
                               capture_output=True, text=True)
            times.append(time.perf_counter() - t0)
            if p.returncode != 0:
                sys.exit(p.stderr[-2000:])
            out = Path(tmp) / "results"
            written = (f"{sum(1 for d in out.iterdir() if d.is_dir())} scenarios, "
                       f"{len(list(out.rglob('*.png')))} figures")
    print(f"reproduce ({written}): {' / '.join(f'{t:.2f}' for t in times)} s wall (best {min(times):.2f} s, "
          f"interpreter start included); target <= 5 s")


if __name__ == "__main__":
    main()
