"""Every code block of the documentation runs, and prints what the page says.

The pages: README.md, CONTRIBUTING.md, CHANGELOG.md, docs/**/*.md and
scenarios/**/*.md.  A fenced block's kind is its language tag:

  ```python   run by the interpreter; an ```output block must follow it
  ```pycon    a doctest (>>> lines with what they print)
  ```sh       run by bash (-e); it must exit 0, and an ```output block after
              it, if there is one, is what it prints
  ```toml     must parse
  ```output   what the block before it prints (stdout); a line `...` stands
              for any lines, `...` within a line for any text

An HTML comment on the line(s) just before a block says more, visible in the
page's source only:

  <!-- not run: REASON -->   the block is not run (a placeholder, minutes
                             of work, a file format); the reason is required
  <!-- slow: REASON -->      the block runs in the slow tier only

Any other block without `not run` is an error.  The blocks of a page run in
order in one sandbox: a temporary folder with the repository's top-level
entries linked in, so that `scenarios/...` and `.venv/bin/...` resolve and
`out/...` is written there.  The fast tier runs a page's blocks that are not
slow (a block that needs a slow block's files is slow too); the slow tier
runs every block of the pages that have a slow one.

Besides: every relative link and anchor of the pages resolves, every path
they name in code or in a marker exists, and every figure they show is a PNG
that a named script writes."""
from __future__ import annotations

import doctest
import glob
import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from paths import DOCS, ROOT, SCENARIOS

RUN_KINDS = {"python", "pycon", "sh", "toml"}
MARKER = re.compile(r"<!--\s*(not run|slow)\s*:\s*(.*?)\s*-->")
FENCE = re.compile(r"^(\s*)```(\S*)\s*$")
# Folders a command writes into the sandbox, never the repository's own.
NOT_LINKED = {"out", "results", ".git"}
# Figures the pages show, and the script that writes each.
FIGURES = {"docs/coverage.png": "benchmarks/bench_coverage.py",
           "docs/figures/patch_twist.png": "tools/make_patch_figures.py",
           "docs/figures/patch_twist_cells.png": "tools/make_patch_figures.py",
           "docs/figures/patch_yaw_vs_angle.png": "tools/make_patch_figures.py",
           "docs/figures/pad_pressure_cells.png": "tools/make_patch_figures.py",
           "docs/figures/pad_regimes.png": "tools/make_patch_figures.py",
           "docs/figures/pad_phi_vs_angle.png": "tools/make_patch_figures.py",
           "docs/figures/design_aged_5.png": "tools/make_design_figure.py"}


@dataclass
class Block:
    page: str           # path under the repository
    line: int           # of the opening fence, 1-based
    kind: str
    code: str
    markers: dict = field(default_factory=dict)   # "not run" / "slow" -> reason
    output: str | None = None                     # the expected stdout

    def where(self) -> str:
        return f"{self.page}:{self.line}"


def pages() -> list[str]:
    found = [ROOT / "README.md", ROOT / "CONTRIBUTING.md", ROOT / "CHANGELOG.md",
             *sorted(DOCS.rglob("*.md")), *sorted(SCENARIOS.rglob("*.md"))]
    return [str(p.relative_to(ROOT)) for p in found if p.is_file()]


def parse(text: str, page: str) -> tuple[list[Block], list[str]]:
    """The page's blocks with their markers and expected outputs, and the
    errors of its form (a block of no kind, an output of no block, ...)."""
    lines = text.splitlines()
    blocks, errors, i = [], [], 0
    last_end = None          # the line after the previous block's closing fence
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, kind = m.group(1), m.group(2)
        j = i + 1
        while j < len(lines) and lines[j].strip() != "```":
            j += 1
        code = "\n".join(x[len(indent):] if x.startswith(indent) else x for x in lines[i + 1:j]) + "\n"
        markers, k = {}, i - 1
        while k >= 0 and MARKER.search(lines[k]):
            for name, reason in MARKER.findall(lines[k]):
                markers[name] = reason
            k -= 1
        block = Block(page, i + 1, kind, code, markers)
        if kind == "output":
            between = lines[last_end:i] if last_end is not None else ["?"]
            if not blocks or any(x.strip() for x in between) or blocks[-1].output is not None:
                errors.append(f"{block.where()}: an output block must follow the block it belongs to")
            elif blocks[-1].kind not in ("python", "sh"):
                errors.append(f"{block.where()}: a {blocks[-1].kind or 'plain'} block "
                              "has no output to compare")
            else:
                blocks[-1].output = code
        else:
            if any(not r for r in markers.values()):
                errors.append(f"{block.where()}: a marker needs its reason")
            if kind not in RUN_KINDS and "not run" not in markers:
                errors.append(f"{block.where()}: a ```{kind} block is not run: tag it python, pycon, sh or "
                              "toml, or say why not with <!-- not run: REASON -->")
            blocks.append(block)
        last_end = j + 1
        i = j + 1
    for b in blocks:
        if b.kind == "python" and b.output is None and "not run" not in b.markers:
            errors.append(f"{b.where()}: a python block needs the ```output block of what it prints")
    return blocks, errors


