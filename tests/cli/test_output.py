"""Where a command's results go (orthocontact.cli.output): bad output paths
refused before any work, a staging folder committed only when everything
is written, files the command does not write left alone."""
import subprocess
import sys
import time
from pathlib import Path

import pytest

from orthocontact.cli.main import main

CMD = [sys.executable, "-m", "orthocontact"]
SCEN = Path(__file__).resolve().parents[2] / "scenarios"
ROOT = Path(__file__).resolve().parents[2]


def timed_run(args, cwd, timeout=120):
    t0 = time.monotonic()
    p = subprocess.run(CMD + args, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    return p, time.monotonic() - t0


def leftovers(folder: Path):
    return sorted(p.name for p in folder.iterdir())


@pytest.mark.parametrize("out,says", [
    ("afile", "afile: is a file"),
    ("afile/sub", "afile is a file"),
    ("/proc/x", "/proc is not writable"),
])
def test_bad_output_path_is_refused_before_any_work(tmp_path, out, says):
    (tmp_path / "afile").write_text("keep me")
    before = leftovers(tmp_path)
    p, seconds = timed_run(["reproduce", "--out", out], tmp_path)
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and f"--out {out}" in lines[0] and says in lines[0], p.stderr
    assert "partial" not in p.stderr and "Traceback" not in p.stderr
    assert leftovers(tmp_path) == before and (tmp_path / "afile").read_text() == "keep me"
    assert seconds < 10  # no sweep ran (measured: ~0.3 s, the interpreter's start)


def test_failed_run_leaves_the_output_folder_untouched(tmp_path, monkeypatch):
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("earlier result")
    import orthocontact.reproduction.scenario_outputs as report

    def boom(*a, **k):
        raise RuntimeError("disk full")
    monkeypatch.setattr(report, "sweep_outputs", boom)
    sc = (SCEN / "case4.toml").read_text().replace("step_deg = 1.0", "step_deg = 45.0")
    f = tmp_path / "c4.toml"
    f.write_text(sc)
    with pytest.raises(RuntimeError):
        main(["run", str(f), "--out", str(out), "--workers", "1"])
    assert [p.name for p in out.iterdir()] == ["keep.txt"]
    assert not list(tmp_path.glob(".out.partial-*"))


def run(args, cwd, timeout=120, env=None):
    return subprocess.run(CMD + [str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=env)


def _scenario_named(tmp_path, name) -> Path:
    folder = tmp_path / "scen"
    folder.mkdir(exist_ok=True)
    text = (SCEN / "case4.toml").read_text().replace('name = "case4"', f'name = "{name}"', 1)
    assert f'name = "{name}"' in text
    (folder / "s.toml").write_text(text)
    return folder


def test_reproduce_replaces_only_the_files_it_writes(tmp_path):
    folder = _scenario_named(tmp_path, "case4")
    out = tmp_path / "out"
    (out / "case4").mkdir(parents=True)
    (out / "case4" / "my_notes.txt").write_text("keep me")
    (out / "case4" / "summary.json").write_text("old")
    (out / "mine.txt").write_text("keep me too")
    p = run(["reproduce", "--scenarios", folder, "--out", out], tmp_path)
    assert p.returncode in (0, 1), p.stderr  # 1: the packaged report compares rows of all scenarios
    assert (out / "case4" / "my_notes.txt").read_text() == "keep me"
    assert (out / "mine.txt").read_text() == "keep me too"
    assert (out / "case4" / "summary.json").read_text() != "old"
    assert (out / "case4" / "sweep.csv").is_file() and (out / "report.md").is_file()
