"""The output folder (orthocontact.output.folder): bad output paths
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

from cli_run import CMD, MAT_SWEEP, case4_named, leftovers, one_error_line, timed_run
from cli_run import run_cli as run
from orthocontact.cli.main import main
from orthocontact.errors import InputError
from orthocontact.output.folder import check_output_file, check_output_folder, remove_earlier, staged_output
from orthocontact.output.lines import forget_warnings, warnings_said
from orthocontact.output.manifest import MANIFEST, file_sha256, read_manifest
from orthocontact.runtime.folders import LOCK
from paths import SCENARIOS


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
    sc = (SCENARIOS / "case4.toml").read_text().replace("step_deg = 1.0", "step_deg = 45.0")
    f = tmp_path / "c4.toml"
    f.write_text(sc)
    with pytest.raises(RuntimeError):
        main(["run", str(f), "--out", str(out), "--workers", "1", "--force"])
    assert [p.name for p in out.iterdir()] == ["keep.txt"]
    assert not list(tmp_path.glob(".out.partial-*"))


def test_reproduce_replaces_only_the_files_it_writes(tmp_path):
    """A folder of the user's own files is refused; with --force the run
    writes beside them and replaces only a file named as its output."""
    folder = case4_named(tmp_path, "case4")
    out = tmp_path / "out"
    (out / "case4").mkdir(parents=True)
    (out / "case4" / "my_notes.txt").write_text("keep me")
    (out / "case4" / "summary.json").write_text("old")
    (out / "mine.txt").write_text("keep me too")
    p = run(["reproduce", "--scenarios", folder, "--out", out], tmp_path)
    one_error_line(p, f"--out {out}: holds 2 file(s) or folder(s) no orthocontact run wrote "
                      "(case4, mine.txt)", "--force")
    assert (out / "case4" / "summary.json").read_text() == "old" and files_under(out) == [
        "case4/my_notes.txt", "case4/summary.json", "mine.txt"]
    p = run(["reproduce", "--scenarios", folder, "--out", out, "--force"], tmp_path)
    assert p.returncode in (0, 1), p.stderr  # 1: the packaged report compares rows of all scenarios
    assert (out / "case4" / "my_notes.txt").read_text() == "keep me"
    assert (out / "mine.txt").read_text() == "keep me too"
    assert (out / "case4" / "summary.json").read_text() != "old"
    assert (out / "case4" / "sweep.csv").is_file() and (out / "report.md").is_file()
    assert (f"orthocontact: --force: {out}: wrote beside 2 file(s) or folder(s) no orthocontact run wrote; "
            "replaced case4/summary.json") in p.stderr.splitlines()


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
    p = run(["identify", SCENARIOS / "example_recordings", "--out", out, "--no-validate"], tmp_path)
    assert p.returncode == 0, p.stderr
    (out / "my_notes.txt").write_text("mine")   # in identify's folder: the user's, kept
    first = files_under(out)
    assert {"rig_scenario.toml", "reduction.csv", "reduction.json", "reduction_45deg.png"} <= set(first)
    p = run(["identify", SCENARIOS / "example_identification", "--out", out, "--no-validate"], tmp_path)
    assert p.returncode == 0, p.stderr
    assert files_under(out) == [MANIFEST, "fit.png", "identified.json", "identified.md", "my_notes.txt"]
    assert (out / "my_notes.txt").read_text() == "mine"


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
    def partials():
        return sorted(tmp_path.glob(".out.partial-*"))

    def start(sc):
        return subprocess.Popen(CMD + ["run", str(sc), "--out", "out", "--workers", "2"], cwd=tmp_path,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    live = start(SCENARIOS / "case1.toml")
    try:
        # its .lock appears once held (made as .lock.new, renamed after the flock):
        # stopped before that, the run would stay without one
        _until(lambda: len(partials()) == 1 and (partials()[0] / LOCK).exists())
        os.kill(live.pid, signal.SIGSTOP)   # in progress, its lock held
        theirs = partials()
        killed = start(SCENARIOS / "mat_aged.toml")
        # its folder with its lock: killed before that, a run leaves a folder without one
        _until(lambda: len(partials()) == 2 and all((p / LOCK).exists() for p in partials()))
        os.kill(killed.pid, signal.SIGKILL)
        killed.wait(timeout=30)
        left = [p for p in partials() if p not in theirs]
        assert len(left) == 1 and not (tmp_path / "out").exists()
        _until(lambda: _lock_free(left[0]), timeout=10)   # its workers end with it
        p = run(["run", SCENARIOS / "case4.toml", "--out", "out", "--workers", "2"], tmp_path)
        assert p.returncode == 0, p.stderr
        # the killed run's gone, the live one's kept
        assert partials() == theirs and any(theirs[0].iterdir())
        assert json.loads((tmp_path / "out" / "summary.json").read_text())["scenario"] == "case4"
    finally:
        os.kill(live.pid, signal.SIGCONT)
    assert live.wait(timeout=120) == 0
    assert partials() == []
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["scenario"] == "case1"


# -- an output folder has one owner -------------------------------------------------

def snapshot(folder: Path) -> dict:
    """Every file under `folder` (the manifest too) -> its SHA-256."""
    return {f: file_sha256(folder / f) for f in files_under(folder)}


@pytest.fixture(scope="module")
def identified_once(tmp_path_factory):
    """An identify run's folder (the reduced example set, no validation runs)."""
    base = tmp_path_factory.mktemp("identified")
    p = run(["identify", SCENARIOS / "example_identification", "--out", base / "id", "--no-validate"], base)
    assert p.returncode == 0, p.stderr
    return base / "id"


