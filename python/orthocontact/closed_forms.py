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


def steady_tan_phi(mu1, mu2, eps1, eps2, alpha, beta, rule: str = "coupled") -> float:
    """tan(phi) of steady sliding under a push along X1 with lateral
    equilibrium T2 = 0: the slip moves along G q with q = (q1, 0).

    associated: G = F                -> tan phi = f21 / f11, eq. (10)
    coupled:    G = (B F B)^-1 = A^-1 -> tan phi = -a21 / a22, eq. (23)
    """
    F = friction_tensor(mu1, mu2, beta)
    if rule == "associated":
        return F[1, 0] / F[0, 0]
    if rule in ("coupled", "eq20"):
        A = adhesion_tensor(eps1, eps2, alpha) @ F @ adhesion_tensor(eps1, eps2, alpha)
        return -A[1, 0] / A[1, 1]
    raise ValueError(f"unknown sliding rule {rule!r}")


def steady_tan_phi_with_strip(mu1, mu2, eps1, eps2, alpha, beta, rule, mu_strip) -> float:
    """Steady tan(phi) when the Teflon strip resists the drift with Coulomb
    friction mu_strip on the push P = q1 (beyond the paper).

    Lateral equilibrium T2 = mu_strip P sgn(v2) gives q = q1 (1, -mu_strip s)
    with s = sgn(v2); the block moves along G q, and s must agree with the sign
    of its X2 component.  If neither sign does, the strip holds the block on
    the X1 axis (tan phi = 0)."""
    F = friction_tensor(mu1, mu2, beta)
    if rule == "associated":
        G = F
    else:
        B = adhesion_tensor(eps1, eps2, alpha)
        G = np.linalg.inv(B @ F @ B)
    for s in (1.0, -1.0):
        d = G @ np.array([1.0, -mu_strip * s])
        if d[1] * s > 0:
            return d[1] / d[0]
    return 0.0


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
    """r from the extremal trajectory angle (eq. 29 in this convention):
    tan phi = (r^2 - 1)/(2r) with r > 0, r < 1 for phi < 0.  Takes either
    sign of phi_ext and returns the r < 1 branch for |phi_ext| (the paper's
    aged mat: lambda1 < lambda2)."""
    tp = abs(math.tan(phi_ext))
    return -tp + math.sqrt(tp * tp + 1)


def eps_ratio_from_r(r: float, mu1: float, mu2: float) -> float:
    """eps1/eps2 = (mu2/mu1) r, eq. (39)."""
    return mu2 / mu1 * r


def isotropic_eps_ratio(mu1: float, mu2: float) -> float:
    """eps1/eps2 that makes the mat's motion geometrically isotropic (r = 1):
    mu2/mu1 (erratum 1 of the model notes: not mu1/mu2 as sec. 4.5 says)."""
    return mu2 / mu1


def eq40_objective(r2: float, theta, tan_phi) -> float:
    """Sum of squared residuals of tan(phi) for r^2 (eq. 40 in this convention)."""
    t = np.tan(np.asarray(theta))
    res = np.asarray(tan_phi) - (r2 - 1) * t / (r2 + t**2)
    return float(np.sum(res**2))


def eq41_r2(theta, tan_phi) -> float:
    """The paper's published closed form eq. (41) for r^2, with its
    beta = pi/2 - alpha, mapped to this convention.  It is not the minimiser of
    eq. (40) (model notes, erratum 3); kept to show the difference.

    The paper's variables: tan beta_k = cot(theta_k) = 1/t, and its phi has the
    opposite sign (tan phi_paper = -tan phi)."""
    t = np.tan(np.asarray(theta, dtype=float))
    tb = 1.0 / t
    tphi = -np.asarray(tan_phi, dtype=float)
    num = np.sum(tb * (1 + tb**2) * (tb - tphi))
    den = np.sum(tb * (1 + tb**2) * (tb + tphi))
    return float(num / den)
