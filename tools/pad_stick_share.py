#!/usr/bin/env python3
"""The pad's stick stiffness under lift-off on grids of 1 x 1 to 32 x 32
cells (docs/guides/contact-pad.md): dT1/du1 over eps1 at the guide's pose
(90 x 90 mm, kn = 1e8 N/m^3, d = 20 um, phi2 = 1 mrad: 72.2 % of the area
presses), against the share of the cells that press at all.

    PYTHONPATH=python python tools/pad_stick_share.py"""
from __future__ import annotations

import math

from orthocontact.closed_forms import pad as cpad
from orthocontact.fmu.pad import Foundation, PadFMU
from orthocontact.fmu.params import ContactParams
from orthocontact.fmu.patch import PatchGeometry

SIDE, KN, D, PHI2, EPS = 0.09, 1e8, 2e-5, 1e-3, 1e4


def main() -> None:
    law = ContactParams(0.5, 0.5, EPS, EPS, 0.0, 0.0)
    area = cpad.contact_fraction(SIDE, SIDE, D, 0.0, PHI2)
    print(f"pressed area {area:.4f}")
    print("cells   dT1/du1 / eps1   share of cells pressing")
    for n in (1, 2, 3, 4, 5, 8, 16, 32):
        with PadFMU(None, "stick-share", 2) as f:
            f.initialize(law, PatchGeometry(SIDE, SIDE, n, n), Foundation(KN), (0, 0, 0, D, 0, PHI2))
            f.set_inputs(1e-9, 0, 0, D, 0, PHI2)
            stiffness = -f.jacobian(("u1",), ("T1",))[0][0] / EPS
        # a column of cells presses if its leading (+x) side is past the line x0 = -D/PHI2
        x0 = -D / PHI2
        pressing = sum(1 for i in range(n) if -SIDE / 2 + (i + 1) * SIDE / n > x0) / n
        print(f"{n:2d} x {n:<2d}  {stiffness:16.4f}   {pressing:.4f}")
        assert math.isclose(stiffness, pressing, rel_tol=1e-12)


if __name__ == "__main__":
    main()
