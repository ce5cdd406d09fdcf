"""The model structure every model declares (ModelStructure: every output's and
initial unknown's dependencies and dependenciesKind, FMI 2.0 and 3.0) against
what their binaries do, found independently of the table: each known of a
mode is perturbed through fmpy at several base points, and the outputs that
change are its dependents.  Initialization: the knowns are the inputs, the
parameters (initial = exact) and the start time, read in initialization mode;
step mode: the inputs, read at a communication point after the first step.
The descriptions validate against the FMI schemas fmpy ships, and the
generator refuses a table that leaves an output's dependencies out."""
import functools
import math
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from fmu_values import schema_errors, unzipped
from orthocontact import closed_forms as cf
from orthocontact.fmu import MODEL_IDENTIFIER, RIG_MODEL_IDENTIFIER, find_fmu
from orthocontact.fmu.slave import integer_call
from orthocontact.fmu.variables import manifest, models
from paths import ROOT


class Instance:
    """One instance of a model through fmpy, with the calls both versions
    share.  Each model's description and loaded library are read once
    (loaded); each Instance is a fresh instance of it (instantiate), freed
    without unloading the library: what an importer running several
    instances does."""

    def __init__(self, version, model):
        self.md, self.s = loaded(version, model)
        self.var = {v.name: v for v in self.md.modelVariables}
        self.version = version
        self.s.instantiate()

    def set(self, values: dict):
        for name, x in values.items():
            v = self.var[name]
            if v.type in ("Real", "Float64"):
                (self.s.setReal if self.version == 2 else self.s.setFloat64)([v.valueReference], [x])
            else:   # by the function of its type (FMI 3.0: n1, n2 UInt64, enumerations Int64)
                integer_call(self.s, self.version, v.type)([v.valueReference], [int(x)])

    def outputs(self) -> dict:
        out = {}
        for v in self.md.modelVariables:
            if v.causality != "output":
                continue
            if v.type in ("Real", "Float64"):
                get = self.s.getReal if self.version == 2 else self.s.getFloat64
            else:
                get = self.s.getInteger if self.version == 2 else self.s.getInt32
            if v.dimensions:     # an FMI 3.0 array: all its values, its shape the structural parameters'
                n = math.prod(int(integer_call(self.s, 3, d.variable.type, get=True)(
                    [d.variable.valueReference])[0]) for d in v.dimensions)
                out[v.name] = tuple(get([v.valueReference], nValues=n))
            else:
                out[v.name] = get([v.valueReference])[0]
        return out

    def enter_initialization(self, start_time):
        if self.version == 2:
            self.s.setupExperiment(startTime=start_time)
            self.s.enterInitializationMode()
        else:
            self.s.enterInitializationMode(startTime=start_time)

    def free(self):
        self.s.terminate()
        # fmpy's freeInstance also unloads the library, which the next instance loads again
        (self.s.fmi2FreeInstance if self.version == 2 else self.s.fmi3FreeInstance)(self.s.component)


@functools.cache
def loaded(version, model):
    """(model description, fmpy slave with its library loaded) of the installed FMU."""
    path = str(find_fmu(fmi_version=version, model=model))
    md = read_model_description(path)
    if version == 2:
        from fmpy.fmi2 import FMU2Slave as Slave
    else:
        from fmpy.fmi3 import FMU3Slave as Slave
    return md, Slave(guid=md.guid, unzipDirectory=unzipped(path), modelIdentifier=model,
                     instanceName="structure")


def knowns_by_mode(md):
    """{"step": the inputs, "init": the inputs, parameters and the time}."""
    inputs = [v.name for v in md.modelVariables if v.causality == "input"]
    init = [v.name for v in md.modelVariables
            if v.causality in ("input", "independent") or v.initial == "exact"]
    return {"step": inputs, "init": init}


