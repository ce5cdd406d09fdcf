"""Writes the contact patch guide's figures (docs/guides/contact-patch.md)
from the bundled scenarios, through the command a user runs:

    docs/figures/patch_twist.png         torque against angle (scenarios/twist.toml)
    docs/figures/patch_twist_cells.png   the cells in stick and slip during that twist
    docs/figures/patch_yaw_vs_angle.png  the towed block's steady yaw (scenarios/towed_block.toml)

Usage: python tools/make_patch_figures.py   (after `make setup`; a few seconds)
"""
from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "figures"
# (scenario, figure the run writes, the guide's copy)
FIGURES = (("twist", "twist.png", "patch_twist.png"),
           ("twist", "twist_cells.png", "patch_twist_cells.png"),
           ("towed_block", "yaw_vs_angle.png", "patch_yaw_vs_angle.png"))


def main() -> int:
    OUT.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for scenario in dict.fromkeys(s for s, _, _ in FIGURES):
            out = Path(tmp) / scenario
            p = subprocess.run([sys.executable, "-m", "orthocontact", "run",
                                str(ROOT / "scenarios" / f"{scenario}.toml"), "--out", str(out)],
                               capture_output=True, text=True)
            if p.returncode != 0:
                print(p.stderr, file=sys.stderr)
                return p.returncode
        for scenario, written, copy in FIGURES:
            shutil.copy(Path(tmp) / scenario / written, OUT / copy)
            print(f"wrote {(OUT / copy).relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
