"""docs/explanation/model-notes.md as the tests read it: its text, and the
figures its sign errata script prints (the block that computes
case5_eq28_deg), which the page and the paper report must both state."""
import re
import subprocess
import sys

from paths import DOCS

NOTES = (DOCS / "explanation" / "model-notes.md").read_text()


def errata_numbers() -> dict:
    """{name: the words after it} of each line the errata script prints."""
    block = next(b for b in re.findall(r"```sh\n\.venv/bin/python -c \"\n(.*?)\"\n```", NOTES, re.S)
                 if "case5_eq28_deg" in b)
    out = subprocess.run([sys.executable, "-c", block], capture_output=True, text=True, check=True,
                         timeout=60).stdout
    return {line.split()[0]: line.split()[1:] for line in out.splitlines()}
