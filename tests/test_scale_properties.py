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
never decreases."""
import math

import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from orthocontact.fmu.contact import ContactFMU
from orthocontact.fmu.params import ContactParams

EPS = np.finfo(float).eps
RULES = ["associated", "coupled", "eq20"]


@st.composite
def setups(draw):
    mu1 = 10 ** draw(st.floats(-1.3, 0.0))
    mu2 = mu1 * 10 ** draw(st.floats(-10, 10))
    eps1 = 10 ** draw(st.floats(2, 6))
    eps2 = eps1 * 10 ** draw(st.floats(-10, 10))
    # Angles are 0 or at least 1e-3 rad: a subnormal sin() would put subnormal
    # numbers (which lose bits) into the tensors, where exact scaling cannot hold.
    angle = st.floats(-math.pi, math.pi).filter(lambda x: x == 0 or abs(x) >= 1e-3)
    params = ContactParams(mu1, mu2, eps1, eps2, draw(angle), draw(angle),
                           draw(st.sampled_from(RULES)))
    a, b = draw(st.integers(-498, 498)), draw(st.integers(-498, 498))  # k = 2^a, m = 2^b
    # The scaled law must be representable: its tensors reach eps / mu^2 and mu^2 / eps.
    lg2 = math.log10(2)
    lg = [math.log10(x) for x in (mu1, mu2)]
    for e in (eps1, eps2):
        le = math.log10(e) + (a - b) * lg2
        assume(abs(le) + 2 * max(abs(x) for x in lg) < 290)
    # forces, slips and energies stay normal numbers (subnormals lose bits)
    assume(abs(a + b) <= 400)
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
