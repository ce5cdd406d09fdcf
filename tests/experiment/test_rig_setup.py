"""A lab's rig.toml (orthocontact.experiment.rig_setup): read, checked key by
key, and the same law as a scenario with the same geometry."""
from cli_run import MAT_SWEEP
from orthocontact.experiment.rig_setup import load_rig_toml
from orthocontact.experiment.scenario import load


def test_a_scenario_and_a_rig_toml_with_the_same_geometry_give_the_same_law(tmp_path):
    (tmp_path / "s.toml").write_text(MAT_SWEEP + "[geometry]\nalpha_offset_deg = 90.0\n")
    (tmp_path / "rig.toml").write_text("mass_kg = 1.875\nalpha_offset_deg = 90.0\n")
    sc, rig = load(tmp_path / "s.toml"), load_rig_toml(tmp_path / "rig.toml")
    for a in (0.0, 12.5, 39.2, 90.0):
        assert sc.params_at(a) == rig.params_at(sc.law, a)


def test_rig_toml_has_one_writer_whose_file_reads_back_as_the_rig(tmp_path):
    """write_rig_toml writes every key load_rig_toml reads: a rig with each
    key off its default reads back equal (the strip's viscosity None: left
    out, estimated)."""
    import dataclasses

    from orthocontact.experiment.rig_setup import RigSetup, write_rig_toml
    rig = RigSetup(mass_kg=2.5, g=9.81, f_int_N=4.5, velocity_m_s=0.125, rule="eq20", alpha_offset_deg=80.0,
                   beta_offset_deg=-10.0, phi_convention="paper", ramp_angle_deg=30.0, mode="dynamic",
                   travel_m=0.4, step_s=1e-4, eps2_nominal_N_m=2e4, mu_strip=0.05, c_strip=12.5)
    for r in (rig, dataclasses.replace(rig, c_strip=None)):
        write_rig_toml(tmp_path / "rig.toml", r)
        assert load_rig_toml(tmp_path / "rig.toml") == r
