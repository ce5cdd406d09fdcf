"""The planar body's figures (orthocontact.reproduction.planar_figures): the
twist's torque (log-log, or linear where a torque is 0), the cells during
the twist, the towed block's yaw against the mat angle and time."""
from types import SimpleNamespace

import numpy as np
import pytest

from orthocontact.experiment import load_scenario
from orthocontact.reproduction.planar_figures import (
    figure_cells,
    figure_twist,
    figure_yaw_angle,
    figure_yaw_time,
)
from paths import SCENARIOS

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("lowest", [1e-3, 0.0])   # log-log, or linear with a torque of 0
def test_the_twist_and_its_cells_are_drawn(tmp_path, lowest):
    sc = load_scenario(SCENARIOS / "twist.toml")
    theta = np.linspace(1e-4, 0.1, 50)
    res = SimpleNamespace(theta=theta, Mz=-np.maximum(np.minimum(2.0 * theta, 0.05), lowest))
    figure_twist(sc, {"coupled": (res, -np.full_like(theta, 0.05), 2.0)}, tmp_path / "twist.png")
    g = SimpleNamespace(length=0.1, width=0.05, n1=3, n2=2)
    rows = [(rule, name, k, theta, i, j, 0.0, 0.0, (i + j + k) % 3)
            for rule in ("coupled", "associated") for name, k, theta in (("start", 1, 0.01), ("end", 9, 5.0))
            for i in range(g.n1) for j in range(g.n2)]
    figure_cells(sc, g, rows, tmp_path / "cells.png")
    for name in ("twist.png", "cells.png"):
        assert (tmp_path / name).read_bytes()[:8] == PNG, name


def test_the_towed_blocks_yaw_is_drawn_against_angle_and_time(tmp_path):
    sc = load_scenario(SCENARIOS / "towed_block.toml")
    figure_yaw_angle(sc, [("coupled", a, -a / 10) for a in (0.0, 30.0, 60.0)], tmp_path / "angle.png")
    t = np.linspace(0.0, 1.0, 20)
    figure_yaw_time(sc, {("coupled", 30.0): SimpleNamespace(t=t, theta=-0.05 * t)}, tmp_path / "time.png")
    for name in ("angle.png", "time.png"):
        assert (tmp_path / name).read_bytes()[:8] == PNG, name
