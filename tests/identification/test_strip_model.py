"""The Teflon strip in the fit (orthocontact.identification.strip_model): its
viscosity estimated from two velocities, a known strip taken as an input, the
regimes of motion the model is built for."""
import json
from pathlib import Path

import numpy as np
import pytest

from orthocontact import closed_forms as cf
from orthocontact.cli.main import main
from orthocontact.experiment.rig_setup import RigSetup
from orthocontact.fmu.params import ContactParams
from orthocontact.identification.estimators import joint_fit, start_values
from orthocontact.identification.measurements import MeasurementSet, write_measurements
from orthocontact.identification.strip_model import strip_regimes

TRUTH = ContactParams(0.408, 0.625, 12510.0, 10000.0)
TV = {"mu1": 0.408, "mu2": 0.625, "eps_ratio": 1.251, "eps2": 1e4, "eps1": 12510.0}
FA, AA = [0, 15, 30, 45, 60, 75, 90], list(range(5, 90, 5))


def _strip_data(mu_strip, c_strip, velocities):
    """Noise-free forces (at the rig's velocity) and angles (at each velocity)
    from the quasi-static rig with a strip (the compiled master: lateral
    equilibrium solved by Newton on the FMU, not by the fit's closed form)."""
    from orthocontact.fmu.files import find_fmu
    from orthocontact.rig.compiled import CMaster
    rig = RigSetup(mass_kg=1.875, f_int_N=5.0, mu_strip=mu_strip)
    tasks, meta = [], []
    for v in velocities:
        h = rig.harness(mode="quasistatic", step_s=1e-3, travel_m=0.2, velocity_m_s=v, c_strip=c_strip)
        tasks += [(rig.params_at(TRUTH, a), h) for a in AA]
        meta += [("angle", a, v) for a in AA]
    h = rig.harness(mode="quasistatic", step_s=1e-3, travel_m=0.2, c_strip=c_strip)
    tasks += [(rig.params_at(TRUTH, a), h) for a in FA]
    meta += [("force", a, rig.velocity_m_s) for a in FA]
    cm = CMaster(find_fmu())
    try:
        res = cm.run(tasks)
    finally:
        cm.close()
    angles = np.array([[a, r[0]] for (k, a, _), r in zip(meta, res) if k == "angle"])
    vel = np.array([v for k, _, v in meta if k == "angle"])
    forces = np.array([[a, r[1]] for (k, a, _), r in zip(meta, res) if k == "force"])
    return rig, forces, angles, vel


def test_strip_viscosity_estimated_from_two_velocities_through_the_cli(tmp_path, capsys):
    rig, forces, angles, vel = _strip_data(0.05, 20.0, (0.125, 0.244))
    write_measurements(tmp_path / "data", rig, forces=forces, angles=angles, angle_velocities=vel)
    assert main(["identify", str(tmp_path / "data"), "--out", str(tmp_path / "out"), "--no-validate"]) == 0
    j = json.loads((tmp_path / "out" / "identified.json").read_text())
    assert j["c_strip"]["value"] == pytest.approx(20.0, rel=1e-5)
    for k in ("mu1", "mu2", "eps_ratio"):
        assert j[k]["value"] == pytest.approx(TV[k], rel=1e-6), k
    assert j["assumptions"]["mu_strip"] == 0.05 and j["assumptions"]["c_strip_N_s_m"] == "estimated"
    # people see it too: the terminal summary and identified.md
    assert "  c_strip = 20" in capsys.readouterr().out
    assert "| c_strip | N s/m | 20" in (tmp_path / "out" / "identified.md").read_text()


def test_known_strip_is_an_input_and_one_velocity_cannot_give_the_viscosity():
    rig, forces, angles, vel = _strip_data(0.05, 20.0, (0.244,))
    from dataclasses import replace
    known = MeasurementSet(Path("k"), replace(rig, c_strip=20.0), forces, angles, None, vel)
    fit = joint_fit(known, start_values(known))
    assert "c_strip" not in fit.values
    for k in ("mu1", "mu2", "eps_ratio"):
        assert fit.values[k] == pytest.approx(TV[k], rel=1e-6), k
    unknown = MeasurementSet(Path("u"), rig, forces, angles, None, vel)
    fit = joint_fit(unknown, start_values(unknown))
    assert "c_strip" in fit.not_identifiable and "two or more velocities" in fit.not_identifiable["c_strip"]


def test_the_strips_regimes_against_the_law_without_it():
    angles = np.array([[a, 0.0] for a in (10.0, 30.0, 50.0, 70.0, 85.0)])
    values = {"mu1": 0.408, "mu2": 0.625, "eps_ratio": 1.251}

    def regimes(mu_strip):
        rig = RigSetup(mass_kg=1.875, f_int_N=5.0, mu_strip=mu_strip)
        return strip_regimes(MeasurementSet(Path("s"), rig, None, angles, None), values)
    assert regimes(0.0) == ()                        # no strip: nothing to choose
    assert regimes(10.0) == (0,) * 5                 # friction above mu2 N holds the block
    rig = RigSetup(mass_kg=1.875, f_int_N=5.0)
    free = [cf.steady_tan_phi(0.408, 0.625, 1.251e4, 1e4, *rig.axes(a), rig.rule) for a, _ in angles]
    assert all(abs(t) > 1e-3 for t in free)
    assert regimes(1e-9) == tuple(1 if t > 0 else -1 for t in free)   # a negligible strip: the law's way
