"""The FMI cross-check files of every model of OC_MODELS
(tools/make_crosscheck.py) hold: fmpy reproduces each reference from its
input file and options, the FMI 2.0 and 3.0 references agree, and each
designed path's phases obey independent truths (the law's tensors over the
FMU's default parameters, the cells' sums and the rig's lateral steps
written out here)."""
import csv

import numpy as np
import pytest

import make_crosscheck  # tools/ is on sys.path (conftest)
from conformance.drive import input_rows, inputs, outputs
from orthocontact import closed_forms as cf
from orthocontact.closed_forms import patch as cp
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.variables import law_parameters, models
from paths import ROOT

CONTACT, PATCH, RIG = models()["contact"], models()["patch"], models()["rig"]


def _defaults(model, names):
    """Default parameters, as the FMU's own model description (read by
    fmpy) gives them."""
    from fmpy import read_model_description
    md = read_model_description(str(find_fmu(fmi_version=2, model=model)))
    return {v.name: float(v.start) for v in md.modelVariables if v.name in names}


LAW = _defaults(CONTACT, law_parameters())
assert _defaults(PATCH, law_parameters()) == LAW
B = cf.adhesion_tensor(LAW["eps1"], LAW["eps2"], LAW["alpha"])
F = cf.friction_tensor(LAW["mu1"], LAW["mu2"], LAW["beta"])


def _read(path):
    with open(path) as fh:
        rows = list(csv.reader(fh))
    return rows[0], np.array(rows[1:], dtype=float)


def _crosscheck_dir(version, model):
    platform = {2: "linux64", 3: "x86_64-linux"}[version]
    found = sorted((ROOT / "cross-check" / "fmus" / f"{version}.0" / "cs" / platform /
                    "orthocontact").glob(f"*/{model}"),
                   key=lambda d: tuple(int(x) for x in d.parent.name.split(".") if x.isdigit()))
    assert found, f"cross-check files of {model} missing (make generated)"
    return found[-1]


def _options(version, model) -> dict:
    d = _crosscheck_dir(version, model)
    opt = dict(line.split(", ") for line in (d / f"{model}_ref.opt").read_text().splitlines())
    assert set(opt) == {"StartTime", "StopTime", "StepSize", "RelTol"}
    return {k: float(x) for k, x in opt.items()}


def _files(version, model):
    """(input names, inputs, output names, reference) of the model's files."""
    d = _crosscheck_dir(version, model)
    names, inp = _read(d / f"{model}_in.csv")
    rnames, ref = _read(d / f"{model}_ref.csv")
    assert names[0] == "time" and rnames[0] == "time"
    return names, inp, rnames, ref


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("model", list(models().values()))
def test_every_models_crosscheck_files_are_its_path_and_fmpy_reproduces_them(model, version):
    """fmpy reproduces the reference from the files within their RelTol."""
    from fmpy import simulate_fmu
    path = make_crosscheck.cross_checks([model])[model]
    opt = _options(version, model)
    names, inp, rnames, ref = _files(version, model)
    assert names == ["time", *path.inputs] and rnames == ["time", *path.outputs]
    signals = np.array([tuple(r) for r in inp], dtype=[(n, float) for n in names])
    out = simulate_fmu(str(find_fmu(fmi_version=version, model=model)),
                       start_time=opt["StartTime"], stop_time=opt["StopTime"],
                       step_size=opt["StepSize"], output_interval=opt["StepSize"],
                       input=signals, output=rnames[1:])
    here = np.column_stack([out[n] for n in rnames])
    assert here.shape == ref.shape
    np.testing.assert_allclose(here, ref, rtol=opt["RelTol"], atol=1e-12)


