"""The OrthotropicContact FMU through fmpy, against closed forms (eq. 11, 25),
the tensors B and F, finite differences, and its error contract."""
import math
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from conftest import CASE1, CASE5, G_N, deg
from orthocontact import closed_forms as cf
from orthocontact.fmu.contact import FMUError
from orthocontact.fmu.params import ContactParams
from orthocontact.rig.harness import solve_lateral
from paths import ROOT


def test_fmpy_validate_is_clean(fmu_path):
    assert validate_fmu(str(fmu_path)) == []


HOST_DIR = {2: "linux64", 3: "x86_64-linux"}
PLATFORMS = {2: ("linux64", "win64", "darwin64"),
             3: ("x86_64-linux", "aarch64-linux", "x86_64-windows", "x86_64-darwin", "aarch64-darwin")}
def _ext(platform):
    return "dylib" if "darwin" in platform else "dll" if "win" in platform else "so"


def test_archive_layout_and_capabilities(fmu_path, fmi_version):
    names = set(zipfile.ZipFile(fmu_path).namelist())
    assert "modelDescription.xml" in names
    for platform in PLATFORMS[fmi_version]:
        assert f"binaries/{platform}/OrthotropicContact.{_ext(platform)}" in names
    assert not [n for n in names if n.startswith("binaries/") and n.count("/") != 2 and not n.endswith("/")]
    for src in ("law/contact_law.c", "models/OrthotropicContact/model.c", "glue/fmu_instance.c",
                f"glue/fmi{fmi_version}_glue.c", "models/OrthotropicContact/table.h"):
        assert f"sources/{src}" in names
    assert "documentation/index.html" in names
    assert ("documentation/LICENSE.txt" if fmi_version == 2
            else "documentation/licenses/LICENSE.txt") in names
    if fmi_version == 3:
        assert "sources/buildDescription.xml" in names
    md = read_model_description(str(fmu_path))
    assert md.fmiVersion == f"{fmi_version}.0"
    cs = md.coSimulation
    assert md.modelName == cs.modelIdentifier == "OrthotropicContact"
    assert cs.canHandleVariableCommunicationStepSize and cs.canGetAndSetFMUstate
    assert cs.canSerializeFMUstate
    xml = zipfile.ZipFile(fmu_path).read("modelDescription.xml").decode()
    if fmi_version == 2:
        assert cs.providesDirectionalDerivative
    else:  # fmpy reads FMI 3.0's plural attribute under the FMI 2.0 name: check the XML
        assert 'providesDirectionalDerivatives="true"' in xml and cs.providesAdjointDerivatives
    assert md.license.startswith("BSD-2-Clause") and md.copyright and md.author
    v = {x.name: x for x in md.modelVariables}
    units = {"u1": "m", "u2": "m", "N": "N", "T1": "N", "T2": "N", "s1": "m", "s2": "m",
             "eps1": "N/m", "eps2": "N/m", "alpha": "rad", "beta": "rad", "dissipatedEnergy": "J",
             "time": "s"}
    for name, unit in units.items():
        assert v[name].unit == unit, name
    assert v["alpha"].displayUnit == "deg" and v["beta"].displayUnit == "deg"
    assert v["time"].causality == "independent"
    assert {n for n, x in v.items() if x.causality == "input"} == {"u1", "u2", "N"}
    params = [x for x in v.values() if x.causality == "parameter"]
    assert {x.name for x in params} == {"mu1", "mu2", "eps1", "eps2", "alpha", "beta",
                                        "slidingRule", "initialSlip", "s1Start", "s2Start"}
    assert all(x.min is not None and x.max is not None for x in params)
    rule = v["slidingRule"]
    if fmi_version == 2:
        assert rule.type == "Integer" and (rule.min, rule.max) == ("1", "3")
    else:
        assert rule.type == "Enumeration" and rule.declaredType.name == "SlidingRule"
        items = {i.name: i.value for i in rule.declaredType.items}
        assert items == {"associated": "1", "coupled": "2", "eq20": "3"}
    assert v["contactState"].type == ("Integer" if fmi_version == 2 else "Int32")
    outs = {o.variable.name: {d.name for d in o.dependencies} for o in md.outputs}
    assert set(outs) == {"T1", "T2", "s1", "s2", "contactState", "dissipatedEnergy"}
    assert all(deps == {"u1", "u2", "N"} for deps in outs.values())


