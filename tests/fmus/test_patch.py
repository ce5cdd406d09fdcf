"""The ContactPatch FMU through fmpy, both FMI versions, against independent
truths: the point FMU bit for bit (one cell), the point law's force in
uniform translation (any grid), the torsional stiffness and the full-slip
torque and force of closed_forms.patch, finite differences for the
directional derivatives; and the point FMU's contracts (ranges refused with
a reason, all-or-nothing steps, a damaged state refused; a state restored
into a fresh instance: tests/conformance/test_state.py).

The FMUs: $ORTHOCONTACT_PATCH_FMU / $ORTHOCONTACT_PATCH_FMU3 (e.g. a CMake
build's fmi2/ContactPatch.fmu), else the installed ones.  The point FMU
compared with is the one beside the patch FMU when there is one (the same
build), else the installed one."""
import math
import os
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException

from orthocontact.closed_forms import patch as cp
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.slave import instantiate, integer_call

PATCH_ENV = {2: "ORTHOCONTACT_PATCH_FMU", 3: "ORTHOCONTACT_PATCH_FMU3"}
INTEGERS = ("n1", "n2", "slidingRule", "initialSlip")
RULES = {"associated": 1, "coupled": 2, "eq20": 3}
AGED = dict(mu1=0.408, mu2=0.625, eps1=1.251e4, eps2=1e4, alpha=math.radians(90 + 39.2),
            beta=math.radians(39.2))


def patch_fmu(version):
    return find_fmu(os.environ.get(PATCH_ENV[version]) or None, fmi_version=version,
                    model="ContactPatch")


def point_fmu(version):
    beside = Path(patch_fmu(version)).with_name("OrthotropicContact.fmu")
    return beside if beside.is_file() else find_fmu(fmi_version=version)


class Slave:
    """One instance of a contact FMU (the patch or the point) through fmpy:
    parameters set before initialization, inputs by name, outputs by name."""

    def __init__(self, path, version, name="patch", **params):
        path = str(path)
        md = read_model_description(path)
        self.version = version
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.types = {v.name: v.type for v in md.modelVariables}
        self.messages = []
        # as the package instantiates an FMU: each instance's log lines its own
        self.s, self.callbacks = instantiate(path, md, name,
                                             lambda status, category, text: self.messages.append(text))
        self.t = 0.0
        self.initialized = False
        self.set(**params)

    def initialize(self, **inputs):
        if self.version == 2:
            self.s.setupExperiment(startTime=0.0)
            self.s.enterInitializationMode()
        else:
            self.s.enterInitializationMode(startTime=0.0)
        self.set(**inputs)
        self.s.exitInitializationMode()
        self.initialized = True
        return self

    def set(self, **values):
        for name, v in values.items():
            if name in INTEGERS:   # in FMI 3.0 n1, n2 UInt64, the enumerations Int64
                integer_call(self.s, self.version, self.types[name])([self.vr[name]], [int(v)])
            else:
                (self.s.setReal if self.version == 2 else self.s.setFloat64)([self.vr[name]], [float(v)])

    def get(self, *names):
        out = []
        for n in names:
            if n == "contactState":
                out.append((self.s.getInteger if self.version == 2 else self.s.getInt32)([self.vr[n]])[0])
            else:
                out.append((self.s.getReal if self.version == 2 else self.s.getFloat64)([self.vr[n]])[0])
        return out if len(out) > 1 else out[0]

    def step(self, h=1e-3):
        self.s.doStep(self.t, h)
        self.t += h

    def move(self, h=1e-3, **inputs):
        self.set(**inputs)
        self.step(h)

    def derivative(self, unknowns, knowns, seed):
        u = [self.vr[n] for n in unknowns]
        k = [self.vr[n] for n in knowns]
        if self.version == 2:
            return list(self.s.getDirectionalDerivative(u, k, seed))
        return list(self.s.getDirectionalDerivative(u, k, seed))

    def close(self):
        try:
            if self.initialized:
                self.s.terminate()
        finally:
            self.s.freeInstance()


@pytest.fixture(params=[2, 3], ids=["fmi2", "fmi3"])
def version(request):
    return request.param


@pytest.fixture
def make(version):
    made = []

    def _make(point=False, **params):
        s = Slave(point_fmu(version) if point else patch_fmu(version), version,
                  name=f"s{len(made)}", **params)
        made.append(s)
        return s

    yield _make
    for s in made:
        s.close()


OUT = ("T1", "T2", "dissipatedEnergy")


def _bits(x):
    return np.float64(x).tobytes()


# -- one cell is the point ---------------------------------------------------------


