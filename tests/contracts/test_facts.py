"""Each fact of the code typed once: CONTRIBUTING.md's table quotes what
tools/count_facts.py counts, the counts meet their targets, and the counter
counts honestly (it sees a place, skips comments, and sets aside as
independent references only files that import nothing of the package)."""
import ast
import re

import count_facts as facts  # tools/ is on sys.path (conftest)
import make_generated
from paths import ROOT

ROWS = ("six", "rules", "models", "sources", "forms", "fmi")   # the table's rows, in order


def quoted_now() -> dict:
    """The "now" column of CONTRIBUTING.md's table: its first number per row."""
    text = (ROOT / "CONTRIBUTING.md").read_text()
    table = text[text.index("### How often each fact is typed by hand"):]
    rows = [line for line in table.splitlines() if line.startswith("| ") and not line.startswith("| fact")]
    assert len(rows) == len(ROWS), rows
    return {key: int(re.match(r"\s*(\d+)", row.split("|")[3]).group(1)) for key, row in zip(ROWS, rows)}


def test_contributing_quotes_the_count_and_the_targets_are_met():
    found = facts.count()
    counted = {k: sum(1 for p, _, _ in found[k] if facts.category(p) == "code") for k in ROWS}
    assert quoted_now() == counted, "update CONTRIBUTING.md's table: python3 tools/count_facts.py"
    assert counted["six"] <= 10 and counted["forms"] == 0 and counted["fmi"] == 0


def test_the_independent_references_import_nothing_of_the_package():
    refs = [f for f in facts.tracked_files()
            if facts.category(f) == "independent references" and f.endswith(".py")]
    assert "tools/rig_reference.py" in refs and "tools/make_recordings.py" in refs
    for f in refs:
        for node in ast.walk(ast.parse((ROOT / f).read_text())):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                [node.module or ""] if isinstance(node, ast.ImportFrom) else []
            assert not any(n.split(".")[0] == "orthocontact" for n in names), (f, names)


def test_the_counter_sees_a_place_and_not_a_comment():
    code = facts.code_of("x.py", '"""mu1, mu2, eps1, eps2, alpha, beta"""\n'
                                 "# mu1, mu2, eps1, eps2, alpha, beta\n"
                                 "f(p.mu1, p.mu2, p.eps1,\n  p.eps2, p.alpha, p.beta)\n").splitlines()
    assert facts.six_places("x.py", code) == [(3, 4)]
    dispatch = ['if form == "eq11":', "    pass", 'elif form == "mat":']
    assert facts.form_places(dispatch) == [(1, 3)]
    assert facts.form_places(['if sc.closed_form == "mat":']) == []     # one name: not a list
    assert facts.category("fmu_src/models/ContactPatch/table.h") == "table"
    assert facts.category("python/orthocontact/experiment/scenario.py") == "code"


def test_only_what_the_generator_writes_is_set_aside_as_generated():
    """A file counted apart as generated is one tools/make_generated.py
    writes (and tests/fmu/test_generated.py holds to the tables)."""
    generated = [f for f in facts.tracked_files() if facts.category(f) == "generated"]
    assert generated == [make_generated.TARGET.as_posix()]
    assert facts.category("python/orthocontact/fmu/params.py") == "code"
