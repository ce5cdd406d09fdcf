"""A lab's rig.toml: the rig and the assumptions of a fit (mass [kg], g
[m/s^2], F_int [N], velocity [m/s], sliding rule, axis offsets [deg], strip
terms), validated key by key with the plausible ranges of each unit."""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from pathlib import Path

from .. import closed_forms as cf
from .. import plausibility
from ..errors import InputError
from ..fmu.params import RULES, ContactParams

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


@dataclass
class RigSetup:
    """What rig.toml says: the rig and the assumptions of the fit."""
    mass_kg: float
    g: float = cf.G_STANDARD
    f_int_N: float = 0.0
    velocity_m_s: float = 0.244
    rule: str = "coupled"
    alpha_offset_deg: float = 90.0   # the paper's mat: adhesion axis 1 across the ripples
    beta_offset_deg: float = 0.0     # friction axis 1 along the ripples
    phi_convention: str = "counterclockwise"   # or "paper" (opposite sign)
    ramp_angle_deg: float = 0.0
    mode: str = "quasistatic"        # rig mode of the validation runs (settles within elastic lengths)
    travel_m: float = 0.5
    step_s: float = 2e-4
    eps2_nominal_N_m: float = 1e4    # for validation runs when eps2 is not identifiable
    mu_strip: float = 0.0            # the Teflon strip's Coulomb friction, a known input
    c_strip: float | None = None     # its lateral viscosity [N s/m]: known if given, else
                                     # estimated from angles at two velocities (else 0)
    warnings: tuple = ()             # one line each: unusual values in the files

    @property
    def normal_force(self) -> float:
        return self.mass_kg * self.g

    def axes(self, angle_deg: float) -> tuple[float, float]:
        """(alpha, beta) [rad] at a data orientation angle [deg]."""
        return (math.radians(angle_deg + self.alpha_offset_deg),
                math.radians(angle_deg + self.beta_offset_deg))

    def params_at(self, law: ContactParams, angle_deg: float) -> ContactParams:
        """The law's parameters with the tensors' axes of this orientation and rig.rule."""
        alpha, beta = self.axes(angle_deg)
        return law.replace(alpha=alpha, beta=beta, rule=self.rule)

    def harness(self, **overrides):
        """The rig harness (orthocontact.rig.Rig) for this setup."""
        from ..rig.harness import Rig
        kw = dict(mass_kg=self.mass_kg, g=self.g, f_int_N=self.f_int_N,
                  velocity_m_s=self.velocity_m_s, travel_m=self.travel_m, mode=self.mode,
                  step_s=self.step_s, mu_strip=self.mu_strip, c_strip=self.c_strip or 0.0)
        kw.update(overrides)
        return Rig(**kw)

    @property
    def beta_minus_alpha(self) -> float:
        """Angle [rad] of the friction axes from the adhesion axes."""
        return math.radians(self.beta_offset_deg - self.alpha_offset_deg)


_RIG_KEYS = {
    "mass_kg": ("pos", None), "g": ("pos", cf.G_STANDARD), "f_int_N": ("nonneg", 0.0),
    "velocity_m_s": ("pos", 0.244), "rule": (tuple(RULES), "coupled"),
    "alpha_offset_deg": ("angle", 90.0), "beta_offset_deg": ("angle", 0.0),
    "phi_convention": (("counterclockwise", "paper"), "counterclockwise"),
    "ramp_angle_deg": ("angle", 0.0), "mode": (("dynamic", "quasistatic"), "quasistatic"),
    "travel_m": ("pos", 0.5), "step_s": ("pos", 2e-4), "eps2_nominal_N_m": ("pos", 1e4),
    "mu_strip": ("nonneg", 0.0), "c_strip": ("nonneg", "unset"),
}


def load_rig_toml(path: Path) -> RigSetup:
    try:
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(f"{path}: expected a rig.toml in the data folder (mass_kg, f_int_N, ...)") from None
    except tomllib.TOMLDecodeError as e:
        raise InputError(f"{path}: expected valid TOML ({e})") from None
    out, warnings = {}, []
    for key, value in raw.items():
        if key not in _RIG_KEYS:
            raise InputError(f"{path}: {key}: expected one of the known keys {', '.join(sorted(_RIG_KEYS))}")
    for key, (kind, default) in _RIG_KEYS.items():
        if key not in raw:
            if default is None:
                raise InputError(f"{path}: {key}: expected a value (the key is required)")
            out[key] = None if default == "unset" else default
            continue
        v = raw[key]
        if isinstance(kind, tuple):
            if v not in kind:
                raise InputError(f"{path}: {key}: expected one of {', '.join(map(repr, kind))}, got {v!r}")
        else:
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InputError(f"{path}: {key}: expected a finite number, got {v!r}")
            if (kind == "pos" and v <= 0) or (kind == "nonneg" and v < 0) or \
                    (kind == "angle" and abs(v) > 360):
                what = {"pos": "> 0", "nonneg": ">= 0", "angle": "in [-360, 360]"}[kind]
                raise InputError(f"{path}: {key}: expected a number {what}, got {v!r}")
            v = float(v)
            found = plausibility.check(key, v) or \
                (plausibility.check_angle_deg(key, v) if key.endswith("_deg") else None)
            if found is not None:
                level, message = found
                if level == "error":
                    raise InputError(f"{path}: {message}")
                warnings.append(f"{path}: {message}")
        out[key] = v
    return RigSetup(**out, warnings=tuple(warnings))