@pytest.fixture
def identified(tmp_path, identified_once):
    """A copy of identified_once's folder in this test's tmp_path (its manifest's paths are relative)."""
    import shutil
    return Path(shutil.copytree(identified_once, tmp_path / "id"))


def coarse_case4(folder: Path) -> Path:
    """Case 4 at 45 deg steps (3 angles): a run or reproduce of a second."""
    folder.mkdir(exist_ok=True)
    from cli_run import scenario_variant
    return scenario_variant(SCENARIOS / "case4.toml", "step_deg = 1.0", "step_deg = 45.0",
                            folder / "case4.toml")


@pytest.mark.parametrize("second", ["export", "uq"])
def test_a_command_into_identifys_folder_is_refused_and_loses_nothing(tmp_path, identified, second):
    """The guides chain identify -> export and identify -> uq: with --out
    the identify folder, the second command used to delete identified.json
    (its own input), identified.md and fit.png, with exit 0."""
    before = snapshot(identified)
    args = {"export": ["export", identified / "identified.json", "--angle", "40"],
            "uq": ["uq", identified / "identified.json", "--scenario", SCENARIOS / "mat_aged.toml",
                   "--samples", "4", "--scheduler", "none"]}[second]
    p = run(args + ["--out", identified], tmp_path)
    one_error_line(p, f"--out {identified}: holds {identified / 'identified.json'}, which "
                      f"`orthocontact {second}` reads", "`orthocontact identify` run", "--force")
    assert snapshot(identified) == before


def test_export_then_uq_into_the_export_folder_is_refused_naming_export(tmp_path, identified):
    exported = tmp_path / "export"
    p = run(["export", identified / "identified.json", "--angle", "40", "--out", exported], tmp_path)
    assert p.returncode == 0, p.stderr
    before = snapshot(exported)
    p = run(["uq", identified / "identified.json", "--scenario", SCENARIOS / "mat_aged.toml",
             "--samples", "4", "--scheduler", "none", "--out", exported], tmp_path)
    one_error_line(p, f"--out {exported}: holds the outputs of `orthocontact export` run",
                   "--force to replace them (4 file(s))")
    assert snapshot(exported) == before


@pytest.mark.parametrize("into", [".", "case4"])
def test_run_into_a_reproduce_folder_or_one_of_its_scenarios_is_refused(tmp_path, into):
    """`run case5.toml --out <a reproduce folder>` turned its 64 files into
    case5's 7; its scenario's subfolder is reproduce's too."""
    scen = coarse_case4(tmp_path / "scen")
    results = tmp_path / "results"
    p = run(["reproduce", "--scenarios", scen.parent, "--out", results], tmp_path)
    assert p.returncode in (0, 1), p.stderr
    before = snapshot(results)
    p = run(["run", scen, "--out", results / into], tmp_path)
    one_error_line(p, f"--out {results / into}: holds the outputs of `orthocontact reproduce` run", "--force")
    assert snapshot(results) == before


