"""No function or method of the package is longer than MOST_LINES lines:
a longer one becomes named steps (a function a step, an object for what
they share).  A function's length is end_lineno - lineno + 1 of its `def`
(ast's lineno is the `def` line: decorators are not counted), its
docstring, comments and blank lines inside it included; nested functions
and methods count on their own and within the function around them."""
import ast

from paths import PKG

MOST_LINES = 60
# The package has about a thousand functions (980 when this was written):
# fewer than this means the walk missed files, not that they went.
AT_LEAST = 800


def long_functions(source: str, where: str = "", most: int = MOST_LINES) -> tuple[list, int]:
    """(every function or method of `source` longer than `most` lines, as
    "where:line name (n lines)"; how many functions it looked at)."""
    found, seen = [], 0
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            seen += 1
            n = node.end_lineno - node.lineno + 1
            if n > most:
                found.append(f"{where}:{node.lineno} {node.name} ({n} lines)")
    return found, seen


def test_no_function_of_the_package_is_longer_than_60_lines():
    found, seen = [], 0
    for p in sorted(PKG.rglob("*.py")):
        long, n = long_functions(p.read_text(), str(p.relative_to(PKG)))
        found += long
        seen += n
    assert seen >= AT_LEAST, f"looked at {seen} functions only"
    assert found == [], "split each into named steps"


def test_the_length_check_counts_from_def_to_the_last_line_and_sees_methods():
    body = "\n".join(f"    x{i} = {i}" for i in range(58))
    fits = f"@decorated\n@twice\ndef f():\n    '''doc'''\n{body}\n"          # 60 lines from def
    assert long_functions(fits) == ([], 1)
    deeper = body.replace("    ", "        ")
    over = f"class C:\n    def g(self):\n        '''doc'''\n{deeper}\n        y = 1\n"
    assert long_functions(over, "m.py") == (["m.py:2 g (61 lines)"], 1)
    nested = f"async def outer():\n    def inner():\n        pass\n{body}\n    z = 1\n"
    assert long_functions(nested, "n.py") == (["n.py:1 outer (62 lines)"], 2)
