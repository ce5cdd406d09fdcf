"""The package's layers read one way: subpackages by layer, every import
going down, no cycle between modules, no private name used across modules."""
import ast
from pathlib import Path

PKG = Path(__file__).resolve().parents[2] / "python" / "orthocontact"


def module_name(path: Path) -> str:
    parts = list(path.relative_to(PKG).with_suffix("").parts)
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
    assert "fmu.params" in graph["fmu.contact"] and "rig.harness" in graph["runs.batch"]
    assert find_cycles(graph) == []


def test_the_cycle_finder_finds_cycles():
    assert find_cycles({"a": {"b"}, "b": {"a"}}) == [["a", "b", "a"]]
    assert find_cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == [["a", "b", "c", "a"]]
    assert find_cycles({"a": {"b", "c"}, "b": {"c"}, "c": set()}) == []


# The subpackages' layers, lowest first: a module may import from its own
# subpackage and from the layers below.
LAYERS = [
    {"errors", "plausibility"},
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
    top = lambda m: m.split(".")[0]
    return [(m, d) for m, deps in graph.items() for d in deps
            if top(d) != top(m) and RANK[top(d)] >= RANK[top(m)]]


def test_the_layers_read_one_way():
    """fmu, closed forms -> rig -> experiment -> runs -> output ->
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


def test_modules_are_small():
    sizes = {module_name(p): len(p.read_text().splitlines()) for p in PKG.rglob("*.py")}
    assert max(sizes.values()) < 400, sorted(sizes.items(), key=lambda kv: -kv[1])[:3]