@pytest.mark.parametrize("rule", ["associated", "coupled", "eq20"])
def test_one_cell_is_the_point_fmu_bit_for_bit(make, rule):
    """n1 = n2 = 1: the cell sits at the centre, carries all of N and eps:
    every step's T1, T2, dissipatedEnergy are the point FMU's, bit for bit
    (the contact state 2, slip, reads 3, every pressed cell slips)."""
    params = dict(AGED, slidingRule=RULES[rule])
    patch = make(n1=1, n2=1, length=0.05, width=0.02, **params).initialize(u1=0.001, u2=-0.002, N=18.0)
    point = make(point=True, **params).initialize(u1=0.001, u2=-0.002, N=18.0)
    rng = np.random.default_rng(25)
    u = np.array([0.001, -0.002])
    for k in range(300):
        u = u + rng.normal(scale=2e-4, size=2)
        N = 18.0 if k % 50 < 45 else -1.0
        theta = rng.normal(scale=0.3)   # turns the body about the cell's centre: no effect
        patch.move(u1=u[0], u2=u[1], N=N, theta=theta)
        point.move(u1=u[0], u2=u[1], N=N)
        for name in OUT:
            assert _bits(patch.get(name)) == _bits(point.get(name)), (k, name)
        state = point.get("contactState")
        assert patch.get("contactState") == (3 if state == 2 else state)
        assert patch.get("Mz") == 0.0


@pytest.mark.parametrize("s_start", [(0.0, 0.0), (3e-4, -1e-4)])
def test_one_cell_with_an_explicit_initial_slip_is_the_point_fmu(make, s_start):
    """initialSlip = explicit: the cell starts at slip (s1Start, s2Start), as
    the point does; bit for bit on the first steps."""
    params = dict(AGED, initialSlip=2, s1Start=s_start[0], s2Start=s_start[1])
    patch = make(n1=1, n2=1, **params).initialize(u1=1e-3, u2=5e-4, N=18.0)
    point = make(point=True, **params).initialize(u1=1e-3, u2=5e-4, N=18.0)
    for k in range(5):
        patch.move(u1=1e-3 + 1e-4 * k, u2=5e-4, N=18.0)
        point.move(u1=1e-3 + 1e-4 * k, u2=5e-4, N=18.0)
        assert [_bits(patch.get(n)) for n in OUT] == [_bits(point.get(n)) for n in OUT], k
    assert patch.get("dissipatedEnergy") > 0


# -- translation ---------------------------------------------------------------------


@pytest.mark.parametrize("rule", ["associated", "coupled"])
@pytest.mark.parametrize("grid", [(2, 3), (7, 4)])
def test_uniform_translation_is_the_point_law_for_any_grid(make, rule, grid):
    """Uniform pressure, theta = 0: every cell is the point law with N and eps
    scaled by its share, so T is the point's (homogeneity, to rounding) and
    Mz = 0 by symmetry."""
    params = dict(AGED, slidingRule=RULES[rule])
    patch = make(n1=grid[0], n2=grid[1], length=0.08, width=0.03, **params).initialize(N=18.0)
    point = make(point=True, **params).initialize(N=18.0)
    slid = False
    for k in range(200):
        u1, u2 = 2e-5 * k, 1e-5 * k * math.sin(0.05 * k)
        patch.move(u1=u1, u2=u2, N=18.0)
        point.move(u1=u1, u2=u2, N=18.0)
        T = np.array(point.get("T1", "T2"))
        assert np.array(patch.get("T1", "T2")) == pytest.approx(T, rel=1e-13, abs=1e-13 * 18.0)
        assert patch.get("dissipatedEnergy") == pytest.approx(point.get("dissipatedEnergy"),
                                                              rel=1e-12, abs=1e-18)
        assert abs(patch.get("Mz")) <= 1e-14 * 18.0 * 0.08
        state = point.get("contactState")
        assert patch.get("contactState") == (3 if state == 2 else state)
        assert patch.get("slipFraction") == (1.0 if state == 2 else 0.0)
        slid |= state == 2
    assert slid


# -- rotation ---------------------------------------------------------------------------


