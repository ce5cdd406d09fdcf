"""python/orthocontact/fmu/generated.py is what tools/make_generated.py
writes from the variable tables (through the installed manifests), as
docs/reference/variables.md is: the test fails while the committed file
differs, naming the command.  Its facts are checked against the FMUs' own
model descriptions (fmpy), its ContactParams is declared in the source (a
type checker reads the fields), and a table the code cannot serve is refused."""
import ast
import dataclasses
import math
import pickle
import subprocess
import sys

import pytest
from fmpy import read_model_description

import make_generated as mg  # tools/ is on sys.path (conftest)
from orthocontact.fmu import generated
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.generated import (
    LAW,
    PAD_FLOAT_OUTPUTS,
    PAD_FOUNDATION,
    PAD_INPUTS,
    PAD_INTEGER_OUTPUTS,
    PAD_MODEL,
    PATCH_FLOAT_OUTPUTS,
    PATCH_GEOMETRY,
    PATCH_INPUTS,
    PATCH_INTEGER_OUTPUTS,
    PATCH_MODEL,
    RULES,
    ContactParams,
)
from orthocontact.fmu.variables import contact, manifest, models


def test_the_committed_file_is_what_the_tables_give():
    problem = mg.stale()
    assert not problem, problem


def test_a_stale_file_is_named_with_the_command_that_regenerates_it(tmp_path):
    target = tmp_path / mg.TARGET
    target.parent.mkdir(parents=True)
    target.write_text((mg.ROOT / mg.TARGET).read_text().replace('min=1, max=64', 'min=1, max=63'))
    (tmp_path / mg.TABLES).write_text((mg.ROOT / mg.TABLES).read_text())   # as committed: not named
    problem = mg.stale(tmp_path)
    assert problem.startswith(f"{mg.TARGET} is not what the variable tables give: run make generated")
    assert "-    Row(\"n1\", type=\"Int32\", unit=\"\", min=1, max=63" in problem
    assert "+    Row(\"n1\", type=\"Int32\", unit=\"\", min=1, max=64" in problem
    done = subprocess.run([sys.executable, str(mg.ROOT / "tools" / "make_generated.py"), "--check"],
                          capture_output=True, text=True, timeout=60)
    assert (done.returncode, done.stderr) == (0, "")


def test_contact_params_fields_are_declared_in_the_source_as_the_fmu_has_them():
    """The fields are annotated assignments of a class statement (what mypy
    and pyright read), in the order, with the ranges, of the installed FMU's
    own model description."""
    tree = ast.parse((mg.ROOT / mg.TARGET).read_text())
    cls = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "ContactParams")
    declared = [(n.target.id, ast.unparse(n.annotation)) for n in cls.body
                if isinstance(n, ast.AnnAssign) and "ClassVar" not in ast.unparse(n.annotation)]
    md = read_model_description(str(find_fmu(fmi_version=2)))
    law = [v for v in md.modelVariables if v.name in ContactParams.law_parameters()]
    assert declared == [(v.name, "float") for v in law] + [("rule", "str")]
    assert [f.name for f in dataclasses.fields(ContactParams)] == [name for name, _ in declared]
    for row, v in zip(LAW, law):
        assert (row.name, row.unit, row.min, row.max) == (v.name, v.unit or "", float(v.min), float(v.max))
    degrees = next(n for n in cls.body if isinstance(n, ast.FunctionDef) and n.name == "from_degrees")
    angles = [v.name for v in law if v.unit == "rad"]
    assert angles and [a.arg for a in degrees.args.args][1:] == \
        [f"{n}_deg" if n in angles else n for n in ContactParams.law_parameters()] + ["rule"]
    assert RULES == contact().enumerations["SlidingRule"]


# Each model on the cells: its generated facts and its own parameters' rows
# (the pad's foundation only: the patch's geometry is its own), with the
# causalities they may have (the patch's cell counts size FMI 3.0 arrays).
CELL_MODELS = [
    ("patch", PATCH_MODEL, PATCH_INPUTS, PATCH_FLOAT_OUTPUTS, PATCH_INTEGER_OUTPUTS, PATCH_GEOMETRY,
     ["length", "width", "n1", "n2"], ("parameter", "structuralParameter")),
    ("pad", PAD_MODEL, PAD_INPUTS, PAD_FLOAT_OUTPUTS, PAD_INTEGER_OUTPUTS, PAD_FOUNDATION,
     ["kn", "dn"], ("parameter",)),
]


