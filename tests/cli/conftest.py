"""The CLI tests' shared fixture: the bundled example identified once per
module, for the commands that take an identified.json (uq, export)."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def identified(tmp_path_factory):
    out = tmp_path_factory.mktemp("id") / "id"
    p = subprocess.run([sys.executable, "-m", "orthocontact", "identify",
                        str(ROOT / "scenarios" / "example_identification"), "--out", str(out), "--no-validate"],
                       cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    return out / "identified.json"
