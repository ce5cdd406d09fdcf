"""How the law's axes follow the mat angle: one angle convention at the
experiment's boundary.  Files give the mat angle a (the angle the mat is turned by in the
paper's experiment) and the axes' offsets in degrees, counterclockwise from
the driving axis X1; the law's parameters take radians:
alpha = a + alpha_offset_deg, beta = a + beta_offset_deg."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..fmu import ContactParams


@dataclass(frozen=True)
class AxisGeometry:
    """alpha_offset_deg: adhesion axis 1 from the mat angle [deg];
    beta_offset_deg: friction axis 1 from it [deg]."""
    alpha_offset_deg: float = 0.0
    beta_offset_deg: float = 0.0

    def axes(self, angle_deg):
        """(alpha, beta) [rad] at the mat angle(s) [deg] (a number or an array)."""
        a = np.asarray(angle_deg, dtype=float)
        alpha, beta = np.radians(a + self.alpha_offset_deg), np.radians(a + self.beta_offset_deg)
        return (float(alpha), float(beta)) if alpha.ndim == 0 else (alpha, beta)

    def params_at(self, law: ContactParams, angle_deg: float, rule: str | None = None) -> ContactParams:
        """The law with the axes of the mat angle [deg] (and another rule if given)."""
        alpha, beta = self.axes(angle_deg)
        return law.replace(alpha=alpha, beta=beta, rule=rule or law.rule)

    @property
    def beta_minus_alpha_deg(self) -> float:
        """Angle of the friction axes from the adhesion axes [deg]."""
        return self.beta_offset_deg - self.alpha_offset_deg
