"""Closed forms of a rectangular contact patch (length x width [m]) of a
rigid body on a flat surface, each point of it the law with its own slip:
the torsional stiffness while it sticks and the torque and force while every
point slides in steady state.  Written from the law's tensors
(closed_forms.paper, closed_forms.rig), independently of the ContactPatch FMU.

Conventions: body coordinates (x, y) with the origin at the patch centre,
x along `length`; theta counterclockwise; the surface's force and moment on
the body (T [N], Mz [N m] about the normal through the centre).  The
pressure is linear with resultant N [N] at the centre of pressure (p1, p2)
[m]: over the continuum p = N/A (1 + 12 p1 x / length^2 + 12 p2 y / width^2).
The patch's stiffness (eps1, eps2) [N/m] is shared by area (a point of area
dA holds eps dA / A).  A grid of n1 x n2 cells puts each cell's share at its
centre (the midpoint rule), its normal force the grid's linear pressure
(grid_normal_forces), whose first moment is N (p1, p2) exactly: the
continuum's pressure sampled at the centres would have N p1 (1 - 1/n1^2)."""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from .paper import adhesion_tensor, friction_tensor
from .rig import slip_force_tensor

FULL_SLIP_SQUARE_FACTOR = (math.sqrt(2.0) + math.log(1.0 + math.sqrt(2.0))) / 6.0


def cell_centres(length: float, width: float, n1: int, n2: int) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) [m] of the n1 x n2 cells' centres, flattened with x varying
    fastest (cell i + n1 j)."""
    x = (2.0 * np.arange(n1) + 1.0 - n1) / (2.0 * n1) * length
    y = (2.0 * np.arange(n2) + 1.0 - n2) / (2.0 * n2) * width
    X, Y = np.meshgrid(x, y)
    return X.ravel(), Y.ravel()


def grid_normal_forces(length, width, n1: int, n2: int, N, p1=0.0, p2=0.0) -> np.ndarray:
    """The n1 x n2 cells' normal forces [N] (cell_centres' order) of a linear
    pressure with resultant N [N] at (p1, p2) [m]: N_i = N w (1 + p1 x_i / S1
    + p2 y_i / S2), w = 1/(n1 n2), S1 = sum of w x_i^2 = length^2 (1 - 1/n1^2)/12
    (likewise S2), so that sum N_i = N and sum N_i (x_i, y_i) = N (p1, p2)
    exactly.  A side of one cell has S = 0 and cannot carry p along it:
    ValueError for p off that axis while N > 0.  With N <= 0 (no contact)
    every cell gets N w, whatever p."""
    x, y = cell_centres(length, width, n1, n2)
    if not N > 0:
        return np.full(x.shape, N / (n1 * n2))
    share = np.ones(x.shape)
    for p, r, n, name in ((p1, x, n1, "1"), (p2, y, n2, "2")):
        if n == 1:
            if p != 0:
                raise ValueError(f"grid_normal_forces: p{name} = {p!r} m on a grid with n{name} = 1: "
                                 f"its cells all lie on the axis and cannot carry p{name}")
            continue
        share = share + p * r / np.mean(r * r)
    return N / (n1 * n2) * share


def full_slip_translation(mu, N, p1, p2, direction_rad) -> tuple[float, float, float]:
    """(T1, T2, Mz) [N, N, N m] with isotropic friction mu, every point of the
    patch (at theta = 0) sliding along s = (cos, sin)(direction_rad), the body's
    displacement relative to the surface: each point's force is -mu s times
    its normal force, so T = -mu N s acts at the centre of pressure and
    Mz = p x T = -mu N (p1 s2 - p2 s1), for the continuum and for any grid
    whose normal forces have first moment N p (grid_normal_forces)."""
    s1, s2 = math.cos(direction_rad), math.sin(direction_rad)
    return -mu * N * s1, -mu * N * s2, -mu * N * (p1 * s2 - p2 * s1)


def torsional_stiffness(eps1, eps2, alpha, length, width) -> float:
    """k [N m/rad] of the continuum patch sticking, Mz = -k theta for small
    theta: (1/A) integral of (J r) . B (J r) dA with J r = (-y, x), i.e.
    (B11 width^2 + B22 length^2) / 12; for eps1 = eps2 = eps it is
    eps (length^2 + width^2) / 12."""
    B = adhesion_tensor(eps1, eps2, alpha)
    return (B[0, 0] * width**2 + B[1, 1] * length**2) / 12.0


def torsional_stiffness_grid(eps1, eps2, alpha, length, width, n1: int, n2: int) -> float:
    """k [N m/rad] of the n1 x n2 grid: the exact sum over the cells of
    (J r) . B (J r) / (n1 n2).  It equals the continuum's with length^2
    taken as length^2 (1 - 1/n1^2), width^2 as width^2 (1 - 1/n2^2)."""
    B = adhesion_tensor(eps1, eps2, alpha)
    x, y = cell_centres(length, width, n1, n2)
    Jr = np.stack([-y, x])
    return float(np.sum(Jr * (B @ Jr)) / (n1 * n2))


def stick_rotation_torque(eps, length, width, theta, grid: tuple[int, int] | None = None) -> float:
    """Mz [N m] of a patch with isotropic stiffness eps stuck at rest at
    theta = 0 and turned to theta (no translation, any pressure): each point
    is pulled back by eps (R - I) r, whose moment about the centre sums to
    -k sin(theta) exactly, with k the continuum's or (grid = (n1, n2)) the
    grid's torsional stiffness."""
    k = (torsional_stiffness(eps, eps, 0.0, length, width) if grid is None
         else torsional_stiffness_grid(eps, eps, 0.0, length, width, *grid))
    return -k * math.sin(theta)


