"""A lab's rig.toml (orthocontact.experiment.rig_setup): read, checked key by
key, and the same law as a scenario with the same geometry."""
from orthocontact.experiment.rig_setup import load_rig_toml
from orthocontact.experiment.scenario import load

MAT = '''name = "m"
kind = "sweep"
[law]
mu1 = 0.408
mu2 = 0.625
eps2 = 1.0e4
eps_ratio = 1.251
[sweep]
step_deg = 45.0
'''


def test_a_scenario_and_a_rig_toml_with_the_same_geometry_give_the_same_law(tmp_path):
    (tmp_path / "s.toml").write_text(MAT + "[geometry]\nalpha_offset_deg = 90.0\n")
    (tmp_path / "rig.toml").write_text("mass_kg = 1.875\nalpha_offset_deg = 90.0\n")
    sc, rig = load(tmp_path / "s.toml"), load_rig_toml(tmp_path / "rig.toml")
    for a in (0.0, 12.5, 39.2, 90.0):
        assert sc.params_at(a) == rig.params_at(sc.law, a)
