"""report.md and report.json (orthocontact.reproduction.paper_report): the
sign reading it states, its counts and headline, the calibration chain
by hand."""
import re
import subprocess
import sys

from paths import DOCS, SCENARIOS

NOTES = (DOCS / "explanation" / "model-notes.md").read_text()


def _errata_numbers():
    block = next(b for b in re.findall(r"```sh\n\.venv/bin/python -c \"\n(.*?)\"\n```", NOTES, re.S)
                 if "case5_eq28_deg" in b)
    out = subprocess.run([sys.executable, "-c", block], capture_output=True, text=True, check=True,
                         timeout=60).stdout
    return {line.split()[0]: line.split()[1:] for line in out.splitlines()}


def test_the_report_says_which_sign_reading_it_uses_and_its_sign_free_figures(tmp_path):
    from orthocontact.experiment.scenario import load
    from orthocontact.reproduction import paper_report
    free = paper_report.sign_free_peaks(load(SCENARIOS / "mat_aged.toml"))
    got = _errata_numbers()
    assert f"{free['associated']['peak_abs_phi_deg']:.2f}" == got["associated"][1]
    assert f"{free['associated']['angle_deg']:.2f}" == got["associated"][3]
    text = " ".join(paper_report.SIGN_READING)
    assert "reads both Case 5 and the experiment as clockwise" in text and "1.875" in text
    assert "erratum 6" in text
