"""The rolling pad's figures (orthocontact.reproduction.rolling_figures):
each drawn from rows as rolling_outputs makes them, a run without cell
arrays said in words; the zones' rows spread over the creepages."""
import numpy as np

from orthocontact.experiment import load_scenario
from orthocontact.reproduction.rolling_figures import (
    figure_force_creepage,
    figure_lateral,
    figure_zones,
    zone_creepages,
)
from paths import SCENARIOS

PNG = b"\x89PNG\r\n\x1a\n"


def rows(sc) -> list:
    out = []
    for rule in sc.roll["rules"]:
        for a in sc.roll["angles_deg"]:
            for d in ("longitudinal", "lateral"):
                for xi in sc.roll["creepages"]:
                    closed = -xi if a in (0.0, 90.0) else None
                    out.append({"rule": rule, "angle_deg": a, "direction": d, "creepage": xi,
                                "T1_over_Fn": -xi, "T2_over_Fn": 0.01 * xi * np.sin(np.radians(2 * a)),
                                "closed_form_over_Fn": closed})
    return out


def test_each_figure_is_drawn_and_a_run_without_cells_says_so(tmp_path):
    sc = load_scenario(SCENARIOS / "rolling_wheel.toml")
    shape = (sc.pad["n1"], sc.pad["n2"])
    states = [np.where(np.arange(shape[0])[:, None] < k, 1, 2) * np.ones(shape, int)
              for k in range(len(sc.roll["creepages"]))]
    cells = {(sc.roll["rules"][0], a): states for a in sc.roll["angles_deg"][1:]}   # the first: FMI 2.0
    figure_force_creepage(sc, rows(sc), tmp_path / "force_creepage.png")
    figure_lateral(sc, rows(sc), tmp_path / "lateral_force.png")
    figure_zones(sc, cells, sc.roll["creepages"], tmp_path / "zones.png")
    for name in ("force_creepage.png", "lateral_force.png", "zones.png"):
        assert (tmp_path / name).read_bytes()[:8] == PNG, name


def test_the_zones_show_at_most_four_creepages_first_and_last_among_them():
    assert zone_creepages([0.1, 0.2]) == [0.1, 0.2]
    picked = zone_creepages([0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0])
    assert len(picked) == 4 and picked[0] == 0.0 and picked[-1] == 7.0