def stick_rotation_torque_grid(eps1, eps2, alpha, length, width, n1: int, n2: int, theta) -> float:
    """Mz [N m] of the n1 x n2 grid stuck at rest at theta = 0 and turned to
    theta (no translation, any pressure), any stiffness B (eps1, eps2 at
    alpha, the surface's): each cell pulled back by B (R - I) r / (n1 n2), its
    moment about the centre taken at R r.  On the grid's symmetric cells that
    sums to Mz = -k sin(theta) - (S1 - S2) [(B11 - B22) sin(theta) (1 - cos(theta))
    + B12 (cos(2 theta) - cos(theta))], k = torsional_stiffness_grid = B22 S1
    + B11 S2, S1 and S2 the cells' mean x^2 and y^2: -k sin(theta) exactly for
    isotropic stiffness or S1 = S2, otherwise to a relative O(theta^2) with
    B12 = 0 (axes along the patch's sides) and O(theta) with B12 != 0."""
    B = adhesion_tensor(eps1, eps2, alpha)
    x, y = cell_centres(length, width, n1, n2)
    S1, S2 = float(np.mean(x * x)), float(np.mean(y * y))
    k = torsional_stiffness_grid(eps1, eps2, alpha, length, width, n1, n2)
    s, c = math.sin(theta), math.cos(theta)
    return -k * s - (S1 - S2) * ((B[0, 0] - B[1, 1]) * s * (1.0 - c) + B[0, 1] * (math.cos(2 * theta) - c))


def full_slip_torque_square(mu, N, a) -> float:
    """|Mz| [N m] of a square of side a [m] under uniform pressure with
    isotropic friction mu, every point sliding as the body turns about the
    centre: mu N/A times the integral of |r| dA, mu N a (sqrt 2 + ln(1 + sqrt 2))/6."""
    return mu * N * a * FULL_SLIP_SQUARE_FACTOR


