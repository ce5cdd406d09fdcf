"""A lab's rig.toml: the rig and the assumptions of a fit (mass [kg], g
[m/s^2], F_int [N], velocity [m/s], sliding rule, axis offsets [deg], strip
terms), validated key by key with the plausible ranges of each unit: RigSetup,
its one reader (load_rig_toml) and its one writer (write_rig_toml)."""
from __future__ import annotations

import json
import math
import sys
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from ..fmu import RULES, ContactParams
from ..rig import Rig
from ..textfiles import read_toml
from .geometry import AxisGeometry
from .keys import ANGLE_DEG, POSITIVE, REQUIRED, RIG_KEYS, choice, read_table, rig_spec

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


# rig.toml's own defaults of the rig's keys (the rest are Rig's): no
# carriage resistance known, the strip's viscosity estimated unless given.
LAB_DEFAULTS = {"f_int_N": 0.0, "c_strip": None}


@dataclass
class RigSetup:
    """What rig.toml says: the rig (its keys, defaults and checks are
    rig.harness.Rig's but for LAB_DEFAULTS; the mass is required) and the
    assumptions of the fit."""
    mass_kg: float
    g: float = Rig.g
    f_int_N: float = LAB_DEFAULTS["f_int_N"]
    velocity_m_s: float = Rig.velocity_m_s
    rule: str = "coupled"
    alpha_offset_deg: float = 90.0   # the paper's mat: adhesion axis 1 across the ripples
    beta_offset_deg: float = 0.0     # friction axis 1 along the ripples
    phi_convention: str = "counterclockwise"   # or "paper" (opposite sign)
    ramp_angle_deg: float = 0.0
    mode: str = Rig.mode             # rig mode of the validation runs (settles within elastic lengths)
    travel_m: float = Rig.travel_m
    step_s: float = Rig.step_s
    eps2_nominal_N_m: float = 1e4    # for validation runs when eps2 is not identifiable
    mu_strip: float = Rig.mu_strip   # the Teflon strip's Coulomb friction, a known input
    c_strip: float | None = LAB_DEFAULTS["c_strip"]   # its lateral viscosity [N s/m]: known if
                                     # given, else estimated from angles at two velocities (else 0)
    warnings: tuple = ()             # one line each: unusual values in the files

    @property
    def normal_force(self) -> float:
        return self.mass_kg * self.g

    @property
    def geometry(self) -> AxisGeometry:
        return AxisGeometry(self.alpha_offset_deg, self.beta_offset_deg)

    def axes(self, angle_deg: float) -> tuple[float, float]:
        """(alpha, beta) [rad] at a data mat angle [deg]."""
        return self.geometry.axes(angle_deg)

    def params_at(self, law: ContactParams, angle_deg: float) -> ContactParams:
        """The law's parameters with the tensors' axes of this mat angle [deg]
        and rig.rule (the geometry's params_at: one convention for both files)."""
        return self.geometry.params_at(law, angle_deg, self.rule)

    def harness(self, **overrides):
        """The rig harness (orthocontact.rig.Rig) for this setup: its rig's
        keys (a strip viscosity not given: 0), Rig's defaults for the rest."""
        kw = {k: getattr(self, k) for k in RIG_TOML if k in RIG_KEYS}
        kw.update({"c_strip": self.c_strip or 0.0, **overrides})
        return Rig(**kw)

    @property
    def beta_minus_alpha(self) -> float:
        """Angle [rad] of the friction axes from the adhesion axes."""
        return math.radians(self.geometry.beta_minus_alpha_deg)


RIG_TOML = {
    **rig_spec(omit=("fit_from",), mass_kg=REQUIRED, **LAB_DEFAULTS),
    "rule": (choice(tuple(RULES)), "coupled"),
    "alpha_offset_deg": (ANGLE_DEG, 90.0), "beta_offset_deg": (ANGLE_DEG, 0.0),
    "phi_convention": (choice(("counterclockwise", "paper")), "counterclockwise"),
    "ramp_angle_deg": (ANGLE_DEG, 0.0), "eps2_nominal_N_m": (POSITIVE, 1e4),
}


def load_rig_toml(path: Path) -> RigSetup:
    """Reads and validates rig.toml (experiment.keys); raises one InputError
    naming every problem of the file, one line each."""
    try:   # a BOM, CRLF, a decimal comma, a missing file: textfiles
        raw = read_toml(path, "a rig.toml in the data folder (mass_kg, f_int_N, ...)")
    except tomllib.TOMLDecodeError as e:
        raise InputError(f"{path}: expected valid TOML ({e})") from None
    values, warnings = read_table(path, "", raw, RIG_TOML, InputError)
    values = {k: float(v) if isinstance(v, int) and not isinstance(v, bool) else v for k, v in values.items()}
    return RigSetup(**values, warnings=tuple(warnings))


def toml_value(v) -> str:
    """A TOML value of a scenario's or rig.toml's key: a string, a bool, a
    number (repr: read back to the same float) or a list of them."""
    if isinstance(v, str):
        return json.dumps(v)     # a JSON string is a TOML basic string
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    return repr(float(v)) if isinstance(v, float) else repr(v)


def write_rig_toml(path: Path, rig: RigSetup) -> Path:
    """Writes rig.toml of `rig`: every key load_rig_toml reads (those that
    are None left out: their default), so that it reads back as `rig`."""
    path = Path(path)
    lines = [f"{k} = {toml_value(getattr(rig, k))}" for k in RIG_TOML if getattr(rig, k) is not None]
    path.write_text("\n".join(lines) + "\n")
    return path

