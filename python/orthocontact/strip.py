"""The Teflon strip in the fit's model: the steady state of sliding with the
strip's Coulomb friction and viscosity (closed_forms.steady_tan_phi_with_strip)
as casadi expressions of the fitted parameters, and the regimes of motion
(which way the block drifts, or held) that model is built for."""
from __future__ import annotations

from . import closed_forms as cf
from .measurements import MeasurementSet, RigSetup


def strip_regimes(data: MeasurementSet, values: dict) -> tuple:
    """Per force and angle point: the sign of the lateral motion with the
    strip at `values` (0: the strip holds the block), the regime the fit's
    model is built for."""
    rig = data.rig
    if rig.mu_strip == 0 and not rig.c_strip and "c_strip" not in values:
        return ()
    N, c = rig.normal_force, values.get("c_strip", rig.c_strip or 0.0)
    pts = [] if data.forces is None else [(a, rig.velocity_m_s) for a, _ in data.forces]
    if data.angles is not None:
        pts += [(a, v) for (a, _), v in zip(data.angles, data.velocities_of_angles())]
    out = []
    for a, v in pts:
        al, be = rig.axes(a)
        t = cf.steady_tan_phi_with_strip(values["mu1"], values["mu2"], values.get("eps_ratio", 1.0) * 1e4,
                                         1e4, al, be, rig.rule, rig.mu_strip, c, v, N)
        out.append(0 if t == 0 else (1 if t > 0 else -1))
    return tuple(out)


def _strip_state(val, start: dict, rig: RigSetup, alpha: float, beta: float, velocity: float,
                 c_free: bool, c_known: float):
    """(tan(phi), q1 [N]) of steady sliding with the strip (closed_forms.
    steady_tan_phi_with_strip) as casadi expressions of the fitted
    parameters: explicit for Coulomb friction alone, through a rootfinder with
    a viscous term.  q1 is the push, so the driving force is F_int + q1.  The
    sign of the lateral motion is the one at the start values (fixed during
    the fit); where the strip holds the block there, tan(phi) = 0 and the
    push is the friction ellipse's along X1."""
    import casadi as ca
    mu1, mu2, ratio = val("mu1"), val("mu2"), val("eps_ratio")
    c = val("c_strip") if c_free else c_known
    N = rig.normal_force
    t_start = cf.steady_tan_phi_with_strip(start["mu1"], start["mu2"], start.get("eps_ratio", 1.0) * 1e4,
                                           1e4, alpha, beta, rig.rule, rig.mu_strip,
                                           start.get("c_strip", c_known), velocity, N)
    s = 1.0 if t_start > 0 else -1.0
    # eps enters the direction only through eps1/eps2: eps2 = 1 N/m here
    f, g = cf.strip_tensors(mu1, mu2, ratio, 1.0, alpha, beta, rig.rule)
    if t_start == 0:
        # held on the X1 axis by the strip: the slip runs along X1, so
        # q is along G^-1 e1, on the yield ellipse
        (f11, f12, f22), (_, g12, g22) = f, g
        k = N / ca.sqrt(f11 * g22 * g22 - 2 * f12 * g22 * g12 + f22 * g12 * g12)
        return 0.0, k * g22

    def state(t):
        return cf.strip_equilibrium(f, g, rig.mu_strip, s, c * velocity, N, t)
    if not (c_free or c_known > 0):  # no viscosity: the push does not depend on t
        q1, _, t = state(0.0)
        return t, q1
    ts = ca.MX.sym("t")
    args = ca.vertcat(*ca.symvar(ca.vertcat(mu1, mu2, ratio, c)))
    res = ca.Function("strip_residual", [ts, args], [ts - state(ts)[2]])
    rf = ca.rootfinder("strip_angle", "newton", res, {"abstol": 1e-14})
    t = rf(t_start, args)
    return t, state(t)[0]
