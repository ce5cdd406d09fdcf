"""Plausible ranges of the quantities with a unit, for this kind of rig and
law: a value outside the hard range cannot be right (an error), one outside
the usual range is merely unusual (a warning).  Where a value looks like a
unit slip (cm/s typed into a m/s key, radians into a degree key), the
message names the likely mistake.

One table serves every place a user types such a number: scenario files,
rig.toml, the measurement CSVs, raw recordings' reduction, identified.json,
the identified values before they are written and again before export,
ContactParams and Rig.  gate() is the one verdict over it; the cross-checks
below judge a value against another that bounds it (a ramp's extent and
the elastic length mu N / eps against the rig's travel, a force against
F_int and m g).  docs/reference/plausible-inputs.md lists the ranges."""
from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from .errors import InputError


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


# A length or a stiffness typed in another unit: the factor that brings it into the usual range.
MM_CM, N_MM, SPEEDS = ((0.001, "mm"), (0.01, "cm")), ((1e3, "N/mm"),), ((0.01, "cm/s"), (0.001, "mm/s"))

QUANTITIES = {
    "velocity_m_s": Quantity("m/s", (0.0, 20.0), (1e-3, 2.0), "a lab rig's carriage moves at 0.001-2 m/s",
                             SPEEDS),
    # below a milligram no block can be on a rig, and a smaller mass underflows
    # what the harnesses derive from it (a patch's inertia, a pad's tolerances)
    "mass_kg": Quantity("kg", (1e-6, 1000.0), (0.01, 100.0), "a block on a lab rig weighs 0.01-100 kg",
                        ((0.001, "g"),)),
    "g": Quantity("m/s^2", (1.0, 30.0), (9.76, 9.84), "gravity on Earth is 9.76-9.84 m/s^2",
                  ((0.01, "cm/s^2"),)),
    "f_int_N": Quantity("N", (0.0, 1e4), (0.0, 200.0), "a carriage's internal resistance is 0-200 N",
                        zero_allowed=True),
    "travel_m": Quantity("m", (0.0, 100.0), (0.005, 10.0), "a lab rig's travel is 0.005-10 m", MM_CM),
    "step_s": Quantity("s", (0.0, 0.1), (1e-7, 1e-2), "a communication step of 1e-7-1e-2 s"),
    "mu_strip": Quantity("-", (0.0, 5.0), (0.0, 1.0), "a Teflon strip's friction coefficient is 0-1",
                         zero_allowed=True),
    "c_strip": Quantity("N s/m", (0.0, 1e5), (0.0, 1e3), "a strip's lateral viscosity is 0-1000 N s/m",
                        zero_allowed=True),
    "mu1": Quantity("-", (0.0, 10.0), (0.01, 3.0), "friction coefficients are 0.01-3"),
    "mu2": Quantity("-", (0.0, 10.0), (0.01, 3.0), "friction coefficients are 0.01-3"),
    "eps1": Quantity("N/m", (0.0, 1e12), (10.0, 1e9), "a contact's tangential stiffness is 10-1e9 N/m", N_MM),
    "eps2": Quantity("N/m", (0.0, 1e12), (10.0, 1e9), "a contact's tangential stiffness is 10-1e9 N/m", N_MM),
    "eps2_nominal_N_m": Quantity("N/m", (0.0, 1e12), (10.0, 1e9),
                                 "a contact's tangential stiffness is 10-1e9 N/m", N_MM),
    "eps_ratio": Quantity("-", (0.0, 1e6), (1e-3, 1e3), "stiffness ratios eps1/eps2 are 1e-3-1e3"),
    # a ramp run's stick stiffness dF/dx1 (raw recordings): a stiffness of the contact along x1
    "stiffness_N_m": Quantity("N/m", (0.0, 1e12), (10.0, 1e9),
                              "a ramp's stick stiffness dF/dx1 is 10-1e9 N/m",
                              ((1e3, "positions in mm or forces in kN"),)),
    # the contact patch (twist, towed_block): its sides, the tow's pin ahead of its centre, the twist's rate
    "length_m": Quantity("m", (0.0, 10.0), (1e-3, 1.0), "a block's contact patch is 1 mm-1 m long", MM_CM),
    "width_m": Quantity("m", (0.0, 10.0), (1e-3, 1.0), "a block's contact patch is 1 mm-1 m wide", MM_CM),
    "pin_m": Quantity("m", (0.0, 10.0), (1e-3, 1.0), "a tow's pin is 1 mm-1 m ahead of the block's centre",
                      MM_CM),
    "rate_deg_s": Quantity("deg/s", (0.0, 1e4), (1e-2, 1e3), "a twist turns at 0.01-1000 deg/s"),
    "kn_N_m3": Quantity("N/m^3", (1e3, 1e16), (1e4, 1e15),   # a gel's 1 kPa over 10 cm: 1e4; steel over 1 mm
                        "a pad's foundation (a layer's modulus over its thickness) is 1e4-1e15 N/m^3"),
    "heights_m": Quantity("m", (0.0, 10.0), (0.0, 1.0), "a push's height above the contact is 0-1 m", MM_CM,
                          zero_allowed=True),
    "step_m": Quantity("m", (0.0, 1.0), (1e-6, 1e-2), "a push's carriage step is 1e-6-1e-2 m", MM_CM),
    "load_N": Quantity("N", (0.0, 1e7), (0.1, 1e5), "a wheel's load is 0.1-1e5 N", ((1e3, "kN"),)),
    "vr_m_s": Quantity("m/s", (0.0, 500.0), (1e-3, 100.0), "a wheel or belt rolls at 0.001-100 m/s", SPEEDS),
}