def sandbox(tmp: Path) -> Path:
    """A folder in which the pages' relative paths resolve to the repository's:
    its entries linked, and scenarios/ copied (a command may write beside
    its data; the repository's stays as it is)."""
    for entry in ROOT.iterdir():
        if entry.name == "scenarios":
            shutil.copytree(entry, tmp / entry.name)
        elif entry.name not in NOT_LINKED:
            (tmp / entry.name).symlink_to(entry)
    return tmp


def matches(want: str, got: str) -> bool:
    """`got` is what `want` says: a line `...` stands for any number of lines
    (none included), `...` within a line for any text; trailing spaces aside."""
    pattern = ""
    for line in want.rstrip("\n").split("\n"):
        if line.strip() == "...":
            pattern += r"(?:[^\n]*\n)*?"
        else:
            pattern += "[^\\n]*?".join(re.escape(part) for part in line.rstrip().split("...")) + r"[ \t]*\n"
    return re.fullmatch(pattern, got.rstrip("\n") + "\n") is not None


def run_block(b: Block, cwd: Path) -> str | None:
    """Runs one block in `cwd`; None, or what went wrong."""
    env = dict(os.environ, MPLBACKEND="Agg")
    if b.kind == "toml":
        import tomllib
        try:
            tomllib.loads(b.code)
        except tomllib.TOMLDecodeError as e:
            return f"{b.where()}: not TOML: {e}"
        return None
    if b.kind == "pycon":
        test = doctest.DocTestParser().get_doctest(b.code, {}, b.where(), b.page, b.line)
        if not test.examples:
            return f"{b.where()}: a pycon block without >>> examples"
        f = cwd / f".block_{b.line}.txt"
        f.write_text(b.code)
        cmd = [sys.executable, "-m", "doctest", "-o", "ELLIPSIS", f.name]
    elif b.kind == "python":
        cmd = [sys.executable, "-c", b.code]
    else:
        cmd = ["bash", "-e", "-c", b.code]
    p = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=600)
    if p.returncode != 0:
        return f"{b.where()}: exit status {p.returncode}\n{p.stdout[-3000:]}{p.stderr[-3000:]}"
    if b.output is not None and not matches(b.output, p.stdout):
        return f"{b.where()}: printed\n{p.stdout[-3000:]}\nwhere the page says\n{b.output}"
    return None


def run_page(blocks: list[Block], cwd: Path, slow: bool) -> list[str]:
    failures = []
    for b in blocks:
        if b.kind not in RUN_KINDS or "not run" in b.markers or ("slow" in b.markers and not slow):
            continue
        failure = run_block(b, cwd)
        if failure:
            failures.append(failure)
    return failures


def page_blocks(page: str) -> list[Block]:
    return parse((ROOT / page).read_text(encoding="utf-8"), page)[0]


def runnable(blocks, slow: bool) -> bool:
    return any(b.kind in RUN_KINDS and "not run" not in b.markers and (slow or "slow" not in b.markers)
               for b in blocks)


FAST_PAGES = [p for p in pages() if runnable(page_blocks(p), slow=False)]
SLOW_PAGES = [p for p in pages() if any("slow" in b.markers and "not run" not in b.markers
                                        for b in page_blocks(p))]


def test_every_block_has_a_kind_and_every_output_a_block():
    errors = []
    for page in pages():
        errors += parse((ROOT / page).read_text(encoding="utf-8"), page)[1]
    assert not errors, "\n".join(errors)


