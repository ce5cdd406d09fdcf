"""The paper's closed-form results, in one place for tests, figures and
identification.  Equation numbers are those of Konyukhov & Schweizerhof (2007).

Conventions (docs/explanation/model-notes.md, "Conventions"):
* All angles turn counterclockwise from the driving axis X1, in rad unless a
  name ends in _deg.
* phi is the angle of the block's path, tan(phi) = dx2/dx1, counterclockwise;
  the paper counts it the other way in some figures, so compare magnitudes
  and the locations of extrema with its numbers.
* B = Q(alpha) diag(eps1, eps2) Q(alpha)^T [N/m],
  F = Q(beta) diag(1/mu1^2, 1/mu2^2) Q(beta)^T, A = B F B."""
from __future__ import annotations

import math

import numpy as np

from .named import named

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


def rotated_diagonal(d1, d2, t):
    """Entries (r11, r12, r22) of Q(t) diag(d1, d2) Q(t)^T.  Plain arithmetic
    on d1, d2, so that d1, d2 may be casadi symbols; t a number, an array or
    a casadi symbol (the fit's model maps one function over its points)."""
    if isinstance(t, np.ndarray):
        c, s = np.cos(t), np.sin(t)
    elif isinstance(t, (int, float, np.floating)):
        c, s = math.cos(t), math.sin(t)
    else:
        import casadi as ca
        c, s = ca.cos(t), ca.sin(t)
    return d1 * c * c + d2 * s * s, (d1 - d2) * s * c, d1 * s * s + d2 * c * c


def steady_tan_phi(mu1, mu2, eps1, eps2, alpha, beta, rule: str = "coupled"):
    """tan(phi) of steady sliding under a push along X1 with lateral
    equilibrium T2 = 0: the slip moves along G q with q = (q1, 0).

    associated: G = F                -> tan phi = f21 / f11, eq. (10)
    coupled:    G = (B F B)^-1 = A^-1 -> tan phi = -a21 / a22, eq. (23)

    Angles are numbers; mu and eps may be floats or casadi symbols.
    """
    f11, f12, f22 = rotated_diagonal(1 / mu1**2, 1 / mu2**2, beta)
    if rule == "associated":
        return f12 / f11
    if rule not in ("coupled", "eq20"):
        raise ValueError(f"unknown sliding rule {rule!r}")
    b11, b12, b22 = rotated_diagonal(eps1, eps2, alpha)
    # rows 2 of B F, then (B F B)_21 and (B F B)_22
    bf21, bf22 = b12 * f11 + b22 * f12, b12 * f12 + b22 * f22
    a21, a22 = bf21 * b11 + bf22 * b12, bf21 * b12 + bf22 * b22
    return -a21 / a22


def steady_drive_force(mu1, mu2, beta, f_int_N, mass_kg, g=G_STANDARD):
    """Driving force [N] of steady sliding with lateral equilibrium: q = (q1, 0)
    on the yield ellipse, q1 = N / sqrt(f11), for any sliding rule.  At
    beta = 0 and 90 deg this is eq. (1): F_int + mu_i m g."""
    f11, _, _ = rotated_diagonal(1 / mu1**2, 1 / mu2**2, beta)
    return f_int_N + mass_kg * g / f11**0.5


def stick_stiffness_x1(eps1, eps2, alpha):
    """Stiffness [N/m] of the push against the block's X1 displacement while it
    sticks with lateral equilibrium (q2 = 0): 1 / (B^-1)_11."""
    c, s = math.cos(alpha), math.sin(alpha)
    return 1 / (c * c / eps1 + s * s / eps2)


def friction_entries(mu1, mu2, beta):
    """(f11, f12, f22) of F, eq. (6); plain arithmetic as rotated_diagonal."""
    return rotated_diagonal(1 / mu1**2, 1 / mu2**2, beta)


def steady_phi_deg(mu1, mu2, eps1, eps2, alpha, beta, rule="coupled") -> float:
    return math.degrees(math.atan(steady_tan_phi(mu1, mu2, eps1, eps2, alpha, beta, rule)))


def of_law(form, law, alpha, beta, *rest):
    """form(mu1, mu2, eps1, eps2, alpha, beta, rule, *rest) of a law (anything
    with those attributes but the angles: a ContactParams) at the axes alpha,
    beta [rad]: the one place that spreads a law over the closed forms'
    arguments (steady_tan_phi, steady_phi_deg, slip_force_tensor and the
    strip's forms of closed_forms.rig take them in this order)."""
    return form(law.mu1, law.mu2, law.eps1, law.eps2, alpha, beta, law.rule, *rest)


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


# -- The forms a scenario names (geometry.closed_form; closed_forms.named) ----------
#
# Each is f(law, alpha, beta) -> tan(phi) for numbers and arrays of angles
# alike, with the law and axes it holds for.