def test_every_fmi_function_is_exported(fmu_path, fmi_version, tmp_path):
    """The names come from the FMI header that fmpy ships, not from a list
    of ours."""
    import ctypes
    import os
    import re

    import fmpy
    header = open(os.path.join(os.path.dirname(fmpy.__file__), "c-code",
                               f"fmi{fmi_version}Functions.h")).read()
    names = set(re.findall(rf"FMI{fmi_version}_Export\s+\w+TYPE\s+(fmi{fmi_version}\w+)\s*;", header))
    assert len(names) == (44 if fmi_version == 2 else 75)
    member = f"binaries/{HOST_DIR[fmi_version]}/OrthotropicContact.so"
    zipfile.ZipFile(fmu_path).extract(member, tmp_path)
    lib = ctypes.CDLL(str(tmp_path / member))
    missing = [n for n in sorted(names) if not hasattr(lib, n)]
    assert missing == []
    assert not hasattr(lib, "oc_law_step")  # the core stays internal
    assert not hasattr(lib, "fmu_model_init")


def test_model_description_at_repo_root_is_the_packaged_one(fmu_path, fmi_version):
    name = "modelDescription.xml" if fmi_version == 2 else "modelDescription-fmi3.xml"
    packaged = zipfile.ZipFile(fmu_path).read("modelDescription.xml").decode()
    assert (ROOT / name).read_text() == packaged


def _B(p):
    return cf.adhesion_tensor(p.eps1, p.eps2, p.alpha)


@pytest.mark.parametrize("rule", ["associated", "coupled", "eq20"])
def test_stick_stiffness_is_B(make, rule):
    p = ContactParams(0.3, 0.6, 2.5e4, 7e3, deg(33), deg(-20), rule)
    f = make(p)
    u = np.array([2e-5, -1.5e-5])
    f.set_inputs(*u, 20.0)
    out = f.outputs()
    assert out["contactState"] == 1
    np.testing.assert_allclose([out["T1"], out["T2"]], -_B(p) @ u, rtol=1e-13)
    np.testing.assert_allclose(np.array(f.tangent())[:, :2], -_B(p), rtol=1e-13)


@pytest.mark.parametrize("rule", ["associated", "coupled", "eq20"])
def test_sliding_forces_lie_on_the_yield_ellipse(make, rule):
    """For any trial, the returned force is on the ellipse with half axes
    mu1 N, mu2 N along beta."""
    p = ContactParams(0.2, 0.7, 1e4, 3e3, deg(10), deg(55), rule)
    N = 12.0
    Qb = cf.rotation(p.beta)
    f = make(p)
    for k in range(72):
        th = 2 * math.pi * k / 72
        f.set_inputs(0.05 * math.cos(th), 0.05 * math.sin(th), N)
        out = f.outputs()
        assert out["contactState"] == 2
        xi = Qb.T @ -np.array([out["T1"], out["T2"]])  # force in the friction axes
        assert (xi[0] / (p.mu1 * N)) ** 2 + (xi[1] / (p.mu2 * N)) ** 2 == pytest.approx(1, abs=1e-12)


@pytest.mark.parametrize("rule", ["associated", "coupled", "eq20"])
def test_yield_half_axes_are_mu_N_along_beta(make, rule):
    """With B aligned to F, pushing along a friction axis slides along it at
    exactly mu_i N."""
    b = deg(37)
    p = ContactParams(0.2, 0.7, 1e4, 3e3, b, b, rule)
    N = 12.0
    for axis, mu in ((0, p.mu1), (1, p.mu2)):
        f = make(p)
        d = cf.rotation(b)[:, axis]
        f.set_inputs(*(0.05 * d), N)
        T = np.array(f.force())
        np.testing.assert_allclose(T, -mu * N * d, rtol=1e-13, atol=1e-13)
        f.close()


def push_along_x1(f, N, du1, steps):
    """Quasistatic push along X1 with lateral equilibrium T2 = 0 (the rig's
    safeguarded Newton on u2).  Returns the slip history as an array."""
    u2 = 0.0
    s = []
    for k in range(1, steps + 1):
        u2, _ = solve_lateral(f, k * du1, u2, N, scale=1e-4, tol=1e-13)
        f.do_step(1e-3)
        o = f.outputs()
        s.append((o["s1"], o["s2"]))
    return np.array(s)


def steady_angle(s, last=50):
    d = s[-1] - s[-1 - last]
    return math.atan2(d[1], d[0])


