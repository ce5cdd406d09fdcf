"""Writes the experiment-design guide's figure (docs/guides/experiment-design.md)
through the command a user runs:

    docs/figures/design_aged_5.png   the sensitivity function of the D-optimal 5 slide runs
                                     on the paper's aged mat without a strip
                                     (orthocontact design --runs 5 --sigma-force 0.01
                                      --sigma-angle 1.0 --no-strip)

Usage: python tools/make_design_figure.py   (after `make setup`; about 2 s)
"""
from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "figures" / "design_aged_5.png"
COMMAND = ["design", "--runs", "5", "--sigma-force", "0.01", "--sigma-angle", "1.0", "--no-strip"]


def main() -> int:
    OUT.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        p = subprocess.run([sys.executable, "-m", "orthocontact", *COMMAND, "--out", str(Path(tmp) / "D")],
                           capture_output=True, text=True)
        if p.returncode != 0:
            print(p.stderr, file=sys.stderr)
            return p.returncode
        shutil.copy(Path(tmp) / "D" / "design.png", OUT)
    print(f"wrote {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
