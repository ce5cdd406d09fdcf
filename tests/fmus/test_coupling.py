"""A body coupled to the contact FMU as a user's simulator couples it (through
fmpy, both FMI versions): a mass m = 0.05 kg pushed by a constant force F
from rest on the unloaded contact, stiffness eps1 = 25,000 N/m along the push.
The truth is the stuck mass-spring, u(t) = u_eq (1 - cos w t), u_eq = F/eps1,
w = sqrt(eps1/m): the contact never carries more than 2F, below its friction
limit, so the body sticks and nothing is dissipated.

The explicit coupling (the loop of the FMU's documentation: the body steps
with the contact's force held, symplectic Euler; the contact takes the new
position) is the central-difference update of that spring,
u[n+1] - 2 u[n] + u[n-1] = h^2 (F - eps u[n]) / m, stable only for h w < 2:
h < 2 sqrt(m / eps_max) = 2.83 ms here.  At h = 4 ms (h w = 2.83) its first
step loads the contact with (h w)^2 F = 8 F and the body slides; at 1 ms it
sticks on the scheme's closed form.  A Newton iteration per step on the
trapezoidal update, with the FMU's directional derivative of T with respect
to u, sticks at 4 ms on its own closed form, u[n] = u_eq (1 - cos(n theta)),
theta = 2 atan(h w / 2): the amplitude of the truth, a phase that lags."""
import math
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description

from fmu_values import unzipped
from orthocontact.fmu import find_fmu

M = 0.05                  # the body [kg]
EPS1 = 25000.0            # stick stiffness along the push [N/m], the larger of the two
EPS2 = 1e4
N = M * 9.81              # [N]
MU = 0.5
LIMIT = MU * N            # friction limit along X1 [N]
F = 0.3 * LIMIT           # the push [N]: the truth's largest force, 2 F, is 0.6 of the limit
U_EQ = F / EPS1           # [m]
W = math.sqrt(EPS1 / M)   # [rad/s]
H_LIMIT = 2 * math.sqrt(M / EPS1)   # the explicit coupling's largest stable step [s]
H_LARGE, H_SMALL = 4e-3, 1e-3       # [s]
T_END = 0.052             # [s]: 13 large steps

# A residual check at the level of rounding: the stuck step is linear in u,
# so with the exact tangent Newton's first update solves it and the second
# only confirms (anything above ~10 eps u_eq is not rounding).
NEWTON_TOL = 1e-13 * U_EQ
# The closed forms to 1e-12 u_eq: the runs' rounding is a few eps u_eq a step
# over 13-52 steps (measured 1.4e-15 and 4.3e-15 u_eq), a margin of hundreds,
# while a step of the scheme or the law off by one part in 1e12 would fail.
CLOSED_FORM_TOL = 1e-12 * U_EQ


class Contact:
    """The contact FMU through fmpy: the calls a simulator makes."""

    def __init__(self, version, mu=MU):
        path = str(find_fmu(fmi_version=version))
        md = read_model_description(path)
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        if version == 2:
            from fmpy.fmi2 import FMU2Slave as Slave
        else:
            from fmpy.fmi3 import FMU3Slave as Slave
        self.version = version
        self.s = Slave(guid=md.guid, unzipDirectory=unzipped(path), modelIdentifier="OrthotropicContact",
                       instanceName="coupled")
        self.s.instantiate()
        self.set = self.s.setReal if version == 2 else self.s.setFloat64
        self.get = self.s.getReal if version == 2 else self.s.getFloat64
        self.set([self.vr[k] for k in ("mu1", "mu2", "eps1", "eps2", "alpha", "beta")],
                 [mu, mu, EPS1, EPS2, 0.0, 0.0])
        if version == 2:
            self.s.setupExperiment(startTime=0.0)
            self.s.enterInitializationMode()
        else:
            self.s.enterInitializationMode(startTime=0.0)
        self.set([self.vr["u1"], self.vr["u2"], self.vr["N"]], [0.0, 0.0, N])
        self.s.exitInitializationMode()
        self.t = 0.0

    def force(self, u):
        """T [N] for the body at u [m]: the pending step's, nothing committed."""
        self.set([self.vr["u1"], self.vr["u2"], self.vr["N"]], [u[0], u[1], N])
        return np.array(self.get([self.vr["T1"], self.vr["T2"]]))

    def tangent(self):
        """dT/du [N/m], 2x2, from fmi2GetDirectionalDerivative / fmi3GetDirectionalDerivative."""
        T = [self.vr["T1"], self.vr["T2"]]
        return np.array([self.s.getDirectionalDerivative(T, [self.vr[k]], [1.0]) for k in ("u1", "u2")]).T

    def commit(self, h):
        """doStep: the state (0 open, 1 stick, 2 slip), s1 [m] and the energy [J] of the step."""
        self.s.doStep(self.t, h)
        self.t += h
        state = (self.s.getInteger if self.version == 2 else self.s.getInt32)([self.vr["contactState"]])[0]
        s1, energy = self.get([self.vr["s1"], self.vr["dissipatedEnergy"]])
        return state, s1, energy

    def close(self):
        self.s.terminate()
        self.s.freeInstance()


