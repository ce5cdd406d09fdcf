"""The package's layers read one way: subpackages by layer, every import
going down, no cycle between modules, no private name used across modules
(nor by the tests); and ruff finds nothing in the repository's Python."""
import ast
import subprocess
import sys
from pathlib import Path

from paths import PKG, ROOT, TESTS


def module_name(path: Path, pkg: Path = PKG) -> str:
    parts = list(path.relative_to(pkg).with_suffix("").parts)
    if parts[-1] == "__init__" and len(parts) > 1:
        parts = parts[:-1]
    return ".".join(parts)


def resolve(mod: str, is_pkg: bool, node: ast.ImportFrom, known: set) -> set:
    """The package modules a relative ImportFrom in `mod` reaches."""
    base = mod.split(".") if is_pkg else mod.split(".")[:-1]
    if node.level > 1:
        base = base[:len(base) - (node.level - 1)]
    if node.module:
        target = ".".join(base + node.module.split("."))
        return {target} if target in known else {target.rsplit(".", 1)[0]} & known
    return {".".join(base + [a.name]) for a in node.names} & known


def import_graph() -> dict:
    """module -> the package modules it imports (lazy imports included)."""
    paths = {module_name(p): p for p in PKG.rglob("*.py")}
    known = set(paths)
    graph = {}
    for mod, p in paths.items():
        deps = set()
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level >= 1:
                deps |= resolve(mod, p.name == "__init__.py", node, known)
        graph[mod] = deps - {mod}
    return graph


def find_cycles(graph: dict) -> list:
    """Every back edge of a depth-first search, as the cycle it closes."""
    state, cycles = {}, []

    def visit(m, path):
        state[m] = "open"
        for d in sorted(graph.get(m, ())):
            if state.get(d) == "open":
                cycles.append(path[path.index(d):] + [d])
            elif d not in state:
                visit(d, path + [d])
        state[m] = "done"
    for m in sorted(graph):
        if m not in state:
            visit(m, [m])
    return cycles


def test_the_import_graph_has_no_cycle():
    graph = import_graph()
    assert {"cli.main", "rig.harness", "identification.job", "runs.sweep", "fmu.contact"} <= set(graph)
    assert "fmu.params" in graph["fmu.contact"] and "rig" in graph["runs.batch"]   # through rig's door
    assert "rig.harness" in graph["rig"]   # which imports its modules
    assert find_cycles(graph) == []


def test_the_cycle_finder_finds_cycles():
    assert find_cycles({"a": {"b"}, "b": {"a"}}) == [["a", "b", "a"]]
    assert find_cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == [["a", "b", "c", "a"]]
    assert find_cycles({"a": {"b", "c"}, "b": {"c"}, "c": set()}) == []


# The subpackages' layers, lowest first: a module may import from its own
# subpackage and from the layers below.
LAYERS = [
    {"errors", "version"},
    {"textfiles", "plausibility"},
    {"runtime"},
    {"fmu", "closed_forms"},
    {"rig"},
    {"experiment"},
    {"runs"},
    {"output"},
    {"identification"},
    {"uq", "reproduction"},
    {"cli"},
    {"__init__", "__main__"},
]
RANK = {m: i for i, layer in enumerate(LAYERS) for m in layer}


def upward_imports(graph: dict) -> list:
    def top(m):
        return m.split(".")[0]
    return [(m, d) for m, deps in graph.items() for d in deps
            if top(d) != top(m) and RANK[top(d)] >= RANK[top(m)]]


def test_the_layers_read_one_way():
    """runtime -> fmu, closed forms -> rig -> experiment -> runs -> output ->
    identification -> uq, reproduction -> cli: every import goes down."""
    graph = import_graph()
    missing = {m.split(".")[0] for m in graph} - set(RANK)
    assert not missing, f"a subpackage without a layer: add {missing} to LAYERS"
    assert upward_imports(graph) == []


def test_the_layer_check_sees_an_upward_import():
    assert upward_imports({"fmu.contact": {"cli.main"}, "cli.main": {"fmu.contact"}}) == \
        [("fmu.contact", "cli.main")]


def test_no_private_name_is_imported_across_modules():
    crossing = []
    for p in PKG.rglob("*.py"):
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level >= 1:
                crossing += [(module_name(p), a.name) for a in node.names
                             if a.name.startswith("_") and a.name != "__version__"]
    assert crossing == []