@pytest.mark.parametrize("a_deg", [5, 20, 45, 60, 78.69, 85])
def test_case1_steady_angle_matches_eq11(make, a_deg):
    p = CASE1.replace(alpha=deg(a_deg), beta=deg(a_deg))
    phi = steady_angle(push_along_x1(make(p), G_N, 2e-4, 300))
    expected = math.atan(cf.eq11_tan_phi(p.mu1, p.mu2, p.beta))
    assert abs(phi - expected) < 1e-9


@pytest.mark.parametrize("a_deg", [5, 15, 26.565, 45, 70, 85])
def test_case5_steady_angle_matches_eq25(make, a_deg):
    p = CASE5.replace(alpha=deg(a_deg), beta=deg(a_deg + 90))
    phi = steady_angle(push_along_x1(make(p), G_N, 2e-4, 300))
    l1, l2 = cf.eigen_ratio_case5(p.mu1, p.mu2, p.eps1, p.eps2)
    expected = math.atan(cf.eq25_tan_phi(l1, l2, p.alpha))
    assert abs(phi - expected) < 1e-9


@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_steady_slip_direction_is_G_q(make, rule):
    """Pushed along a fixed direction d, steady sliding moves along d, and
    d is parallel to F q (associated) or (B F B)^-1 q (coupled)."""
    p = ContactParams(0.25, 0.55, 2e4, 4e3, deg(30), deg(100), rule)
    f = make(p)
    d = np.array([math.cos(0.4), math.sin(0.4)])
    for k in range(1, 400):
        f.set_inputs(*(k * 1e-4 * d), 9.0)
        f.do_step(1e-3)
    o = f.outputs()
    q = -np.array([o["T1"], o["T2"]])
    F = cf.friction_tensor(p.mu1, p.mu2, p.beta)
    B = _B(p)
    G = F if rule == "associated" else np.linalg.inv(B @ F @ B)
    g = G @ q
    assert abs(g[0] * d[1] - g[1] * d[0]) < 1e-10 * np.linalg.norm(g)


@pytest.mark.parametrize("rule", ["associated", "coupled"])
def test_steady_angle_independent_of_step_size(make, rule):
    p = CASE5.replace(alpha=deg(26.565), beta=deg(116.565), rule=rule)
    coarse = steady_angle(push_along_x1(make(p), G_N, 1e-3, 120), last=20)
    fine = steady_angle(push_along_x1(make(p), G_N, 1e-4, 1200), last=200)
    assert abs(coarse - fine) < 1e-11


def test_eq20_rule_is_step_size_dependent(make):
    """The literal eq. (20) is offered for reproduction only: its steady state
    moves with the step size (model notes)."""
    p = CASE5.replace(alpha=deg(26.565), beta=deg(116.565), rule="eq20")
    coarse = steady_angle(push_along_x1(make(p), G_N, 1e-3, 300), last=20)
    fine = steady_angle(push_along_x1(make(p), G_N, 1e-4, 3000), last=200)
    assert abs(coarse - fine) > 1e-3


def _fd_tangent(f, u1, u2, N, h=(1e-8, 1e-8, 1e-6)):
    st = f.get_state()
    cols = []
    for j in range(3):
        xp = [u1, u2, N]
        xm = [u1, u2, N]
        xp[j] += h[j]
        xm[j] -= h[j]
        f.set_state(st)
        f.set_inputs(*xp)
        Tp = np.array(f.force())
        f.set_state(st)
        f.set_inputs(*xm)
        Tm = np.array(f.force())
        cols.append((Tp - Tm) / (2 * h[j]))
    f.set_state(st)
    f.set_inputs(u1, u2, N)
    f.free_state(st)
    return np.array(cols).T


@pytest.mark.parametrize("rule", ["associated", "coupled", "eq20"])
@pytest.mark.parametrize("where", ["stick", "slip", "open"])
def test_directional_derivative_matches_finite_differences(make, rule, where):
    p = ContactParams(0.15, 0.45, 1.2e4, 3e3, deg(28), deg(75), rule)
    f = make(p)
    for k in range(1, 30):  # a loaded history, so that s != 0
        f.set_inputs(1e-4 * k, 4e-5 * k, 10.0)
        f.do_step(1e-3)
    o = f.outputs()
    u = {"stick": (o["s1"] + 1e-4, o["s2"] + 1e-4, 10.0),
         "slip": (4e-3, -1e-3, 10.0), "open": (4e-3, -1e-3, -2.0)}[where]
    f.set_inputs(*u)
    assert f.outputs()["contactState"] == {"stick": 1, "slip": 2, "open": 0}[where]
    J = np.array(f.tangent())
    fd = _fd_tangent(f, *u)
    np.testing.assert_allclose(J, fd, rtol=1e-5, atol=1e-6)