@pytest.mark.parametrize("grid", [(1, 1), (2, 2), (5, 3), (16, 8)])
def test_stick_in_rotation_is_minus_k_sin_theta_with_the_grids_stiffness(make, grid):
    """Isotropic eps, stuck: Mz = -k sin(theta) exactly with the grid's exact
    sum k (closed_forms.patch), T = 0; the grid's k tends to the
    continuum's eps (L^2 + W^2)/12 as 1 - O(1/n^2)."""
    L, W, eps = 0.08, 0.05, 2e4
    patch = make(n1=grid[0], n2=grid[1], length=L, width=W, mu1=0.5, mu2=0.5, eps1=eps, eps2=eps,
                 alpha=0.3, beta=0.0).initialize(N=100.0)
    k = cp.torsional_stiffness_grid(eps, eps, 0.0, L, W, *grid)
    for theta in (1e-4, -3e-4, 2e-3):
        patch.move(theta=theta, N=100.0)
        assert patch.get("contactState") == 1
        assert patch.get("Mz") == pytest.approx(cp.stick_rotation_torque(eps, L, W, theta, grid),
                                                rel=1e-12)
        assert patch.get("Mz") == pytest.approx(-k * math.sin(theta), rel=1e-12)
        assert abs(patch.get("T1")) < 1e-12 * eps * L * abs(theta)
    # the derivative at the stuck state is -k cos(theta) (the tangent, not a difference)
    d = patch.derivative(["Mz"], ["theta"], [1.0])[0]
    assert d == pytest.approx(-k * math.cos(2e-3), rel=1e-12)
    k_cont = cp.torsional_stiffness(eps, eps, 0.0, L, W)
    assert k == pytest.approx(k_cont * (1 - (L**2 / grid[0]**2 + W**2 / grid[1]**2) / (L**2 + W**2)),
                              rel=1e-13)


@pytest.mark.parametrize("alpha", [0.0, 0.4])
def test_stick_in_rotation_with_orthotropic_stiffness_is_the_grids_sum(make, alpha):
    """Orthotropic eps, stuck (mu large), finite turns: Mz is
    closed_forms.patch.stick_rotation_torque_grid, which departs from
    -k sin(theta) (to O(theta^2) relative with the axes along the sides,
    O(theta) otherwise); its tangent at 0 is -k."""
    L, W, grid, eps = 0.08, 0.05, (5, 3), (1e4, 3e4)
    patch = make(n1=grid[0], n2=grid[1], length=L, width=W, mu1=1e3, mu2=1e3, eps1=eps[0],
                 eps2=eps[1], alpha=alpha, beta=0.0).initialize(N=100.0)
    k = cp.torsional_stiffness_grid(*eps, alpha, L, W, *grid)
    assert patch.derivative(["Mz"], ["theta"], [1.0])[0] == pytest.approx(-k, rel=1e-12)
    for theta in (1e-3, 0.3, -0.5):
        patch.set(theta=theta)
        assert patch.get("contactState") == 1
        want = cp.stick_rotation_torque_grid(*eps, alpha, L, W, *grid, theta)
        assert patch.get("Mz") == pytest.approx(want, rel=1e-12)
        if abs(theta) > 0.1:
            assert abs(want / (-k * math.sin(theta)) - 1) > 1e-3


def _full_slip(make, grid, rule, mu, eps, L, W, N, p=(0.0, 0.0), beta=0.0, alpha=0.0):
    """T1, T2, Mz of one step turning the body by 1e-9 rad from rest with a
    stiffness so high that every cell slides (rigid-plastic: the cell's force
    is the law's steady force for its chord, which is the tangent up to
    0.5e-9 rad; the elastic part mu N / (eps |r| 1e-9) is below 1e-8)."""
    patch = make(n1=grid[0], n2=grid[1], length=L, width=W, mu1=mu[0], mu2=mu[1], eps1=eps[0],
                 eps2=eps[1], alpha=alpha, beta=beta, slidingRule=RULES[rule]).initialize(
        N=N, p1=p[0], p2=p[1])
    patch.move(theta=1e-9, N=N, p1=p[0], p2=p[1])
    centre = grid[0] % 2 == 1 and grid[1] % 2 == 1   # a centre cell does not move: it sticks
    assert patch.get("contactState") == (2 if centre else 3)
    assert patch.get("slipFraction") == pytest.approx(1 - centre / (grid[0] * grid[1]), rel=1e-15)
    return np.array(patch.get("T1", "T2", "Mz"))


def test_full_slip_of_a_square_reaches_the_continuum_at_the_midpoint_rate(make):
    """Isotropic mu, uniform pressure, a square of side a: |Mz| tends to
    mu N a (sqrt 2 + ln(1 + sqrt 2))/6, the error falling as 1/n^2."""
    a, N, mu = 0.1, 50.0, 0.4
    exact = cp.full_slip_torque_square(mu, N, a)
    errs = []
    for n in (4, 8, 16, 32):
        T1, T2, Mz = _full_slip(make, (n, n), "associated", (mu, mu), (1e20, 1e20), a, a, N)
        grid = cp.full_slip_rotation_grid(mu, mu, 1e20, 1e20, 0.0, 0.0, "associated", a, a, N, n, n)
        assert Mz == pytest.approx(grid[2], rel=1e-9)
        assert abs(T1) < 1e-12 * N and abs(T2) < 1e-12 * N
        errs.append(-Mz - exact)
    assert all(e < 0 for e in errs)   # the grid's arms are shorter
    # second order: the ratio of successive errors climbs to 4 (the cells at
    # the centre, where |r| has its kink, add a term of higher order)
    ratios = [coarse / fine for coarse, fine in zip(errs, errs[1:])]
    assert 3.7 < ratios[0] < ratios[1] < ratios[2] < 4.0
    assert ratios[2] == pytest.approx(4, rel=0.02)


