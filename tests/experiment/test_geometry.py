"""The one angle convention at the experiment's boundary
(orthocontact.experiment.geometry): degrees in the files, radians in the law."""
import math

import numpy as np

from orthocontact.experiment.geometry import AxisGeometry
from orthocontact.fmu import ContactParams


def test_one_angle_convention_degrees_in_the_files_radians_in_the_law():
    g = AxisGeometry(90.0, 0.0)
    alpha, beta = g.axes(39.0)
    assert alpha == math.radians(129.0) and beta == math.radians(39.0)
    arr = g.axes(np.array([0.0, 39.0]))
    assert arr[0].tolist() == [math.radians(90.0), math.radians(129.0)]
    law = ContactParams(0.408, 0.625, 12510.0, 1e4)
    assert g.params_at(law, 39.0, "associated") == law.replace(alpha=alpha, beta=beta, rule="associated")
    assert g.beta_minus_alpha_deg == -90.0
