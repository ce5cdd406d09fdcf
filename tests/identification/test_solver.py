"""The joint fit's own verdict on itself (orthocontact.identification.solver
and its use): every solve's status recorded, a fit that did not converge
refused by identify (unless --force) and by export, and a law that does not
describe the recordings (lack of fit) refused by export, naming the group
and the likely cause."""
import json

import numpy as np

from cli_run import one_error_line, run_cli
from orthocontact import closed_forms as cf
from orthocontact.cli.main import main
from orthocontact.experiment.rig_setup import RigSetup
from orthocontact.identification import solver
from orthocontact.identification.measurements import write_measurements
from paths import SCENARIOS


def test_the_bundled_recordings_converge_and_the_law_describes_them(tmp_path):
    assert main(["identify", str(SCENARIOS / "example_recordings"), "--out", str(tmp_path / "id"),
                 "--no-validate"]) == 0
    fit = json.loads((tmp_path / "id" / "identified.json").read_text())["fit"]
    assert fit["converged"] is True and not fit["forced"]
    assert fit["convergence"] == {"solver": True, "noise_model": True, "strip_regimes": True,
                                  "strip_roots": True}
    last = fit["solves"][-1]
    assert last["status"] in solver.ACCEPTED and last["step_left_se"] < solver.STEP_TOLERANCE_SE
    assert len(fit["solves"]) == fit["reweighting_rounds"] < 10
    assert set(fit["lack_of_fit"]) == {"forces", "angles"}
    assert not any(t["rejected"] for t in fit["lack_of_fit"].values())


def test_a_fit_that_did_not_converge_is_refused_unless_forced_and_never_exported(tmp_path, monkeypatch,
                                                                                 capsys):
    """IPOPT given one iteration stops at Maximum_Iterations_Exceeded: identify
    refuses in one line, writes nothing; with --force it writes the fit marked
    not converged, and export refuses it (with --force, says so in the FMUs)."""
    data = SCENARIOS / "example_recordings"
    monkeypatch.setitem(solver.IPOPT_OPTIONS, "ipopt.max_iter", 1)
    assert main(["identify", str(data), "--out", str(tmp_path / "refused"), "--no-validate"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "the joint fit did not converge" in err[0], err
    assert "Maximum_Iterations_Exceeded" in err[0] and "--force" in err[0]
    assert not (tmp_path / "refused").exists()
    assert main(["identify", str(data), "--out", str(tmp_path / "id"), "--no-validate", "--force"]) == 0
    identified = tmp_path / "id" / "identified.json"
    fit = json.loads(identified.read_text())["fit"]
    assert fit["converged"] is False and fit["forced"] is True
    assert fit["solves"][-1]["status"] == "Maximum_Iterations_Exceeded"
    p = run_cli(["export", identified, "--out", tmp_path / "export"], tmp_path, timeout=300)
    one_error_line(p, "the joint fit did not converge", "refused (`orthocontact export --force`")
    assert not (tmp_path / "export").exists()


def _forces_with_a_wrong_f_int(folder, f_int_in_toml):
    """Reduced data of the aged mat, three runs at each of seven mat angles
    (forces with 0.05 N of scatter, angles with 0.2 deg), F_int = 5 N in
    truth, rig.toml saying f_int_in_toml."""
    rig = RigSetup(mass_kg=1.875, f_int_N=f_int_in_toml)
    rng = np.random.default_rng(11)
    grid = [a for a in (0, 15, 30, 45, 60, 75, 90) for _ in range(3)]
    forces = [(a, 5.0 + cf.steady_drive_force(0.408, 0.625, rig.axes(a)[1], 0.0, 1.875, rig.g)
               + rng.normal(0, 0.05)) for a in grid]
    angles = [(a, cf.steady_phi_deg(0.408, 0.625, 1.251, 1.0, *rig.axes(a), rig.rule) + rng.normal(0, 0.2))
              for a in grid if 0 < a < 90]
    write_measurements(folder, rig, forces=np.array(forces), angles=np.array(angles))
    return folder


def test_forces_the_law_cannot_describe_are_refused_by_export_naming_the_group(tmp_path):
    """F_int typed in kN in rig.toml (0.005): every mu is plausible, but the
    forces follow no friction ellipse; identify warns, export refuses."""
    data = _forces_with_a_wrong_f_int(tmp_path / "data", 0.005)
    p = run_cli(["identify", data, "--out", tmp_path / "id", "--no-validate"], tmp_path, timeout=300)
    assert p.returncode == 0, p.stderr
    assert "forces: the fitted law does not describe the recordings (lack of fit" in p.stderr
    fit = json.loads((tmp_path / "id" / "identified.json").read_text())["fit"]
    assert fit["converged"] and fit["lack_of_fit"]["forces"]["rejected"]
    p = run_cli(["export", tmp_path / "id" / "identified.json", "--out", tmp_path / "export"], tmp_path,
                timeout=300)
    one_error_line(p, "forces: the fitted law does not describe the recordings",
                   "likely cause: the driving forces do not follow the friction ellipse",
                   "refused (`orthocontact export --force`")
    assert not (tmp_path / "export").exists()
    # the same data with rig.toml's F_int right: no lack of fit, exported
    data = _forces_with_a_wrong_f_int(tmp_path / "right", 5.0)
    assert run_cli(["identify", data, "--out", tmp_path / "id2", "--no-validate"], tmp_path).returncode == 0
    fit = json.loads((tmp_path / "id2" / "identified.json").read_text())["fit"]
    assert not fit["lack_of_fit"]["forces"]["rejected"]


def test_a_viscosity_the_data_do_not_show_is_held_at_its_bound_and_said():
    """Angles at two velocities of a rig with no strip viscosity (c = 0 in
    truth, 0.2 deg of scatter; with this seed the data ask for a viscosity
    below 0): the fit converges with c_strip held at its lower bound (the
    interior-point solver stops just short of it; the Gauss-Newton step
    left is the other parameters'), and says so."""
    from pathlib import Path

    from orthocontact.identification.estimators import joint_fit, start_values
    from orthocontact.identification.measurements import MeasurementSet
    rig = RigSetup(mass_kg=1.875, f_int_N=5.0)
    rng = np.random.default_rng(0)
    grid = [(a, v) for a in (15, 30, 45, 60, 75) for v in (0.125, 0.244) for _ in range(3)]
    angles = np.array([(a, cf.steady_phi_deg(0.408, 0.625, 1.251, 1.0, *rig.axes(a), rig.rule)
                        + rng.normal(0, 0.2)) for a, _ in grid])
    forces = np.array([(a, 5.0 + cf.steady_drive_force(0.408, 0.625, rig.axes(a)[1], 0.0, 1.875, rig.g)
                        + rng.normal(0, 0.05)) for a in (0, 45, 90) for _ in range(3)])
    data = MeasurementSet(Path("held"), rig, forces, angles, None, np.array([v for _, v in grid]))
    fit = joint_fit(data, start_values(data))
    assert "c_strip" in fit.free and fit.converged, fit.solves[-1]
    assert fit.solves[-1]["at_bound"] == ["c_strip"] and fit.values["c_strip"] < 1e-3
