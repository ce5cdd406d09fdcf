"""The package's layers read one way: no module imports, directly or through
others, a module that imports it back."""
import ast
from pathlib import Path

PKG = Path(__file__).resolve().parents[1] / "python" / "orthocontact"


def import_graph() -> dict:
    """module -> the package modules it imports (lazy imports included)."""
    mods = {p.stem for p in PKG.glob("*.py")}
    graph = {}
    for p in PKG.glob("*.py"):
        deps = set()
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                if node.module:
                    deps.add(node.module.split(".")[0])
                else:
                    deps |= {a.name for a in node.names if a.name in mods}
        graph[p.stem] = deps - {p.stem}
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
    assert {"cli", "report", "identify", "sweep", "fmu"} <= set(graph)
    assert find_cycles(graph) == []


def test_the_cycle_finder_finds_cycles():
    assert find_cycles({"a": {"b"}, "b": {"a"}}) == [["a", "b", "a"]]
    assert find_cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == [["a", "b", "c", "a"]]
    assert find_cycles({"a": {"b", "c"}, "b": {"c"}, "c": set()}) == []


# The layers, lowest first: a module may import only from layers below its own.
LAYERS = [
    {"errors", "tables"},
    {"fmu", "closed_forms"},
    {"rig"},
    {"cmaster", "scenarios"},
    {"cluster", "ssp"},
    {"sweep"},
    {"figures", "measurements", "uncertainty"},
    {"strip"},
    {"estimators"},
    {"identify_report"},
    {"identify"},
    {"uq", "sensitivity"},
    {"report"},
    {"cli"},
    {"__init__", "__main__"},
]


def test_the_layers_read_one_way():
    """fmu -> closed forms / rig -> scenarios -> sweep -> identification ->
    report -> cli, as the package's design says: every import goes down."""
    graph = import_graph()
    rank = {m: i for i, layer in enumerate(LAYERS) for m in layer}
    assert set(graph) == set(rank), "a module without a layer: add it to LAYERS"
    upward = [(m, d) for m, deps in graph.items() for d in deps if rank[d] >= rank[m]]
    assert upward == [], upward


def test_identification_is_split_by_job():
    sizes = {m: len((PKG / f"{m}.py").read_text().splitlines())
             for m in ("measurements", "estimators", "uncertainty", "identify", "identify_report")}
    assert max(sizes.values()) < 400, sizes
