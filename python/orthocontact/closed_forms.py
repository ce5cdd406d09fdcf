"""The paper's closed-form results, in one place for tests, figures and
identification.  Equation numbers are those of Konyukhov & Schweizerhof (2007).

Conventions (see README, "Angles and signs"):
* All angles turn counterclockwise from the driving axis X1, in rad unless a
  name ends in _deg.
* phi is the angle of the block's path, tan(phi) = dx2/dx1, counterclockwise;
  the paper counts it the other way in some figures, so compare magnitudes
  and the locations of extrema with its numbers.
* B = Q(alpha) diag(eps1, eps2) Q(alpha)^T [N/m],
  F = Q(beta) diag(1/mu1^2, 1/mu2^2) Q(beta)^T, A = B F B.
"""
from __future__ import annotations

import math

import numpy as np

G_STANDARD = 9.806  # m/s^2, the paper's value


def rotation(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s], [s, c]])


def adhesion_tensor(eps1: float, eps2: float, alpha: float) -> np.ndarray:
    """B [N/m], eq. (30) with positive stiffnesses."""
    Q = rotation(alpha)
    return Q @ np.diag([eps1, eps2]) @ Q.T


def friction_tensor(mu1: float, mu2: float, beta: float) -> np.ndarray:
    """F [-], eq. (6)."""
    Q = rotation(beta)
    return Q @ np.diag([1.0 / mu1**2, 1.0 / mu2**2]) @ Q.T


def _sym2(d1, d2, t):
    """Entries (r11, r12, r22) of Q(t) diag(d1, d2) Q(t)^T.  Plain arithmetic
    on d1, d2, so that d1, d2 may be casadi symbols; t a number or an array."""
    c, s = (np.cos(t), np.sin(t)) if isinstance(t, np.ndarray) else (math.cos(t), math.sin(t))
    return d1 * c * c + d2 * s * s, (d1 - d2) * s * c, d1 * s * s + d2 * c * c


def steady_tan_phi(mu1, mu2, eps1, eps2, alpha, beta, rule: str = "coupled"):
    """tan(phi) of steady sliding under a push along X1 with lateral
    equilibrium T2 = 0: the slip moves along G q with q = (q1, 0).

    associated: G = F                -> tan phi = f21 / f11, eq. (10)
    coupled:    G = (B F B)^-1 = A^-1 -> tan phi = -a21 / a22, eq. (23)

    Angles are numbers; mu and eps may be floats or casadi symbols.
    """
    f11, f12, f22 = _sym2(1 / mu1**2, 1 / mu2**2, beta)
    if rule == "associated":
        return f12 / f11
    if rule not in ("coupled", "eq20"):
        raise ValueError(f"unknown sliding rule {rule!r}")
    b11, b12, b22 = _sym2(eps1, eps2, alpha)
    # rows 2 of B F, then (B F B)_21 and (B F B)_22
    bf21, bf22 = b12 * f11 + b22 * f12, b12 * f12 + b22 * f22
    a21, a22 = bf21 * b11 + bf22 * b12, bf21 * b12 + bf22 * b22
    return -a21 / a22


def steady_drive_force(mu1, mu2, beta, f_int_N, mass_kg, g=G_STANDARD):
    """Driving force [N] of steady sliding with lateral equilibrium: q = (q1, 0)
    on the yield ellipse, q1 = N / sqrt(f11), for any sliding rule.  At
    beta = 0 and 90 deg this is eq. (1): F_int + mu_i m g."""
    f11, _, _ = _sym2(1 / mu1**2, 1 / mu2**2, beta)
    return f_int_N + mass_kg * g / f11**0.5


def stick_stiffness_x1(eps1, eps2, alpha):
    """Stiffness [N/m] of the push against the block's X1 displacement while it
    sticks with lateral equilibrium (q2 = 0): 1 / (B^-1)_11."""
    c, s = math.cos(alpha), math.sin(alpha)
    return 1 / (c * c / eps1 + s * s / eps2)


