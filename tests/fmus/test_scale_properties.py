"""The law's contract at every scale, as properties over random parameters,
paths and units (hypothesis, derandomized so that CI is repeatable).

Homogeneity: scaling N, eps1, eps2 by k scales T and the dissipated energy by
k and leaves s unchanged; scaling u by m and eps by 1/m scales s and the energy
by m.  With k and m powers of two from 2^-498 to 2^498 (1e-150 to 1e150) the
scaling is exact in floating point, so the FMU must reproduce it bit for bit:
no decision in the code may depend on the units.  (Decimal factors would move
results by rounding amplified by the condition of the yield map, up to
(mu_max/mu_min)(eps_max/eps_min) eps, which says nothing about the code.)
At every step with an OK status: every output and derivative is finite,
sqrt(T.F T) <= N up to the rounding with which T can be represented, a repeated
step with held inputs changes nothing, and the dissipated energy is >= 0 and
never decreases.

Accuracy: with the friction and stiffness axes shared (alpha = beta), the
return map is diagonal in those axes, and an independent reference solves it
in long double (aligned_return_map).  The FMU's force and energy must agree
with it to a few units of what the inputs' own rounding allows: eps |T| plus
the largest change of the exact T when the displacement moves by up to 4 eps
|u| along an axis (at a contrast of 1e20 an ulp of the rotation is a
different force)."""
import math

import numpy as np

from optional_parts import need
from orthocontact.fmu.contact import ContactFMU
from orthocontact.fmu.params import ContactParams

need("hypothesis", module_level=True)
from hypothesis import HealthCheck, assume, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

EPS = np.finfo(float).eps
RULES = ["associated", "coupled", "eq20"]


def coefficients(draw):
    """mu1 in [0.05, 1], mu2 up to 1e10 times larger or smaller; eps1 in
    [1e2, 1e6] N/m, eps2 likewise within 1e10 of it."""
    mu1 = 10 ** draw(st.floats(-1.3, 0.0))
    mu2 = mu1 * 10 ** draw(st.floats(-10, 10))
    eps1 = 10 ** draw(st.floats(2, 6))
    eps2 = eps1 * 10 ** draw(st.floats(-10, 10))
    return mu1, mu2, eps1, eps2


def scale_exponents(draw, mus, epss):
    """a, b of the scales k = 2^a (force), m = 2^b (length) under which the
    scaled law stays representable: its tensors reach eps / mu^2 and
    mu^2 / eps, and forces, slips and energies stay normal numbers
    (subnormals lose bits)."""
    a, b = draw(st.integers(-498, 498)), draw(st.integers(-498, 498))
    lg = [math.log10(x) for x in mus]
    for e in epss:
        assume(abs(math.log10(e) + (a - b) * math.log10(2)) + 2 * max(abs(x) for x in lg) < 290)
    assume(abs(a + b) <= 400)
    return a, b


@st.composite
def setups(draw):
    mu1, mu2, eps1, eps2 = coefficients(draw)
    # Angles are 0 or at least 1e-3 rad: a subnormal sin() would put subnormal
    # numbers (which lose bits) into the tensors, where exact scaling cannot hold.
    angle = st.floats(-math.pi, math.pi).filter(lambda x: x == 0 or abs(x) >= 1e-3)
    params = ContactParams(mu1, mu2, eps1, eps2, draw(angle), draw(angle),
                           draw(st.sampled_from(RULES)))
    a, b = scale_exponents(draw, (mu1, mu2), (eps1, eps2))
    # A path in units of the largest elastic length: sticks, slides, holds, opens.
    N0 = 10.0
    L = max(mu1, mu2) * N0 / min(eps1, eps2)
    direction = st.floats(-1, 1).filter(lambda x: x == 0 or abs(x) >= 1e-6)  # no subnormal inputs
    steps = draw(st.lists(st.tuples(direction, direction, st.floats(-3, 1),
                                    st.sampled_from(["move", "move", "move", "hold", "open"]),
                                    st.floats(0.5, 1.5)), min_size=5, max_size=25))
    u = np.zeros(2)
    path, N = [], N0
    for d1, d2, lg_size, kind, nf in steps:
        if kind == "move":
            u = u + L * 10 ** lg_size * np.array([d1, d2])
            N = N0 * nf
        elif kind == "open":
            N = 0.0
        path.append((u[0], u[1], N))
    return params, math.ldexp(1.0, a), math.ldexp(1.0, b), path, draw(st.sampled_from([2, 3]))