def number_problem(v, lo: float | None = None, hi: float | None = None, lo_open: bool = False) -> str | None:
    """What a finite number in [lo, hi] ((lo, hi] with lo_open; None
    unbounded) is, in words, if `v` is not one; None if it is.  The type and
    range check of every number a file gives (experiment.keys.Number) and of
    the rig's fields (rig.harness.Rig), before the plausible ranges above."""
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        return "a finite number"
    if lo is not None and (v <= lo if lo_open else v < lo):
        return f"a number {'>' if lo_open else '>='} {lo}"
    if hi is not None and v > hi:
        return f"a number <= {hi}"
    return None


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


def check(key: str, value: float, shown: str | None = None) -> tuple[str, str] | None:
    """("error" | "warning", message) for an implausible value of the
    quantity `key`, None if it is plausible or `key` is not in the table.
    The message starts with 'key = value' (`shown` in place of key, e.g. a
    list's item 'key[2]') and ends with the likely slip."""
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
    name = shown or key
    msg = f"{name} = {value:g} {q.unit}: {q.what}" if q.unit != "-" else f"{name} = {value:g}: {q.what}"
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


# |angle| [deg] within which a list of mat angles was typed in radians: the
# paper's 0-90 deg is 0-pi/2 in rad (the identification's columns: the same).
RADIAN_LIST_DEG = math.pi / 2 + 1e-9


def check_angles_deg(key: str, values_deg) -> tuple[str, str] | None:
    """A warning for a list of angles [deg] that looks typed in radians:
    every one within +-pi/2 (two distinct values at least), or one a round
    angle in radians (check_angle_deg, naming it as key[i])."""
    if looks_like_radians(values_deg, RADIAN_LIST_DEG):
        shown = ", ".join(f"{v:g}" for v in values_deg)
        meant = ", ".join(f"{math.degrees(v):.4g}" for v in values_deg)
        return "warning", (f"{key} = [{shown}]: all within +-pi/2, they look like radians; this key is in "
                           f"degrees ([{meant}] deg if they were meant in rad)")
    return next((found for i, v in enumerate(values_deg)
                 if (found := check_angle_deg(f"{key}[{i}]", v)) is not None), None)