@pytest.mark.parametrize("version", [2, 3])
def test_point_crosscheck_files_obey_the_law(version):
    names, inp, rnames, ref = _files(version, CONTACT)
    assert names == ["time", "u1", "u2", "N"]
    col = {n: ref[:, i] for i, n in enumerate(rnames)}
    u_prev = inp[:-1]          # outputs at t_k come from the inputs of t_{k-1}
    y = ref[1:]
    state = y[:, rnames.index("contactState")]
    T = y[:, [rnames.index("T1"), rnames.index("T2")]]
    s = y[:, [rnames.index("s1"), rnames.index("s2")]]
    stick0 = (inp[1:, 0] <= 0.15) & (state == 1)
    assert stick0.sum() > 100
    np.testing.assert_allclose(T[stick0], -(u_prev[stick0, 1:3] @ B.T), rtol=1e-12, atol=1e-12)
    open_ = u_prev[:, 3] <= 0
    assert open_.sum() > 50 and np.all(state[open_] == 0)
    assert np.all(T[open_] == 0)
    # the importer interpolates the input table at its own time points: rounding
    np.testing.assert_allclose(s[open_], u_prev[open_, 1:3], rtol=1e-12)
    slip = state == 2
    assert slip.sum() > 200
    yield_ = np.sqrt(np.einsum("ij,jk,ik->i", T[slip], F, T[slip]))
    np.testing.assert_allclose(yield_, u_prev[slip, 3], rtol=1e-12)
    E = col["dissipatedEnergy"]
    assert np.all(np.diff(E) >= 0) and E[-1] > 0
    held = (inp[1:, 0] > 0.46) & (inp[1:, 0] <= 0.55)
    assert np.all(np.diff(T[held], axis=0) == 0) and np.all(np.diff(E[1:][held]) == 0)


@pytest.mark.parametrize("version", [2, 3])
def test_patch_crosscheck_files_obey_the_law(version):
    """The patch's path against the cells written out here (0.1 m x 0.1 m,
    8 x 8 cells, each holding B/64 and its share of N at its centre)."""
    names, inp, rnames, ref = _files(version, PATCH)
    assert names == ["time", "u1", "u2", "theta", "N", "p1", "p2"]
    x, y = cp.cell_centres(0.1, 0.1, 8, 8)
    t_in, out = inp[:-1], ref[1:]          # outputs at t_k come from the inputs of t_{k-1}
    at = {n: out[:, i] for i, n in enumerate(rnames)}
    u, theta, N, p1 = t_in[:, 1:3], t_in[:, 3], t_in[:, 4], t_in[:, 5]
    T, Mz, state = np.column_stack([at["T1"], at["T2"]]), at["Mz"], at["contactState"]
    scale = np.abs(T).max()

    # stick in translation and back: the point's T = -B u, no moment
    moved = t_in[:, 0] < 0.25
    assert np.all(state[moved] == 1) and moved.sum() > 200
    np.testing.assert_allclose(T[moved], -(u[moved] @ B.T), rtol=1e-12, atol=1e-12 * scale)
    assert np.all(np.abs(Mz[moved]) <= 1e-12 * scale * 0.1)

    # stick in a small turn: every cell pulled back by B/64 (R - I) r
    turned = (t_in[:, 0] > 0.25) & (t_in[:, 0] < 0.45)
    assert np.all(state[turned] == 1)
    r = np.stack([x, y])
    for k in np.flatnonzero(turned)[::20]:
        Rr = cf.rotation(theta[k]) @ r
        t = -(B / 64) @ (Rr - r)
        assert Mz[k] == pytest.approx(np.sum(Rr[0] * t[1] - Rr[1] * t[0]), rel=1e-12)
        np.testing.assert_allclose(T[k], t.sum(axis=1), atol=1e-12 * abs(Mz[k]) / 0.05)

    # turned on: every cell slides, and the moment approaches the grid's
    # steady full-slip moment at that angle (the law's steady force at each
    # cell, the texture turned by -theta in the body's frame) within the
    # elastic lag, the elastic length over the cells' mean radius
    end = np.flatnonzero(t_in[:, 0] < 0.75)[-1]
    assert state[end] == 3 and at["slipFraction"][end] == 1.0
    th = theta[end]
    steady = cp.full_slip_rotation_grid(LAW["mu1"], LAW["mu2"], LAW["eps1"], LAW["eps2"],
                                        LAW["alpha"] - th, LAW["beta"] - th, "coupled",
                                        0.1, 0.1, N[end], 8, 8)[2]
    lag = max(LAW["mu1"], LAW["mu2"]) * N[end] / min(LAW["eps1"], LAW["eps2"]) / np.mean(np.hypot(x, y))
    assert abs(Mz[end] - steady) <= lag * abs(steady) and np.sign(Mz[end]) == np.sign(steady)

    # held: sticks with the last force and moment, dissipates nothing
    held = (t_in[:, 0] > 0.751) & (t_in[:, 0] <= 0.80)
    assert np.all(state[held] == 1)
    for q in (T[held, 0], T[held, 1], Mz[held], at["dissipatedEnergy"][held]):
        assert np.all(q == q[0])

    # the centre of pressure moves towards +x with the turn held: the cells
    # at x < 0 lose load on the yield surface and slide, those at x > 0 stick
    shifted = (t_in[:, 0] > 0.801) & (t_in[:, 0] < 0.85)
    assert np.all(state[shifted] == 2) and np.all(at["slipFraction"][shifted] == 0.5)
    assert np.all(p1[shifted] > 0)

    # open: nothing
    open_ = N <= 0
    assert open_.sum() > 20 and np.all(state[open_] == 0)
    assert np.all(T[open_] == 0) and np.all(Mz[open_] == 0) and np.all(at["slipFraction"][open_] == 0)

    # re-contact unloaded and slide in translation, uniform pressure: every
    # cell goes the same way with the same share, so the force lies on the
    # friction ellipse of N and the moment vanishes
    slid = np.flatnonzero((state == 3) & (t_in[:, 0] > 0.9))
    assert len(slid) > 100
    yield_ = np.sqrt(np.einsum("ij,jk,ik->i", T[slid], F, T[slid]))
    np.testing.assert_allclose(yield_, N[slid], rtol=1e-12)
    assert np.all(np.abs(Mz[slid]) <= 1e-12 * scale * 0.1)

    E = at["dissipatedEnergy"]
    assert np.all(np.diff(E) >= 0) and E[-1] > E[end] > 0