def _implicit(law) -> str | None:
    return None if law.rule != "associated" else "an implicit rule (coupled or eq20), not 'associated'"


def _case_shift(beta_minus_alpha_deg, cases) -> np.ndarray:
    """Whether beta - alpha [deg] is one of `cases` (0, 90) modulo 180 deg."""
    d = np.mod(beta_minus_alpha_deg, 180.0)
    return np.any([np.minimum(np.abs(d - c), 180.0 - np.abs(d - c)) < 1e-9 for c in cases], axis=0)


@named("general", "eq. (10) or (23) from the tensors themselves: any law, any axes")
def general_form(law, alpha, beta):
    return of_law(steady_tan_phi, law, alpha, beta)


@named("eq11", "Case 1, orthotropic Coulomb friction: eq. (11) at a = beta",
       refusal=lambda law, shift: None if law.rule == "associated" else
       f"the associated rule, not {law.rule!r}")
def eq11_form(law, alpha, beta):
    return eq11_tan_phi(law.mu1, law.mu2, beta)


@named("eq31", "Case 2, isotropic adhesion (eps1 = eps2): eq. (31) at b = beta",
       refusal=lambda law, shift: _implicit(law) or (
           None if math.isclose(law.eps1, law.eps2, rel_tol=1e-9) else "eps1 = eps2"))
def eq31_form(law, alpha, beta):
    return eq31_tan_phi(law.mu1, law.mu2, beta)


@named("eq33", "Case 3, isotropic friction (mu1 = mu2): eq. (33) at a = alpha",
       refusal=lambda law, shift: _implicit(law) or (
           None if math.isclose(law.mu1, law.mu2, rel_tol=1e-9) else "mu1 = mu2"))
def eq33_form(law, alpha, beta):
    return eq33_tan_phi(law.eps1, law.eps2, alpha)


@named("eq25", "Case 4 (beta = alpha) or 5 (beta = alpha + 90 deg): eq. (25) with the eigenvalues "
       "of eq. (34) or (36)",
       refusal=lambda law, shift: _implicit(law) or (
           None if _case_shift(shift, (0.0, 90.0)) else "beta_offset_deg - alpha_offset_deg = 0 or 90"))
def eq25_form(law, alpha, beta):
    """nan where beta - alpha is neither Case 4's nor Case 5's."""
    shift = np.degrees(np.subtract(beta, alpha))
    case4, case5 = _case_shift(shift, (0.0,)), _case_shift(shift, (90.0,))
    c4, c5 = eigen_ratio_case4(law.mu1, law.mu2, law.eps1, law.eps2), \
        eigen_ratio_case5(law.mu1, law.mu2, law.eps1, law.eps2)
    l1 = np.where(case4, c4[0], np.where(case5, c5[0], np.nan))
    l2 = np.where(case4, c4[1], np.where(case5, c5[1], np.nan))
    return eq25_tan_phi(l1, l2, alpha)


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


def mat_ratio(eps_ratio: float, mu1: float, mu2: float) -> float:
    """r = lambda1/lambda2 = (eps1/eps2)(mu1/mu2), eq. (37)."""
    return eps_ratio * mu1 / mu2


def mat_tan_phi(r, theta):
    """Steady tan(phi) of the mat at angle theta for eigenvalue ratio r
    (counterclockwise convention)."""
    t = np.tan(theta)
    return (r**2 - 1) * t / (r**2 + t**2)


@named("mat", "the paper's mat (friction axis 1 along the ripples, adhesion axis 1 across): "
       "eq. (37)'s r = (eps1/eps2)(mu1/mu2) at the mat angle beta",
       refusal=lambda law, shift: _implicit(law) or (
           None if _case_shift(shift, (90.0,)) else "beta_offset_deg - alpha_offset_deg = 90 (mod 180)"))
def mat_form(law, alpha, beta):
    return mat_tan_phi(mat_ratio(law.eps1 / law.eps2, law.mu1, law.mu2), beta)


def mat_extremum(r) -> tuple[float, float]:
    """(theta_ext, phi_ext) [rad]: at tan theta = r, tan phi = (r^2 - 1)/(2 r)."""
    return math.atan(r), math.atan((r**2 - 1) / (2 * r))


def eps_ratio_from_r(r: float, mu1: float, mu2: float) -> float:
    """eps1/eps2 = (mu2/mu1) r, eq. (39)."""
    return mu2 / mu1 * r


def isotropic_eps_ratio(mu1: float, mu2: float) -> float:
    """eps1/eps2 that makes the mat's motion geometrically isotropic (r = 1):
    mu2/mu1 (docs/explanation/model-notes.md, erratum 1: not mu1/mu2 as sec. 4.5 says)."""
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
    (docs/explanation/model-notes.md, erratum 4); kept to show the difference."""
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