def private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def private_uses(source: str) -> list:
    """The package's private names a test reaches (sorted): imported (`from
    orthocontact.x import _y`) or read off a name imported from the package
    (`m._y`, `m.C._y`, `monkeypatch.setattr(m, "_y", ...)`)."""
    tree = ast.parse(source)
    bound, found = set(), []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            bound |= {a.asname or "orthocontact" for a in node.names
                      if a.name.split(".")[0] == "orthocontact"}
        elif isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "orthocontact":
            found += [a.name for a in node.names if private(a.name)]
            bound |= {a.asname or a.name for a in node.names}
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and private(node.attr):
            root = node.value
            while isinstance(root, ast.Attribute):
                root = root.value
            if isinstance(root, ast.Name) and root.id in bound:
                found.append(node.attr)
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr == "setattr" and len(node.args) >= 2
              and isinstance(node.args[0], ast.Name) and node.args[0].id in bound
              and isinstance(node.args[1], ast.Constant) and private(str(node.args[1].value))):
            found.append(node.args[1].value)
    return sorted(set(found))


def test_no_test_reaches_a_private_name_of_the_package():
    """Tests go through the package's public names, as its other modules
    must (above): a private one may change without notice."""
    found = {str(p.relative_to(TESTS)): private_uses(p.read_text()) for p in TESTS.rglob("*.py")}
    assert {f: names for f, names in found.items() if names} == {}


def test_the_private_name_check_sees_imports_attributes_and_monkeypatches():
    assert private_uses("from orthocontact.uq.outputs import _inside, widest") == ["_inside"]
    assert private_uses("from orthocontact.rig import compiled as cm\ncm._load()\ncm.CMaster._lib") == \
        ["_lib", "_load"]
    assert private_uses("import orthocontact.rig.harness as h\nmonkeypatch.setattr(h, '_simulate', f)") == \
        ["_simulate"]
    assert private_uses("import orthocontact\northocontact.rig._x") == ["_x"]
    # the package's dunders, and private names of what is not the package's, are not its private names
    assert private_uses("from orthocontact import __version__\nimport argparse\np._actions\n"
                        "from orthocontact.fmu.slave import FreedOnClose\nx = FreedOnClose()\n"
                        "x.__class__") == []


def test_ruff_finds_nothing():
    """pyproject's [tool.ruff] (lines <= 110 characters, pycodestyle,
    pyflakes, import order, bugbear, pyupgrade) over every Python file:
    what `make check` runs first (tools/run_tests.sh)."""
    p = subprocess.run([sys.executable, "-m", "ruff", "check", "."], cwd=ROOT,
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-1000:]


def test_only_paths_py_finds_the_repository_root():
    """tests/paths.py names the root and its folders once; a test that
    finds them from its own place (`Path(__file__).resolve().parents[2]`)
    breaks when it moves, and spells the fact again."""
    finds = sorted(str(p.relative_to(TESTS)) for p in TESTS.rglob("*.py")
                   if any(isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id == "Path"
                          and [getattr(a, "id", None) for a in n.args] == ["__file__"]
                          for n in ast.walk(ast.parse(p.read_text()))))
    assert finds == ["paths.py"]


def test_modules_are_small():
    sizes = {module_name(p): len(p.read_text().splitlines()) for p in PKG.rglob("*.py")}
    assert max(sizes.values()) < 400, sorted(sizes.items(), key=lambda kv: -kv[1])[:3]


# -- tests/ mirrors the package -------------------------------------------------
# Each module python/orthocontact/<sub>/<mod>.py has its tests in
# tests/<sub>/test_<mod>.py (a top-level module: tests/test_<mod>.py;
# __main__ shares cli/test_main.py), and that file imports the module.  Tests
# of no single module live in folders no subpackage is named like.
NOT_A_MODULE = {"fmus", "contracts", "conformance"}   # FMU binaries; the repository's contracts; FMI rules
SHARED_BY = {"__main__": "cli.main"}            # tested in that module's file


def file_of_tests(module: str) -> Path:
    """tests/<sub>/test_<mod>.py of a dotted module name under the package."""
    *sub, mod = module.split(".")
    return Path(*sub, f"test_{mod}.py")


def top_level_names(source: str) -> set:
    """The names a module defines at its top level."""
    names = set()
    for node in ast.parse(source).body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            names |= {n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)}
    return names


def imports_module(source: str, module: str, defined: set) -> bool:
    """The test file imports orthocontact.<module>, or an object the module
    defines (`defined`) through the module or one of its packages
    (`from orthocontact.fmu import ContactParams`, `cf.eq25_tan_phi` after
    `from orthocontact import closed_forms as cf`)."""
    dotted = f"orthocontact.{module}"
    parts = dotted.split(".")
    ancestors = {".".join(parts[:k]) for k in range(1, len(parts))}
    aliases = set()                     # names bound to the module's packages
    tree = ast.parse(source)
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name == dotted:
                    return True
                if a.name in ancestors and a.asname:
                    aliases.add(a.asname)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            for a in node.names:
                if f"{node.module}.{a.name}" == dotted:
                    return True
                if node.module == dotted or (node.module in ancestors and a.name in defined):
                    return True
                if f"{node.module}.{a.name}" in ancestors:
                    aliases.add(a.asname or a.name)
    return any(isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name) and n.value.id in aliases
               and n.attr in defined for n in ast.walk(tree))