# A length column typed in another unit: the factor it comes out too large by.
LENGTH_SLIPS = ((1000.0, "mm"), (100.0, "cm"))


def scale_slip(ratio: float, slips=LENGTH_SLIPS) -> str | None:
    """The unit a column was likely typed in, if `ratio` (what the column
    gives over what it should, e.g. a tracked speed over the carriage's
    velocity) is within a factor 2 of that unit's factor."""
    found = slip(ratio, slips)
    return None if found is None else found[1]


# Time and force columns typed in another unit: the factor a time comes out
# too large by; N per unit of a force (kN, daN: too small; gram-force, mN: too large).
TIME_SLIPS = ((1e3, "ms"), (1e6, "us"))
FORCE_SLIPS = ((1e3, "kN"), (10.0, "daN"), (9.80665e-3, "gram-force"), (1e-3, "mN"))


def slip(ratio: float, slips) -> tuple[float, str] | None:
    """(factor, unit) of `slips` (LENGTH_SLIPS, TIME_SLIPS, FORCE_SLIPS)
    within a factor 2 of `ratio`: the unit a column was likely typed in."""
    return next(((f, u) for f, u in slips if 0.5 * f < ratio < 2 * f), None)


@dataclass(frozen=True)
class Finding:
    """One implausible value: level "error" (it cannot be right) or
    "warning" (it is unusual), and the user's line naming where it is."""
    level: str
    line: str