@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_full_slip_with_orthotropic_friction_is_the_quadrature(make, rule):
    """Orthotropic mu and eps, linear pressure: each cell's force is the law's
    steady sliding force, so the patch gives the midpoint sum of it to
    rounding and tends to the quadrature over the area as the grid refines."""
    mu, eps, alpha, beta = (0.4, 0.6), (1e20, 1.5e20), 0.4, 1.0
    L, W, N, p = 0.2, 0.1, 2.0, (0.01, -0.005)
    exact = np.array(cp.full_slip_rotation(*mu, *eps, alpha, beta, rule, L, W, N, *p))
    errs = []
    for n in (8, 16, 32):
        got = _full_slip(make, (n, n), rule, mu, eps, L, W, N, p, beta=beta, alpha=alpha)
        grid = np.array(cp.full_slip_rotation_grid(*mu, *eps, alpha, beta, rule, L, W, N, n, n, *p))
        assert got == pytest.approx(grid, rel=1e-8, abs=1e-9 * N * L)
        errs.append(abs(got[2] - exact[2]))
    assert errs[0] > errs[1] > errs[2]
    assert errs[1] / errs[2] == pytest.approx(4, rel=0.15)
    assert errs[2] < 1e-3 * abs(exact[2])


# -- directional derivatives ----------------------------------------------------------------

KNOWNS = ("u1", "u2", "theta", "N", "p1", "p2")
UNKNOWNS = ("T1", "T2", "Mz", "dissipatedEnergy")
STEPS = {"u1": 1e-9, "u2": 1e-9, "theta": 1e-8, "N": 1e-6, "p1": 1e-8, "p2": 1e-8}


def _pending(patch, inputs):
    """The outputs of the pending step for `inputs` (nothing committed)."""
    patch.set(**inputs)
    return np.array(patch.get(*UNKNOWNS))


@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_directional_derivatives_match_central_differences(make, rule):
    """Partly slipping (the outer cells slide, the inner stick), linear
    pressure: each column of the FMU's Jacobian of T1, T2, Mz, energy with
    respect to u1, u2, theta, N, p1, p2 against central differences of the
    pending step, and the seeds combine linearly."""
    patch = make(n1=6, n2=4, length=0.06, width=0.04, slidingRule=RULES[rule], **AGED)
    inputs = dict(u1=0.0, u2=0.0, theta=0.0, N=20.0, p1=0.002, p2=-0.001)
    patch.initialize(**inputs)
    for k in range(1, 41):   # turn and drift: slip spreads from the edges inwards
        inputs.update(u1=2e-6 * k, u2=-1e-6 * k, theta=1.5e-3 * k)
        patch.move(**inputs)
    inputs.update(u1=inputs["u1"] + 3e-6, theta=inputs["theta"] + 2e-3)
    patch.set(**inputs)
    assert patch.get("contactState") == 2
    assert 0.1 < patch.get("slipFraction") < 0.9
    J = np.array([patch.derivative(UNKNOWNS, [x], [1.0]) for x in KNOWNS]).T
    for j, x in enumerate(KNOWNS):
        h = STEPS[x]
        fd = (_pending(patch, {**inputs, x: inputs[x] + h}) -
              _pending(patch, {**inputs, x: inputs[x] - h})) / (2 * h)
        scale = np.abs(J).max(axis=1) + 1e-30
        assert np.all(np.abs(J[:, j] - fd) <= 2e-5 * scale), (x, J[:, j], fd)
    _pending(patch, inputs)
    seed = [0.3, -1.2, 0.7, 0.01, 2.0, -0.5]
    assert patch.derivative(UNKNOWNS, KNOWNS, seed) == pytest.approx(J @ seed, rel=1e-12, abs=1e-12)
    # every output moves with the inputs here, theta's column through the moment's arm too
    assert np.all(np.abs(J[:, :4]).max(axis=1) > 0) and J[2, 2] != 0


def test_derivative_of_what_it_does_not_provide_is_refused(make, version):
    patch = make(**AGED).initialize(N=10.0)
    with pytest.raises(FMICallException):
        patch.derivative(["slipFraction"], ["u1"], [1.0])
    assert any("not an output T1, T2, Mz, dissipatedEnergy" in m for m in patch.messages)
    with pytest.raises(FMICallException):
        patch.derivative(["T1"], ["length"], [1.0])
    assert any("is not an input u1, u2, theta, N, p1, p2" in m for m in patch.messages)


# -- the point FMU's contracts ---------------------------------------------------------------