@pytest.mark.parametrize("version", [2, 3])
def test_rig_crosscheck_files_obey_the_rig(version):
    """The rig's path against its motion written out here: x1 = u1 =
    velocity t, N = mass g, driveForce = fInt - T1, and x2 = u2 each step
    with the step's T2 held (symplectic Euler, v += h T2 / mass, x2 += h v:
    the defaults have no strip friction or viscosity, checked)."""
    names, inp, rnames, ref = _files(version, RIG)
    assert names == ["time", "T1", "T2"]
    p = _defaults(RIG, ("mass", "g", "fInt", "velocity", "muStrip", "cStrip"))
    assert p["muStrip"] == 0 and p["cStrip"] == 0
    at = {n: ref[:, i] for i, n in enumerate(rnames)}
    t, h = ref[:, 0], _options(version, RIG)["StepSize"]
    np.testing.assert_allclose(at["x1"], p["velocity"] * t, rtol=1e-15, atol=0)
    assert np.array_equal(at["u1"], at["x1"]) and np.array_equal(at["u2"], at["x2"])
    assert np.all(at["N"] == p["mass"] * p["g"])
    # outputs at t_k come from the inputs of t_{k-1}; the importer interpolates
    # the input table at its own time points: rounding
    np.testing.assert_allclose(at["driveForce"][1:], p["fInt"] - inp[:-1, 1], rtol=1e-12)
    v, x, x2 = 0.0, 0.0, [0.0]
    for T2 in inp[:-1, 2]:
        v += h * T2 / p["mass"]
        x += h * v
        x2.append(x)
    np.testing.assert_allclose(at["x2"], x2, rtol=1e-12, atol=1e-18)
    # the phases: straight on, sideways and back, coasting at a constant lateral velocity
    assert np.all(at["x2"][t <= 0.301] == 0) and at["x2"].max() > 1e-3
    coast = np.diff(at["x2"][t > 0.812])
    assert np.all(coast < 0) and np.ptp(coast) <= 1e-12 * np.abs(at["x2"]).max()   # x2's rounding


@pytest.mark.parametrize("model", list(models().values()))
def test_crosscheck_references_of_both_versions_agree(model):
    assert np.array_equal(_read(_crosscheck_dir(2, model) / f"{model}_ref.csv")[1],
                          _read(_crosscheck_dir(3, model) / f"{model}_ref.csv")[1])


@pytest.mark.parametrize("model", list(models().values()))
def test_a_model_without_a_designed_path_would_get_the_conformance_drive(model):
    """What make_crosscheck writes for a model of a new role: its inputs
    and outputs, the drive's signals at every communication point."""
    path = make_crosscheck.driven(model)
    assert path.inputs == tuple(v.name for v in inputs(model))
    assert path.outputs == tuple(v.name for v in outputs(model))
    table = make_crosscheck.input_table(path)
    assert np.array_equal(table[:, 1:], input_rows(model, len(table), make_crosscheck.STEP))


def test_every_model_of_oc_models_has_a_crosscheck_path_and_no_other():
    assert list(make_crosscheck.cross_checks()) == list(models().values())
    assert set(make_crosscheck.PATHS) <= set(models())   # a designed path of no model's role is stale
