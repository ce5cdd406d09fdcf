"""The size of the work (orthocontact.runs.size): huge work is refused before
it starts unless --yes."""
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CMD = [sys.executable, "-m", "orthocontact"]
SCEN = ROOT / "scenarios"


def run(args, cwd, timeout=120, env=None):
    return subprocess.run(CMD + [str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=env)


# -- huge work: said before it starts, and progress while it runs ---------------------

def _aged_with(tmp_path, old, new) -> Path:
    text = (SCEN / "mat_aged.toml").read_text()
    assert old in text
    path = tmp_path / "big.toml"
    path.write_text(text.replace(old, new))
    return path


@pytest.mark.parametrize("old,new,key", [
    ("step_deg = 1.0", "step_deg = 1e-6", "sweep.step_deg"),      # 90 million angles
    ("step_s = 2.0e-4", "step_s = 1e-9", "rig.step_s"),           # 2e9 steps a run
])
def test_huge_work_is_refused_before_it_starts_unless_yes(tmp_path, old, new, key):
    big = _aged_with(tmp_path, old, new)
    t0 = time.monotonic()
    p = run(["run", big, "--out", tmp_path / "out"], tmp_path)
    lines = [x for x in p.stderr.strip().splitlines() if ": warning: " not in x]
    assert p.returncode == 2 and len(lines) == 1, p.stderr
    assert key in lines[0] and "--yes" in lines[0] and "rig steps" in lines[0]
    assert time.monotonic() - t0 < 20 and not (tmp_path / "out").exists()
