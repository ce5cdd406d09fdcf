"""Where a command's results go (orthocontact.cli.output): bad output paths
refused before any work, a staging folder committed only when everything
is written, files the command does not write left alone, an earlier run's
files removed (the folder's manifest)."""
import fcntl
import json
import os
import signal
import subprocess
import time
from pathlib import Path

import pytest
from cli_run import CMD, case4_named, leftovers, one_error_line, run_cli as run, timed_run

from orthocontact.cli.main import main
from orthocontact.cli.output import (check_output_file, check_output_folder, forget_warnings,
                                     staged_output, warn, warnings_said)
from orthocontact.errors import InputError
from orthocontact.fmu.files import LOCK
from orthocontact.output.manifest import MANIFEST, file_sha256

SCEN = Path(__file__).resolve().parents[2] / "scenarios"
ROOT = Path(__file__).resolve().parents[2]


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


def test_reproduce_replaces_only_the_files_it_writes(tmp_path):
    folder = case4_named(tmp_path, "case4")
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


def test_output_checks_in_process_name_the_users_path(tmp_path):
    (tmp_path / "afile").write_text("x")
    check_output_folder(tmp_path / "new" / "deeper")          # can be made: fine, nothing made
    assert leftovers(tmp_path) == ["afile"]
    with pytest.raises(InputError, match=r"--scenarios .*afile: is a file; expected a folder"):
        check_output_folder(tmp_path / "afile", "--scenarios")
    check_output_file(tmp_path / "a.ssp")
    with pytest.raises(InputError, match="is a folder; expected a file name"):
        check_output_file(tmp_path)
    with pytest.raises(InputError, match=r"the folder .*nowhere does not exist"):
        check_output_file(tmp_path / "nowhere" / "a.ssp")
    assert leftovers(tmp_path) == ["afile"]


def test_staged_output_commits_on_success_and_leaves_nothing_on_failure(tmp_path):
    out = tmp_path / "made" / "results"
    with pytest.raises(RuntimeError):
        with staged_output(out) as stage:
            (stage / "summary.json").write_text("{}")
            raise RuntimeError("disk full")
    assert leftovers(tmp_path) == []            # nor the parent folder made for it
    with staged_output(out) as stage:
        (stage / "sub").mkdir()
        (stage / "sub" / "a.csv").write_text("1")
        assert not out.exists()                 # nothing in place before the block ends
    assert sorted(p.relative_to(out).as_posix() for p in out.rglob("*")) == [MANIFEST, "sub", "sub/a.csv"]
    assert leftovers(out.parent) == ["results"]


def files_under(folder: Path) -> list:
    return sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file())


def test_a_new_run_removes_the_earlier_runs_files_and_nothing_else(tmp_path, capsys):
    out = tmp_path / "out"
    with staged_output(out, "identify") as stage:
        for name in ("identified.json", "reduction.csv", "figs/reduction_45deg.png", "identified.md"):
            (stage / name).parent.mkdir(exist_ok=True)
            (stage / name).write_text(f"first run's {name}")
    first = json.loads((out / MANIFEST).read_text())
    (out / "my_notes.txt").write_text("mine")
    (out / "identified.md").write_text("the first run's, with my notes")
    forget_warnings()
    with staged_output(out, "identify") as stage:
        (stage / "identified.json").write_text("second run's")
    assert files_under(out) == [MANIFEST, "identified.json", "identified.md", "my_notes.txt"]
    assert (out / "identified.json").read_text() == "second run's"
    assert (out / "my_notes.txt").read_text() == "mine"
    assert (out / "identified.md").read_text() == "the first run's, with my notes"   # changed: the user's
    assert warnings_said() == 1 and "kept identified.md" in capsys.readouterr().err
    second = json.loads((out / MANIFEST).read_text())
    assert second["run_id"] != first["run_id"] and second["command"] == "identify"
    assert second["files"] == {"identified.json": file_sha256(out / "identified.json")}
    forget_warnings()


def test_a_bad_manifest_in_the_output_folder_is_refused_before_any_work(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / MANIFEST).write_text('{"written_by": "orthocontact", "run_id": "r", "files": {"../x": "0"}}')
    p = run(["reproduce", "--out", out], tmp_path)
    one_error_line(p, f"{out / MANIFEST}: files: expected paths inside the folder")
    assert leftovers(out) == [MANIFEST]


