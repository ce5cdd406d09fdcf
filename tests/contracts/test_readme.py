"""The README is a front door a newcomer reads in five minutes: at most about
150 lines; what it is; the two commands (which .ci/run and the Makefile
keep); three first paths, each ending in a link into docs/; citing and the
license.  Its code blocks run in test_doc_blocks.py like every page's."""
import re

from paths import ROOT

README = (ROOT / "README.md").read_text(encoding="utf-8")


def sections(text: str, level: str) -> dict:
    parts = re.split(rf"^{level} (.+)$", text, flags=re.M)
    return dict(zip(parts[1::2], parts[2::2]))


def test_the_readme_is_short():
    assert len(README.splitlines()) <= 155


def test_the_two_commands_are_the_makefiles_and_ci_runs_one():
    block = sections(README, "##")["The two commands"]
    assert "make reproduce" in block and "make test" in block
    makefile = (ROOT / "Makefile").read_text()
    assert re.search(r"^reproduce:", makefile, re.M) and re.search(r"^test:", makefile, re.M)
    assert "make test" in (ROOT / ".ci" / "run").read_text()


def test_three_first_paths_each_end_in_a_link_into_docs():
    paths = sections(sections(README, "##")["The first five minutes"], "###")
    assert list(paths) == ["The FMU in fmpy", "The FMU in another simulator",
                           "Your recordings to a calibrated FMU"]
    for name, text in paths.items():
        last = text.strip().split("\n\n")[-1]
        assert re.search(r"\]\(docs/[\w/.-]+\.md(#[\w-]+)?\)\.?$", last.strip()), name
    assert "h < 2√(m/ε_max)" in paths["The FMU in another simulator"]


def test_it_says_what_it_is_for_whom_and_how_to_cite_it():
    intro = README.split("\n## ")[0]
    for said in ("textured surfaces", "friction **and** the tangential", "FMI 2.0 and FMI 3.0"):
        assert said in intro, said
    assert {"Features", "Documentation", "Citing", "License"} <= set(sections(README, "##"))
