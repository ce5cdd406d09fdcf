"""The pushed block's figures (orthocontact.reproduction.pushed_figures):
each drawn from the runs' rows whatever their regimes, a height without
cells said in words on its panel."""
import numpy as np

from orthocontact.closed_forms import FULL_CONTACT, LIFT_OFF, TIPS
from orthocontact.experiment import load_scenario
from orthocontact.reproduction.pushed_figures import figure_cells, figure_phi, figure_regimes
from paths import SCENARIOS

PNG = b"\x89PNG\r\n\x1a\n"


def rows() -> list:
    """A push at each regime, as pushed_outputs makes its rows."""
    return [{"height_m": 0.0, "angle_deg": 30.0, "regime": FULL_CONTACT, "phi_deg": -5.0, "mu": 0.5,
             "e_m": 0.0, "contact_fraction": 1.0},
            {"height_m": 0.05, "angle_deg": 30.0, "regime": LIFT_OFF, "phi_deg": -5.0, "mu": 0.5,
             "e_m": 0.025, "contact_fraction": 0.8},
            {"height_m": 0.2, "angle_deg": 30.0, "regime": TIPS, "phi_deg": None, "mu": 0.5,
             "e_m": None, "contact_fraction": None}]


def test_each_figure_is_drawn_for_every_regime(tmp_path):
    sc = load_scenario(SCENARIOS / "pushed_block.toml")
    N = np.ones((sc.pad["n1"], sc.pad["n2"]))
    S = np.ones(N.shape, dtype=int)
    S[0, 0], S[-1, -1] = 0, 2          # an open cell, a slipping one
    cells = {0.0: (N, S, "this run"), 0.05: (None, None, "FMI 2.0 has no arrays"),
             0.2: (None, None, "the block tipped")}
    figure_cells(sc, rows(), cells, tmp_path / "pressure_cells.png")
    figure_phi(sc, rows(), tmp_path / "phi_vs_angle.png")
    figure_regimes(sc, rows(), tmp_path / "regimes.png")
    for name in ("pressure_cells.png", "phi_vs_angle.png", "regimes.png"):
        assert (tmp_path / name).read_bytes()[:8] == PNG, name
