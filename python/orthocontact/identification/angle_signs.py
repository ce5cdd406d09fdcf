"""The slide runs' trajectory angles against the signs the law can give:
the sign of a steady path's angle at a mat angle depends only on the
sliding rule, the rig's axis offsets and the ratios mu2/mu1 and eps1/eps2
(a strip's friction and viscosity shrink the angle, never turn it), and the
slide forces fix mu2/mu1.  Angles whose signs no eps1/eps2 can give, where
the opposite signs can, are the tracker's x2 flipped (or the rig's
phi_convention).  Where both signs are possible, as in the paper's
geometry (Cases 4 and 5: beta - alpha = 0 or 90 deg, the coupled rule), a
flip shows only in the fit's lack of fit, not here.  Units: deg, N."""
from __future__ import annotations

import math

import numpy as np

from ..closed_forms import steady_tan_phi
from .recordings import Recordings

# A group's median |phi| under this has no sign judged: a tracker's drift
# over velocity (0.14 deg on the bundled set) and a strip's hold live there.
SIGN_MIN_DEG = 1.0

# ... nor one within this many standard errors of 0 (its runs' scatter).
SIGN_Z = 5.0

# The forces' mu2/mu1 is taken within this factor (a strip's friction turns
# the push off the ellipse's X1 point by a few per cent).
MU_RATIO_SPREAD = 1.3

# eps1/eps2 over the usual range of eps_ratio (plausibility).
EPS_RATIOS = np.logspace(-3.0, 3.0, 601)

# mu2/mu1 where the forces cannot tell it: the usual range of mu1, mu2 apart.
MU_RATIOS = np.logspace(-2.0, 2.0, 201)


def mu_ratio(rec: Recordings, runs: list, f_int: float) -> float | None:
    """mu2/mu1 of the slide runs' forces [N]: (m g / (F - F_int))^2 =
    cos^2(beta) / mu1^2 + sin^2(beta) / mu2^2 by least squares (the paper's
    eq. 1 at any mat angle); None without two friction directions or with a
    force at or below F_int."""
    rig = rec.rig
    slides = [r for r in runs if r.kind == "slide" and r.used]
    F = np.array([r.force_N for r in slides])
    if not len(F) or np.any(F <= f_int):
        return None
    beta = np.array([rig.axes(r.mat_angle_deg)[1] for r in slides])
    A = np.column_stack([np.cos(beta) ** 2, np.sin(beta) ** 2])
    if np.linalg.matrix_rank(A, tol=1e-6) < 2:
        return None
    (f1, f2), *_ = np.linalg.lstsq(A, (rig.normal_force / (F - f_int)) ** 2, rcond=None)
    return math.sqrt(f1 / f2) if f1 > 0 and f2 > 0 else None


def signed_groups(rec: Recordings, runs: list) -> dict:
    """{(mat angle, velocity): (median phi [deg] counterclockwise, sign)} of
    the slide runs that settled, sign 0 where it cannot be told (SIGN_MIN_DEG,
    SIGN_Z over the groups' pooled robust scatter)."""
    conv = -1.0 if rec.rig.phi_convention == "paper" else 1.0
    groups = {}
    for r in runs:
        if r.kind == "slide" and r.used and math.isfinite(r.phi_deg):
            groups.setdefault((r.mat_angle_deg, r.velocity_m_s), []).append(conv * r.phi_deg)
    dev = [p - np.median(v) for v in groups.values() if len(v) > 1 for p in v]
    sd = 1.4826 * float(np.median(np.abs(dev))) if dev else 0.0
    out = {}
    for k, v in groups.items():
        m = float(np.median(v))
        told = abs(m) > max(SIGN_MIN_DEG, SIGN_Z * sd / math.sqrt(len(v)))
        out[k] = (m, int(np.sign(m)) if told else 0)
    return out


def law_signs(rec: Recordings, angles_deg, ratio: float | None) -> np.ndarray:
    """(mu ratios, EPS_RATIOS, angles) array of the signs of the law's
    steady tan(phi) at the mat angles, over mu2/mu1 within MU_RATIO_SPREAD
    of `ratio` (over MU_RATIOS without one) and over EPS_RATIOS."""
    rig = rec.rig
    mus = (ratio * np.geomspace(1 / MU_RATIO_SPREAD, MU_RATIO_SPREAD, 13) if ratio else MU_RATIOS)
    axes = np.array([rig.axes(a) for a in angles_deg])
    tan = steady_tan_phi(1.0, mus[:, None, None], EPS_RATIOS[None, :, None], 1.0, axes[:, 0], axes[:, 1],
                         rig.rule)
    tan = np.broadcast_to(tan, (len(mus), len(EPS_RATIOS), len(angles_deg)))
    return np.where(np.abs(tan) < 1e-9, 0, np.sign(tan))


def angle_sign_finding(rec: Recordings, runs: list) -> str | None:
    """One line if no mu2/mu1 near the forces' and no eps1/eps2 gives the
    signs of the slide groups' angles while some give the opposite signs:
    the first group the law turns the other way, its first run's trajectory
    file.  None otherwise."""
    groups = {k: v for k, v in signed_groups(rec, runs).items() if v[1]}
    if not groups:
        return None
    carriage = [r.force_N for r in runs if r.kind == "carriage" and math.isfinite(r.force_N)]
    f_int = float(np.mean(carriage)) if carriage else rec.rig.f_int_N
    ratio = mu_ratio(rec, runs, f_int)
    keys = list(groups)
    signs = np.array([groups[k][1] for k in keys])
    law = law_signs(rec, [a for a, _ in keys], ratio)
    if np.all(law == signs, axis=-1).any() or not np.all(law == -signs, axis=-1).any():
        return None
    angle, v = keys[0]
    first = next(r for r in rec.runs if r.kind == "slide" and (r.mat_angle_deg, r.velocity_m_s) == keys[0])
    rig = rec.rig
    mus = f"mu2/mu1 = {ratio:.3g} of the slide forces" if ratio else "any mu2/mu1"
    return (f"{first.trajectory_path}: x2_m: the slide runs at {angle:g} deg, {v:g} m/s go at "
            f"{groups[keys[0]][0]:+.2f} deg (counterclockwise); the law ({rig.rule}, axes at the mat angle "
            f"+ {rig.alpha_offset_deg:g} / {rig.beta_offset_deg:g} deg) gives the signs of the {len(keys)} "
            f"groups' angles for no eps1/eps2 at {mus}, and the opposite signs for some: x2_m sign "
            f"flipped, or phi_convention? (rig.toml: {rig.phi_convention!r})")
