"""Plausible ranges of the quantities with a unit, for this kind of rig and
law: a value outside the hard range cannot be right (an error), one outside
the usual range is merely unusual (a warning).  Where a value looks like a
unit slip (cm/s typed into a m/s key, radians into a degree key), the
message names the likely mistake.

One table serves every place a user types such a number: scenario files,
rig.toml, the measurement CSVs, ContactParams and Rig.  README, "What the
tool checks", lists the ranges."""
from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Quantity:
    """hard: (lo, hi) outside which a value is an error (None: unbounded);
    usual: (lo, hi) outside which it is a warning; what: the range in words
    for the message; slips: (factor, unit) pairs: a value that lands in the
    usual range when multiplied by factor was likely typed in that unit;
    zero_allowed: whether 0 is a legal value (the hard range's ends are
    otherwise inclusive)."""
    unit: str
    hard: tuple
    usual: tuple
    what: str
    slips: tuple = ()
    zero_allowed: bool = False


QUANTITIES = {
    "velocity_m_s": Quantity("m/s", (0.0, 20.0), (1e-3, 2.0),
                             "a lab rig's carriage moves at 0.001-2 m/s",
                             ((0.01, "cm/s"), (0.001, "mm/s"))),
    "mass_kg": Quantity("kg", (0.0, 1000.0), (0.01, 100.0), "a block on a lab rig weighs 0.01-100 kg",
                        ((0.001, "g"),)),
    "g": Quantity("m/s^2", (1.0, 30.0), (9.76, 9.84), "gravity on Earth is 9.76-9.84 m/s^2",
                  ((0.01, "cm/s^2"),)),
    "f_int_N": Quantity("N", (0.0, 1e4), (0.0, 200.0), "a carriage's internal resistance is 0-200 N",
                        zero_allowed=True),
    "travel_m": Quantity("m", (0.0, 100.0), (0.005, 10.0), "a lab rig's travel is 0.005-10 m",
                         ((0.001, "mm"), (0.01, "cm"))),
    "step_s": Quantity("s", (0.0, 0.1), (1e-7, 1e-2), "a communication step of 1e-7-1e-2 s"),
    "mu_strip": Quantity("-", (0.0, 5.0), (0.0, 1.0), "a Teflon strip's friction coefficient is 0-1",
                         zero_allowed=True),
    "c_strip": Quantity("N s/m", (0.0, 1e5), (0.0, 1e3), "a strip's lateral viscosity is 0-1000 N s/m",
                        zero_allowed=True),
    "mu1": Quantity("-", (0.0, 10.0), (0.01, 3.0), "friction coefficients are 0.01-3"),
    "mu2": Quantity("-", (0.0, 10.0), (0.01, 3.0), "friction coefficients are 0.01-3"),
    "eps1": Quantity("N/m", (0.0, 1e12), (10.0, 1e9), "a contact's tangential stiffness is 10-1e9 N/m",
                     ((1e3, "N/mm"),)),
    "eps2": Quantity("N/m", (0.0, 1e12), (10.0, 1e9), "a contact's tangential stiffness is 10-1e9 N/m",
                     ((1e3, "N/mm"),)),
    "eps2_nominal_N_m": Quantity("N/m", (0.0, 1e12), (10.0, 1e9),
                                 "a contact's tangential stiffness is 10-1e9 N/m", ((1e3, "N/mm"),)),
    "eps_ratio": Quantity("-", (0.0, 1e6), (1e-3, 1e3), "stiffness ratios eps1/eps2 are 1e-3-1e3"),
}


# An angle in degrees that equals a "round" angle in radians (a multiple of
# pi/12 up to a full turn) was most likely typed in radians.
_RAD_STEP = math.pi / 12


def radian_slip(value_deg: float) -> str | None:
    """'pi/2' etc. if value_deg [deg] looks like a round angle in radians."""
    v = abs(value_deg)
    if v == 0 or v > 2 * math.pi + 1e-3:
        return None
    k = round(v / _RAD_STEP)
    if k == 0 or abs(v - k * _RAD_STEP) > 5e-4:
        return None
    num, den = k, 12
    g = math.gcd(num, den)
    num, den = num // g, den // g
    text = ("" if num == 1 else f"{num} ") + "pi" + ("" if den == 1 else f"/{den}")
    return ("-" if value_deg < 0 else "") + text


def check(key: str, value: float) -> tuple[str, str] | None:
    """("error" | "warning", message) for an implausible value of the
    quantity `key`, None if it is plausible or `key` is not in the table.
    The message starts with 'key = value' and ends with the likely slip."""
    q = QUANTITIES.get(key)
    if q is None:
        return None
    lo, hi = q.hard
    level = None
    if value < lo or value > hi or (value == 0 and not q.zero_allowed):
        level = "error"
    elif not (q.usual[0] <= value <= q.usual[1]):
        level = "warning"
    if level is None:
        return None
    msg = f"{key} = {value:g} {q.unit}: {q.what}" if q.unit != "-" else f"{key} = {value:g}: {q.what}"
    for factor, unit in q.slips:
        if q.usual[0] <= value * factor <= q.usual[1]:
            msg += f"; {unit}?"
            break
    return level, msg


def check_angle_deg(key: str, value: float) -> tuple[str, str] | None:
    """A warning for an angle [deg] that looks typed in radians."""
    slip = radian_slip(value)
    if slip is None:
        return None
    return "warning", (f"{key} = {value:g}: looks like {slip} in radians; this key is in degrees "
                       f"({math.degrees(value):.6g} deg if it was meant in rad)")


def looks_like_radians(values_deg, limit: float) -> bool:
    """True if a column of angles [deg] with at least two distinct values
    all lies within +-limit: a sweep in degrees does not, one in radians does."""
    vals = [abs(v) for v in values_deg]
    return len(set(values_deg)) >= 2 and max(vals) <= limit


# A length column typed in another unit: the factor it comes out too large by.
LENGTH_SLIPS = ((1000.0, "mm"), (100.0, "cm"))


def scale_slip(ratio: float, slips=LENGTH_SLIPS) -> str | None:
    """The unit a column was likely typed in, if `ratio` (what the column
    gives over what it should, e.g. a tracked speed over the carriage's
    velocity) is within a factor 2 of that unit's factor."""
    for factor, unit in slips:
        if 0.5 * factor < ratio < 2 * factor:
            return unit
    return None
