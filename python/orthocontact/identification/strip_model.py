"""The Teflon strip in the fit's model: the steady state of sliding with the
strip's Coulomb friction and viscosity (closed_forms.steady_tan_phi_with_strip)
as casadi expressions of the fitted parameters, and the regimes of motion
(which way the block drifts, or held) that model is built for."""
from __future__ import annotations

import math

import numpy as np

from .. import closed_forms as cf
from ..experiment.rig_setup import RigSetup
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


def strip_steady_states(val, start: dict, rig: RigSetup, points: list, c_free: bool, c_known: float):
    """(tan(phi), q1 [N]) of steady sliding with the strip (closed_forms.
    steady_strip_state_array) at each point (mat angle [deg], velocity
    [m/s]), as casadi expressions of the fitted parameters: the root of the
    lateral force (closed_forms.strip_lateral_force) in the slope, by one
    casadi Newton rootfinder mapped over the points, from the slope at the
    start values.  q1 is the push, so the driving force is F_int + q1.  The
    sign of each point's lateral motion is the one at the start values
    (fixed during the fit; strip_regimes tells whether the fitted values
    keep it); where the strip holds the block there, tan(phi) = 0 and the
    push is that of slip along X1."""
    import casadi as ca
    N = rig.normal_force
    c = val("c_strip") if c_free else c_known
    params = ca.vertcat(val("mu1"), val("mu2"), val("eps_ratio"), c)
    angles = np.array([a for a, _ in points], float)
    velocities = np.array([v for _, v in points], float)
    alpha, beta = rig.axes(angles)
    t0 = np.zeros(len(points))
    for v in np.unique(velocities):     # the start's slopes, one array per velocity
        m = velocities == v
        ratio = start.get("eps_ratio", 1.0)
        t0[m] = cf.steady_tan_phi_with_strip_array(start["mu1"], start["mu2"], ratio * 1e4, 1e4, alpha[m],
                                                   beta[m], rig.rule, rig.mu_strip,
                                                   start.get("c_strip", c_known), v, N)
    rows = [(al, be, v, 0.0 if t == 0 else math.copysign(1.0, t), t)
            for al, be, v, t in zip(alpha, beta, velocities, t0)]
    p, d, t = ca.MX.sym("p", 4), ca.MX.sym("d", 5), ca.MX.sym("t")

    def balance(slope):
        # eps enters the direction only through eps1/eps2: eps2 = 1 N/m here
        h = cf.slip_force_tensor(p[0], p[1], p[2], 1.0, d[0], d[1], rig.rule)
        return cf.strip_lateral_force(h, cf.friction_entries(p[0], p[1], d[1]), slope, d[3], rig.mu_strip,
                                      p[3] * d[2], N)
    residual = ca.Function("strip_lateral_force", [t, ca.vertcat(p, d)], [balance(t)[0]])
    root = ca.rootfinder("strip_slope", "newton", residual, {"abstol": 1e-14 * N})
    one = ca.Function("strip_steady_state", [p, d], [root(d[4], ca.vertcat(p, d))])
    moving = [i for i, row in enumerate(rows) if row[3] != 0]
    slopes = one.map(len(moving))(ca.repmat(params, 1, len(moving)), np.array([rows[i] for i in moving]).T) \
        if moving else []
    tan_phi = [0.0] * len(rows)
    for k, i in enumerate(moving):
        tan_phi[i] = slopes[k]
    held = ca.Function("strip_push", [t, p, d], [balance(t)[1]])
    push = held.map(len(rows))(ca.horzcat(*[ca.MX(x) if isinstance(x, float) else x for x in tan_phi]),
                               ca.repmat(params, 1, len(rows)), np.array(rows).T)
    return tan_phi, [push[i] for i in range(len(rows))]