def test_force_replaces_another_runs_files_but_never_what_the_command_reads(tmp_path, identified):
    said = json.loads((identified / MANIFEST).read_text())
    p = run(["export", identified / "identified.json", "--angle", "40", "--out", identified, "--force"],
            tmp_path)
    assert p.returncode == 0, p.stderr
    assert files_under(identified) == [MANIFEST, "calibration.ssv", "fmi2/OrthotropicContact.fmu",
                                       "fmi3/OrthotropicContact.fmu", "identified.json", "rig_40.ssp"]
    assert file_sha256(identified / "identified.json") == said["files"]["identified.json"]
    now = json.loads((identified / MANIFEST).read_text())
    assert now["command"] == "export" and "identified.json" not in now["files"]
    assert (f"orthocontact: --force: {identified}: replaced `orthocontact identify` run "
            f"{said['run_id'][:12]} of {said['date']} (3 file(s); kept identified.json, read by this "
            "command)") in p.stderr.splitlines()


def test_the_same_command_replaces_its_earlier_run_and_says_so_in_one_line(tmp_path):
    scen = coarse_case4(tmp_path / "scen")
    out = tmp_path / "out"
    assert run(["run", scen, "--out", out], tmp_path).returncode == 0
    first = json.loads((out / MANIFEST).read_text())
    p = run(["run", scen, "--out", out], tmp_path)
    assert p.returncode == 0, p.stderr
    said = [line for line in p.stderr.splitlines() if line.startswith("orthocontact:")]   # not the progress
    assert said == [f"orthocontact: {out}: replaced `orthocontact run` run {first['run_id'][:12]} "
                    f"of {first['date']} ({len(first['files'])} file(s))"]
    assert p.stderr.count("warning") == 0   # not a warning: --strict does not count it


@pytest.mark.parametrize("case", ["run", "identify", "ssp"])
def test_a_commands_own_input_is_never_its_output(tmp_path, case):
    """A folder (or file) holding what the command reads is refused; with
    --force a folder is written, the input kept (ssp's file: never)."""
    if case == "identify":
        import shutil
        folder = Path(shutil.copytree(SCENARIOS / "example_identification", tmp_path / "data"))
        args, read = ["identify", folder, "--no-validate", "--out", folder], folder
    elif case == "run":
        read = coarse_case4(tmp_path / "scen")
        folder = read.parent
        args = ["run", read, "--out", folder]
    else:
        read = coarse_case4(tmp_path / "scen")
        folder = read.parent
        args = ["ssp", read, "--angle", "40", "--out", read]
    before = snapshot(folder)
    p = run(args, tmp_path)
    says = "is a file this command reads" if case == "ssp" else f"which `orthocontact {case}` reads"
    one_error_line(p, says)
    assert snapshot(folder) == before
    p = run(args + ["--force"], tmp_path)
    if case == "ssp":
        one_error_line(p, says)
        assert snapshot(folder) == before
    else:
        assert p.returncode == 0, p.stderr
        assert all(snapshot(folder)[f] == h for f, h in before.items())   # every file kept as it was


def test_ssp_replaces_an_ssp_but_another_file_only_with_force(tmp_path):
    scen = coarse_case4(tmp_path / "scen")
    target = tmp_path / "notes.ssp"
    target.write_text("my notes")
    p = run(["ssp", scen, "--angle", "40", "--out", target], tmp_path)
    one_error_line(p, f"--out {target}: exists and is not an SSP package", "--force")
    assert target.read_text() == "my notes"
    assert run(["ssp", scen, "--angle", "40", "--out", target, "--force"], tmp_path).returncode == 0
    assert run(["ssp", scen, "--angle", "40", "--out", target], tmp_path).returncode == 0   # an SSP now


# -- the commit: --out takes its new content in one step, manifest included ------------

def _earlier_run(out: Path) -> dict:
    """`out` as an earlier identify run left it, with a file of the user's
    beside and one of the run's changed since; its snapshot."""
    with staged_output(out, "identify") as stage:
        for name in ("identified.json", "figs/reduction.png", "identified.md"):
            (stage / name).parent.mkdir(exist_ok=True)
            (stage / name).write_text(f"first run's {name}")
    (out / "my_notes.txt").write_text("mine")
    (out / "identified.md").write_text("the first run's, with my notes")
    return snapshot(out)