@pytest.mark.parametrize("name,value,why", [
    ("n1", 0, "n1 = 0 rejected: outside [1, 64]"),
    ("n2", 65, "n2 = 65 rejected: outside [1, 64]"),
    ("length", 0.0, "length = 0 rejected: outside [1e-100, 1e+100] m"),
    ("width", -1.0, "width = -1 rejected"),
    ("eps1", math.nan, "eps1 = nan rejected: values must be finite"),
])
def test_parameters_out_of_range_are_refused_with_their_reason(make, name, value, why):
    patch = make()
    with pytest.raises(FMICallException):
        patch.set(**{name: value})
    assert any(why in m for m in patch.messages), patch.messages


def test_a_centre_of_pressure_outside_the_kern_is_refused_and_changes_nothing(make):
    """|p1|/length + |p2|/width > 1/6 would pull at a corner: refused with
    the reason, the pending outputs as they were; on the kern's edge it is
    accepted."""
    patch = make(n1=4, n2=4, length=0.06, width=0.03, **AGED).initialize(N=10.0)
    patch.move(u1=1e-4, N=10.0)
    before = patch.get("T1", "T2", "Mz")
    with pytest.raises(FMICallException):
        patch.set(p1=0.006, p2=0.003)   # 0.1 + 0.1 > 1/6
    assert any("outside the kern" in m and "no-tension pressure is not modelled" in m
               for m in patch.messages), patch.messages
    assert patch.get("T1", "T2", "Mz") == before
    patch.set(p1=0.06 / 6, p2=0.0)
    assert patch.get("contactState") in (1, 2, 3)


def _set_together(patch, **values):
    """Sets Float64 inputs in one call (one fmi2SetReal / fmi3SetFloat64)."""
    (patch.s.setReal if patch.version == 2 else patch.s.setFloat64)(
        [patch.vr[n] for n in values], [float(v) for v in values.values()])


def test_an_open_contact_takes_any_centre_of_pressure(make):
    """N <= 0: no pressure, p not looked at (outside the kern, off the axis of a
    side of one cell), every cell open; closing it with such a p is refused by
    that call, whole, and one call setting N and p together closes it."""
    patch = make(n1=4, n2=1, length=0.06, width=0.03, **AGED).initialize(N=10.0)
    patch.move(u1=1e-4, N=10.0)
    patch.set(N=-1.0)
    patch.set(p1=0.5, p2=-0.2)          # far outside the kern, and p2 on a side of one cell
    assert patch.get("contactState") == 0
    assert patch.get("T1", "T2", "Mz") == [0.0, 0.0, 0.0]
    patch.step()
    before = patch.get(*UNKNOWNS)
    with pytest.raises(FMICallException):
        patch.set(N=10.0)
    assert "outside the kern" in patch.messages[-1], patch.messages
    assert patch.get(*UNKNOWNS) == before
    _set_together(patch, N=0.0, p1=0.5, p2=-0.2)   # N = 0 is open too
    assert patch.get("contactState") == 0
    _set_together(patch, N=10.0, p1=0.005, p2=0.0)
    assert patch.get("contactState") in (1, 2, 3)


@pytest.mark.parametrize("n1,n2,name", [(1, 4, "p1"), (3, 1, "p2"), (1, 1, "p1"), (1, 1, "p2")])
def test_a_side_of_one_cell_refuses_a_centre_of_pressure_off_its_axis(make, n1, n2, name):
    """One cell along a side: every cell's centre is on the patch's axis, so
    no pressure on the grid has its resultant off it.  With N > 0 a p off it
    is refused, with the reason, changing nothing; with N <= 0 accepted."""
    patch = make(n1=n1, n2=n2, length=0.06, width=0.03, **AGED).initialize(N=10.0)
    patch.move(u1=1e-4, N=10.0)
    before = patch.get(*UNKNOWNS)
    with pytest.raises(FMICallException):
        patch.set(**{name: 0.001})
    axis = name[1]
    assert f"{name}=0.001 m off the axis of a grid with n{axis} = 1" in patch.messages[-1], patch.messages
    assert patch.get(*UNKNOWNS) == before
    _set_together(patch, N=-2.0, **{name: 0.001})
    assert patch.get("contactState") == 0


@pytest.mark.parametrize("grid,p", [((1, 1), (0.0, 0.0)), ((2, 2), (0.005, -0.002)),
                                    ((3, 1), (-0.007, 0.0)), ((1, 3), (0.0, 0.003)),
                                    ((4, 2), (0.004, 0.002)), ((8, 8), (-0.005, 0.002)),
                                    ((32, 32), (0.002, -0.004))])
