"""Writes the contact patch's and the contact pad's guides' figures
(docs/guides/contact-patch.md, contact-pad.md) from the bundled scenarios,
through the command a user runs:

    docs/figures/patch_twist.png         torque against angle (scenarios/twist.toml)
    docs/figures/patch_twist_cells.png   the cells in stick and slip during that twist
    docs/figures/patch_yaw_vs_angle.png  the towed block's steady yaw (scenarios/towed_block.toml)
    docs/figures/pad_pressure_cells.png  the pressure under the pushed block (scenarios/pushed_block.toml)
    docs/figures/pad_regimes.png         its full contact, lift-off and tipping against mu h / length
    docs/figures/pad_phi_vs_angle.png    its trajectory angle at every height

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
           ("towed_block", "yaw_vs_angle.png", "patch_yaw_vs_angle.png"),
           ("pushed_block", "pressure_cells.png", "pad_pressure_cells.png"),
           ("pushed_block", "regimes.png", "pad_regimes.png"),
           ("pushed_block", "phi_vs_angle.png", "pad_phi_vs_angle.png"))


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
