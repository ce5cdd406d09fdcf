"""docs/reference/variables.md and docs/reference/cli.md are what
tools/make_reference.py generates from the variable tables and the parser,
checked against argparse's own --help, fmpy's reading of the FMUs and the
exit status the command really gives; the generator refuses sources that
contradict each other."""
import argparse
import copy
import dataclasses
import difflib
import math
import re
import subprocess
import sys

import pytest
from fmpy import read_model_description

import make_reference as mr
from cli_run import run_cli
from orthocontact.cli.main import OS_ERROR
from orthocontact.cli.parser import build_parser
from orthocontact.fmu.files import find_fmu
from orthocontact.fmu.variables import models

ROOT = mr.ROOT


def differs(rel, generated) -> str:
    old = (ROOT / rel).read_text() if (ROOT / rel).is_file() else ""
    if old == generated:
        return ""
    diff = "\n".join(list(difflib.unified_diff(
        old.splitlines(), generated.splitlines(), "committed", "generated", lineterm="", n=0))[:30])
    return f"{rel} is not what its sources give: run {mr.REFRESH}\n{diff}"


def test_the_variables_page_is_generated_from_the_tables():
    problem = differs(mr.PAGES["variables"], mr.variables_page(mr.installed_models()))
    assert not problem, problem


def test_the_cli_page_is_generated_from_the_parser():
    problem = differs(mr.PAGES["cli"], mr.cli_page(build_parser()))
    assert not problem, problem