def scaled(p: ContactParams, k, m):
    return p.replace(eps1=p.eps1 * k / m, eps2=p.eps2 * k / m)


def run_checked(params, path, k, m, version):
    """Runs the path at scale (k, m), checking every step; returns T, s, E per step."""
    p = scaled(params, k, m)
    c, sn = math.cos(p.beta), math.sin(p.beta)
    mu_min = min(p.mu1, p.mu2)
    out = []
    with ContactFMU(fmi_version=version, instance_name="prop") as f:
        f.initialize(p)
        E_prev = 0.0
        for u1, u2, N in path:
            u1, u2, N = u1 * m, u2 * m, N * k
            f.set_inputs(u1, u2, N)
            f.do_step(1e-3)
            o = f.outputs()
            T = np.array([o["T1"], o["T2"]])
            vals = [o["T1"], o["T2"], o["s1"], o["s2"], o["dissipatedEnergy"]]
            assert all(math.isfinite(v) for v in vals), vals
            assert all(math.isfinite(x) for row in f.tangent() for x in row)
            # yield, in the friction axes (T.F T in X1, X2 cancels when mu1/mu2 is
            # extreme), up to the rounding of T itself: |T| eps seen through F^(1/2)
            t1, t2 = c * T[0] + sn * T[1], -sn * T[0] + c * T[1]
            phi = math.hypot(t1 / p.mu1, t2 / p.mu2)
            assert phi <= N * (1 + 1e-12) + 64 * EPS * math.hypot(T[0], T[1]) / mu_min + 1e-300
            E = o["dissipatedEnergy"]
            assert E >= 0 and E >= E_prev
            E_prev = E
            # the same inputs again: a step that changes nothing
            f.set_inputs(u1, u2, N)
            f.do_step(1e-3)
            again = f.outputs()
            assert [again[x] for x in ("T1", "T2", "s1", "s2", "dissipatedEnergy")] == vals
            if N > 0:
                assert again["contactState"] == 1
            out.append(vals)
    return np.array(out)


@settings(max_examples=int(__import__("os").environ.get("ORTHOCONTACT_PROPERTY_EXAMPLES", 100)),
          deadline=None, derandomize=True, suppress_health_check=[HealthCheck.filter_too_much,
                                                                   HealthCheck.too_slow])
@given(setups())
def test_contract_and_homogeneity_at_every_scale(setup):
    params, k, m, path, version = setup
    base = run_checked(params, path, 1.0, 1.0, version)
    both = run_checked(params, path, k, m, version)
    # Homogeneity, exact: T scales by k, s by m, the energy by k m.
    np.testing.assert_array_equal(both[:, 0:2], base[:, 0:2] * k)
    np.testing.assert_array_equal(both[:, 2:4], base[:, 2:4] * m)
    np.testing.assert_array_equal(both[:, 4], base[:, 4] * (k * m))


# ---- accuracy against an exact reference --------------------------------------

LD = np.longdouble


def aligned_return_map(rule, mu, eps, th, d, N):
    """Reference for tests only (independent of the C law): the implicit
    return map for alpha = beta = th from an unloaded start, with the
    displacement d given in the shared axes, in long double.  Each component
    returns as q_i = qtr_i / (1 + l k_i), k_i = eps_i / mu_i^2 (associated) or
    mu_i^2 / eps_i (coupled), l by bisection on sum (q_i / mu_i)^2 = N^2.
    Returns T = -q in X1, X2 and the dissipation l q.G q."""
    mu, eps, d = [LD(x) for x in mu], [LD(x) for x in eps], [LD(x) for x in d]
    qt = [eps[i] * d[i] for i in range(2)]
    k = [eps[i] / (mu[i] * mu[i]) if rule == "associated" else mu[i] * mu[i] / eps[i]
         for i in range(2)]
    N = LD(N)

    def phi(x):
        return np.hypot(qt[0] / (mu[0] * (1 + x * k[0])), qt[1] / (mu[1] * (1 + x * k[1])))

    lam = LD(0)
    if phi(LD(0)) > N:
        # each term alone at most N^2 / 2 above hi; halve down to a lower end
        hi = max(2 * abs(qt[i]) / (mu[i] * N) / k[i] for i in range(2))
        lo = hi
        while phi(lo) <= N:
            hi, lo = lo, lo / 2
        for _ in range(200):
            mid = (lo + hi) / 2
            if not lo < mid < hi:
                break
            if phi(mid) > N:
                lo = mid
            else:
                hi = mid
        lam = (lo + hi) / 2
    q = [qt[i] / (1 + lam * k[i]) for i in range(2)]
    c, s = np.cos(LD(th)), np.sin(LD(th))
    T = np.array([-(c * q[0] - s * q[1]), -(s * q[0] + c * q[1])], dtype=LD)
    G = [k[i] / eps[i] for i in range(2)]
    return T, lam * (q[0] * q[0] * G[0] + q[1] * q[1] * G[1])