@pytest.mark.parametrize("page", FAST_PAGES)
def test_page(page, tmp_path):
    failures = run_page(page_blocks(page), sandbox(tmp_path), slow=False)
    assert not failures, "\n\n".join(failures)


@pytest.mark.parametrize("page", SLOW_PAGES)
def test_slow_page(page, tmp_path):
    failures = run_page(page_blocks(page), sandbox(tmp_path), slow=True)
    assert not failures, "\n\n".join(failures)


def test_the_pages_run_their_examples():
    """The front door's paths are run, not only parsed: the README's fmpy
    example in the fast tier, its recordings path in the slow one."""
    readme = page_blocks("README.md")
    assert any(b.kind == "python" and "simulate_fmu" in b.code and b.output for b in readme)
    assert any(b.kind == "sh" and "identify" in b.code and "slow" in b.markers and b.output for b in readme)
    assert {"README.md", "docs/reference/python-api.md", "docs/guides/system-simulator.md"} <= set(FAST_PAGES)


# --- the runner can fail ------------------------------------------------------

PAGE = '''Text.

```python
print("a", 1 + 1)
```

```output
a 3
```

<!-- slow: on purpose -->
```sh
echo one; echo two; echo three
```

```output
one
...
```

```sh
exit 3
```

```text
data
```

```output
orphan
```
'''


def test_the_runner_sees_a_wrong_output_a_failed_command_and_a_block_of_no_kind(tmp_path):
    blocks, errors = parse(PAGE, "page.md")
    assert [b.kind for b in blocks] == ["python", "sh", "sh", "text"]
    assert blocks[1].markers == {"slow": "on purpose"} and blocks[1].output == "one\n...\n"
    assert any("page.md:25: a ```text block is not run" in e for e in errors), errors
    assert any("page.md:29: a text block has no output" in e for e in errors), errors
    fast = run_page(blocks, tmp_path, slow=False)
    assert len(fast) == 2 and "printed\na 2" in fast[0] and "exit status 3" in fast[1], fast
    assert len(run_page(blocks, tmp_path, slow=True)) == 2      # "one ... " matches its three lines
    blocks[1].output = "two\n...\n"
    assert "printed\none\ntwo" in run_page(blocks, tmp_path, slow=True)[1]


def test_an_output_line_of_dots_stands_for_any_lines_and_dots_in_a_line_for_any_text():
    assert matches("...\nb\n", "b\n") and matches("...\nb\n", "a\nx\nb\n") and matches("a\n...\n", "a\n")
    assert matches("x = ...; y\n", "x = 12 34; y\n") and matches("a\n", "a  \n")
    assert not matches("...\nb\n", "a\nb\nc\n") and not matches("a\n", "a\nb\n")
    assert not matches("x = ...; y\n", "x = 1\n; y\n") and not matches("a.c\n", "abc\n")


def test_a_python_block_needs_its_output_and_a_marker_its_reason():
    errors = parse("```python\nprint(1)\n```\n\n<!-- not run: -->\n```text\nx\n```\n", "p.md")[1]
    assert any("p.md:1: a python block needs" in e for e in errors), errors
    assert any("p.md:6: a marker needs its reason" in e for e in errors), errors


# --- links, paths and figures ---------------------------------------------------

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
CODE_SPAN = re.compile(r"`([^`\n]+)`")


def prose(text: str) -> str:
    """The page without its fenced blocks (links and paths in code are not the page's)."""
    out, fenced = [], False
    for line in text.splitlines():
        if FENCE.match(line):
            fenced = not fenced
            continue
        out.append("" if fenced else line)
    return "\n".join(out)


def slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces as hyphens."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def anchors(path: Path) -> set[str]:
    seen, out = {}, set()
    for line in prose(path.read_text(encoding="utf-8")).splitlines():
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            s = slug(m.group(1))
            n = seen.get(s, 0)
            out.add(s if n == 0 else f"{s}-{n}")
            seen[s] = n + 1
    return out


def broken_links(page: str) -> list[str]:
    here = ROOT / page
    bad = []
    for target in LINK.findall(prose(here.read_text(encoding="utf-8"))):
        if re.match(r"^[a-z]+:", target):
            continue                      # http(s), mailto: not ours to check here
        path, _, anchor = target.partition("#")
        dest = (here.parent / path).resolve() if path else here
        if not dest.exists():
            bad.append(f"{page}: {target}: no such file")
        elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
            bad.append(f"{page}: {target}: no heading with that anchor in {dest.relative_to(ROOT)}")
    return bad


