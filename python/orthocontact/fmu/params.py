"""The law's parameters as the FMU takes them (ContactParams: angles in rad,
stiffness in N/m) and the sliding rules' numbers."""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from .variables import contact, law_parameters

# The sliding rules' names and the numbers the FMU's slidingRule takes (the
# table's enumeration SlidingRule).
RULES: dict[str, int] = dict(contact().enumerations["SlidingRule"])


ANGLE_LIMIT_RAD = 4 * math.pi   # the FMU's range of alpha and beta [rad]


@dataclass(frozen=True)
class ContactParams:
    """Parameters of the law.

    mu1, mu2   friction coefficients along the friction axes [-]
    eps1, eps2 tangential stiffnesses along the adhesion axes [N/m]
    alpha      angle of adhesion axis 1 from X1, counterclockwise [rad]
    beta       angle of friction axis 1 from X1, counterclockwise [rad]
    rule       "associated", "coupled" or "eq20"

    The angles are in radians, as the FMU takes them; ContactParams.from_degrees
    takes degrees, as scenario files do.  Invalid values raise ValueError.
    """
    mu1: float
    mu2: float
    eps1: float
    eps2: float
    alpha: float = 0.0
    beta: float = 0.0
    rule: str = "coupled"

    def __post_init__(self):
        if self.rule not in RULES:
            raise ValueError(f"ContactParams: rule must be one of {', '.join(map(repr, RULES))}, "
                             f"got {self.rule!r}")
        for name in ("mu1", "mu2", "eps1", "eps2"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                raise ValueError(f"ContactParams: {name} must be a finite number > 0, got {v!r}")
        for name in ("alpha", "beta"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"ContactParams: {name} [rad] must be a finite number, got {v!r}")
            if abs(v) > ANGLE_LIMIT_RAD:
                raise ValueError(f"ContactParams: {name} = {v!r} rad is outside [-4 pi, 4 pi] rad, the FMU's "
                                 f"range; degrees? ({name} is in rad: ContactParams.from_degrees takes deg)")

    @classmethod
    def from_degrees(cls, mu1: float, mu2: float, eps1: float, eps2: float,
                     alpha_deg: float = 0.0, beta_deg: float = 0.0,
                     rule: str = "coupled") -> "ContactParams":
        """The same parameters with the axis angles in degrees (as scenario
        files give them): alpha_deg, beta_deg counterclockwise from X1."""
        return cls(mu1, mu2, eps1, eps2, math.radians(alpha_deg), math.radians(beta_deg), rule)

    @property
    def alpha_deg(self) -> float:
        """alpha in degrees."""
        return math.degrees(self.alpha)

    @property
    def beta_deg(self) -> float:
        """beta in degrees."""
        return math.degrees(self.beta)

    def replace(self, **kw) -> "ContactParams":
        return dataclasses.replace(self, **kw)

    def fmu_values(self) -> dict:
        """The contact FMU's parameters by the manifest's names: the law's in
        the table's order (floats: angles in rad, stiffnesses in N/m) and
        slidingRule (the rule's number)."""
        return {**{name: float(getattr(self, name)) for name in law_parameters()},
                "slidingRule": RULES[self.rule]}
