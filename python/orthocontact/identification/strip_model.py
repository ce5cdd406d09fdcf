"""The Teflon strip in the fit's model: the steady state of sliding with the
strip's Coulomb friction and viscosity (closed_forms.steady_tan_phi_with_strip)
as casadi expressions of the fitted parameters, and the regimes of motion
(which way the block drifts, or held) that model is built for."""
from __future__ import annotations

import math

import numpy as np

from .. import closed_forms as cf
from ..experiment import RigSetup
from .measurements import MeasurementSet


def strip_regimes(data: MeasurementSet, values: dict) -> tuple:
    """Per force and angle point: the sign of the lateral motion with the
    strip at `values` (0: the strip holds the block), the regime the fit's
    model is built for."""
    rig = data.rig
    if rig.mu_strip == 0:   # the sign enters only through the strip's Coulomb friction
        return ()
    N, c = rig.normal_force, values.get("c_strip", rig.c_strip or 0.0)
    pts = [] if data.forces is None else [(a, v) for (a, _), v in
                                          zip(data.forces, data.velocities_of_forces())]
    if data.angles is not None:
        pts += [(a, v) for (a, _), v in zip(data.angles, data.velocities_of_angles())]
    out = []
    for a, v in pts:
        al, be = rig.axes(a)
        t = cf.steady_tan_phi_with_strip(values["mu1"], values["mu2"], values.get("eps_ratio", 1.0) * 1e4,
                                         1e4, al, be, rig.rule, rig.mu_strip, c, v, N)
        out.append(0 if t == 0 else (1 if t > 0 else -1))
    return tuple(out)


# Newton steps from the start values' slope: quadratic convergence reaches rounding in
# four for the steps a fit takes; the force left says at the solution whether it did
# (FitModel.strip_roots_converged), and the fit is made again from there if not.
NEWTON_STEPS = 4


def strip_steady_states(val, start: dict, rig: RigSetup, points: list, c_free: bool, c_known: float):
    """(tan(phi), q1 [N], the lateral force left [N], 0 where held) of steady sliding with
    the strip (closed_forms.steady_strip_state_array) at each point (mat
    angle [deg], velocity [m/s]), as casadi expressions of the fitted
    parameters: NEWTON_STEPS Newton steps on the lateral force
    (closed_forms.strip_lateral_force) in the slope, unrolled from the slope
    at the start values, so that the fit's Jacobian is exact algebra
    (scalar graph) and the root's derivative that of the implicit function
    once the steps have converged: the force left at the last step tells.
    q1 is the push, so the driving force is F_int + q1.  The sign of each
    point's lateral motion is the one at the start values (fixed during the
    fit; strip_regimes tells whether the fitted values keep it); where the
    strip holds the block there, tan(phi) = 0 and the push is that of slip
    along X1."""
    import casadi as ca
    N = rig.normal_force
    c = val("c_strip") if c_free else c_known
    mu1, mu2, ratio = val("mu1"), val("mu2"), val("eps_ratio")
    angles = np.array([a for a, _ in points], float)
    velocities = np.array([v for _, v in points], float)
    alpha, beta = rig.axes(angles)
    t0 = np.zeros(len(points))
    eps1, c0 = start.get("eps_ratio", 1.0) * 1e4, start.get("c_strip", c_known)
    for v in np.unique(velocities):     # the start's slopes, one array per velocity
        m = velocities == v
        t0[m] = cf.steady_tan_phi_with_strip_array(start["mu1"], start["mu2"], eps1, 1e4, alpha[m], beta[m],
                                                   rig.rule, rig.mu_strip, c0, v, N)
    # one Newton step and the balance as functions of (slope, parameters, point), inlined per point
    t, p, d = ca.SX.sym("t"), ca.SX.sym("p", 4), ca.SX.sym("d", 4)

    def balance(slope):
        # eps enters the direction only through eps1/eps2: eps2 = 1 N/m here
        h = cf.slip_force_tensor(p[0], p[1], p[2], 1.0, d[0], d[1], rig.rule)
        return cf.strip_lateral_force(h, cf.friction_entries(p[0], p[1], d[1]), slope, d[3], rig.mu_strip,
                                      p[3] * d[2], N)
    lateral, q1 = balance(t)
    newton = ca.Function("strip_newton_step", [t, p, d], [t - lateral / ca.jacobian(lateral, t)])
    state = ca.Function("strip_balance", [t, p, d], [lateral, q1])
    params = ca.vertcat(mu1, mu2, ratio, c)
    tan_phi, push, left = [], [], []
    for al, be, v, slope in zip(alpha, beta, velocities, t0):
        point = ca.DM([al, be, v, 0.0 if slope == 0 else math.copysign(1.0, slope)])
        slope = float(slope)
        if point[3] != 0:
            for _ in range(NEWTON_STEPS):
                slope = newton(slope, params, point)
        force_left, push_x1 = state(slope, params, point)
        tan_phi.append(slope)
        push.append(push_x1)
        # a held block is no root: the strip's friction takes what is left (strip_regimes)
        left.append(force_left if point[3] != 0 else 0.0)
    return tan_phi, push, left