def test_every_relative_link_and_anchor_resolves():
    bad = [b for page in pages() for b in broken_links(page)]
    assert not bad, "\n".join(bad)


def test_the_link_checker_sees_a_missing_file_and_a_missing_anchor(tmp_path, monkeypatch):
    assert slug("4. Eq. (41) is not the least-squares solution of eq. (40)") == \
        "4-eq-41-is-not-the-least-squares-solution-of-eq-40"
    assert slug("`make reproduce` (`benchmarks/bench_reproduce.py`)") == \
        "make-reproduce-benchmarksbench_reproducepy"
    (tmp_path / "a.md").write_text("# Top\n\n[x](b.md) [y](a.md#top) [z](a.md#bottom) [w](#top)\n"
                                   "```sh\n[not a link](nowhere.md)\n```\n")
    monkeypatch.setattr(sys.modules[__name__], "ROOT", tmp_path)
    assert broken_links("a.md") == ["a.md: b.md: no such file",
                                    "a.md: a.md#bottom: no heading with that anchor in a.md"]


def top_level() -> set[str]:
    return {p.name for p in ROOT.iterdir() if p.name not in NOT_LINKED | {"build", "dist", ".venv"}}


def named_paths(text: str) -> list[str]:
    """Repository paths a page names in inline code and in its markers: a
    token whose first part is one of the repository's top-level entries."""
    spans = CODE_SPAN.findall(prose(text)) + [r for _, r in MARKER.findall(text)]
    roots, out = top_level(), []
    for span in spans:
        for token in re.split(r"[\s;:()]+|,(?![^{]*\})", span):
            token = token.rstrip(".")
            if "/" in token and token.split("/")[0] in roots and "…" not in token and "..." not in token:
                out.append(token)
    return out


def expand(pattern: str) -> list[str]:
    """{a,b} alternatives and <placeholder> parts as globs."""
    m = re.search(r"\{([^{}]*)\}", pattern)
    if m:
        return [q for alt in m.group(1).split(",")
                for q in expand(pattern[:m.start()] + alt + pattern[m.end():])]
    return [re.sub(r"<[^>]*>", "*", pattern)]


def test_every_path_the_pages_name_exists():
    missing = []
    for page in pages():
        for path in named_paths((ROOT / page).read_text(encoding="utf-8")):
            if not any(glob.glob(str(ROOT / g)) for g in expand(path)):
                missing.append(f"{page}: {path}")
    assert not missing, "\n".join(missing)


def test_the_path_check_sees_what_it_should():
    text = ("`fmu_src/contact_law.[ch]`, `tests/rig/test_harness.py -k teflon`, `out/identify/x.json`, "
            "`fmpy/c-code`, `cross-check/fmus/{2.0,3.0}/cs/<platform>/`\n```sh\n`tools/x`\n```\n"
            "<!-- not run: tests/nothing_here.py checks it -->\n")
    assert named_paths(text) == ["fmu_src/contact_law.[ch]", "tests/rig/test_harness.py",
                                 "cross-check/fmus/{2.0,3.0}/cs/<platform>/", "tests/nothing_here.py"]
    assert expand("a/{2.0,3.0}/<p>/b") == ["a/2.0/*/b", "a/3.0/*/b"]
    assert not glob.glob(str(ROOT / "tests/nothing_here.py"))


def test_every_figure_the_pages_show_is_a_png_a_named_script_writes():
    shown = set()
    for page in pages():
        for target in LINK.findall(prose((ROOT / page).read_text(encoding="utf-8"))):
            if target.lower().endswith((".png", ".svg", ".jpg")):
                shown.add(str(((ROOT / page).parent / target).resolve().relative_to(ROOT)))
    assert shown and shown <= set(FIGURES), shown - set(FIGURES)
    for figure in shown:
        data = (ROOT / figure).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR", figure
        width, height = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
        assert width >= 200 and height >= 150, (figure, width, height)
        script = (ROOT / FIGURES[figure]).read_text()
        assert Path(figure).name in script, f"{FIGURES[figure]} does not write {figure}"
