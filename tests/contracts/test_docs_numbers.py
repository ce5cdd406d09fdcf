"""The numbers the documentation states are the ones the commands, the
code and the closed forms give: the uq guide's example, the compiled
master's speed-up (one range in the README, the guides, --help and
docs/benchmarks.md), every benchmark figure the building guide's summary and
the README's features quote (the range of its table in docs/benchmarks.md,
which holds today's tables only), the commands' limits and progress
intervals and the workers' bound (the code's constants), the step limit's
worked example (its closed form, the defaults), the model notes' errata, the
libcosim example of the system-simulator guide; and the documentation names
no "issue" a reader cannot see.  CITATION.cff is valid."""
import json
import re
import subprocess
import sys

import pytest

from cli_run import CMD
from model_notes import NOTES, errata_numbers
from optional_parts import record, usable
from orthocontact.cli.parser import build_parser
from paths import DOCS, ROOT, SCENARIOS

README = (ROOT / "README.md").read_text()
UQ_GUIDE = (DOCS / "guides" / "uncertainty.md").read_text()
SYSTEM_GUIDE = (DOCS / "guides" / "system-simulator.md").read_text()


def _help(name):
    sub = next(a for a in build_parser()._actions if a.__class__.__name__ == "_SubParsersAction")
    return " ".join(sub.choices[name].format_help().split())