@pytest.mark.parametrize("key, model, inputs, float_outputs, integer_outputs, rows, names, causalities",
                         CELL_MODELS, ids=[m[0] for m in CELL_MODELS])
def test_the_cell_models_facts_are_their_model_descriptions(fmi_version, key, model, inputs, float_outputs,
                                                           integer_outputs, rows, names, causalities):
    md = read_model_description(str(find_fmu(fmi_version=fmi_version, model=model)))
    assert md.coSimulation.modelIdentifier == model == models()[key]
    assert inputs == tuple(v.name for v in md.modelVariables if v.causality == "input")
    outputs = [v for v in md.modelVariables if v.causality == "output" and v.name not in
               {a.name for a in manifest(model).arrays}]
    assert float_outputs == tuple(v.name for v in outputs if v.type in ("Real", "Float64"))
    assert integer_outputs == tuple(v.name for v in outputs if v.type in ("Integer", "Int32"))
    by_name = {v.name: v for v in md.modelVariables}
    assert [row.name for row in rows] == names
    for row in rows:
        v = by_name[row.name]
        assert v.causality in causalities and float(v.start) == row.start


def test_the_patchs_cell_counts_are_at_most_patch_max_side():
    assert max(row.max for row in PATCH_GEOMETRY if row.type == "Int32") == 64   # PATCH_MAX_SIDE


def test_contact_params_cross_to_another_process():
    """Worker processes get ContactParams pickled: the class is importable there by its module."""
    p = ContactParams.from_degrees(0.408, 0.625, 12510, 1e4, 129.2, 39.2, "eq20")
    done = subprocess.run([sys.executable, "-c", "import pickle, sys; p = pickle.load(sys.stdin.buffer); "
                           "print(repr(p), p.alpha_deg)"], input=pickle.dumps(p), capture_output=True,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.decode().split()[-1] == repr(p.alpha_deg) and repr(p) in done.stdout.decode()


def refused(contact_m, patch_m) -> str:
    with pytest.raises(ValueError) as e:
        mg.source(contact_m, patch_m, {contact_m.model_identifier: "c.h", patch_m.model_identifier: "p.h"})
    return str(e.value)


def changed(m, which, **kw):
    """The manifest m with its variable `which` changed by kw."""
    return dataclasses.replace(m, variables=tuple(dataclasses.replace(v, **kw) if v.name == which else v
                                                  for v in m.variables))


def test_a_table_the_generated_code_cannot_serve_is_refused():
    c, p = contact(), manifest(PATCH_MODEL)
    assert "law parameter eps1 is Int32; ContactParams holds floats" in \
        refused(changed(c, "eps1", type="Int32"), p)
    assert "'rule' cannot be a field" in refused(changed(c, "mu2", name="rule"), p)
    assert "slidingRule's start 7 is no item of SlidingRule" in refused(changed(c, "slidingRule", start=7), p)
    assert "input theta is Int32" in refused(c, changed(p, "theta", type="Int32"))
    assert "output Mz is Enumeration" in refused(c, changed(p, "Mz", type="Enumeration"))
    assert 'a description with \\ or """' in refused(changed(c, "beta", description='x """ y'), p)


def test_a_later_parameter_defaults_to_its_start_an_angle_to_zero():
    """The generator's rule for defaults, on the contact's table with a
    parameter added after the angles."""
    c = contact()
    extra = dataclasses.replace(c.variable("eps2"), name="kappa", unit="", start=0.25, value_reference=99)
    more = dataclasses.replace(c, variables=(*c.variables, extra))
    text = mg.source(more, manifest(PATCH_MODEL), {more.model_identifier: "c.h", PATCH_MODEL: "p.h"})
    assert "    alpha: float = 0.0\n    beta: float = 0.0\n    kappa: float = 0.25\n" in text
    assert "beta_deg: float = 0.0, kappa: float = 0.25" in text
    assert "radians(beta_deg), kappa, rule)" in text
    assert math.isclose(generated.ContactParams(0.1, 0.2, 1e4, 1e4).alpha, 0.0)