def _second_run(out: Path) -> None:
    forget_warnings()
    with staged_output(out, "identify") as stage:
        (stage / "identified.json").write_text("second run's")
    forget_warnings()


def _is_second_run(out: Path) -> bool:
    m = json.loads((out / MANIFEST).read_text())
    return (files_under(out) == [MANIFEST, "identified.json", "identified.md", "my_notes.txt"]
            and m["files"] == {"identified.json": file_sha256(out / "identified.json")}
            and (out / "my_notes.txt").read_text() == "mine")


def test_the_commit_exchanges_the_folder_whole(tmp_path):
    """The new content is built beside --out (hard links of what stays) and
    takes its place in one step: the user's files are the same files (their
    inode), the earlier run's are gone, the manifest is the new run's."""
    out = tmp_path / "out"
    _earlier_run(out)
    inode = (out / "my_notes.txt").stat().st_ino
    _second_run(out)
    assert _is_second_run(out) and (out / "my_notes.txt").stat().st_ino == inode
    assert leftovers(tmp_path) == ["out"]


@pytest.mark.parametrize("step", ["link", "write_manifest", "exchange"])
def test_a_full_disk_at_any_step_of_the_commit_leaves_out_as_it_was(tmp_path, monkeypatch, step):
    """ENOSPC from the system at each step before --out takes its new
    content: the command fails (exit 74 in the CLI), --out is as it was,
    nothing is left beside it."""
    import errno

    import orthocontact.output.folder as output
    out = tmp_path / "out"
    before = _earlier_run(out)
    real = {"link": os.link, "write_manifest": output.write_manifest, "exchange": output.exchange}[step]
    calls = []

    def full(*a, **k):
        calls.append(a)
        if len(calls) == 2 or step != "link":   # link: the second file
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(a[-1]))
        return real(*a, **k)
    monkeypatch.setattr(*((os, "link") if step == "link" else (output, step)), full)
    with pytest.raises(OSError, match="No space left"):
        _second_run(out)
    assert snapshot(out) == before and leftovers(tmp_path) == ["out"]


def test_a_full_disk_as_a_new_out_is_written_leaves_no_out(tmp_path, monkeypatch):
    import errno

    import orthocontact.output.folder as output

    def full(folder, m):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(folder))
    monkeypatch.setattr(output, "write_manifest", full)
    with pytest.raises(OSError):
        _second_run(tmp_path / "new" / "out")
    assert leftovers(tmp_path) == []   # not a folder of files without their manifest


KILL_AT = """
import os, signal, sys
from pathlib import Path
import orthocontact.output.folder as output
step = sys.argv[2]
real = getattr(output, step.split()[-1])
def at(*a, **k):
    if not step.startswith("after"):
        os.kill(os.getpid(), signal.SIGKILL)
    value = real(*a, **k)
    os.kill(os.getpid(), signal.SIGKILL)
setattr(output, step.split()[-1], at)
with output.staged_output(Path(sys.argv[1]), "identify") as stage:
    (stage / "identified.json").write_text("second run's")
"""


@pytest.mark.parametrize("step", ["link_tree", "merge_into", "write_manifest", "exchange", "after exchange"])
def test_a_commit_killed_at_any_step_leaves_out_as_it_was_or_complete(tmp_path, step):
    """SIGKILL (no cleanup) before each step of the commit and after its
    last: --out is the earlier run's folder as it was, or the new run's,
    complete with its manifest, and the user's file is there either way."""
    out = tmp_path / "out"
    before = _earlier_run(out)
    p = subprocess.run([CMD[0], "-c", KILL_AT, str(out), step], capture_output=True, text=True, timeout=60)
    assert p.returncode == -signal.SIGKILL, p.stderr
    if step == "after exchange":
        assert _is_second_run(out)
    else:
        assert snapshot(out) == before
    # the killed run's locked folder (the old content, or the one being built) goes with the next run
    _second_run(out)
    assert _is_second_run(out) and leftovers(tmp_path) == ["out"]