@st.composite
def aligned_slides(draw):
    mu1, mu2, eps1, eps2 = coefficients(draw)
    th = draw(st.one_of(st.just(0.0), st.floats(-math.pi, math.pi).filter(lambda x: abs(x) >= 1e-3)))
    # slide directions include the axes themselves
    phi = draw(st.one_of(st.floats(-math.pi, math.pi),
                         st.sampled_from([0, 1, 2, 3]).map(lambda j: th + j * math.pi / 2)))
    N = draw(st.floats(1.0, 20.0))
    size = max(mu1, mu2) * N / min(eps1, eps2) * 10 ** draw(st.floats(-3, 4))
    a, b = scale_exponents(draw, (mu1, mu2), (eps1, eps2))
    rule = draw(st.sampled_from(["associated", "coupled"]))
    return (rule, (mu1, mu2), (eps1, eps2), th, (size * math.cos(phi), size * math.sin(phi)), N,
            math.ldexp(1.0, a), math.ldexp(1.0, b), draw(st.sampled_from([2, 3])))


@settings(max_examples=int(__import__("os").environ.get("ORTHOCONTACT_PROPERTY_EXAMPLES", 100)),
          deadline=None, derandomize=True, suppress_health_check=[HealthCheck.filter_too_much,
                                                                   HealthCheck.too_slow])
@given(aligned_slides())
def test_accuracy_against_the_exact_aligned_return_map(case):
    rule, mu, eps, th, du, N, k, m, version = case
    p = ContactParams(mu[0], mu[1], eps[0] * k / m, eps[1] * k / m, th, th, rule)
    with ContactFMU(fmi_version=version, instance_name="acc") as f:
        f.initialize(p)
        f.set_inputs(du[0] * m, du[1] * m, N * k)
        o = f.outputs()
    # back to the unscaled units (exact: powers of two)
    T = np.array([o["T1"] / k, o["T2"] / k], dtype=LD)
    E = LD(o["dissipatedEnergy"] / (k * m))
    c, s = np.cos(LD(th)), np.sin(LD(th))
    d = (c * LD(du[0]) + s * LD(du[1]), -s * LD(du[0]) + c * LD(du[1]))
    T_ref, E_ref = aligned_return_map(rule, mu, eps, th, d, N)
    dl = 4 * LD(EPS) * np.hypot(d[0], d[1])
    # the exact result over a grid of displacements within 4 eps |u| along each
    # axis (and with a component that small set to 0): what the rounding of the
    # inputs alone can change (near the point where the weak axis alone reaches
    # the yield surface the exact map is that steep)
    near = [(d[0] + j * dl / 4, d[1]) for j in range(-4, 5) if j]
    near += [(d[0], d[1] + j * dl / 4) for j in range(-4, 5) if j]
    near += [(0 if abs(d[0]) <= dl else d[0], d[1]), (d[0], 0 if abs(d[1]) <= dl else d[1])]
    sens_T = sens_E = LD(0)
    for dn in near:
        T2, E2 = aligned_return_map(rule, mu, eps, th, dn, N)
        sens_T = max(sens_T, np.hypot(*(T2 - T_ref)))
        sens_E = max(sens_E, abs(E2 - E_ref))
    err_T = np.hypot(*(T - T_ref)) / (LD(EPS) * np.hypot(*T_ref) + sens_T)
    assert err_T <= 4, (float(err_T), [float(x) for x in T], [float(x) for x in T_ref])
    if E_ref > 0:
        err_E = abs(E - E_ref) / (LD(EPS) * E_ref + sens_E)
        assert err_E <= 4, (float(err_E), float(E), float(E_ref))