def explicit(version, h, mu=MU, t_end=T_END):
    """The explicit coupling: positions u[n], velocities v[n], states and the
    contact's last s1 and energy."""
    c = Contact(version, mu)
    u, v, T, push = np.zeros(2), np.zeros(2), np.zeros(2), np.array([F, 0.0])
    us, vs, states = [], [], []
    try:
        for _ in range(round(t_end / h)):
            v = v + h * (push + T) / M          # the body's step, T held
            u = u + h * v
            T = c.force(u)                       # the contact at the new position
            state, s1, energy = c.commit(h)
            us.append(u)
            vs.append(v)
            states.append(state)
    finally:
        c.close()
    return np.array(us), np.array(vs), states, s1, energy


def newton(version, h, t_end=T_END):
    """Trapezoidal steps of the body, each solved by Newton on the pending
    step with the FMU's tangent: R(u) = u - u[n] - h v[n] - h^2/4 (a[n] + a(u)),
    dR/du = I - h^2/(4 m) dT/du.  Returns u[n], states, iterations per step,
    the last s1 and energy."""
    c = Contact(version)
    push = np.array([F, 0.0])
    u, v, a = np.zeros(2), np.zeros(2), push / M
    us, states, iterations = [], [], []
    try:
        for _ in range(round(t_end / h)):
            x = u.copy()   # from where the contact holds: the pending step sticks there
            for k in range(1, 11):   # noqa: B007 (k, the iterations taken, is read after the loop)
                R = x - u - h * v - h * h / 4 * (a + (push + c.force(x)) / M)
                dx = np.linalg.solve(np.eye(2) - h * h / (4 * M) * c.tangent(), -R)
                x = x + dx
                if np.max(np.abs(dx)) <= NEWTON_TOL:
                    break
            iterations.append(k)
            a_next = (push + c.force(x)) / M     # the pending step at the solution
            v = v + h / 2 * (a + a_next)
            u, a = x, a_next
            state, s1, energy = c.commit(h)
            us.append(u)
            states.append(state)
    finally:
        c.close()
    return np.array(us), states, iterations, s1, energy


@pytest.mark.parametrize("version", [2, 3])
def test_explicit_coupling_above_the_step_limit_slides_where_the_body_sticks(version):
    assert H_LARGE * W == pytest.approx(2 * math.sqrt(2)) and H_LARGE > H_LIMIT
    us, _, states, s1, energy = explicit(version, H_LARGE)
    assert us[0, 0] == pytest.approx(8 * U_EQ, rel=1e-12)   # (h w)^2 u_eq: 8 F on the contact ...
    assert 8 * F > LIMIT and states[0] == 2                   # ... beyond the limit: slides on step 1
    assert s1 > 10 * U_EQ and energy > 0                      # the truth: no slip, 0 J


