"""Regenerates scenarios/example_identification/: measurements made by the
FMU in the rig harness with known parameters, plus Gaussian noise of a fixed
seed.  Truth: mu1 = 0.408, mu2 = 0.625, eps1 = 12510 N/m, eps2 = 10000 N/m
(the paper's aged mat, with an assumed absolute stiffness).

    .venv/bin/python tools/make_example_data.py
"""
from pathlib import Path

import numpy as np

from orthocontact.experiment.rig_setup import RigSetup
from orthocontact.fmu.params import ContactParams
from orthocontact.identification.job import simulate_measurements
from orthocontact.identification.measurements import write_measurements

OUT = Path(__file__).resolve().parents[1] / "scenarios" / "example_identification"
TRUTH = ContactParams(0.408, 0.625, 12510.0, 10000.0)
NOISE = {"force_N": 0.05, "phi_deg": 0.3, "ramp_N": 0.02}


def main():
    rig = RigSetup(mass_kg=1.875, f_int_N=5.0, velocity_m_s=0.244)
    force_angles = [0, 15, 30, 45, 60, 75, 90]
    angle_angles = list(range(5, 90, 5))
    m = simulate_measurements(TRUTH, rig, force_angles, angle_angles, ramp_max_x1_m=2e-3)
    rng = np.random.default_rng(20071)
    forces = [(a, f + rng.normal(0, NOISE["force_N"])) for a, f in m["forces"] for _ in range(3)]
    angles = [(a, p + rng.normal(0, NOISE["phi_deg"])) for a, p in m["angles"] for _ in range(2)]
    ramp = [(x, f + rng.normal(0, NOISE["ramp_N"])) for x, f in m["ramp"][::8]]

    def r(rows, d):
        return [(round(float(a), 9), round(float(b), d)) for a, b in rows]
    write_measurements(OUT, rig, r(forces, 4), r(angles, 3), r(ramp, 4))
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