def observe(version, model, point, mode):
    """The outputs of `model` at a base point: {"time": start time, "init":
    parameters and inputs set before and in initialization mode, "step":
    inputs set after the first step}; read in initialization mode (init) or
    at the communication point after the first step (step)."""
    f = Instance(version, model)
    try:
        kinds = {n: v.causality for n, v in f.var.items()}
        init = point["init"]
        f.set({n: x for n, x in init.items() if kinds[n] in ("parameter", "structuralParameter")})
        f.enter_initialization(point["time"])
        f.set({n: x for n, x in init.items() if kinds[n] == "input"})
        if mode == "init":
            return f.outputs()
        f.s.exitInitializationMode()
        f.s.doStep(point["time"], 1e-3)
        f.set(point["step"])
        return f.outputs()
    finally:
        f.free()


def perturbations(model, var, value):
    """Other admissible values of a known: every other item of an
    enumeration / integer of at most 8 (its range the table's: fmpy 0.3.32
    reads no min/max of an FMI 3.0 UInt64, such as n1); of a longer range
    (n1, n2: 1 to 32 cells) both ends, their neighbours and the middle, each
    a fresh instance; 10 % either side of a number (0.1 of its unit beside 0,
    as an angle, a time or a coefficient that starts at 0)."""
    if var.type not in ("Real", "Float64"):
        row = manifest(model).variable(var.name)
        lo, hi = int(row.min), int(row.max)
        items = range(lo, hi + 1) if hi - lo < 8 else (lo, lo + 1, (lo + hi) // 2, hi - 1, hi)
        return [k for k in items if k != value]
    if value != 0:
        return [value * 1.1, value * 0.9]
    return [0.1, -0.1] if var.min is None or float(var.min) < 0 else [0.1]


def admissible(model, values):
    """Whether the model takes these values together: the patch refuses n1 = 1
    (n2 = 1) with p1 (p2) off the axis while pressed, its one cell along that
    side cannot carry it (tests/fmus/test_patch.py), so such an n is no
    perturbation of a point whose centre of pressure is off the centre."""
    if model != "ContactPatch" or not values.get("N", 0.0) > 0:
        return True
    return not any(values.get(n) == 1 and values.get(p, 0.0) != 0 for n, p in (("n1", "p1"), ("n2", "p2")))


def measured_dependencies(version, model, points, mode):
    """{output: {known: the changes it makes, as (base, perturbed) pairs}}."""
    md = loaded(version, model)[0]
    var = {v.name: v for v in md.modelVariables}
    found = {v.name: {} for v in md.modelVariables if v.causality == "output"}
    for point in points:
        base = observe(version, model, point, mode)
        for known in knowns_by_mode(md)[mode]:
            where = "time" if known == "time" else "step" if mode == "step" else "init"
            value = point[where] if known == "time" else point[where][known]
            for other in perturbations(model, var[known], value):
                moved = dict(point)
                if known == "time":
                    moved["time"] = other
                else:
                    moved[where] = {**point[where], known: other}
                    if not admissible(model, moved[where]):
                        continue
                out = observe(version, model, moved, mode)
                for name in found:
                    if out[name] != base[name]:
                        found[name].setdefault(known, []).append((value, other, base[name], out[name]))
    return found


def declared(version, model):
    """{mode: {output: {known: kind}}} from the model description, as fmpy reads it."""
    md = loaded(version, model)[0]
    out = {}
    for mode, unknowns in (("step", md.outputs), ("init", md.initialUnknowns)):
        out[mode] = {}
        for u in unknowns:
            assert u.dependencies is not None and u.dependenciesKind is not None, u.variable.name
            assert len(u.dependencies) == len(u.dependenciesKind)
            out[mode][u.variable.name] = {d.name: k for d, k in zip(u.dependencies, u.dependenciesKind)}
    return out


# -- the base points: each branch of each model, so that every dependency can show ----------------

LAW = dict(mu1=0.408, mu2=0.625, eps1=12510.0, eps2=1e4, alpha=math.pi / 2, beta=0.0)  # the defaults
N0 = 18.39
S0 = (4e-4, -3e-4)   # an explicit initial slip [m]


def elastic_at(ratio, angle=math.pi / 4):
    """The displacement along `angle` whose trial force is `ratio` times the
    friction limit at N0 (the yield function's sqrt(q.F q) / N)."""
    B = cf.adhesion_tensor(LAW["eps1"], LAW["eps2"], LAW["alpha"])
    F = cf.friction_tensor(LAW["mu1"], LAW["mu2"], LAW["beta"])
    d = np.array([math.cos(angle), math.sin(angle)])
    q = B @ d
    return d * ratio * N0 / math.sqrt(q @ F @ q)


def contact_points(mode):
    def at(ratio, **extra):
        u = elastic_at(ratio) + (np.array(S0) if extra.get("initialSlip") == 2 else 0.0)
        return {"u1": float(u[0]), "u2": float(u[1]), "N": N0}
    explicit = dict(initialSlip=2, s1Start=S0[0], s2Start=S0[1])
    if mode == "init":
        return [{"time": 0.0, "init": {**LAW, "slidingRule": 2, "initialSlip": 1, "s1Start": 0.0,
                                       "s2Start": 0.0, **at(0.5)}},
                {"time": 0.0, "init": {**LAW, "slidingRule": 2, **explicit, **at(0.99, **explicit)}},
                {"time": 0.0, "init": {**LAW, "slidingRule": 2, **explicit, **at(1.5, **explicit)}}]
    # step mode: from an unloaded start at u = 0, just inside and well beyond the limit
    return [{"time": 0.0, "init": {**LAW, "u1": 0.0, "u2": 0.0, "N": N0}, "step": at(r)}
            for r in (0.99, 1.5)]


RIG = dict(mass=1.875, g=9.806, fInt=5.0, velocity=0.244, muStrip=0.3, cStrip=2.0)


def rig_points(mode):
    return [{"time": t, "init": {**RIG, "T1": -8.0, "T2": 3.0}, "step": {"T1": -7.0, "T2": 2.5}}
            for t in (0.25, 1.0)]


# The patch: 4 x 4 cells, the centre of pressure off the centre, turned and
# displaced so that each branch (every cell stuck at the edge of sliding,
# every cell sliding) shows at a base point.  Which cell slides first, and so
# which knowns move it by more than the 1 % margin, depends on the direction
# of the push and the share of the turn: three of them.
PATCH = dict(LAW, slidingRule=2, length=0.1, width=0.08, n1=4, n2=4)
P0 = dict(p1=5e-3, p2=-4e-3)        # inside the kern: 0.05 + 0.05 < 1/6
PUSHES = ((-40.0, 5e-3), (60.0, 2e-2), (150.0, 1e-2))   # direction [deg], turn [rad] per unit


def patch_inputs(scale, push, slip=(0.0, 0.0)):
    """u, theta along one direction of the patch's inputs: `scale` times the
    point's elastic range along push[0] [deg] and push[1] * scale [rad]."""
    u = elastic_at(scale, math.radians(push[0])) + np.array(slip)
    return {"u1": float(u[0]), "u2": float(u[1]), "theta": push[1] * scale, "N": N0, **P0}


def patch_stick_edge(mode, base, model="ContactPatch"):
    """The largest scale of base(scale) at which every cell still sticks
    (contactState 1), by bisection through the FMU, less 1 %: a cell then
    sits within 1 % of sliding, so that every known that moves its trial or
    its limit by 10 % changes the state."""
    lo, hi = 0.0, 1.0
    assert observe(3, model, base(lo), mode)["contactState"] == 1     # the bracket holds
    assert observe(3, model, base(hi), mode)["contactState"] != 1
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        state = observe(3, model, base(mid), mode)["contactState"]
        lo, hi = (mid, hi) if state == 1 else (lo, mid)
    return 0.99 * lo


def patch_points(mode):
    explicit = dict(initialSlip=2, s1Start=S0[0], s2Start=S0[1])
    points = []
    for push in PUSHES:
        if mode == "init":
            def base(scale, push=push):
                return {"time": 0.0, "init": {**PATCH, **explicit, **patch_inputs(scale, push, S0)}}
        else:
            def base(scale, push=push):
                return {"time": 0.0, "init": {**PATCH, **patch_inputs(0.0, push)},
                        "step": patch_inputs(scale, push)}
        points += [base(patch_stick_edge(mode, base)), base(3.0)]
    if mode == "init":
        points.append({"time": 0.0, "init": {**PATCH, "initialSlip": 1, "s1Start": 0.0, "s2Start": 0.0,
                                             **patch_inputs(0.5, PUSHES[0])}})
    return points


# The pad: the patch's pushes on a pose in full contact, tilted (every
# known of the pose moves each cell's limit, so each flips the state at the
# edge of sliding), and on one whose trailing corners lift (the contact and
# the pressure's resultants move with every known of the pose, the grid's
# rounding with n1, n2); its foundation presses with ~4-19 N.
PAD = dict(LAW, slidingRule=2, length=0.1, width=0.08, n1=4, n2=4, kn=1.2e7, dn=0.0)
# Rolling in full contact (a step moves the states by 0.02 cells), not on the
# lifted pose: no output depends on vr, which moves the states from the next step on.
FULL = dict(d=2e-4, phi1=3e-4, phi2=1.2e-3, vr=0.5)    # corners 2e-4 +- 6e-5 +- 1.2e-5 m
LIFTED = dict(d=4e-5, phi1=3e-4, phi2=1.2e-3, vr=0.0)  # corners 4e-5 +- 6e-5 +- 1.2e-5 m: x < -0.023 m lifts


def pad_inputs(scale, push, pose, slip=(0.0, 0.0)):
    x = patch_inputs(scale, push, slip)
    return {**{k: x[k] for k in ("u1", "u2", "theta")}, **pose}


def pad_points(mode):
    explicit = dict(initialSlip=2, s1Start=S0[0], s2Start=S0[1])
    points = []
    for pose, pushes in ((FULL, PUSHES), (LIFTED, PUSHES[:1])):
        for push in pushes:
            if mode == "init":
                def base(scale, push=push, pose=pose):
                    return {"time": 0.0, "init": {**PAD, **explicit, **pad_inputs(scale, push, pose, S0)}}
            else:
                def base(scale, push=push, pose=pose):
                    return {"time": 0.0, "init": {**PAD, **pad_inputs(0.0, push, pose)},
                            "step": pad_inputs(scale, push, pose)}
            points += [base(patch_stick_edge(mode, base, "ContactPad")), base(3.0)]
    return points


POINTS = {MODEL_IDENTIFIER: contact_points, RIG_MODEL_IDENTIFIER: rig_points, "ContactPatch": patch_points,
          "ContactPad": pad_points}
CELLS = ("ContactPatch", "ContactPad")   # n1, n2 at five values each: tests of their own


@pytest.mark.parametrize("model", [m for m in models().values() if m not in CELLS])
@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("mode", ["init", "step"])
def test_declared_dependencies_are_what_the_binary_does(model, version, mode):
    """Each output's declared knowns are exactly those whose perturbation
    changes it; a declared constant factor is the same at every base point."""
    check_declared_dependencies(model, version, mode)


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("mode", ["init", "step"])
def test_the_patchs_declared_dependencies_are_what_the_binary_does(version, mode):
    """As for the other models, over the patch's knowns at 7 base points
    (initialization) or 6 (step mode), each found through the FMI 3.0 FMU
    (the two versions compute the same bits: tests/fmus/test_patch.py); n1
    and n2 at both ends of 1 to 32, their neighbours and the middle."""
    check_declared_dependencies("ContactPatch", version, mode)


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("mode", ["init", "step"])
def test_the_pads_declared_dependencies_are_what_the_binary_does(version, mode):
    """The same for the pad at 6 base points: its normal force, moments and
    contact follow from the pose and the foundation alone (not u1, u2, the
    law; the contact not kn, which scales the pressure but not where it
    acts), its damping dn from nothing while the rate has no step to be
    taken over (initialization)."""
    check_declared_dependencies("ContactPad", version, mode)


def check_declared_dependencies(model, version, mode):
    found = measured_dependencies(version, model, POINTS[model](mode), mode)
    said = declared(version, model)[mode]
    assert set(said) == set(found)
    for output, knowns in said.items():
        assert set(knowns) == set(found[output]), (output, sorted(knowns), sorted(found[output]))
        for known, kind in knowns.items():
            if kind == "constant":
                factors = {(new - old) / (b - a) for a, b, old, new in found[output][known]}
                assert max(factors) - min(factors) <= 1e-9 * max(map(abs, factors)), (output, known)


@pytest.mark.parametrize("model", list(models().values()))
@pytest.mark.parametrize("version", [2, 3])
def test_the_structure_validates_and_the_rigs_positions_need_no_contact_force(model, version):
    """The schema and fmpy's own checks; no initial unknown or output left
    without its dependencies (which an importer must read as "on every
    known": the rig's positions on the contact's force, an algebraic loop at
    initialization)."""
    path = find_fmu(fmi_version=version, model=model)
    assert validate_fmu(str(path)) == [] and schema_errors(path) == []
    said = declared(version, model)
    if model == RIG_MODEL_IDENTIFIER:
        for mode in ("step", "init"):
            for position in ("u1", "u2", "N", "x1", "x2"):
                assert not {"T1", "T2"} & set(said[mode][position]), (mode, position)


def _compiler():
    cc = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    return [cc] if cc else [sys.executable, "-m", "ziglang", "cc"]


@pytest.mark.parametrize("edit, message", [
    ('D(contactState, "u1 u2 N", OC_INIT_KNOWNS_NO_RULE)', "output contactState has no FMU_DEPENDENCIES row"),
    ('D(contactState, "u1 u2 N mu1", OC_INIT_KNOWNS_NO_RULE)',
     "contactState depends on mu1:dependent in step mode: not a known of this mode"),
    ('D(contactState, "u1 u2 N:constant", OC_INIT_KNOWNS_NO_RULE)', "a kind not allowed here"),
    ('D(contactState, "u1 u2 N", OC_INIT_KNOWNS_NO_RULE " u1")', "named twice"),
])
def test_the_generator_refuses_a_table_without_exact_dependencies(tmp_path, edit, message):
    src = tmp_path / "fmu_src"
    shutil.copytree(ROOT / "fmu_src", src)
    table = (src / "models" / "OrthotropicContact" / "table.h").read_text()
    row = 'D(contactState, "u1 u2 N", OC_INIT_KNOWNS_NO_RULE)'
    assert row in table
    edited = table.replace(row, "" if edit == row else edit)
    (src / "models" / "OrthotropicContact" / "table.h").write_text(edited)
    gen = tmp_path / "gen"
    subprocess.run(_compiler() + ["-std=c99", "-I", str(src),
                                  '-DFMU_TABLE_HEADER="models/OrthotropicContact/table.h"',
                                  '-DFMU_VERSION="0"',
                                  *map(str, sorted((src / "glue").glob("gen_model_description*.c"))),
                                  "-o", str(gen), "-lm"], check=True, capture_output=True, timeout=120)
    r = subprocess.run([str(gen), "fmi2"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 1 and r.stdout == "" and message in r.stderr, r.stderr


def test_the_law_keeps_its_block_of_value_references():
    """Every model that carries the law has the law's rows in its block,
    value references 1 to OC_LAW_VR_END - 1 (law/law_table.h), alike in
    each, and its own rows from OC_LAW_VR_END on: a new row of the law moves
    none of a model's rows.  The rig, which has no law, starts at 1."""
    end = int(re.search(r"#define OC_LAW_VR_END (\d+)",
                        (ROOT / "fmu_src" / "law" / "law_table.h").read_text()).group(1))
    carrying, law_vrs = [], set()
    for model in models().values():
        m = manifest(model)
        law = set(m.group("law")) | ({"slidingRule"} if m.group("law") else set())
        own = [v.value_reference for v in m.variables if v.name != "time" and v.name not in law]
        if law:
            carrying.append(model)
            law_vrs.add(tuple((v.name, v.value_reference) for v in m.variables if v.name in law))
            assert all(0 < vr < end for _, vr in next(iter(law_vrs))), model
            assert min(own) == end, model
        else:
            assert min(own) == 1, model
    assert {"OrthotropicContact", "ContactPatch", "ContactPad"} <= set(carrying)
    assert len(law_vrs) == 1   # the same rows at the same value references in every model