@pytest.mark.parametrize("version", [2, 3])
def test_explicit_coupling_above_the_step_limit_gains_energy_while_it_sticks(version):
    """With friction enough to stick for a few steps the explicit update's
    energy grows by |lambda|^2 = 34 a step, lambda = c - sqrt(c^2 - 1),
    c = 1 - (h w)^2 / 2, where the truth keeps 1/2 eps u_eq^2."""
    us, vs, states, _, _ = explicit(version, H_LARGE, mu=100.0, t_end=5 * H_LARGE)
    stuck = states.index(2) if 2 in states else len(states)
    assert stuck >= 3
    energy = 0.5 * M * vs[:stuck, 0] ** 2 + 0.5 * EPS1 * (us[:stuck, 0] - U_EQ) ** 2
    c = 1 - (H_LARGE * W) ** 2 / 2
    lam = c - math.sqrt(c * c - 1)
    assert energy[stuck - 1] > 1000 * 0.5 * EPS1 * U_EQ ** 2
    assert (us[stuck - 1, 0] - U_EQ) / (us[stuck - 2, 0] - U_EQ) == pytest.approx(lam, rel=1e-3)


@pytest.mark.parametrize("version", [2, 3])
def test_explicit_coupling_below_the_step_limit_sticks_on_its_closed_form(version):
    """u[n] = u_eq (1 - cos(n phi) + tan(phi/2) sin(n phi)), cos phi = 1 - (h w)^2 / 2."""
    assert H_SMALL < H_LIMIT
    us, _, states, s1, energy = explicit(version, H_SMALL)
    assert set(states) == {1} and s1 == 0.0 and energy == 0.0
    n = np.arange(1, len(us) + 1)
    phi = math.acos(1 - (H_SMALL * W) ** 2 / 2)
    closed = U_EQ * (1 - np.cos(n * phi) + math.tan(phi / 2) * np.sin(n * phi))
    assert np.max(np.abs(us[:, 0] - closed)) <= CLOSED_FORM_TOL
    assert np.all(us[:, 1] == 0.0)
    assert EPS1 * np.max(us[:, 0]) < LIMIT


@pytest.mark.parametrize("version", [2, 3])
def test_newton_coupling_with_the_fmus_derivatives_sticks_at_the_large_step(version):
    us, states, iterations, s1, energy = newton(version, H_LARGE)
    assert len(us) == 13 and set(states) == {1} and s1 == 0.0 and energy == 0.0
    # from a stuck start the exact stick tangent solves each step in one update (a second confirms)
    assert set(iterations) == {2}
    n = np.arange(1, len(us) + 1)
    theta = 2 * math.atan(H_LARGE * W / 2)
    assert np.max(np.abs(us[:, 0] - U_EQ * (1 - np.cos(n * theta)))) <= CLOSED_FORM_TOL
    assert np.all(us[:, 1] == 0.0)
    assert np.max(us[:, 0]) <= 2 * U_EQ * (1 + 1e-12)   # the truth's amplitude, never beyond


@pytest.mark.parametrize("version", [2, 3])
def test_the_fmus_documentation_states_the_limit_with_this_example(version):
    """documentation/index.html: the formula, this file's example with the
    numbers computed here, and the version's own derivative function."""
    text = zipfile.ZipFile(find_fmu(fmi_version=version)).read("documentation/index.html").decode()
    assert "<b>h &lt; 2 sqrt(m / &epsilon;<sub>max</sub>)</b>" in text
    assert f"m = {M} kg on &epsilon;<sub>max</sub> = {EPS1:,.0f} N/m" in text
    assert f"h &lt; 2 sqrt({M} / {EPS1:.0f}) = {H_LIMIT * 1e3:.2f} ms" in text
    assert f"At h = {H_LARGE * 1e3:.0f} ms (h &omega; = {H_LARGE * W:.2f})" in text
    assert f"= {(H_LARGE * W) ** 2:.0f} F / &epsilon;" in text
    assert f"fmi{version}GetDirectionalDerivative" in text


# -- the patch turning: the same limit in rotation, h < 2 sqrt(I / k) ----------------