def strip_tensors(mu1, mu2, eps1, eps2, alpha, beta, rule):
    """(f11, f12, f22) of F and (g11, g12, g22) of a positive multiple of the
    slip tensor G (F, or adj(B F B) = det(B F B) (B F B)^-1 for the coupled
    rule: the same directions).  Plain arithmetic: floats, numpy arrays of
    angles, or casadi symbols."""
    f11, f12, f22 = _sym2(1 / mu1**2, 1 / mu2**2, beta)
    if rule == "associated":
        return (f11, f12, f22), (f11, f12, f22)
    b11, b12, b22 = _sym2(eps1, eps2, alpha)
    bf11, bf12 = b11 * f11 + b12 * f12, b11 * f12 + b12 * f22
    bf21, bf22 = b12 * f11 + b22 * f12, b12 * f12 + b22 * f22
    a11, a12, a22 = bf11 * b11 + bf12 * b12, bf11 * b12 + bf12 * b22, bf21 * b12 + bf22 * b22
    return (f11, f12, f22), (a22, -a12, a11)


def strip_equilibrium(f, g, mu_strip, s, c_times_v, normal_force, t):
    """Steady sliding with the strip at slope t = tan(phi) and lateral
    motion of sign s: lateral equilibrium T2 = mu_strip P s + c_strip v2
    gives q2 = a q1 + b with a = -mu_strip s, b = -c_strip v t; q on the
    yield ellipse q.Fq = N^2 fixes q1 > 0.  Returns (q1, q2, t') with
    t' = (Gq)_2 / (Gq)_1 the slope the block then takes: the steady state is
    t' = t.  f, g from strip_tensors; floats, arrays or casadi symbols."""
    f11, f12, f22 = f
    g11, g12, g22 = g
    a, b = -mu_strip * s, -c_times_v * t
    # f11 q1^2 + 2 f12 q1 (a q1 + b) + f22 (a q1 + b)^2 = N^2
    A = f11 + 2 * f12 * a + f22 * a * a
    Bq = 2 * (f12 + f22 * a) * b
    C = f22 * b * b - normal_force**2
    q1 = (-Bq + (Bq * Bq - 4 * A * C) ** 0.5) / (2 * A)
    q2 = a * q1 + b
    return q1, q2, (g12 * q1 + g22 * q2) / (g11 * q1 + g12 * q2)


def steady_tan_phi_with_strip(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip, c_strip=0.0,
                              velocity=0.0, normal_force=1.0) -> float:
    """Steady tan(phi) when the Teflon strip resists the drift (beyond the
    paper): Coulomb friction mu_strip on the push P = q1 and a viscous force
    c_strip [N s/m] on the lateral velocity v2 = velocity tan(phi) [m/s];
    normal_force [N] matters only with c_strip.

    The steady slope solves t = t'(t) of strip_equilibrium, by bisection (the
    direction turns back towards X1 as t, and with it the viscous force,
    grows).  If neither sign of motion is consistent, the strip holds the
    block on the X1 axis (tan phi = 0)."""
    f, g = strip_tensors(mu1, mu2, eps1, eps2, alpha, beta, rule)
    cv = c_strip * velocity

    def turned(t, s):
        return strip_equilibrium(f, g, mu_strip, s, cv, normal_force, t)[2]

    for s in (1.0, -1.0):
        t0 = turned(0.0, s)
        if t0 * s <= 0:
            continue  # this sign of motion is not consistent even without viscosity
        if cv == 0:
            return t0
        lo, hi = 0.0, t0  # t - turned(t) < 0 at 0, >= 0 at t0 (the viscous force only turns back)
        for _ in range(STRIP_BISECTIONS):
            mid = 0.5 * (lo + hi)
            if (mid - turned(mid, s)) * s < 0:
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)
    return 0.0


STRIP_BISECTIONS = 64  # halvings of [0, t0]: past double precision for any t0


