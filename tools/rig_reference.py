"""An independent simulator of the paper's rig, for testing the identification
on data that the code under test did not make.

Written from the law's definition alone (docs/explanation/law.md: q = B(u - s), yield
sqrt(q.Fq) <= N, implicit slip s = s_c + dgamma G q with G = F or (B F B)^-1),
in plain Python floats, with none of the package's code: no FMU, no
yield-coordinate series, no closed form.  The return map is a bracketed
secant (Illinois) on dgamma; the rig is quasi-static (lateral equilibrium
q2 = 0 every step, solved the same way on x2).  Units: N, m, rad.
"""
from __future__ import annotations

import math


def _rot_diag(d1, d2, t):
    c, s = math.cos(t), math.sin(t)
    return (d1 * c * c + d2 * s * s, (d1 - d2) * s * c, d1 * s * s + d2 * c * c)


def _mul(a, b):  # 2x2 as (a11, a12, a21, a22)
    return (a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3],
            a[2] * b[0] + a[3] * b[2], a[2] * b[1] + a[3] * b[3])


def _inv(a):
    det = a[0] * a[3] - a[1] * a[2]
    return (a[3] / det, -a[1] / det, -a[2] / det, a[0] / det)


def _sym(t3):
    return (t3[0], t3[1], t3[1], t3[2])


def _apply(a, x):
    return (a[0] * x[0] + a[1] * x[1], a[2] * x[0] + a[3] * x[1])


def _illinois(f, a, fa, b, fb, tol):
    """A root of f in [a, b] with f(a), f(b) of opposite signs."""
    side = 0
    for _ in range(200):
        c = (a * fb - b * fa) / (fb - fa)
        fc = f(c)
        if fc == 0 or abs(b - a) <= tol:
            return c
        if (fc > 0) == (fb > 0):
            b, fb = c, fc
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb *= 0.5
            side = 1
    return c


class Interface:
    """The contact law at fixed parameters: force of a displacement from a
    committed slip, and the commit."""

    def __init__(self, mu1, mu2, eps1, eps2, alpha, beta, rule):
        self.B = _sym(_rot_diag(eps1, eps2, alpha))
        self.F = _sym(_rot_diag(1 / mu1**2, 1 / mu2**2, beta))
        self.G = self.F if rule == "associated" else _inv(_mul(_mul(self.B, self.F), self.B))
        self.BG = _mul(self.B, self.G)
        self.Binv = _inv(self.B)

    def _norm(self, q):
        Fq = _apply(self.F, q)
        return math.sqrt(q[0] * Fq[0] + q[1] * Fq[1])

    def force(self, u, s, N):
        """q [N] for the displacement u [m] from the committed slip s [m]."""
        q_tr = _apply(self.B, (u[0] - s[0], u[1] - s[1]))
        if self._norm(q_tr) <= N:
            return q_tr

        def q_of(g):
            m = (1 + g * self.BG[0], g * self.BG[1], g * self.BG[2], 1 + g * self.BG[3])
            return _apply(_inv(m), q_tr)

        def phi(g):
            return self._norm(q_of(g)) - N
        # The root if BG were its largest eigenvalue (at most its trace)
        # times I: below the root then; the bracket widened from there.
        hi = (self._norm(q_tr) / N - 1.0) / (self.BG[0] + self.BG[3])
        f_hi = phi(hi)
        while f_hi > 0:
            hi *= 4
            f_hi = phi(hi)
        g = _illinois(phi, 0.0, phi(0.0), hi, f_hi, 1e-15 * hi)
        return q_of(g)

    def slip_after(self, u, q):
        """The committed slip once u is taken with force q: s = u - B^-1 q."""
        e = _apply(self.Binv, q)
        return (u[0] - e[0], u[1] - e[1])


def run_rig(mu1, mu2, eps1, eps2, alpha, beta, rule, N, travel, steps, fit_from=0.5,
            mu_strip=0.0, c_strip=0.0, velocity=1.0):
    """Quasi-static rig: x1 = travel k / steps, x2 from the lateral balance
    each step: q2 = 0 without a strip; with one, the strip holds the block
    while |q2| <= mu_strip q1, else q2 = -mu_strip s q1 - c_strip v2 with s
    the sign of the lateral motion and v2 = (x2 - x2_before) / dt [m/s],
    dt = travel / (steps velocity).  Returns (x1 list, x2 list, q1 list)."""
    law = Interface(mu1, mu2, eps1, eps2, alpha, beta, rule)
    s = (0.0, 0.0)
    x2 = 0.0
    xs1, xs2, q1s = [], [], []
    scale = min(mu1, mu2) * N / max(eps1, eps2)
    visc = c_strip * steps * velocity / travel      # c_strip / dt [N/m]
    for k in range(1, steps + 1):
        x1 = travel * k / steps
        x2_before = x2
        q_here = law.force((x1, x2), s, N)
        if mu_strip > 0 and abs(q_here[1]) <= mu_strip * max(q_here[0], 0.0):
            side = 0.0      # held by the strip's friction
        else:
            side = -math.copysign(1.0, q_here[1]) if mu_strip > 0 else 0.0

        def r(y, x1=x1, s=s, side=side, x2_before=x2_before):   # this step's, bound now
            q = law.force((x1, y), s, N)
            if mu_strip > 0 and side == 0.0:
                return 0.0
            return q[1] + mu_strip * side * max(q[0], 0.0) + visc * (y - x2_before)
        r0 = r(x2)
        if r0 != 0:
            # r rises with x2 (B is positive definite, the return map
            # monotone): step against the sign of r until it changes
            step = scale
            b, fb = x2 - math.copysign(step, r0), None
            fb = r(b)
            while (fb > 0) == (r0 > 0) and fb != 0:
                step *= 2
                if step > 1.0:
                    raise RuntimeError("no lateral equilibrium within 1 m")
                b = x2 - math.copysign(step, r0)
                fb = r(b)
            x2 = b if fb == 0 else _illinois(r, x2, r0, b, fb, 1e-17 + 1e-15 * abs(b))
        q = law.force((x1, x2), s, N)
        s = law.slip_after((x1, x2), q)
        xs1.append(x1)
        xs2.append(x2)
        q1s.append(q[0])
    return xs1, xs2, q1s


def measure(mu1, mu2, eps1, eps2, rule, alpha_offset, beta_offset, angles_deg, N, f_int,
            travel=0.05, steps=200):
    """The steady trajectory angle [deg, counterclockwise] and mean driving
    force [N] at each orientation [deg] (fit over the second half)."""
    out = {}
    for a in angles_deg:
        t = math.radians(a)
        x1, x2, q1 = run_rig(mu1, mu2, eps1, eps2, t + alpha_offset, t + beta_offset, rule, N,
                             travel, steps)
        k = len(x1) // 2
        X, Y = x1[k:], x2[k:]
        n = len(X)
        mx, my = sum(X) / n, sum(Y) / n
        slope = sum((x - mx) * (y - my) for x, y in zip(X, Y)) / sum((x - mx) ** 2 for x in X)
        out[a] = (math.degrees(math.atan(slope)), f_int + sum(q1[k:]) / n)
    return out


def ramp(mu1, mu2, eps1, eps2, rule, alpha_offset, beta_offset, angle_deg, N, f_int, x1_max,
         steps=400):
    """(x1 [m], driving force [N]) over the start of a pull."""
    t = math.radians(angle_deg)
    x1, _, q1 = run_rig(mu1, mu2, eps1, eps2, t + alpha_offset, t + beta_offset, rule, N, x1_max,
                        steps)
    return [(a, f_int + b) for a, b in zip(x1, q1)]