def test_reproduce_into_the_same_folder_leaves_no_scenario_of_the_earlier_run(tmp_path):
    """Nested outputs: the first run's <out>/alpha/ goes, files and folder,
    except what the user put there."""
    out = tmp_path / "out"
    (tmp_path / "a").mkdir(), (tmp_path / "b").mkdir()
    p = run(["reproduce", "--scenarios", case4_named(tmp_path / "a", "alpha"), "--out", out], tmp_path)
    assert p.returncode in (0, 1), p.stderr
    assert (out / "alpha" / "sweep.csv").is_file()
    (out / "mine.txt").write_text("keep me")
    (out / "beta_notes").mkdir()
    (out / "beta_notes" / "n.txt").write_text("keep me too")
    p = run(["reproduce", "--scenarios", case4_named(tmp_path / "b", "beta"), "--out", out], tmp_path)
    assert p.returncode in (0, 1), p.stderr
    assert not (out / "alpha").exists()
    assert (out / "mine.txt").read_text() == "keep me" and (out / "beta_notes" / "n.txt").is_file()
    m = json.loads((out / MANIFEST).read_text())
    assert m["command"] == "reproduce" and "beta/sweep.csv" in m["files"]
    assert sorted(m["files"]) == [f for f in files_under(out)
                                  if f not in (MANIFEST, "mine.txt", "beta_notes/n.txt")]
    assert all(file_sha256(out / f) == h for f, h in m["files"].items())


def test_identify_twice_into_one_folder_leaves_only_the_second_runs_outputs(tmp_path):
    """The guides' sequence: the recordings, then the example set, both
    into out/identify; before, the first run's reduction and rig scenario
    stayed beside the second run's identified.json (and uq took that rig)."""
    out = tmp_path / "out" / "identify"
    out.mkdir(parents=True)
    (out / "my_notes.txt").write_text("mine")
    p = run(["identify", SCEN / "example_recordings", "--out", out, "--no-validate"], tmp_path)
    assert p.returncode == 0, p.stderr
    first = files_under(out)
    assert {"rig_scenario.toml", "reduction.csv", "reduction.json", "reduction_45deg.png"} <= set(first)
    p = run(["identify", SCEN / "example_identification", "--out", out, "--no-validate"], tmp_path)
    assert p.returncode == 0, p.stderr
    assert files_under(out) == [MANIFEST, "fit.png", "identified.json", "identified.md", "my_notes.txt"]
    assert (out / "my_notes.txt").read_text() == "mine"


def test_warnings_are_counted_for_strict(capsys):
    forget_warnings()
    warn("angles.csv: a value looks like radians")
    warn("second")
    assert warnings_said() == 2
    assert capsys.readouterr().err.splitlines() == [
        "orthocontact: warning: angles.csv: a value looks like radians", "orthocontact: warning: second"]
    forget_warnings()
    assert warnings_said() == 0


# -- a killed run's staging folder: the next run into its --out removes it ------------

def _until(cond, timeout=60.0):
    t0 = time.monotonic()
    while not cond():
        assert time.monotonic() - t0 < timeout, "timed out"
        time.sleep(0.02)


def _lock_free(folder: Path) -> bool:
    """No process holds the folder's lock (every process of its run is gone)."""
    fd = os.open(folder / LOCK, os.O_RDWR)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        return True
    except OSError:
        return False
    finally:
        os.close(fd)


def test_a_killed_runs_staging_folder_goes_with_the_next_run_and_a_live_ones_stays(tmp_path):
    """SIGKILL runs no cleanup: `run` killed while it writes leaves its
    .out.partial-* folder; the next run into that --out removes it and
    succeeds, while the staging folder of a run still in progress (stopped
    with SIGSTOP, its lock held) is left alone, and that run then completes."""
    partials = lambda: sorted(tmp_path.glob(".out.partial-*"))
    start = lambda sc: subprocess.Popen(CMD + ["run", str(sc), "--out", "out", "--workers", "2"], cwd=tmp_path,
                                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    live = start(SCEN / "case1.toml")
    try:
        _until(lambda: len(partials()) == 1)
        os.kill(live.pid, signal.SIGSTOP)   # in progress, its lock held
        theirs = partials()
        killed = start(SCEN / "mat_aged.toml")
        _until(lambda: len(partials()) == 2)
        os.kill(killed.pid, signal.SIGKILL)
        killed.wait(timeout=30)
        left = [p for p in partials() if p not in theirs]
        assert len(left) == 1 and not (tmp_path / "out").exists()
        _until(lambda: _lock_free(left[0]), timeout=10)   # its workers end with it
        p = run(["run", SCEN / "case4.toml", "--out", "out", "--workers", "2"], tmp_path)
        assert p.returncode == 0, p.stderr
        assert partials() == theirs and any(theirs[0].iterdir())   # the killed run's gone, the live one's kept
        assert json.loads((tmp_path / "out" / "summary.json").read_text())["scenario"] == "case4"
    finally:
        os.kill(live.pid, signal.SIGCONT)
    assert live.wait(timeout=120) == 0
    assert partials() == [] and json.loads((tmp_path / "out" / "summary.json").read_text())["scenario"] == "case1"