def findings(values: Mapping[str, float], where: str = "") -> list[Finding]:
    """The Finding of each value of `values` {key of QUANTITIES: value in its
    unit} outside its range; `where` prefixes each line (a file and the
    field's path, e.g. 'identified.json: ').  A non-finite value is an
    error; a key not in the table is a programming error (KeyError): a value
    the gate is given must be one it can judge."""
    out = []
    for key, v in values.items():
        q = QUANTITIES[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            out.append(Finding("error", f"{where}{key} = {v!r}: expected a finite number [{q.unit}]"))
            continue
        found = check(key, float(v))
        if found is not None:
            out.append(Finding(found[0], where + found[1] + (f"; {hard_limit(q, v)}" if found[0] == "error"
                                                             else "")))
    return out


def hard_limit(q: Quantity, v: float) -> str:
    """The hard limit a value `v` of the quantity `q` crosses, in words."""
    unit = "" if q.unit == "-" else f" {q.unit}"
    if v > q.hard[1]:
        return f"none above {q.hard[1]:g}{unit} can be right"
    if v == 0 and not q.zero_allowed:
        return "it cannot be 0"
    return f"none below {q.hard[0]:g}{unit} can be right"


def split(found: Iterable[Finding | None]) -> tuple[list[str], list[str]]:
    """(error lines, warning lines) of the findings (None: a check that found nothing)."""
    found = [f for f in found if f is not None]
    return [f.line for f in found if f.level == "error"], [f.line for f in found if f.level == "warning"]


def gate(values: Mapping[str, float], where: str = "", also: Iterable[Finding | None] = (),
         refused: str = "") -> list[str]:
    """The one verdict over quantities with a unit: raises InputError (one
    line: the first error, then `refused`, e.g. what overrides it) if a value
    of `values` (see findings) or a cross-check in `also` cannot be right;
    returns the warning lines of the unusual ones."""
    errors, warnings = split(list(findings(values, where)) + list(also))
    if errors:
        raise InputError(errors[0] + (f"; {refused}" if refused else ""))
    return warnings


def last_gate(values: Mapping[str, float], where: str = "", also: Iterable[Finding | None] = (),
              force: bool = False, override: str = "") -> list[Finding]:
    """gate()'s verdict where values leave the tool (export: FMUs, an SSV,
    an SSP, read by a simulator where no one reads a terminal): a value gate()
    would only warn about is refused too.  Raises InputError (one line: the
    first finding, an error before a warning, a cross-check in `also` (it
    names a cause) before a single value; then `refused (override)`) unless
    `force`; then returns every finding, errors first, for the terminal and
    what is exported."""
    found = [f for f in list(also) + list(findings(values, where)) if f is not None]
    found = [f for f in found if f.level == "error"] + [f for f in found if f.level != "error"]
    if found and not force:
        raise InputError(f"{found[0].line}; refused" + (f" ({override})" if override else ""))
    return found


def angle_findings(values_deg: Mapping[str, float], where: str = "") -> list[Finding]:
    """A warning Finding for each angle of `values_deg` {name: deg} that
    looks typed in radians (check_angle_deg); non-finite ones are left to
    the readers that need them."""
    found = []
    for key, v in values_deg.items():
        hit = check_angle_deg(key, v) if math.isfinite(v) else None
        if hit is not None:
            found.append(Finding(hit[0], where + hit[1]))
    return found


# The rig's fitted part of a path starts at half its travel (Rig.fit_from),
# and the quasi-static rig settles within ELASTIC_LENGTHS elastic lengths of
# the start: over 300 random laws with strip terms, |phi - closed form| <
# 3e-8 deg (99th percentile) with the fit starting 10 elastic lengths in,
# < 1e-3 deg at 5, up to 0.4 deg at 2 (a scenario's default travel is
# refused where it would not settle: experiment.scenario).
FIT_FROM = 0.5
ELASTIC_LENGTHS = 10.0


def elastic_lengths(mu1: float, mu2: float, eps1: float, eps2: float, normal_force: float) -> tuple:
    """(shortest, longest) [m] elastic length mu N / eps of the law: the
    carriage travel a stick branch takes before sliding starts, in any
    direction, lies between min(mu) N / max(eps) and max(mu) N / min(eps)
    (normal_force N [N], eps [N/m])."""
    return (min(mu1, mu2) * normal_force / max(eps1, eps2),
            max(mu1, mu2) * normal_force / min(eps1, eps2))


def elastic_length_check(mu1: float, mu2: float, eps1: float, eps2: float, normal_force: float,
                         travel_m: float, where: str = "",
                         slip: str = "eps1, eps2 in N/mm?") -> Finding | None:
    """The elastic length mu N / eps against the rig's travel [m]: an error
    if even the shortest reaches the travel (the block would stick over the
    whole of it: no force or angle of sliding could be measured or
    simulated); a warning if the longest puts the fitted part of a path
    (from FIT_FROM of the travel) within ELASTIC_LENGTHS of the start (the
    rig's runs would not settle).  `slip`: the likely unit slip, named where
    1000 times the stiffness would fit."""
    short, long = elastic_lengths(mu1, mu2, eps1, eps2, normal_force)
    fit_start = FIT_FROM * travel_m
    text = (f"{where}the elastic length mu N / eps is {short:.3g} .. {long:.3g} m (mu1 = {mu1:.4g}, "
            f"mu2 = {mu2:.4g}, eps1 = {eps1:.4g} N/m, eps2 = {eps2:.4g} N/m, N = m g = {normal_force:.4g} N)")
    hint = f"; {slip}" if slip and ELASTIC_LENGTHS * long / 1e3 <= fit_start else ""
    if short >= travel_m:
        return Finding("error", f"{text}, the rig's travel is {travel_m:g} m: the block would stick over "
                                f"the whole travel{hint}")
    if ELASTIC_LENGTHS * long > fit_start:
        return Finding("warning", f"{text}: the rig's runs fit from {fit_start:g} m of its {travel_m:g} m "
                                  f"travel, within {ELASTIC_LENGTHS:g} elastic lengths, and would not settle"
                                  f"{hint}")
    return None


def ramp_extent_check(max_x1_m: float, travel_m: float, where: str = "",
                      travel_said: str = "") -> Finding | None:
    """An error if a ramp (a pull's start) reaches beyond the rig's travel
    [m] (`travel_said`: where that travel comes from): its x1 column was
    likely typed in mm or cm."""
    if max_x1_m <= travel_m:
        return None
    slip = next((u for f, u in LENGTH_SLIPS if max_x1_m / f <= travel_m), None)
    return Finding("error", f"{where}x1_m reaches {max_x1_m:.4g} m, beyond the rig's travel "
                            f"{travel_m:g} m{travel_said}" + (f": x1_m in {slip}? the column is in m"
                                                              if slip else ""))


# (F - F_int) / (m g) of a plausible sliding force: friction coefficients
# up to 5 (the hard range of mu_strip; mu1, mu2's usual range ends at 3).
MU_FROM_FORCE = (0.0, 5.0)

# A force logged in kN comes out this many times too small.
KN = 1e3


# Units a force log may be in that give larger numbers than N: factor to N, name.
SMALL_FORCE_UNITS = ((1e-3, "mN"), (9.80665e-3, "gram-force"))


def force_check(force_N: float, f_int_N: float, normal_force: float, where: str = "") -> Finding | None:
    """A driving force of sliding [N] against the carriage's internal
    resistance F_int [N] and the normal force m g [N]: an error at or below
    F_int (the sensor reads F_int plus the push; kN named where KN times
    the force would imply a friction coefficient in MU_FROM_FORCE), or
    implying a friction coefficient (F - F_int)/(m g) outside MU_FROM_FORCE
    (a larger one names the smaller unit that fits: mN, gram-force)."""
    mu = (force_N - f_int_N) / normal_force
    if MU_FROM_FORCE[0] < mu < MU_FROM_FORCE[1]:
        return None
    if force_N <= f_int_N:
        why = f"below f_int_N = {f_int_N:g} N (the sensor reads F_int plus the push)"
        if MU_FROM_FORCE[0] < (KN * force_N - f_int_N) / normal_force < MU_FROM_FORCE[1]:
            why += "; force_N in kN?"
    else:   # too large a force: logged in a smaller unit than N
        why = f"mu = (F - F_int)/(m g) = {mu:.3g}, outside ({MU_FROM_FORCE[0]:g}, {MU_FROM_FORCE[1]:g})"
        lo, hi = MU_FROM_FORCE
        slip = next((unit for factor, unit in SMALL_FORCE_UNITS
                     if lo < (factor * force_N - f_int_N) / normal_force < hi), "N")
        why += f"; force_N in {slip}? (the column is in N)"
    return Finding("error", f"{where}force_N = {force_N:g}: {why}")


def force_unit_check(mus: Iterable[float], f_int_N: float, where: str = "", what: str = "mu",
                     normal_force: float | None = None) -> Finding | None:
    """A warning naming kN where every friction coefficient `mus` [-] the
    forces give ((F - F_int)/(m g) of each measured force, or mu1, mu2 as
    identified) lies below the usual range of mu1, mu2 and KN times each
    within it, and KN times F_int [N] is a usual F_int too: the forces were
    likely logged in kN.  A whole set in kN (slides, carriage runs, ramps)
    keeps every ratio, the angles and eps1/eps2 sane; only the forces'
    size against m g shows it.  `what` names the coefficients; m g [N] is
    said where given."""
    mus = [float(m) for m in mus]
    lo, hi = QUANTITIES["mu1"].usual
    if not mus or not all(0 < m < lo and lo <= KN * m <= hi for m in mus):
        return None
    if check("f_int_N", KN * f_int_N) is not None:
        return None
    mg = "" if normal_force is None else f"m g = {normal_force:.4g} N, "
    return Finding("warning", f"{where}{what} = {min(mus):.3g} .. {max(mus):.3g} ({mg}F_int = "
                              f"{f_int_N:.3g} N): all below the usual {lo:g}-{hi:g} of a friction "
                              f"coefficient, and {KN:g} times each within it; forces in kN? (force_N is "
                              "in N)")