def test_full_slip_in_translation_acts_at_the_centre_of_pressure(make, grid, p):
    """Isotropic mu and eps, theta = 0, every cell sliding along s: T = -mu N s
    at the centre of pressure, Mz = p x T (closed_forms.patch.full_slip_translation)
    to 1e-12 on every grid: the cells' normal forces have first moment N p."""
    L, W, N, mu = 0.06, 0.03, 18.0, 0.4
    assert abs(p[0]) / L + abs(p[1]) / W <= 1 / 6
    patch = make(n1=grid[0], n2=grid[1], length=L, width=W, mu1=mu, mu2=mu, eps1=1e4, eps2=1e4,
                 alpha=0.3, beta=1.1).initialize(N=N, p1=p[0], p2=p[1])
    moments = []
    for psi in (0.0, 2.0, -0.9):
        s = 0.01 * np.array([math.cos(psi), math.sin(psi)])   # mu N / eps = 0.7 mm: every cell slides
        _set_together(patch, u1=s[0], u2=s[1], theta=0.0, N=N, p1=p[0], p2=p[1])
        assert patch.get("slipFraction") == 1.0
        T1, T2, Mz = cp.full_slip_translation(mu, N, *p, psi)
        assert patch.get("T1", "T2") == pytest.approx([T1, T2], rel=1e-12, abs=1e-15 * N)
        assert patch.get("Mz") == pytest.approx(Mz, rel=1e-12, abs=1e-15 * N * L)
        moments.append(Mz)
    assert any(moments) == (p != (0.0, 0.0))


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_nonfinite_inputs_are_refused_and_change_nothing(make, bad):
    patch = make(**AGED).initialize(N=10.0)
    patch.move(u1=1e-4, theta=0.01, N=10.0)
    before = patch.get(*UNKNOWNS)
    for name in ("u1", "theta", "N", "p2"):
        with pytest.raises(FMICallException):
            patch.set(**{name: bad})
        assert patch.get(*UNKNOWNS) == before
    assert any("values must be finite" in m for m in patch.messages)


def test_an_overflowing_step_is_refused_whole_never_nan(make):
    """A displacement whose force overflows in some cell: the whole step is
    refused with the reason, no cell changes, the next step goes on from
    the committed state as if nothing happened."""
    params = dict(AGED, eps1=1e300, eps2=1e300, mu1=1e150, mu2=1e150)
    a = make(n1=3, n2=2, **params).initialize(N=1e150)
    b = make(n1=3, n2=2, **params).initialize(N=1e150)
    a.move(u1=1e-3, N=1e150)
    b.move(u1=1e-3, N=1e150)
    before = a.get(*UNKNOWNS)
    with pytest.raises(FMICallException):
        a.set(u1=1e300)
    assert any("overflow" in m for m in a.messages), a.messages
    assert a.get(*UNKNOWNS) == before
    a.move(u1=2e-3, N=1e150)
    b.move(u1=2e-3, N=1e150)
    assert [_bits(x) for x in a.get(*UNKNOWNS)] == [_bits(x) for x in b.get(*UNKNOWNS)]
    assert all(math.isfinite(x) for x in a.get(*UNKNOWNS))


def _path(k):
    return dict(u1=3e-5 * k, u2=1e-5 * math.sin(0.2 * k), theta=2e-3 * math.sin(0.1 * k),
                N=15.0 + 5.0 * math.cos(0.3 * k), p1=0.002 * math.sin(0.05 * k), p2=0.0)


def test_a_damaged_state_is_refused_with_its_reason(make, version):
    a = make(n1=2, n2=2, **AGED).initialize(N=10.0)
    a.move(u1=1e-4, theta=0.01, N=10.0)
    s = a.s
    blob = bytearray(s.serializeFMUState(s.getFMUState()))
    # the last cell's slot beyond n1 n2 = 4 cells must hold no state
    blob[-8:] = np.float64(1.0).tobytes()
    with pytest.raises(FMICallException):
        s.deserializeFMUState(bytes(blob))
    assert any("holds a state" in m for m in a.messages), a.messages


def test_held_inputs_step_again_and_energy_never_decreases(make):
    """As the point: a doStep with held inputs takes a new step from the
    committed states (rate-independent, the same result when it sticks)."""
    patch = make(n1=4, n2=4, **AGED).initialize(N=10.0)
    last = 0.0
    for k in range(1, 50):
        patch.move(theta=0.01 * k, N=10.0)
        e = patch.get("dissipatedEnergy")
        assert e >= last
        last = e
    T = patch.get("T1", "T2", "Mz")
    patch.step()
    assert patch.get("T1", "T2", "Mz") == pytest.approx(T, rel=1e-9, abs=1e-12)


# -- FMI 3.0: the cells as arrays, n1 and n2 structural parameters -------------------


def _cells(patch, n1, n2):
    """cellT1, cellT2 and cellState as (n1, n2) arrays, read with nValues."""
    vr = patch.vr
    t1 = np.array(patch.s.getFloat64([vr["cellT1"]], nValues=n1 * n2)).reshape(n1, n2)
    t2 = np.array(patch.s.getFloat64([vr["cellT2"]], nValues=n1 * n2)).reshape(n1, n2)
    st = np.array(patch.s.getInt32([vr["cellState"]], nValues=n1 * n2)).reshape(n1, n2)
    return t1, t2, st


