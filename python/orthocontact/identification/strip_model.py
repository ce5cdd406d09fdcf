"""The Teflon strip in the fit's model: the steady state of sliding with the
strip's Coulomb friction and viscosity (closed_forms.steady_tan_phi_with_strip)
as casadi expressions of the fitted parameters, and the regimes of motion
(which way the block drifts, or held) that model is built for."""
from __future__ import annotations

from .. import closed_forms as cf
from ..experiment.rig_setup import RigSetup
from .measurements import MeasurementSet


def strip_regimes(data: MeasurementSet, values: dict) -> tuple:
    """Per force and angle point: the sign of the lateral motion with the
    strip at `values` (0: the strip holds the block), the regime the fit's
    model is built for."""
    rig = data.rig
    if rig.mu_strip == 0 and not rig.c_strip and "c_strip" not in values:
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


def strip_steady_state(val, start: dict, rig: RigSetup, alpha: float, beta: float, velocity: float,
                       c_free: bool, c_known: float):
    """(tan(phi), q1 [N]) of steady sliding with the strip (closed_forms.
    steady_strip_state_array) as casadi expressions of the fitted
    parameters: the root of the lateral force (closed_forms.
    strip_lateral_force) in the slope, by casadi's Newton rootfinder from
    the slope at the start values.  q1 is the push, so the driving force is
    F_int + q1.  The sign of the lateral motion is the one at the start values
    (fixed during the fit); where the strip holds the block there,
    tan(phi) = 0 and the push is that of slip along X1."""
    import casadi as ca
    mu1, mu2, ratio = val("mu1"), val("mu2"), val("eps_ratio")
    c = val("c_strip") if c_free else c_known
    N = rig.normal_force
    t_start = cf.steady_tan_phi_with_strip(start["mu1"], start["mu2"], start.get("eps_ratio", 1.0) * 1e4,
                                           1e4, alpha, beta, rig.rule, rig.mu_strip,
                                           start.get("c_strip", c_known), velocity, N)
    sign = 0.0 if t_start == 0 else (1.0 if t_start > 0 else -1.0)
    # eps enters the direction only through eps1/eps2: eps2 = 1 N/m here
    h = cf.slip_force_tensor(mu1, mu2, ratio, 1.0, alpha, beta, rig.rule)
    f = cf.friction_entries(mu1, mu2, beta)

    def balance(t):
        return cf.strip_lateral_force(h, f, t, sign, rig.mu_strip, c * velocity, N)
    if sign == 0:
        return 0.0, balance(0.0)[1]
    sym = ca.MX if any(isinstance(x, ca.MX) for x in (*h, c)) else ca.SX
    ts = sym.sym("t")
    args = ca.vertcat(*ca.symvar(ca.vertcat(mu1, mu2, ratio, c)))
    res = ca.Function("strip_lateral_force", [ts, args], [balance(ts)[0]])
    rf = ca.rootfinder("strip_slope", "newton", res, {"abstol": 1e-14 * N})
    t = rf(t_start, args)
    return t, balance(t)[1]