@pytest.mark.parametrize("why", ["no exchange", "no hard links", "a symbolic link"])
def test_where_no_exchange_can_be_made_the_files_move_one_by_one(tmp_path, monkeypatch, why):
    """The way of before, manifest last: a system without renameat2 or a
    file system without RENAME_EXCHANGE, one without hard links, and --out
    a symbolic link (its target is written, the link stays)."""
    import errno

    import orthocontact.output.folder as output
    out = tmp_path / "out"
    _earlier_run(out)
    if why == "no exchange":
        monkeypatch.setattr(output, "can_exchange", lambda folder: False)
    elif why == "no hard links":
        def refused(*a, **k):
            raise OSError(errno.EPERM, os.strerror(errno.EPERM), str(a[-1]))
        monkeypatch.setattr(os, "link", refused)
    else:
        out.rename(tmp_path / "target")
        out.symlink_to(tmp_path / "target")
    _second_run(out)
    assert _is_second_run(out)
    assert out.is_symlink() == (why == "a symbolic link")
    assert sorted(leftovers(tmp_path)) == sorted(["out"] + (["target"] if why == "a symbolic link" else []))


def test_an_output_the_user_edited_is_never_overwritten_by_the_same_command(tmp_path):
    """The same `run` again into its folder after sweep.csv was edited:
    refused in one line naming the file, the edit and every other file as
    they were; with --force the run replaces it.  Before, the edit was gone
    with exit 0."""
    sc = tmp_path / "m.toml"
    sc.write_text(MAT_SWEEP)
    out = tmp_path / "out"
    assert run(["run", sc, "--out", out], tmp_path).returncode == 0
    edited = (out / "sweep.csv").read_text() + "# my note\n"
    (out / "sweep.csv").write_text(edited)
    before = {n: (out / n).read_bytes() for n in files_under(out)}
    p = run(["run", sc, "--out", out], tmp_path)
    # after the run's progress lines (the check needs the files it would write): one error line
    errors = [x for x in p.stderr.splitlines() if x.startswith("orthocontact: error: ")]
    assert p.returncode == 2 and len(errors) == 1 and errors[0] == p.stderr.strip().splitlines()[-1]
    assert "sweep.csv changed since `orthocontact run`" in errors[0] and "--force to replace it" in errors[0]
    assert {n: (out / n).read_bytes() for n in files_under(out)} == before
    assert run(["run", sc, "--out", out, "--force"], tmp_path).returncode == 0
    assert (out / "sweep.csv").read_text() != edited


# -- an earlier run's files: removed but for those changed since, never through a link --

def committed(out: Path, files: dict):
    """`out` as a run of identify leaves it: `files` (path -> bytes) and its manifest."""
    with staged_output(out, "identify") as stage:
        for name, data in files.items():
            (stage / name).parent.mkdir(parents=True, exist_ok=True)
            (stage / name).write_bytes(data)
    return read_manifest(out)


def test_an_earlier_runs_files_go_the_users_and_changed_ones_stay(tmp_path):
    out = tmp_path / "out"
    old = committed(out, {"reduction.csv": b"1\n", "figs/a.png": b"png", "figs/b.png": b"png2",
                          "identified.md": b"# old\n", "shared.json": b"old"})
    (out / "my_notes.txt").write_text("mine")
    (out / "figs" / "mine.png").write_bytes(b"my figure")
    (out / "identified.md").write_text("# old, with my notes\n")
    kept = remove_earlier(out, old, keep={"shared.json": "x"})
    assert kept == ["identified.md"]
    assert sorted(p.relative_to(out).as_posix() for p in out.rglob("*")) == [
        MANIFEST, "figs", "figs/mine.png", "identified.md", "my_notes.txt", "shared.json"]
    old2 = committed(out / "sub", {"x/y/z.csv": b"1"})
    remove_earlier(out / "sub", old2, keep={})
    assert sorted(p.name for p in (out / "sub").iterdir()) == [MANIFEST]   # emptied folders go


def test_nothing_is_removed_through_a_symbolic_link(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "a.csv").write_bytes(b"1")
    out = tmp_path / "out"
    old = committed(out, {"sub/a.csv": b"1"})
    (out / "sub" / "a.csv").unlink()
    (out / "sub").rmdir()
    (out / "sub").symlink_to(outside)
    remove_earlier(out, old, keep={})
    assert (outside / "a.csv").read_bytes() == b"1"
