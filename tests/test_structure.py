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