def layout_problems(pkg: Path, tests: Path) -> list:
    """What keeps `tests` from mirroring the package at `pkg`: a module
    without its test file, a test file that does not import its module, a
    test file (or folder) of a module that is gone."""
    paths = {module_name(p, pkg): p for p in pkg.rglob("*.py") if p.name != "__init__.py"}
    modules = set(paths)
    subpackages = {module_name(p, pkg) for p in pkg.rglob("__init__.py") if p.parent != pkg}
    problems = []
    for m in sorted(modules - set(SHARED_BY)):
        f = tests / file_of_tests(m)
        if not f.is_file():
            problems.append(f"{m}: no {f.relative_to(tests)}")
        elif not imports_module(f.read_text(), m, top_level_names(paths[m].read_text())):
            problems.append(f"{f.relative_to(tests)} does not import orthocontact.{m}")
    for f in sorted(tests.rglob("test_*.py")):
        rel = f.relative_to(tests)
        top = rel.parts[0] if len(rel.parts) > 1 else None
        if top in NOT_A_MODULE or f.parent.name == "c":
            continue
        m = ".".join(rel.with_suffix("").parts[:-1] + (rel.stem[len("test_"):],))
        if m not in modules:
            problems.append(f"{rel}: no module orthocontact.{m}")
    for d in sorted(p for p in tests.iterdir() if p.is_dir() and any(p.glob("test_*.py"))):
        if d.name not in subpackages | NOT_A_MODULE:
            problems.append(f"{d.name}/: no subpackage orthocontact.{d.name}")
    return problems


def test_every_module_has_its_test_file_and_no_test_file_outlives_its_module():
    assert layout_problems(PKG, TESTS) == []
    assert {"fmu", "cli", "identification"} <= {d.name for d in TESTS.iterdir() if d.is_dir()}


def test_the_import_check_sees_the_module_an_object_of_it_or_neither():
    defined = {"eq25_tan_phi", "G_STANDARD"}
    for source in ("import orthocontact.closed_forms.paper", "from orthocontact.closed_forms import paper",
                   "from orthocontact.closed_forms.paper import eq25_tan_phi",
                   "from orthocontact.closed_forms import eq25_tan_phi",
                   "from orthocontact import closed_forms as cf\ncf.eq25_tan_phi(1, 2, 0.3)",
                   "import orthocontact.closed_forms as cf\nx = cf.G_STANDARD"):
        assert imports_module(source, "closed_forms.paper", defined), source
    for source in ("from orthocontact.closed_forms import rig",
                   "from orthocontact import closed_forms as cf\ncf.settling_length_array()",
                   "from orthocontact.closed_forms import settling_length_array",
                   "# orthocontact.closed_forms.paper", "from orthocontact.fmu import eq25_tan_phi"):
        assert not imports_module(source, "closed_forms.paper", defined), source


def test_the_layout_check_sees_a_missing_a_foreign_and_a_stale_test_file(tmp_path):
    pkg, tests = tmp_path / "orthocontact", tmp_path / "tests"
    for f in ("__init__.py", "errors.py", "runs/__init__.py", "runs/size.py", "runs/pool.py"):
        (pkg / f).parent.mkdir(parents=True, exist_ok=True)
        (pkg / f).write_text("")
    (tests / "runs").mkdir(parents=True)
    (tests / "fmus").mkdir()
    (tests / "test_errors.py").write_text("from orthocontact.errors import InputError\n")
    (tests / "runs" / "test_size.py").write_text("from orthocontact.runs import size\n")
    (tests / "runs" / "test_pool.py").write_text("import orthocontact.runs.pool\n")
    (tests / "fmus" / "test_dropin.py").write_text("")
    assert layout_problems(pkg, tests) == []
    (tests / "runs" / "test_pool.py").unlink()
    assert layout_problems(pkg, tests) == ["runs.pool: no runs/test_pool.py"]
    (tests / "runs" / "test_pool.py").write_text("from orthocontact.runs.size import check_run_size\n")
    assert layout_problems(pkg, tests) == ["runs/test_pool.py does not import orthocontact.runs.pool"]
    (tests / "runs" / "test_pool.py").write_text("from orthocontact.runs.pool import Progress\n")
    (tests / "runs" / "test_batch.py").write_text("from orthocontact.runs import batch\n")
    assert layout_problems(pkg, tests) == ["runs/test_batch.py: no module orthocontact.runs.batch"]
    (tests / "runs" / "test_batch.py").unlink()
    (tests / "uq").mkdir()
    (tests / "uq" / "test_outputs.py").write_text("from orthocontact.uq import outputs\n")
    assert layout_problems(pkg, tests) == ["uq/test_outputs.py: no module orthocontact.uq.outputs",
                                           "uq/: no subpackage orthocontact.uq"]