def steady_tan_phi_with_strip_array(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip, c_strip=0.0,
                                    velocity=0.0, normal_force=1.0) -> np.ndarray:
    """steady_tan_phi_with_strip for arrays of angles alpha, beta [rad]: the
    same equations, every angle bisected at once."""
    alpha, beta = np.asarray(alpha, dtype=float), np.asarray(beta, dtype=float)
    f, g = strip_tensors(mu1, mu2, eps1, eps2, alpha, beta, rule)
    cv = c_strip * velocity

    def turned(t, s):
        return strip_equilibrium(f, g, mu_strip, s, cv, normal_force, t)[2]

    out = np.zeros(np.broadcast(alpha, beta).shape)
    done = np.zeros(out.shape, dtype=bool)
    for s in (1.0, -1.0):
        t0 = turned(np.zeros(out.shape), s)
        ok = (t0 * s > 0) & ~done
        if cv == 0:
            t = t0
        else:
            lo, hi = np.zeros(out.shape), t0.copy()
            for _ in range(STRIP_BISECTIONS):
                mid = 0.5 * (lo + hi)
                left = (mid - turned(mid, s)) * s < 0
                lo, hi = np.where(left, mid, lo), np.where(left, hi, mid)
            t = 0.5 * (lo + hi)
        out = np.where(ok, t, out)
        done |= ok
    return out


def steady_phi_deg(mu1, mu2, eps1, eps2, alpha, beta, rule="coupled") -> float:
    return math.degrees(math.atan(steady_tan_phi(mu1, mu2, eps1, eps2, alpha, beta, rule)))


# -- Case-specific forms ---------------------------------------------------------

def eq11_tan_phi(mu1, mu2, a):
    """Case 1, orthotropic Coulomb (associated): eq. (11); a = beta."""
    t = np.tan(a)
    return (mu2**2 - mu1**2) * t / (mu2**2 + mu1**2 * t**2)


def eq25_tan_phi(l1, l2, a):
    """Coupled model in the eigenbasis of A (angle a): eq. (25)."""
    t = np.tan(a)
    return -(l1**2 - l2**2) * t / (l1**2 * t**2 + l2**2)


def eq31_tan_phi(mu1, mu2, b):
    """Case 2, isotropic adhesion: eq. (31); b = beta."""
    t = np.tan(b)
    return (mu1**2 - mu2**2) * t / (mu1**2 + mu2**2 * t**2)


def eq33_tan_phi(eps1, eps2, a):
    """Case 3, isotropic friction: eq. (33); a = alpha."""
    t = np.tan(a)
    return (eps2**2 - eps1**2) * t / (eps2**2 + eps1**2 * t**2)


def eigen_ratio_case4(mu1, mu2, eps1, eps2):
    """Case 4 (alpha = beta): lambda_i = eps_i / mu_i, eq. (34)."""
    return eps1 / mu1, eps2 / mu2


def eigen_ratio_case5(mu1, mu2, eps1, eps2):
    """Case 5 (beta = alpha + 90 deg): lambda_1 = eps1/mu2, lambda_2 = eps2/mu1, eq. (36)."""
    return eps1 / mu2, eps2 / mu1


def eq27_alpha_ext(l1, l2) -> float:
    """Angle of the extremum of eq. (25) [rad]: tan a = l2 / l1."""
    return math.atan(l2 / l1)


def eq28_tan_phi_ext(l1, l2) -> float:
    """tan(phi) at the extremum: (l2^2 - l1^2) / (2 l1 l2)."""
    return (l2**2 - l1**2) / (2 * l1 * l2)


def eq29_ratio(tan_phi_ext: float) -> float:
    """l1/l2 from the extremal angle, positive root of eq. (29), in the
    convention of eq. (28)."""
    return -tan_phi_ext + math.sqrt(tan_phi_ext**2 + 1)


def eq11_extremum(mu1, mu2):
    """Case 1 maximum: (a_ext, phi_max) [rad] = (atan(mu2/mu1), atan((mu2^2-mu1^2)/(2 mu1 mu2)))."""
    return math.atan(mu2 / mu1), math.atan((mu2**2 - mu1**2) / (2 * mu1 * mu2))


# -- The experiment (section 2, 4.6) in the law's terms ------------------------------
#
# theta: the mat angle, direction of the ripples counterclockwise from X1.
# mu1 acts along the ripples, mu2 across (eq. 1), so beta = theta; adhesion
# axis 1 lies across the ripples: alpha = theta + 90 deg (Case 5 geometry).
# With r = lambda1/lambda2 = (eps1/eps2)(mu1/mu2) (eq. 37):
#     tan phi = (r^2 - 1) t / (r^2 + t^2),  t = tan theta.