def test_check_says_which_page_is_stale_and_how_to_refresh(tmp_path):
    done = subprocess.run([sys.executable, str(ROOT / "tools" / "make_reference.py"), "--check"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    (tmp_path / "docs" / "reference").mkdir(parents=True)
    (tmp_path / mr.PAGES["cli"]).write_text((ROOT / mr.PAGES["cli"]).read_text().replace("--seed", "--sead"))
    stale = dict(mr.stale(tmp_path))
    assert set(stale) == set(mr.PAGES.values())            # the variables page is missing there
    assert "-| `--sead S`" in stale[mr.PAGES["cli"]] and "+| `--seed S`" in stale[mr.PAGES["cli"]]


# -- the command line, against argparse's own help and the real command ----------------

def sections(page: str) -> dict[str, str]:
    """'orthocontact run' -> its section of the page."""
    return {m.group(1): m.group(2) for m in re.finditer(r"^## (orthocontact \S+)\n(.*?)(?=^## |\Z)",
                                                         page, re.S | re.M)}


def test_every_command_and_option_of_the_help_is_on_the_page(tmp_path):
    page = (ROOT / mr.PAGES["cli"]).read_text()
    top = run_cli(["--help"], tmp_path)
    assert top.returncode == 0
    listed = re.findall(r"^    (\w+)\s", top.stdout, re.M)       # the commands under COMMAND
    assert len(listed) >= 7 and set(listed) >= {"run", "reproduce", "identify", "uq"}
    found = sections(page)
    assert sorted(found) == sorted(f"orthocontact {c}" for c in listed)
    ap = build_parser()
    commands = {name: p for name, _, p in mr.subcommands(ap)}
    for c in listed:
        options = set(re.findall(r"(?<![\w-])--[a-z][a-z0-9-]*", commands[c].format_help())) - {"--help"}
        assert options, c
        on_page = set(re.findall(r"^\| `(--[a-z][a-z0-9-]*)", found[f"orthocontact {c}"], re.M))
        assert on_page == options, c


def test_the_exit_status_table_has_what_the_command_returns(tmp_path):
    page = (ROOT / mr.PAGES["cli"]).read_text()
    table = dict(re.findall(r"^\| (\d+) \| (.*) \|$", page.split("## Exit status")[1].split("\n## ")[0], re.M))
    bad = run_cli(["run", "--no-such-option"], tmp_path)
    assert bad.returncode == 2 and "bad input" in table["2"]
    assert str(OS_ERROR) in table and "refused" in table[str(OS_ERROR)]
    assert "0" in table


def one_command(name, *option, **kw):
    ap = argparse.ArgumentParser(prog="tool", epilog="Exit status: 0 success, 2 bad input.")
    ap.add_subparsers(dest="cmd").add_parser(name, help="h", description="d").add_argument(*option, **kw)
    return ap


def test_a_help_text_that_states_another_default_is_refused():
    ap = one_command("uq", "--chunk-runs", type=int, default=20000, help="runs per task (default 5000)")
    with pytest.raises(ValueError, match=r"^tool uq --chunk-runs: the help says the default is 5000, "
                                         r"the option's default is 20000"):
        mr.cli_page(ap)
    ap = one_command("run", "--fmi", type=int, choices=(2, 3), default=2, help="2 or 3 (default)")
    with pytest.raises(ValueError, match=r"^tool run --fmi: the help says the default is 3"):
        mr.cli_page(ap)


def test_stated_defaults_that_agree_pass():
    ap = argparse.ArgumentParser(prog="tool", epilog="Exit status: 0 success.")
    ap.add_argument("--angle", type=float, default=45.0, help="angle [deg] (default 45)")
    ap.add_argument("--fmi", type=int, choices=(2, 3), default=2, help="2 (default) or 3")
    ap.add_argument("--step", type=float, default=None, help="(default: 0.004 for the implicit rules)")
    page = mr.cli_page(ap)
    assert "| `--angle ANGLE` | `45.0` | angle [deg] (default 45) |" in page
    assert "| `--fmi {2,3}` | `2` |" in page


def test_the_exit_status_is_read_with_its_parentheses_and_notes():
    codes, notes = mr.exit_status("Before. Exit status: 0 ok, 2 bad (one line, 3 words; no more), "
                                  "74 refused; a closed pipe (| head) is no error.  Angles in deg.")
    assert codes == [(0, "ok"), (2, "bad (one line, 3 words; no more)"), (74, "refused")]
    assert notes == "Before. a closed pipe (| head) is no error. Angles in deg."
    with pytest.raises(ValueError, match="states no exit status"):
        mr.cli_page(argparse.ArgumentParser(prog="tool", epilog="Angles in degrees."))
    with pytest.raises(ValueError, match="'ok 0' is not '<status> <meaning>'"):
        mr.exit_status("Exit status: ok 0, 2 bad.")


def test_markdown_specials_in_help_texts_are_literal():
    assert mr.md_text("rig_<angle>.ssp (*.toml; | head), mat_angle_deg, `a | b`, N <= 0") == \
        r"rig\_&lt;angle&gt;.ssp (\*.toml; \| head), mat_angle_deg, `a \| b`, N &lt;= 0"


# -- the variables, against fmpy's reading of the installed FMUs --------------------------

def rows(page: str, model: str) -> dict[str, list[str]]:
    """name -> the cells of its row in the model's table of variables."""
    section = page.split(f"\n## {model}\n")[1].split("\n## ")[0]
    body = section.split("### Variables")[1].split("\n### ")[0]
    return {m.group(1): [c.strip() for c in re.split(r"(?<!\\)\|", m.group(0))[1:-1]]
            for m in re.finditer(r"^\| `(\w+)` \|.*\|$", body, re.M)}


@pytest.mark.parametrize("model", list(models().values()))
def test_every_variable_is_on_the_page_as_the_model_description_has_it(model):
    assert model in models().values()
    page = (ROOT / mr.PAGES["variables"]).read_text()
    md = read_model_description(str(find_fmu(fmi_version=3, model=model)))
    found = rows(page, model)
    assert list(found) == [v.name for v in md.modelVariables]
    for v in md.modelVariables:
        name, vr, causality, variability, kind, unit, start, rng, description = found[v.name]
        assert (int(vr), causality, variability) == (v.valueReference, v.causality, v.variability), v.name
        assert kind.startswith(v.type) and unit.startswith(v.unit or "—"), v.name
        assert description == mr.md_text(v.description), v.name
        if v.start is None:
            assert start in ("calculated", "—"), v.name
        else:
            assert float(start.split()[0]) == float(v.start), v.name
        if v.displayUnit == "deg" and v.start is not None:
            assert f"({math.degrees(float(v.start)):.6g} deg)" in start, v.name
        if v.min is not None:
            assert float(rng.strip("[").split(",")[0]) == float(v.min), v.name
    for o in md.outputs:
        line = re.search(rf"^\| `{o.variable.name}` \| (.*) \|$", page.split(f"\n## {model}\n")[1]
                         .split("### Outputs")[1].split("\n## ")[0], re.M).group(1)
        assert re.findall(r"`(\w+)`", line) == [d.name for d in o.dependencies], o.variable.name
        assert set(re.findall(r"\((?:all )?(\w+)\)", line)) == set(o.dependenciesKind or ()), o.variable.name


def test_a_manifest_its_model_description_contradicts_is_refused():
    contact, *others = mr.installed_models()
    m = contact.manifest
    moved = dataclasses.replace(m.variables[3], unit="N/mm")
    stale = dataclasses.replace(m, variables=(*m.variables[:3], moved, *m.variables[4:]))
    with pytest.raises(ValueError, match=rf"^OrthotropicContact: the installed FMI 2.0 model description and "
                                         rf"variables/OrthotropicContact.json disagree on {moved.name}'s unit "
                                         r".*reinstall the package"):
        mr.variables_page([dataclasses.replace(contact, manifest=stale), *others])


def test_outputs_whose_dependencies_differ_between_fmi_versions_are_refused():
    models = {m.manifest.model_identifier: m for m in mr.installed_models()}
    rig = models["CarriageBlock"]
    fmi3 = copy.deepcopy(rig.fmi3)
    fmi3.outputs[-1].dependencies = []
    with pytest.raises(ValueError, match=r"^CarriageBlock: the outputs' dependencies differ between FMI 2.0"):
        mr.variables_page([*(m for m in models.values() if m is not rig), dataclasses.replace(rig, fmi3=fmi3)])
