"""docs/reference/variables.md, docs/reference/cli.md and the models' block
of docs/reference/fmus.md are what tools/make_reference.py generates from
the variable tables, OC_MODELS and the parser, checked against argparse's
own --help, fmpy's reading of the FMUs, the FMUs `--version` lists and the
exit status the command really gives; the generator refuses sources that
contradict each other, and no other page counts the models by hand."""
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
from paths import DOCS, ROOT, TOOLS


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


def test_the_generated_blocks_of_hand_written_pages_are_what_the_models_give():
    sources = mr.installed_models()
    for rel in mr.BLOCK_PAGES:
        problem = differs(rel, mr.fill_blocks((ROOT / rel).read_text(), rel, sources))
        assert not problem, problem


def test_check_says_which_page_is_stale_and_how_to_refresh(tmp_path):
    done = subprocess.run([sys.executable, str(TOOLS / "make_reference.py"), "--check"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    (tmp_path / "docs" / "reference").mkdir(parents=True)
    (tmp_path / mr.PAGES["cli"]).write_text((ROOT / mr.PAGES["cli"]).read_text().replace("--seed", "--sead"))
    fmus = next(iter(mr.BLOCK_PAGES))
    (tmp_path / fmus).write_text((ROOT / fmus).read_text().replace("ships eight", "ships four"))
    stale = dict(mr.stale(tmp_path))
    assert set(stale) == {*mr.PAGES.values(), fmus}         # the variables page is missing there
    assert "-| `--sead S`" in stale[mr.PAGES["cli"]] and "+| `--seed S`" in stale[mr.PAGES["cli"]]
    assert "ships four" in stale[fmus] and "ships eight" in stale[fmus]
    (tmp_path / fmus).unlink()
    with pytest.raises(FileNotFoundError, match="fmus.md, which holds generated blocks, is not in"):
        mr.stale(tmp_path)


# -- the models, in the FMU reference: from OC_MODELS, as --version lists the FMUs -------

def models_table(page: str) -> dict[str, list[str]]:
    """model -> the cells of its row in the generated table of models."""
    block = page.split(mr.BEGIN.format("models"))[1].split(mr.END.format("models"))[0]
    return {m.group(1): [c.strip() for c in re.split(r"(?<!\\)\|", m.group(0))[1:-1]]
            for m in re.finditer(r"^\| \[`(\w+)`\].*\|$", block, re.M)}


def test_the_fmu_reference_names_every_model_and_counts_what_version_lists(tmp_path):
    page = (DOCS / "reference" / "fmus.md").read_text()
    found = models_table(page)
    assert list(found) == list(models().values())
    listed = run_cli(["--version"], tmp_path)
    assert listed.returncode == 0, listed.stderr
    fmus = re.findall(r"^  FMI ([23])\.0 FMU: (\w+) ", listed.stdout, re.M)
    assert sorted(fmus) == sorted((str(v), m) for v in (2, 3) for m in models().values()), listed.stdout
    said = re.search(r"The package ships (\w+) Co-Simulation FMUs: the (\w+) models", page)
    words = "zero one two three four five six seven eight nine ten eleven twelve".split()
    assert said and (words.index(said.group(1)), words.index(said.group(2))) == (len(fmus), len(found))
    for role, model in models().items():
        md = read_model_description(str(find_fmu(fmi_version=3, model=model)))
        cells = found[model]
        assert cells[1] == role and cells[2] == mr.md_text(md.description), model
        assert re.findall(r"`(\w+)`", cells[4]) == [v.name for v in md.modelVariables
                                                    if v.causality == "input"]
        arrays = {v.name for v in md.modelVariables if v.dimensions}
        assert re.findall(r"`(\w+)`", cells[5]) == \
            [v.name for v in md.modelVariables if v.causality == "output" and v.name not in arrays]
        assert all(f"`{a}`" in cells[7] for a in arrays), model
        structural = [v.name for v in md.modelVariables if v.causality == "structuralParameter"]
        assert all(f"`{n}`" in cells[7] for n in structural) and (not structural or "UInt64" in cells[7])


def test_a_new_model_is_a_new_row_and_new_counts():
    """A model added to OC_MODELS appears with nothing edited by hand."""
    sources = mr.installed_models()
    pad = dataclasses.replace(sources[-1], role="pad", manifest=dataclasses.replace(
        sources[-1].manifest, model_identifier="ContactPad"))
    block = "\n".join(mr.models_block([*sources, pad]))
    assert block.startswith(f"The package ships {mr.count(2 * len(sources) + 2, 'Co-Simulation FMU')}: "
                            f"the {mr.count(len(sources) + 1, 'model')} of `OC_MODELS`")
    assert "| [`ContactPad`](variables.md#contactpad) | pad |" in block


def test_a_page_without_its_block_or_with_one_left_open_is_refused():
    rel = next(iter(mr.BLOCK_PAGES))
    for text in ("# page\n", f"# page\n{mr.BEGIN.format('models')}\nold\n",
                 f"{mr.END.format('models')}\n{mr.BEGIN.format('models')}\n"):
        with pytest.raises(ValueError, match="the generated block 'models' needs one line"):
            mr.fill_blocks(text, rel, [])


COUNTED = re.compile(r"\b(two|three|four|five|six|seven|eight|nine|ten|eleven|twelve)\s+"
                     r"(?:installed\s+)?(?:Co-Simulation\s+)?(FMUs|models)\b", re.I)


def test_no_page_counts_the_fmus_or_models_by_hand():
    """Counts of the models and FMUs are generated (a new model changes them);
    elsewhere a page says "every model" or links the FMU reference's table."""
    pages = [ROOT / "README.md", *sorted(DOCS.rglob("*.md"))]
    found = []
    for page in pages:
        text = page.read_text()
        for name in mr.BLOCK_PAGES.get(page.relative_to(ROOT), ()):
            head, rest = text.split(mr.BEGIN.format(name), 1)
            text = head + rest.split(mr.END.format(name), 1)[1]
        found += [f"{page.relative_to(ROOT)}: {m.group(0)}" for m in COUNTED.finditer(" ".join(text.split()))]
    assert not found, found
    assert COUNTED.search("ships four Co-Simulation FMUs") and COUNTED.search("the two models")


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
    section = page.split("## Exit status")[1].split("\n## ")[0]
    table = dict(re.findall(r"^\| (\d+) \| (.*) \|$", section, re.M))
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
    with pytest.raises(ValueError, match=r"^OrthotropicContact: the installed FMI 2.0 model description and "
                                         r"variables/OrthotropicContact.json disagree on "
                                         rf"{moved.name}'s unit .*reinstall the package"):
        mr.variables_page([dataclasses.replace(contact, manifest=stale), *others])


def test_outputs_whose_dependencies_differ_between_fmi_versions_are_refused():
    models = {m.manifest.model_identifier: m for m in mr.installed_models()}
    rig = models["CarriageBlock"]
    fmi3 = copy.deepcopy(rig.fmi3)
    fmi3.outputs[-1].dependencies = []
    with pytest.raises(ValueError, match=r"^CarriageBlock: the outputs' dependencies differ between FMI 2.0"):
        mr.variables_page([*(m for m in models.values() if m is not rig),
                           dataclasses.replace(rig, fmi3=fmi3)])
