"""The model notes are in the repository, the README, the docs' map, the
report and the scenarios point to them, and the evidence they quote is what
the commands give."""
import re
import subprocess
import sys

from paths import DOCS, ROOT, SCENARIOS

NOTES = DOCS / "explanation" / "model-notes.md"


def test_readme_report_and_scenarios_link_the_model_notes(tmp_path):
    from orthocontact.reproduction import paper_report as report
    where = "docs/explanation/model-notes.md"
    assert where in (ROOT / "README.md").read_text()
    assert "explanation/model-notes.md" in (DOCS / "index.md").read_text()
    assert where in (SCENARIOS / "README.md").read_text()
    assert where in report.reproduction_report(tmp_path, [], [], 0.0)
    # the path a scenario's description names leads to the notes
    named = re.search(r"docs/[\w/-]+\.md", (SCENARIOS / "mat_new.toml").read_text()).group(0)
    assert (ROOT / named).is_file() and "model-notes.md" in (ROOT / named).read_text() + named
    text = NOTES.read_text()
    for topic in ("counterclockwise", "eq. (20)", "eq. (41)", "μ₂/μ₁", "Teflon strip"):
        assert topic in text


def test_the_isotropy_erratum_command_gives_what_the_notes_say():
    block = re.search(r"```sh\n\.venv/bin/python -c \"\n(.*?)\"\n```", NOTES.read_text(), re.S).group(1)
    out = subprocess.run([sys.executable, "-c", block], capture_output=True, text=True, check=True,
                         timeout=60).stdout.split()
    assert out[0] == "mu2/mu1" and float(out[1]) < 1e-9
    assert out[2] == "mu1/mu2" and round(float(out[3]), 1) == 43.8
    assert "43.8°" in NOTES.read_text()