def test_outputs_pending_until_do_step(make):
    f = make(CASE5)
    f.set_inputs(0.01, 0.0, G_N)
    pending = f.outputs()
    f.set_inputs(0.02, 0.0, G_N)  # iterate: the first trial was not committed
    f.set_inputs(0.01, 0.0, G_N)
    assert f.outputs() == pending
    f.do_step(1e-3)
    assert f.outputs() == pending  # after the commit the outputs read the same
    f.do_step(1e-3)  # held inputs: a new step that sticks with the same force
    held = f.outputs()
    assert held["contactState"] == 1
    assert held["T1"] == pytest.approx(pending["T1"], rel=1e-12)
    assert held["dissipatedEnergy"] == pending["dissipatedEnergy"]


def test_open_contact_and_unloaded_recontact(make):
    f = make(CASE5)
    f.set_inputs(0.01, 0.003, G_N)
    f.do_step(1e-3)
    assert f.outputs()["contactState"] == 2
    e_before = f.outputs()["dissipatedEnergy"]
    f.set_inputs(0.02, 0.004, 0.0)
    f.do_step(1e-3)
    o = f.outputs()
    assert (o["contactState"], o["T1"], o["T2"], o["s1"], o["s2"]) == (0, 0.0, 0.0, 0.02, 0.004)
    assert math.copysign(1.0, o["T1"]) == 1.0  # +0.0, not -0.0
    assert o["dissipatedEnergy"] == e_before
    f.set_inputs(0.02, 0.004, G_N)
    o = f.outputs()
    assert (o["contactState"], o["T1"], o["T2"]) == (1, 0.0, 0.0)


def test_dissipated_energy_equals_friction_work_in_steady_sliding(make):
    """Sliding along the friction axis 1 at force mu1 N: the energy grows by
    mu1 N per metre of slip."""
    p = ContactParams(0.3, 0.8, 1e4, 1e4, 0.0, 0.0, "coupled")
    f = make(p)
    for k in range(1, 201):
        f.set_inputs(1e-3 * k, 0.0, 10.0)
        f.do_step(1e-3)
    e1, s1 = f.outputs()["dissipatedEnergy"], f.outputs()["s1"]
    for k in range(201, 301):
        f.set_inputs(1e-3 * k, 0.0, 10.0)
        f.do_step(1e-3)
    o = f.outputs()
    assert (o["dissipatedEnergy"] - e1) == pytest.approx(0.3 * 10.0 * (o["s1"] - s1), rel=1e-12)


def test_instances_are_independent(make):
    a, b = make(CASE5), make(CASE1)
    a.set_inputs(0.01, 0.0, G_N)
    a.do_step(1e-3)
    b.set_inputs(1e-6, 0.0, G_N)
    assert a.outputs()["contactState"] == 2 and b.outputs()["contactState"] == 1
    assert a.outputs()["s1"] != 0 and b.outputs()["s1"] == 0


# -- the error contract ------------------------------------------------------

def set_real(f, vrs, values):
    """fmpy's raising setter of the FMU's version: setReal (2.0) / setFloat64 (3.0)."""
    return f.slave.setReal(vrs, values) if f.fmi_version == 2 else f.slave.setFloat64(vrs, values)


def get_real(f, vrs):
    return f.slave.getReal(vrs) if f.fmi_version == 2 else f.slave.getFloat64(vrs)


def set_rule(f, vrs, values):
    """slidingRule: an Integer in FMI 2.0, an Enumeration (Int64 calls) in FMI 3.0."""
    return f.slave.setInteger(vrs, values) if f.fmi_version == 2 else f.slave.setInt64(vrs, values)


@pytest.mark.parametrize("name,value,why", [
    ("mu1", 0.0, "mu1"), ("mu2", -0.2, "mu2"), ("eps1", 0.0, "eps1"), ("eps2", -1.0, "eps2"),
    ("mu1", float("nan"), "finite"), ("alpha", float("inf"), "finite")])
def test_invalid_parameters_are_rejected_and_logged(make, name, value, why):
    f = make()
    with pytest.raises(FMICallException):
        set_real(f, [f.vr[name]], [value])
    assert f.messages and f.messages[-1][0] == 3 and why in f.messages[-1][2]
    f.initialize(CASE5)  # the rejected value did not stick: defaults are still valid