@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_fmi3_cells_sum_to_the_patch_and_carry_its_states(rule):
    """On a path through stick, partial and full slip: the cells' forces,
    summed cell by cell in the model's order, are T1, T2 bit for bit; their
    moments about the centre (cell centres from the geometry, written here)
    are Mz; the share of slipping cells is slipFraction and the states give
    contactState (0 open, 1 all stick, 2 some slip, 3 all slip)."""
    n1, n2, L, W = 5, 3, 0.05, 0.02
    patch = Slave(patch_fmu(3), 3, name="cells", n1=n1, n2=n2, length=L, width=W,
                  slidingRule=RULES[rule], **AGED)
    try:
        patch.initialize(**_path(0))
        seen = set()
        for k in range(1, 200):
            inputs = _path(k)
            inputs["theta"] = 0.02 * math.sin(0.05 * k)   # enough turning to slip the corners
            inputs["N"] = -1.0 if 90 <= k < 95 else inputs["N"]
            patch.move(**inputs)
            t1, t2, st = _cells(patch, n1, n2)
            T1, T2, Mz, frac = patch.get("T1", "T2", "Mz", "slipFraction")
            s1 = s2 = 0.0
            for j in range(n2):           # cell c = i + n1 j: i fastest, as the model sums
                for i in range(n1):
                    s1 += t1[i, j]
                    s2 += t2[i, j]
            assert (_bits(s1), _bits(s2)) == (_bits(T1), _bits(T2)), k
            xi = (2 * np.arange(n1) + 1 - n1) / (2 * n1)
            eta = (2 * np.arange(n2) + 1 - n2) / (2 * n2)
            r1, r2 = np.meshgrid(xi * L, eta * W, indexing="ij")
            c, s = math.cos(inputs["theta"]), math.sin(inputs["theta"])
            R1, R2 = c * r1 - s * r2, s * r1 + c * r2
            moment = float(np.sum(R1 * t2 - R2 * t1))
            assert moment == pytest.approx(Mz, rel=1e-12, abs=1e-15 * (abs(T1) + abs(T2)) * L), k
            assert set(np.unique(st)) <= {0, 1, 2}
            assert frac == np.count_nonzero(st == 2) / (n1 * n2), k
            pressed, slipping = np.count_nonzero(st != 0), np.count_nonzero(st == 2)
            expect = 0 if pressed == 0 else 1 if slipping == 0 else 3 if slipping == pressed else 2
            assert patch.get("contactState") == expect, k
            if expect == 0:
                assert not t1.any() and not t2.any()
            seen.add(expect)
        assert {0, 1, 2} <= seen, seen   # the path visits open, stick and partial slip
        # a state restored into a fresh instance (at the table's 8 x 8) shows the same cells
        blob = bytes(patch.s.serializeFMUState(patch.s.getFMUState()))
        fresh = Slave(patch_fmu(3), 3, name="cells-restored")
        try:
            fresh.s.setFMUState(fresh.s.deserializeFMUState(blob))
            for ours, theirs in zip(_cells(fresh, n1, n2), _cells(patch, n1, n2)):
                assert ours.tobytes() == theirs.tobytes()
        finally:
            fresh.close()
    finally:
        patch.close()


def test_fmi3_uniform_translation_loads_every_cell_alike():
    """Uniform pressure, pure translation: every cell is the point law at
    1/(n1 n2) of N and eps, the same force in each (to rounding in N w)."""
    n1, n2 = 4, 6
    patch = Slave(patch_fmu(3), 3, name="alike", n1=n1, n2=n2, **AGED)
    try:
        patch.initialize(N=12.0)
        patch.move(u1=2e-4, u2=-1e-4, N=12.0)
        t1, t2, st = _cells(patch, n1, n2)
        T1, T2 = patch.get("T1", "T2")
        assert np.allclose(t1, T1 / (n1 * n2), rtol=1e-13, atol=0.0)
        assert np.allclose(t2, T2 / (n1 * n2), rtol=1e-13, atol=0.0)
        assert (st == st[0, 0]).all() and st[0, 0] in (1, 2)
    finally:
        patch.close()


def _fmi3_patch(name):
    """The FMI 3.0 patch FMU instantiated as the package does it (fmu.slave),
    not initialized: (fmpy's instance, model description, value references
    by name, the log lines it writes)."""
    path = patch_fmu(3)
    md = read_model_description(str(path))
    messages = []
    s, keep = instantiate(path, md, name, lambda status, category, text: messages.append(text))
    _KEPT.append(keep)   # the log callback lives as long as the instance may call it
    return s, md, {v.name: v.valueReference for v in md.modelVariables}, messages


