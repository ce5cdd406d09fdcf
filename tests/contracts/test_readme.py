"""The README's Python examples run as written (doctests, from the repository
root), and its fmpy example too."""
import doctest
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _blocks():
    text = (ROOT / "README.md").read_text()
    return re.findall(r"```python\n(.*?)```", text, re.S)


@pytest.mark.parametrize("index", range(len([b for b in _blocks() if ">>>" in b])))
def test_readme_doctest(index, monkeypatch):
    block = [b for b in _blocks() if ">>>" in b][index]
    monkeypatch.chdir(ROOT)
    parser = doctest.DocTestParser()
    test = parser.get_doctest(block, {}, f"README block {index}", "README.md", 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    runner.run(test)
    assert runner.failures == 0 and runner.tries > 0


def test_readme_fmpy_example_runs(monkeypatch):
    block = next(b for b in _blocks() if "FMU2Slave" in b and ">>>" not in b)
    monkeypatch.chdir(ROOT)
    exec(compile(block, "README.md", "exec"), {})