def eq1_mu(force_N: float, f_int_N: float, mass_kg: float, g: float = G_STANDARD) -> float:
    """Friction coefficient from a driving force, eq. (1)."""
    return (force_N - f_int_N) / (mass_kg * g)


def driving_force(mu: float, f_int_N: float, mass_kg: float, g: float = G_STANDARD) -> float:
    """Inverse of eq. (1): driving force [N] when sliding along a friction axis."""
    return f_int_N + mu * mass_kg * g


def mat_geometry(theta: float) -> tuple[float, float]:
    """(alpha, beta) [rad] of the paper's mat at mat angle theta [rad]."""
    return theta + math.pi / 2, theta


def mat_ratio(eps_ratio: float, mu1: float, mu2: float) -> float:
    """r = lambda1/lambda2 = (eps1/eps2)(mu1/mu2), eq. (37)."""
    return eps_ratio * mu1 / mu2


def mat_tan_phi(r, theta):
    """Steady tan(phi) of the mat at angle theta for eigenvalue ratio r
    (counterclockwise convention)."""
    t = np.tan(theta)
    return (r**2 - 1) * t / (r**2 + t**2)


def mat_extremum(r) -> tuple[float, float]:
    """(theta_ext, phi_ext) [rad]: at tan theta = r, tan phi = (r^2 - 1)/(2 r)."""
    return math.atan(r), math.atan((r**2 - 1) / (2 * r))


def mat_ratio_from_extremum(phi_ext: float) -> float:
    """r = lambda1/lambda2 from the mat's extremal trajectory angle [rad]
    (eq. 29 in this convention: tan phi_ext = (r^2 - 1)/(2r), so phi < 0
    gives r < 1 as for the paper's aged mat)."""
    tp = math.tan(phi_ext)
    return tp + math.sqrt(tp * tp + 1)


def eps_ratio_from_r(r: float, mu1: float, mu2: float) -> float:
    """eps1/eps2 = (mu2/mu1) r, eq. (39)."""
    return mu2 / mu1 * r


def isotropic_eps_ratio(mu1: float, mu2: float) -> float:
    """eps1/eps2 that makes the mat's motion geometrically isotropic (r = 1):
    mu2/mu1 (docs/model-notes.md, erratum 1: not mu1/mu2 as sec. 4.5 says)."""
    return mu2 / mu1


def eq40_objective(r2: float, tan_alpha, tan_phi) -> float:
    """Eq. (40): sum over the data of (tan phi_k - eq25(r, alpha_k))^2 with
    l1/l2 = r, in the eq. (25) form: tan_alpha is the tangent of the adhesion
    axis angle, tan_phi the measured tangent in this (counterclockwise)
    convention."""
    t = np.asarray(tan_alpha, dtype=float)
    res = np.asarray(tan_phi, dtype=float) + (r2 - 1) * t / (r2 * t**2 + 1)
    return float(np.sum(res**2))


def eq41_r2(tan_alpha, tan_phi) -> float:
    """The paper's published closed form eq. (41) for r^2 (its tan beta_k is
    tan_alpha here, as in eq. 40).  It is not the minimiser of eq. (40)
    (docs/model-notes.md, erratum 4); kept to show the difference."""
    tb = np.asarray(tan_alpha, dtype=float)
    tphi = np.asarray(tan_phi, dtype=float)
    num = np.sum(tb * (1 + tb**2) * (tb - tphi))
    den = np.sum(tb * (1 + tb**2) * (tb + tphi))
    return float(num / den)


def eq25_lambdas(mu1, mu2, eps1, eps2, beta_minus_alpha: float):
    """(lambda1, lambda2) of A = B F B when its eigenbasis is alpha: Case 4
    (beta - alpha = 0 mod 180 deg) or Case 5 (= 90 mod 180 deg); None
    otherwise."""
    d = math.degrees(beta_minus_alpha) % 180.0
    if min(d, 180.0 - d) < 1e-9:
        return eigen_ratio_case4(mu1, mu2, eps1, eps2)
    if abs(d - 90.0) < 1e-9:
        return eigen_ratio_case5(mu1, mu2, eps1, eps2)
    return None
