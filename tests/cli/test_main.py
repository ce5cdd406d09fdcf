"""The `orthocontact` command (orthocontact.cli.main, python -m orthocontact):
--version, an error is one line with exit 2, the system's refusals (a full
disk, a read-only file system, a full or closed standard output) one line
with exit 74 or none, and no Python or numpy warning text."""
import contextlib
import re
import subprocess
from pathlib import Path

import pytest

from cli_run import CMD, run_cli
from cli_run import timed_run as run
from orthocontact.cli.main import OS_ERROR, main
from paths import SCENARIOS


def test_version_names_the_package_and_both_fmus(tmp_path):
    from orthocontact import __version__
    p, _ = run(["--version"], tmp_path)
    assert p.returncode == 0
    assert p.stdout.splitlines()[0] == f"orthocontact {__version__}"
    assert "FMI 2.0 FMU:" in p.stdout and "FMI 3.0 FMU:" in p.stdout and "not found" not in p.stdout


def test_main_in_process_an_error_is_one_line_and_exit_2(tmp_path, capsys):
    assert main(["run", str(tmp_path / "none.toml"), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("orthocontact: error: ") and "none.toml" in err[0]
    assert main(["run", str(tmp_path / "none.toml"), "--out", str(tmp_path / "o"), "--fmi", "3",
                 "--master", "c"]) == 2
    assert "--master c runs FMI 2.0 FMUs" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


# --- one way out for every error ---------------------------------------------

def error_lines(p):
    """stderr's lines that are not progress lines ("case4: 91/91 (100%, 0.2s)")."""
    return [ln for ln in p.stderr.strip().splitlines() if not re.match(r"^\S+: \d+/\d+ \(", ln)]


needs_root = pytest.mark.needs("root")   # mounting a tmpfs (tests/optional_parts.py)


@contextlib.contextmanager
def tmpfs(path: Path, options: str):
    """A tmpfs mounted at `path` (made if missing) for the block."""
    path.mkdir(parents=True, exist_ok=True)
    subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(path)], check=True)
    try:
        yield path
    finally:
        subprocess.run(["umount", str(path)], check=True)


@needs_root
def test_a_full_disk_is_one_line_with_its_own_exit_status_and_nothing_left(tmp_path):
    # Was a 30-line traceback and exit 1, "does not match the paper".
    with tmpfs(tmp_path / "disk", "size=200k") as disk:
        p = run_cli(["run", SCENARIOS / "case4.toml", "--out", disk / "out", "--workers", "1"], tmp_path)
        assert p.returncode == OS_ERROR == 74, p.stderr
        assert error_lines(p) == [f"orthocontact: error: cannot write the results: No space left on "
                                  f"device ({disk / 'out'})"], p.stderr
        assert list(disk.iterdir()) == []


@needs_root
@pytest.mark.parametrize("made", [False, True])
def test_a_read_only_file_system_is_one_line_with_the_same_exit_status(tmp_path, made):
    # Root ignores file modes, not a read-only mount.  Refused by the check
    # of --out before any work (was: exit 2, "bad input").
    with tmpfs(tmp_path / "ro", "size=1m") as ro:
        if made:
            (ro / "out").mkdir()
        subprocess.run(["mount", "-o", "remount,ro", str(ro)], check=True)
        p = run_cli(["identify", SCENARIOS / "example_identification", "--out", ro / "out",
                     "--no-validate"], tmp_path)
        where = ro / "out" if made else ro
        assert p.returncode == 74, p.stderr
        assert error_lines(p) == [f"orthocontact: error: cannot write the results: Read-only file "
                                  f"system ({where})"], p.stderr
        assert list(ro.iterdir()) == ([ro / "out"] if made else [])
        subprocess.run(["mount", "-o", "remount,rw", str(ro)], check=True)


def test_a_full_standard_output_is_one_line(tmp_path):
    with open("/dev/full", "w") as full:
        p = subprocess.run(CMD + ["--version"], stdout=full, stderr=subprocess.PIPE, text=True,
                           cwd=tmp_path, timeout=60)
    assert p.returncode == 74
    assert p.stderr.splitlines() == ["orthocontact: error: cannot write the command's text: No space "
                                     "left on device (standard output)"]


@pytest.mark.parametrize("args", [["--version"], ["--help"], ["identify", "--help"]])
def test_a_closed_pipe_ends_the_text_not_in_a_traceback(tmp_path, args):
    # `orthocontact --version | head -1`: was a 27-line BrokenPipeError, exit 1.
    for read_first in (False, True, False, True):
        proc = subprocess.Popen(CMD + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=tmp_path)
        if read_first:
            proc.stdout.readline()   # head -1
        proc.stdout.close()
        err = proc.stderr.read().decode()
        assert proc.wait(timeout=60) == 0 and err == "", err


def test_a_long_text_into_a_closed_pipe_still_writes_the_results(tmp_path):
    out = tmp_path / "out"
    proc = subprocess.Popen(CMD + ["identify", SCENARIOS / "example_identification", "--out", out,
                                   "--no-validate"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            cwd=tmp_path)
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 0 and err == "", err
    assert (out / "identified.json").is_file()


def test_python_and_numpy_warnings_are_at_most_one_line_each(capsys):
    """The command's warnings.showwarning (main installs it for the command):
    numpy's floating-point noise says nothing, another warning one line."""
    import warnings

    import numpy as np

    from orthocontact.cli.main import show_warning
    from orthocontact.output.lines import forget_warnings, warnings_said
    forget_warnings()
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        warnings.showwarning = show_warning
        np.nanmax(np.array([np.nan]))             # All-NaN slice encountered
        np.array([1.0]) / np.array([0.0])          # divide by zero encountered
        np.mean(np.array([]))                      # Mean of empty slice
        warnings.warn("a library's note\nsecond line", UserWarning, stacklevel=1)
        warnings.warn("a library's note\nsecond line", UserWarning, stacklevel=1)
    assert capsys.readouterr().err.splitlines() == [
        "orthocontact: warning: a library's note (UserWarning in test_main)"]
    assert warnings_said() == 1   # --strict counts it as it counts every warning line


def test_uq_at_a_step_that_never_settles_prints_no_warning_text(tmp_path, identified):
    # was: numpy's RuntimeWarning with its source line, twice
    p = run_cli(["uq", identified, "--scenario", SCENARIOS / "mat_aged.toml", "--samples", "2",
                 "--step-s", "0.5", "--workers", "1", "--out", tmp_path / "uq"], tmp_path)
    assert p.returncode == 0, p.stderr
    assert "Warning:" not in p.stderr and "RuntimeWarning" not in p.stderr
    assert all(ln.startswith(("orthocontact: warning: ", "uq mat_aged: ")) for ln in p.stderr.splitlines()), \
        p.stderr


@needs_root
def test_an_output_folder_that_is_a_file_system_of_its_own_is_written(tmp_path):
    # --out a mount point (a container's volume): the scratch folder beside
    # it was on another file system, and the commit's rename failed
    # ("Invalid cross-device link"), leaving .out.partial-* beside it.
    with tmpfs(tmp_path / "out", "size=5m") as out:
        p = run_cli(["identify", SCENARIOS / "example_identification", "--out", out, "--no-validate"],
                    tmp_path)
        assert p.returncode == 0, p.stderr
        assert (out / "identified.json").is_file()
        assert not [f for f in out.iterdir() if "partial" in f.name]
    assert [f.name for f in tmp_path.iterdir()] == ["out"]