def steady_force_direction(mu1, mu2, eps1, eps2, alpha, beta, rule, v):
    """The steady sliding force q [N per N of normal force] of a point that
    slides along v (2 x ..., any length): q parallel to H v (the slip runs
    along G q, rig.slip_force_tensor) on the yield ellipse |q|_F = 1.  The
    surface acts on the body with -q."""
    h11, h12, h22 = slip_force_tensor(mu1, mu2, eps1, eps2, alpha, beta, rule)
    H = np.array([[h11, h12], [h12, h22]])
    F = friction_tensor(mu1, mu2, beta)
    q = H @ np.asarray(v, dtype=float)
    return q / np.sqrt(np.sum(q * (F @ q), axis=0))


@lru_cache(maxsize=8)
def _gauss_legendre(points: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights on [-1, 1], computed once per count (costly at 512)."""
    return np.polynomial.legendre.leggauss(points)


def _rotation_density(mu1, mu2, eps1, eps2, alpha, beta, rule, phi):
    """-q per unit pressure at polar angle phi of a body turning
    counterclockwise about the centre (a point at r slides along J r)."""
    v = np.stack([-np.sin(phi), np.cos(phi)])
    return -steady_force_direction(mu1, mu2, eps1, eps2, alpha, beta, rule, v)


def full_slip_rotation(mu1, mu2, eps1, eps2, alpha, beta, rule, length, width, N,
                       p1=0.0, p2=0.0, points: int = 512) -> tuple[float, float, float]:
    """(T1, T2, Mz) [N, N, N m] on a body turning counterclockwise about the
    patch centre, every point in steady sliding (rule: "associated" or
    "coupled"), at theta = 0: the law's steady force integrated over the
    area.  In polar coordinates the force depends on the angle alone, so the
    radial integral of the linear pressure is exact and the angular one is
    Gauss-Legendre on each side's sector (smooth there, but sharp where H is
    strongly anisotropic: 512 points reach rounding for a contrast of 50)."""
    A = length * width
    c = np.array([12.0 * p1 / length**2, 12.0 * p2 / width**2])
    corner = math.atan2(width, length)
    sectors = [(-corner, corner, 0), (corner, math.pi - corner, 1),
               (math.pi - corner, math.pi + corner, 0), (math.pi + corner, 2 * math.pi - corner, 1)]
    nodes, weights = _gauss_legendre(points)
    T = np.zeros(2)
    Mz = 0.0
    for lo, hi, axis in sectors:
        phi = 0.5 * (hi - lo) * nodes + 0.5 * (hi + lo)
        w = 0.5 * (hi - lo) * weights
        e = np.stack([np.cos(phi), np.sin(phi)])
        rho = (length if axis == 0 else width) / (2.0 * np.abs(e[axis]))
        ce = c @ e
        t = _rotation_density(mu1, mu2, eps1, eps2, alpha, beta, rule, phi)
        # integral over rho of rho (1 + ce rho) and of rho^2 (1 + ce rho)
        r1 = rho**2 / 2 + ce * rho**3 / 3
        r2 = rho**3 / 3 + ce * rho**4 / 4
        T += (t * r1) @ w
        Mz += ((e[0] * t[1] - e[1] * t[0]) * r2) @ w
    return float(N / A * T[0]), float(N / A * T[1]), float(N / A * Mz)


def full_slip_rotation_grid(mu1, mu2, eps1, eps2, alpha, beta, rule, length, width, N, n1: int,
                            n2: int, p1=0.0, p2=0.0) -> tuple[float, float, float]:
    """(T1, T2, Mz) as full_slip_rotation for the n1 x n2 grid: each cell's
    steady force with its normal force (grid_normal_forces) at its centre
    (the midpoint rule)."""
    x, y = cell_centres(length, width, n1, n2)
    Nc = grid_normal_forces(length, width, n1, n2, N, p1, p2)
    at_centre = (x == 0) & (y == 0)   # the centre does not move: no force there
    v = np.stack([np.where(at_centre, 1.0, -y), x])
    t = np.where(at_centre, 0.0,
                 -steady_force_direction(mu1, mu2, eps1, eps2, alpha, beta, rule, v) * Nc)
    return float(t[0].sum()), float(t[1].sum()), float(np.sum(x * t[1] - y * t[0]))