def test_unknown_rule_rejected(make):
    f = make()
    with pytest.raises(FMICallException):
        set_rule(f, [f.vr["slidingRule"]], [4])
    assert "slidingRule" in f.messages[-1][2]


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -float("inf")])
def test_nonfinite_inputs_rejected_state_kept(make, bad):
    f = make(CASE5)
    f.set_inputs(0.001, 0.0, G_N)
    before = f.outputs()
    with pytest.raises(FMUError, match="finite"):
        f.set_inputs(0.002, bad, G_N)
    assert f.outputs() == before
    assert get_real(f, [f.vr["u1"]]) == [0.001]


def test_overflowing_inputs_rejected_never_nan(make):
    f = make(CASE5)
    with pytest.raises(FMUError, match="overflow"):
        f.set_inputs(1e300, -1e300, 1e300)
    assert all(math.isfinite(v) for k, v in f.outputs().items())


def test_unknown_value_reference_and_wrong_type(make):
    f = make(CASE5)
    with pytest.raises(FMICallException):
        get_real(f, [999])
    assert "999" in f.messages[-1][2]
    with pytest.raises(FMICallException):
        get_real(f, [f.vr["contactState"]])
    with pytest.raises(FMICallException):
        set_real(f, [f.vr["T1"]], [1.0])
    assert "output" in f.messages[-1][2]


def test_illegal_call_sequences(make):
    f = make()
    with pytest.raises(FMICallException):
        f.slave.doStep(0.0, 1e-3)  # before initialization
    assert "must not be called" in f.messages[-1][2]
    f.initialize(CASE5)
    with pytest.raises(FMICallException):
        set_real(f, [f.vr["mu1"]], [0.3])  # fixed parameter after init
    assert "fixed" in f.messages[-1][2]
    with pytest.raises(FMICallException):
        f.slave.doStep(1.0, 1e-3)  # wrong communication point
    with pytest.raises(FMICallException):
        f.slave.doStep(0.0, 0.0)
    f.slave.terminate()
    f.initialized = False
    with pytest.raises(FMICallException):
        f.slave.doStep(0.0, 1e-3)
    f.reset(CASE1)  # reset makes parameters settable again
    assert get_real(f, [f.vr["mu2"]]) == [0.5]


def test_debug_logging_categories(make):
    f = make(CASE5)
    n = len(f.messages)
    f.set_inputs(0.0, 0.0, 1.0)
    assert len(f.messages) == n  # no call trace unless asked for
    f.slave.setDebugLogging(True, ["logCalls"])
    f.set_inputs(0.0, 0.0, 2.0)
    assert f.messages[-1][1] == "logCalls"
    assert ("fmi2SetReal" if f.fmi_version == 2 else "fmi3SetFloat64") in f.messages[-1][2]
    f.slave.setDebugLogging(False, ["logCalls", "logStatusError"])
    n = len(f.messages)
    with pytest.raises(FMUError):
        f.set_inputs(float("nan"), 0.0, 1.0)
    assert len(f.messages) == n  # errors filtered out on request
    with pytest.raises(FMICallException):
        f.slave.setDebugLogging(True, ["noSuchCategory"])


def test_sources_compile_into_a_working_binary(fmu_path, fmi_version, tmp_path):
    """The sources/ folder builds on an importer's side (fmpy's CMake build;
    for FMI 3.0 from sources/buildDescription.xml)."""
    from fmpy import extract
    from fmpy.build import build_platform_binary

    from orthocontact.fmu.contact import ContactFMU
    unzip = extract(str(fmu_path), unzipdir=str(tmp_path / "fmu"))
    so = tmp_path / "fmu" / "binaries" / HOST_DIR[fmi_version] / "OrthotropicContact.so"
    so.unlink()
    (tmp_path / "build").mkdir()
    build_platform_binary(unzip, build_dir=str(tmp_path / "build"))
    assert so.exists()
    rebuilt = tmp_path / "rebuilt.fmu"
    with zipfile.ZipFile(rebuilt, "w") as z:
        for path in (tmp_path / "fmu").rglob("*"):
            if path.is_file():
                z.write(path, path.relative_to(tmp_path / "fmu").as_posix())
    f = ContactFMU(rebuilt, instance_name="rebuilt")
    f.initialize(CASE1)
    f.set_inputs(1e-6, 0.0, 1.0)
    assert f.force()[0] == pytest.approx(-1e-2, rel=1e-12)
    f.close()