def test_the_uq_guides_example_prints_what_the_guide_says(tmp_path):
    """The guide's two commands (identify, then uq with 2000 draws), run
    serially: the files are the same bit for bit on any cluster."""
    block = re.search(r"```sh\n(.*?)```", UQ_GUIDE, re.S).group(1).replace("\\\n", " ")
    assert [ln.split()[1] for ln in block.splitlines()] == ["identify", "uq"]
    assert "--samples 2000" in block and "scenarios/mat_aged.toml" in block
    ident = tmp_path / "identify"
    p = subprocess.run(CMD + ["identify", str(SCENARIOS / "example_identification"), "--out",
                              str(ident)], capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    p = subprocess.run(CMD + ["uq", str(ident / "identified.json"), "--scenario", "scenarios/mat_aged.toml",
                              "--samples", "2000", "--out", str(tmp_path / "uq"), "--scheduler", "none"],
                       capture_output=True, text=True, timeout=900, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    uq = json.loads((tmp_path / "uq" / "uq.json").read_text())
    inside = uq["data_inside_measurement_band"]
    said = re.search(r"\((\d+) of (\d+) for the example set\)", UQ_GUIDE)
    assert said and (int(said.group(1)), int(said.group(2))) == (inside["inside"], inside["points"])
    w = uq["widest_band"]
    said = re.search(r"widest parameter band is ([\d.]+)° wide \(at\s+(\d+)°", UQ_GUIDE)
    assert said and said.group(1) == f"{w['width_deg']:.3f}" and float(said.group(2)) == w["angle_deg"]
    assert f"{w['width_deg']:.3f} deg at {w['angle_deg']:g} deg" in p.stdout


def test_the_compiled_masters_speed_up_is_one_range_everywhere():
    """docs/benchmarks.md holds the measured table (benchmarks/bench_masters.py);
    the README, the rig's guide, the benchmarks' summary and --help state its
    range, rounded outwards to whole numbers."""
    bench = (DOCS / "benchmarks.md").read_text()
    table = bench.split("## The compiled master")[1].split("##")[0]
    ratios = [float(x) for row in re.findall(r"\| ([\d.]+–[\d.]+)× \|", table) for x in row.split("–")]
    assert len(ratios) == 4, table
    lo, hi = int(min(ratios)), int(-(-max(ratios) // 1))
    said = f"{lo}–{hi}×"
    rig = (DOCS / "guides" / "scenarios-and-rig.md").read_text()
    assert said in rig.split("## Workers and masters")[1].split("\n## ")[0]
    building = (DOCS / "guides" / "building.md").read_text()
    assert f"measured {said}" in building.split("## Benchmarks")[1].split("\n## ")[0]
    assert said in README.split("## Features")[1].split("\n## ")[0]
    assert f"{lo}-{hi}x faster" in _help("run")


def test_identify_help_names_every_column():
    text = _help("identify")
    for column in ("mat_angle_deg", "force_N", "phi_deg", "velocity_m_s", "x1_m", "runs.csv", "t_s"):
        assert column in text, column


def test_no_documentation_names_an_issue_the_reader_cannot_see():
    files = [ROOT / "README.md", ROOT / "CITATION.cff", ROOT / "CONTRIBUTING.md", ROOT / "CHANGELOG.md",
             ROOT / "benchmarks" / "bench_coverage.py", *sorted(SCENARIOS.rglob("*.md")),
             *sorted(DOCS.rglob("*.md")), DOCS / "coverage.json"]
    assert len(files) > 20
    texts = {str(f.relative_to(ROOT)): f.read_text() for f in files}
    texts["--help"] = " ".join(_help(c) for c in ("run", "reproduce", "identify", "ssp", "uq", "sensitivity"))
    for name, text in texts.items():
        assert not re.search(r"\bissue(?:'s|s)?\b", text, re.I), name


def test_the_sign_errata_say_what_the_closed_forms_give():
    got = errata_numbers()
    assert got["case5_eq28_deg"] == ["-36.87"] and "give **−36.87°**" in NOTES
    assert got["case5_eq27_deg"] == ["26.565"] and "α = 26.565°" in NOTES
    assert got["mat_ratio"][0] == "0.817" and "λ₁/λ₂ = 0.817" in NOTES
    assert got["other_reading_eps_ratio"] == ["1.875"] and "**ε₁/ε₂ = 1.875**" in NOTES
    c, a = got["coupled"], got["associated"]
    assert f"{a[1]}° at a mat angle of {a[3]}°" in " ".join(NOTES.split())
    assert f"coupled rule's {c[1].lstrip('-')}° at {c[3]}°" in " ".join(NOTES.split())
    assert f"(−{c[1].lstrip('-')}° at {c[3]}°)" in " ".join(NOTES.split())
    m = got["case5_in_mat_frame"]
    assert f"(+{m[0]}° at {m[2]}°)" in " ".join(NOTES.split())


@pytest.mark.needs("libcosimpy")
def test_the_guides_libcosim_example_runs_as_written_and_prints_the_harness_angle(tmp_path):
    block = next(b for b in re.findall(r"```sh\n(.*?)```", SYSTEM_GUIDE, re.S)
                 if "from_ssp_file('aged.ssp')" in b)
    lines = block.splitlines()
    ssp_line = next(x for x in lines if " ssp " in x)
    # the guide's paths are relative to the repository root
    p = subprocess.run(CMD + [a.replace("scenarios/", str(SCENARIOS) + "/")
                              for a in ssp_line.split()[1:]], capture_output=True, text=True, timeout=120,
                       cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    code = block.split('-c "\n', 1)[1].rsplit('"', 1)[0]
    q = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600,
                       cwd=tmp_path)
    assert q.returncode == 0, q.stderr[-2000:]
    printed = q.stdout.strip().splitlines()[-1]
    said = re.search(r"from_ssp_file\('aged.ssp'\).*?```\n\n```output\n\.\.\.\n(phi = [-\d.]+ deg)\n```",
                     SYSTEM_GUIDE, re.S).group(1)
    assert printed == said
    from orthocontact.experiment.scenario import load
    from orthocontact.rig.harness import run
    sc = load(SCENARIOS / "mat_aged.toml")
    assert abs(float(printed.split()[2]) - run(sc.params_at(39.2), sc.rig).phi_deg) < 5e-3


def test_citation_cff_is_valid_and_names_the_paper_as_given():
    text = (ROOT / "CITATION.cff").read_text()
    # The CFF schema through cffconvert where it is installed (not a test
    # dependency: reported as not run elsewhere); the fields below everywhere.
    if usable("cffconvert") is None:
        from cffconvert.cli.create_citation import create_citation
        from cffconvert.cli.validate_or_write_output import validate_or_write_output
        citation = create_citation(str(ROOT / "CITATION.cff"), None)
        validate_or_write_output(None, "cff", True, citation)  # raises if the schema is not met
    record("cffconvert", usable("cffconvert"))
    import yaml
    data = yaml.safe_load(text)
    assert data["cff-version"] == "1.2.0" and data["message"] and data["title"] and data["authors"]
    assert data["version"] == (ROOT / "VERSION").read_text().strip()
    paper = data["references"][0]
    assert paper["type"] == "report" and paper["year"] == 2007
    assert paper["institution"]["name"] == "Institut für Mechanik, Universität Karlsruhe"
    assert paper["title"] == ("On coupled models of anisotropic contact surfaces and their "
                              "experimental validation")
    assert "## Citing" in README and "CITATION.cff" in README.split("## Citing")[1]
    assert "Institut für Mechanik" in README.split("## Citing")[1]


@pytest.mark.parametrize("version", [2, 3])
def test_each_fmus_documentation_is_its_own_versions(version):
    """documentation/index.html of the installed FMUs: the version's types and
    functions only, the wiring, the output timing, angles in degrees, how to cite."""
    import zipfile

    from orthocontact.fmu.files import find_fmu
    text = zipfile.ZipFile(find_fmu(fmi_version=version)).read("documentation/index.html").decode()
    other = 3 if version == 2 else 2
    assert f"FMI {version}.0 Co-Simulation" in text
    assert f"fmi{other}" not in text and f"fmi{version}DoStep" in text
    types = set(re.findall(r"<tr><td><code>\w+</code></td><td>\d+</td><td>\w+</td><td>\w+</td>"
                           r"<td>([^<]+)</td>", text))
    assert types == ({"Real", "Integer", "Integer (see below)"} if version == 2 else
                     {"Float64", "Int32", "Enumeration SlidingRule", "Enumeration InitialSlip"}), types
    words = " ".join(re.sub(r"<[^>]+>", " ", text).split())
    for said in ("relative to the surface", "T(u, N)", "one step behind", "N starts at 0",
                 "1.5707963267948966 (90&deg;)", "How to cite", "Universit&auml;t Karlsruhe, 2007"):
        assert said in words, said
    assert "machine precision" not in words


# -- the benchmarks: today's tables, and the summaries that quote them -------------------

BENCH = (DOCS / "benchmarks.md").read_text()


def _section(text: str, heading: str) -> str:
    """The text of the `## heading...` section, up to the next `## `."""
    return text.split(f"\n## {heading}", 1)[1].split("\n## ", 1)[0]


def _rows(text: str) -> list[list[str]]:
    """The cells of every table row of `text` (headers and separators left out)."""
    lines = text.splitlines() + [""]
    return [[c.replace("**", "").strip() for c in ln.strip("|").split(" | ")]
            for ln, after in zip(lines, lines[1:]) if ln.startswith("| ") and not after.startswith("|---")]


def _span(cells: list[str]) -> str:
    """"0.89–1.00": the range of the figures (each a value or "a–b", rounds in brackets dropped)."""
    xs = [float(x) for c in cells for x in c.split(" [")[0].rstrip("×").split("–")]
    return f"{min(xs):.2f}–{max(xs):.2f}"


def _words(text: str) -> str:
    return " ".join(text.split())


def test_the_benchmarks_page_is_todays_tables_each_with_its_command():
    """docs/benchmarks.md: at most 300 lines, no history in its prose (that
    is CHANGELOG.md's), a command block in every section with a table."""
    assert len(BENCH.splitlines()) <= 300
    prose = re.sub(r"```.*?```", "", BENCH, flags=re.S)
    for word in (r"\bbefore\b", r"\bearlier\b", r"\bprevious\b", "→", r"\bwas\b", r"\bnow\b"):
        assert not re.search(word, prose, re.I), word
    for section in BENCH.split("\n## ")[1:]:
        if "\n| " in section:
            assert "```sh\n" in section, section.splitlines()[0]


def test_the_building_guide_and_the_readme_quote_the_benchmark_tables():
    """Every figure the building guide's summary and the README's features
    state is the range of the benchmarks' table it comes from."""
    building = _words(_section((DOCS / "guides" / "building.md").read_text(), "Benchmarks"))
    features = _words(README.split("## Features")[1].split("\n## ")[0])
    peer = [r for r in _rows(_section(BENCH, "One step through the FMI calls")) if r[0] in ("2.0", "3.0")]
    assert len(peer) == 12
    stick = _span([r[5] for r in peer if r[2] == "stick"])
    slip = _span([r[5] for r in peer if r[2] == "slip" and r[1] != "eq20"])
    eq20 = _span([r[5] for r in peer if r[2] == "slip" and r[1] == "eq20"])
    assert f"measured on the shipped binaries {stick}×, {slip}×, {eq20}×" in building

    def median_ns(path, rules):
        xs = sorted(float(x) for r in peer if r[0] == "2.0" and r[2] == path and r[1] in rules
                    for x in r[3].split("–"))
        return round((xs[len(xs) // 2] + xs[(len(xs) - 1) // 2]) / 2)
    assert f"stick ~{median_ns('stick', ('associated', 'coupled', 'eq20'))} ns, " \
           f"slip ~{median_ns('slip', ('associated', 'coupled'))} ns" in building
    master = _rows(_section(BENCH, "The compiled master"))
    overhead = [r for r in master if len(r) == 4]
    assert len(overhead) == 1 and f"measured {overhead[0][2].split(' [')[0]}×" in building
    patch = {(r[0], r[1]): r for r in _rows(_section(BENCH, "The contact patch"))}
    cell_law, per_points = (lambda c, p: patch[(c, p)][5].split(" [")[0]), \
        (lambda c, p: patch[(c, p)][7].split(" [")[0])
    assert (f"measured {cell_law('400', 'stick')}× stick and {cell_law('400', 'slip')}× slip at 400 cells, "
            f"{per_points('100', 'stick')}× stick and {per_points('100', 'slip')}× slip at 100") in building
    assert max(float(per_points("100", p)) for p in ("stick", "slip")) < 0.5
    assert "100 cells for under half of 100 point FMUs' cost" in features
    reproduce = _rows(_section(BENCH, "`make reproduce`"))
    assert len(reproduce) == 1 and f"measured {reproduce[0][1]} on the machine" in building
    uq = _rows(_section(BENCH, "Uncertainty propagation"))
    assert len(uq) == 1 and f"measured {uq[0][1]} on a quiet machine" in building
    assert float(uq[0][1].split("–")[1].split()[0]) < 30 and "10⁶ rig runs in under 30 s" in features


# -- figures of the guides that the code's constants and defaults give ------------------

def test_the_commands_limits_and_progress_are_the_codes():
    from orthocontact.runs import progress, size
    from orthocontact.runtime import workers
    commands = _words((DOCS / "reference" / "commands.md").read_text())
    exponent = {6: "⁶", 9: "⁹"}
    runs, steps = (f"{m:g}·10{exponent[e]}" for m, e in
                   ((size.LIMIT_RUNS / 10 ** 6, 6), (size.LIMIT_STEPS / 10 ** 9, 9)))
    assert f"Above {runs} runs or {steps} steps" in commands
    p = progress.Progress
    assert f"a progress line within {p.FIRST_S:g} s and then every {p.HEARTBEAT_S:g} s" in commands
    rig = _words((DOCS / "guides" / "scenarios-and-rig.md").read_text())
    per_worker = workers.WORKER_MB * workers.PROCESSES_PER_WORKER
    assert f"{workers.WORKERS_PER_CORE} per usable core" in rig
    assert f"about {per_worker:g} MB per worker" in rig


def test_the_step_limits_example_is_the_closed_form_with_the_defaults():
    """system-simulator.md: h < 2 sqrt(m / eps_max) for its 0.05 kg example
    and for the rig's block on the default eps1, and what a step above does."""
    import math

    from orthocontact import Rig
    from orthocontact.fmu.variables import contact
    text = _words(SYSTEM_GUIDE)
    m, eps, h = 0.05, 25000.0, 4e-3
    assert f"0.05 kg on ε_max = 25,000 N/m gives h < {2e3 * math.sqrt(m / eps):.2f} ms" in text
    assert f"at h = 4 ms (hω = {h * math.sqrt(eps / m):.2f}) the first step moves the body by " \
           f"h²F/m = {h * h * eps / m:g}F/ε" in text
    assert f"30 % of the friction limit loads the contact with {0.3 * h * h * eps / m:.1f} times" in text
    eps1, eps2 = (contact().variable(n).start for n in ("eps1", "eps2"))
    rig = Rig()
    limit = 2e3 * math.sqrt(rig.mass_kg / max(eps1, eps2))
    assert f"default ε₁ = {eps1:,.0f} N/m with the rig's {rig.mass_kg:g} kg block: " \
           f"h < {limit:.1f} ms" in text


def test_the_reproducing_guides_calibration_chain_is_the_reports():
    """reproducing-the-paper.md: eps1/eps2 from the measured forces unrounded,
    as report.json's chain has it, and the paper's 1.251, the report's row of
    eq. (39) with the rounded mu (matched within its tolerance)."""
    from orthocontact.reproduction.paper_report import calibration_chain, calibration_rows
    unrounded = next(c["value"] for c in calibration_chain() if c["step"] == "ε1/ε2 by eq. (39)")
    paper = next(r for r in calibration_rows() if r["quantity"].startswith("ε1/ε2 by eq. (39)"))
    guide = _words((DOCS / "guides" / "reproducing-the-paper.md").read_text())
    assert paper["match"] and f"(ε1/ε2 = {unrounded:.4f}; the paper's {paper['paper']:g} is what its " \
        "rounded μ give)" in guide