def _turn_explicitly(version, h, steps):
    """A body of inertia I on a 0.1 m x 0.1 m patch of 4 x 4 cells (isotropic
    eps = 1e4 N/m, mu = 0.5, N = 10 N), turned from rest about the patch
    centre by a constant moment, coupled explicitly: the body steps with the
    patch's moment held, the patch takes the new angle.  Returns the angles,
    the contact states and the dissipated energy."""
    from orthocontact.fmu.params import ContactParams
    from orthocontact.fmu.patch import PatchFMU, PatchGeometry
    law = ContactParams(0.5, 0.5, 1e4, 1e4)
    theta, omega, Mz, angles, states = 0.0, 0.0, 0.0, [], []
    with PatchFMU(fmi_version=version) as f:
        f.initialize(law, PatchGeometry(0.1, 0.1, 4, 4), inputs=(0.0, 0.0, 0.0, PATCH_N))
        for _ in range(steps):
            omega += h * (PATCH_MOMENT + Mz) / INERTIA
            theta += h * omega
            f.set_inputs(0.0, 0.0, theta, PATCH_N)
            out = f.outputs()
            Mz = out["Mz"]
            angles.append(theta)
            states.append(out["contactState"])
            f.do_step(h)
        return np.array(angles), states, out["dissipatedEnergy"]


INERTIA = 1e-4                                        # [kg m^2]
PATCH_N = 10.0                                        # [N]
K_PATCH = 1e4 * (0.1**2 + 0.1**2) * (1 - 1 / 16) / 12  # the 4 x 4 grid's torsional stiffness [N m/rad]
# A corner cell (r = 0.0375 sqrt 2 m) slides past mu N / (eps r) [rad] (its
# shares of eps and N alike); the moment holds the body at a quarter of it,
# so the stuck truth, never past twice that, stays below it.
CORNER_SLIDES = 0.5 * PATCH_N / (1e4 * 0.0375 * math.sqrt(2))
PATCH_MOMENT = K_PATCH * 0.25 * CORNER_SLIDES         # [N m]
W_TURN = math.sqrt(K_PATCH / INERTIA)                 # [rad/s]


@pytest.mark.parametrize("version", [2, 3])
def test_the_patch_turning_explicitly_slides_above_2_sqrt_I_over_k_and_sticks_below(version):
    """Above h = 2 sqrt(I/k) (h w = 2.83) the first step turns the body by
    (h w)^2 theta_eq = 2 CORNER_SLIDES: the corner cells slide at once.
    Below (h w = 1) it sticks for 300 steps, dissipates nothing, and follows
    the same scheme run on the stuck patch's closed-form moment, -k sin theta
    (closed_forms.patch.stick_rotation_torque); the scheme on the linear
    spring, theta_n = theta_eq (1 - cos((n + 1/2) phi) / cos(phi / 2)) with
    cos phi = 1 - (h w)^2 / 2, never exceeds 2.155 theta_eq (a peak 2.0 at
    the sampled steps, phi being 60 deg)."""
    from orthocontact.closed_forms import patch as cp
    assert K_PATCH == pytest.approx(cp.torsional_stiffness_grid(1e4, 1e4, 0.0, 0.1, 0.1, 4, 4), rel=1e-12)
    theta_eq = PATCH_MOMENT / K_PATCH
    angles, states, energy = _turn_explicitly(version, 2 * math.sqrt(2) / W_TURN, 3)
    assert angles[0] == pytest.approx(8 * theta_eq, rel=1e-12) and states[0] == 2 and energy > 0
    angles, states, energy = _turn_explicitly(version, 1.0 / W_TURN, 300)
    assert set(states) == {1} and energy == 0.0
    h, theta, omega, scheme = 1.0 / W_TURN, 0.0, 0.0, []
    for _ in range(300):
        omega += h * (PATCH_MOMENT + cp.stick_rotation_torque(1e4, 0.1, 0.1, theta, grid=(4, 4))) / INERTIA
        theta += h * omega
        scheme.append(theta)
    np.testing.assert_allclose(angles, scheme, rtol=1e-9)
    assert 1.99 * theta_eq < angles.max() < 2.01 * theta_eq