_KEPT = []


def test_fmi3_structural_parameters_resize_the_arrays_in_configuration_mode():
    """n1, n2 set in configuration mode size the arrays; there nothing else
    may be set; a get whose nValues is not the arrays' size is refused with
    the count, and configuration mode is refused after initialization."""
    s, md, vr, messages = _fmi3_patch("config")
    try:
        s.enterConfigurationMode()
        s.setUInt64([vr["n1"], vr["n2"]], [3, 7])
        with pytest.raises(FMICallException):
            s.setFloat64([vr["mu1"]], [0.5])
        assert any("mu1 (vr 1) is not a structural parameter" in m for m in messages), messages
        s.exitConfigurationMode()
        s.enterInitializationMode(startTime=0.0)
        s.setFloat64([vr["N"]], [10.0])
        s.exitInitializationMode()
        s.setFloat64([vr["u1"], vr["theta"]], [1e-4, 0.01])
        s.doStep(0.0, 1e-3)
        both = s.getFloat64([vr["T1"], vr["cellT1"], vr["T2"]], nValues=23)
        t1 = both[1:22]
        assert both[0] == sum(np.array(t1).reshape(3, 7).T.ravel().tolist(), 0.0)
        assert len(s.getInt32([vr["cellState"], vr["contactState"]], nValues=22)) == 22
        with pytest.raises(FMICallException):
            s.getFloat64([vr["cellT1"]], nValues=20)
        assert any("nValues = 20 but the 1 variables hold 21 values" in m for m in messages), messages
        with pytest.raises(FMICallException):
            s.enterConfigurationMode()
        assert any("must not be called in the current state (step mode)" in m
                   for m in messages), messages
    finally:
        s.terminate()
        s.freeInstance()


def test_fmi3_n1_n2_are_uint64_and_only_uint64():
    """FMI 3.0 wants an array's dimension to be a UInt64 structural
    parameter: n1, n2 are set and read through the UInt64 functions only;
    the Int32 ones refuse them by name, as does a value outside [1, 64]
    (2^64 - 1 as itself, not as -1), each with an error status and a log
    line, the values as they were."""
    s, md, vr, messages = _fmi3_patch("uint64")
    assert {v.name: v.type for v in md.modelVariables if v.name in ("n1", "n2")} == \
        {"n1": "UInt64", "n2": "UInt64"}
    try:
        s.setUInt64([vr["n1"], vr["n2"]], [3, 7])
        for call, why in [(lambda: s.setInt32([vr["n1"]], [4]),
                           "fmi3SetInt32: variable n1 (vr 21) is of type UInt64 (a structural parameter)"),
                          (lambda: s.setUInt64([vr["n2"]], [0]), "n2 = 0 rejected: outside [1, 64]"),
                          (lambda: s.setUInt64([vr["n1"]], [2**64 - 1]),
                           "n1 = 1.84467e+19 rejected: outside [1, 64]"),
                          (lambda: s.setInt64([vr["n1"]], [4]), "is of type UInt64")]:
            with pytest.raises(FMICallException):
                call()
            assert any(why in m for m in messages), (why, messages)
        s.enterInitializationMode(startTime=0.0)
        s.exitInitializationMode()
        assert list(s.getUInt64([vr["n1"], vr["n2"]])) == [3, 7]
        with pytest.raises(FMICallException):
            s.getInt32([vr["n1"]])
        assert any("n1 (vr 21) is of type UInt64 (a structural parameter), not Int32" in m
                   for m in messages), messages
        assert len(s.getFloat64([vr["cellT1"]], nValues=21)) == 21
    finally:
        s.terminate()
        s.freeInstance()


def test_only_fmi3_declares_the_arrays_and_structural_parameters():
    """FMI 3.0: n1, n2 structural parameters, the arrays' dimensions n1, n2 by
    value reference, the arrays outputs in the model structure; FMI 2.0: n1,
    n2 parameters and no array (FMI 2.0 has none)."""
    md3 = read_model_description(str(patch_fmu(3)), validate=True)
    by3 = {v.name: v for v in md3.modelVariables}
    assert by3["n1"].causality == by3["n2"].causality == "structuralParameter"
    assert by3["n1"].type == by3["n2"].type == "UInt64" and int(by3["n1"].start) > 0
    for name in ("cellT1", "cellT2", "cellState"):
        assert [d.variable.name for d in by3[name].dimensions] == ["n1", "n2"]
        assert by3[name].causality == "output"
        assert name in {u.variable.name for u in md3.outputs}
    md2 = read_model_description(str(patch_fmu(2)), validate=True)
    by2 = {v.name: v for v in md2.modelVariables}
    assert by2["n1"].causality == "parameter" and not any(n.startswith("cell") for n in by2)
    assert by2["n1"].type == by2["n2"].type == "Integer"
