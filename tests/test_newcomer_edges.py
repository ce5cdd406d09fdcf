"""The last edges a newcomer hits (issue 18), each through the real command in
a subprocess: a bad argument is one line and exit 2 before any work, --out is
never the current folder by accident, never escaped and never deletes what
the user kept, Excel's CSV UTF-8 is read, Ctrl-C on a Dask command is one
line with nothing left behind."""
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
from procs import alive, descendants

ROOT = Path(__file__).resolve().parents[1]
CMD = [sys.executable, "-m", "orthocontact"]
SCEN = ROOT / "scenarios"
DATA = SCEN / "example_identification"


def run(args, cwd, timeout=120, env=None):
    return subprocess.run(CMD + [str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=env)


def one_error_line(p, *says):
    lines = p.stderr.strip().splitlines()
    assert p.returncode == 2, p.stderr
    assert len(lines) == 1 and lines[0].startswith("orthocontact: error: "), p.stderr
    for s in says:
        assert s in lines[0], lines[0]


@pytest.fixture(scope="module")
def identified(tmp_path_factory):
    out = tmp_path_factory.mktemp("id") / "id"
    p = run(["identify", DATA, "--out", out, "--no-validate"], ROOT)
    assert p.returncode == 0, p.stderr
    return out / "identified.json"


def bad_arguments(identified):
    aged = SCEN / "mat_aged.toml"
    uq = ["uq", identified, "--scenario", aged, "--samples", "2", "--out", "o"]
    return {
        "ssp --angle nan": (["ssp", aged, "--angle", "nan", "--out", "a.ssp"], "--angle"),
        "ssp --angle inf": (["ssp", aged, "--angle", "inf", "--out", "a.ssp"], "--angle"),
        "ssp --angle -inf": (["ssp", aged, "--angle", "-inf", "--out", "a.ssp"], "--angle"),
        "ssp --angle 400": (["ssp", aged, "--angle", "400", "--out", "a.ssp"], "--angle"),
        "uq --seed -1": (uq + ["--seed", "-1"], "--seed"),
        "uq --step-s 1e-300": (uq + ["--step-s", "1e-300"], "--step-s"),
        "uq --step-s nan": (uq + ["--step-s", "nan"], "--step-s"),
        "run --workers 0": (["run", aged, "--out", "o", "--workers", "0"], "--workers"),
        "run --out ''": (["run", aged, "--out", ""], "--out"),
        "reproduce --out ''": (["reproduce", "--out", ""], "--out"),
        "identify --out ''": (["identify", DATA, "--out", ""], "--out"),
        "sensitivity --out ''": (["sensitivity", aged, "--out", ""], "--out"),
        "uq --out ''": (["uq", identified, "--scenario", aged, "--samples", "2", "--out", ""], "--out"),
        "ssp --out ''": (["ssp", aged, "--angle", "10", "--out", ""], "--out"),
        "export --out ''": (["export", identified, "--out", ""], "--out"),
        "run --out ' '": (["run", aged, "--out", " "], "--out"),
    }


CASES = list(bad_arguments(Path("x")))


@pytest.mark.parametrize("case", CASES)
def test_a_bad_argument_is_one_line_and_exit_2_before_any_work(tmp_path, identified, case):
    args, option = bad_arguments(identified)[case]
    t0 = time.monotonic()
    p = run(args, tmp_path)
    one_error_line(p, option)
    assert "Traceback" not in p.stderr
    assert sorted(os.listdir(tmp_path)) == []  # nothing written, here or anywhere under it
    assert time.monotonic() - t0 < 20  # no run started (the interpreter alone: ~1 s)


def _scenario_named(tmp_path, name) -> Path:
    folder = tmp_path / "scen"
    folder.mkdir(exist_ok=True)
    text = (SCEN / "case4.toml").read_text().replace('name = "case4"', f'name = "{name}"', 1)
    assert f'name = "{name}"' in text
    (folder / "s.toml").write_text(text)
    return folder


@pytest.mark.parametrize("name", ["../escaped", "a/b", "..", ".", "", "c:x", "a\\\\b", " lead"])
def test_a_scenario_name_that_is_not_a_plain_file_name_is_refused(tmp_path, name):
    folder = _scenario_named(tmp_path, name)
    p = run(["reproduce", "--scenarios", folder, "--out", tmp_path / "out"], tmp_path)
    one_error_line(p, "s.toml: name: expected a plain file name")
    assert sorted(os.listdir(tmp_path)) == ["scen"]


@pytest.mark.parametrize("name", ["sensitivity", "report.md", "summary.json"])
def test_a_scenario_named_like_the_reports_own_files_is_refused(tmp_path, name):
    folder = _scenario_named(tmp_path, name)
    p = run(["reproduce", "--scenarios", folder, "--out", tmp_path / "out"], tmp_path)
    one_error_line(p, "name: expected a name of its own")


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


def test_excel_csv_utf8_with_a_byte_order_mark_is_read(tmp_path):
    data = tmp_path / "data"
    shutil.copytree(DATA, data)
    for name in ("forces.csv", "angles.csv", "ramp.csv"):
        f = data / name
        f.write_bytes(b"\xef\xbb\xbf" + f.read_bytes().replace(b"\n", b"\r\n"))
    p = run(["identify", data, "--out", tmp_path / "out", "--no-validate"], tmp_path)
    assert p.returncode == 0, p.stderr
    ref = run(["identify", DATA, "--out", tmp_path / "ref", "--no-validate"], tmp_path)
    assert ref.returncode == 0, ref.stderr
    got = json.loads((tmp_path / "out" / "identified.json").read_text())
    want = json.loads((tmp_path / "ref" / "identified.json").read_text())
    # the files' digest differs (their bytes do): everything read from them does not
    assert got.pop("data")["sha256"] != want.pop("data")["sha256"]
    assert json.dumps(got).replace(str(data), "DATA") == json.dumps(want).replace(str(DATA), "DATA")


def test_an_invisible_character_in_a_header_is_shown_escaped(tmp_path):
    data = tmp_path / "data"
    shutil.copytree(DATA, data)
    f = data / "forces.csv"
    f.write_text(f.read_text(encoding="utf-8").replace("mat_angle_deg", "mat_angle_deg\u200b", 1),
                 encoding="utf-8")
    p = run(["identify", data, "--out", tmp_path / "out"], tmp_path)
    one_error_line(p, "forces.csv: line 1: expected column 'mat_angle_deg'", "mat_angle_deg\\u200b")


# -- Ctrl-C on a Dask command -------------------------------------------------------

def _busy_dashboard_port():
    """Holds 127.0.0.1:8787 if it is free (if not, someone else does)."""
    s = socket.socket()
    try:
        s.bind(("127.0.0.1", 8787))
        s.listen(1)
    except OSError:
        s.close()
        return None
    return s


@pytest.mark.parametrize("after", ["start", "progress"])
def test_ctrl_c_on_uq_is_one_line_and_leaves_nothing(tmp_path, identified, after):
    """Ctrl-C as a terminal sends it: SIGINT to the whole process group,
    Dask's worker processes included, while the cluster starts or runs."""
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    env = dict(os.environ, TMPDIR=str(tmp))
    port = _busy_dashboard_port()
    try:
        proc = subprocess.Popen(CMD + ["uq", str(identified), "--scenario", str(SCEN / "mat_aged.toml"),
                                       "--samples", "3000", "--out", "out", "--workers", "2"],
                                cwd=tmp_path, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True, start_new_session=True)
        t0 = time.monotonic()
        if after == "start":
            time.sleep(1.5)  # the interpreter is up, the cluster starting
        else:
            while time.monotonic() - t0 < 90:  # the workers are running chunks
                line = proc.stderr.readline()
                if line.startswith("uq mat_aged:") or not line:
                    break
            time.sleep(1.0)
        kids = descendants(proc.pid)
        os.killpg(proc.pid, signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    finally:
        if port is not None:
            port.close()
    assert proc.returncode == 130, err
    lines = [x for x in err.splitlines() if not x.startswith("uq mat_aged:")]
    assert lines == ["orthocontact: interrupted; nothing written to out"], err
    assert "UserWarning" not in err and "Traceback" not in err and "leaked" not in err
    assert sorted(os.listdir(tmp_path)) == ["tmp"]
    assert sorted(os.listdir(tmp)) == []  # no unpacked FMU, no dask-scratch-space
    time.sleep(0.5)
    assert [k for k in kids if alive(k)] == []


def test_a_dask_run_leaves_nothing_in_the_temp_folder(tmp_path):
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    env = dict(os.environ, TMPDIR=str(tmp))
    port = _busy_dashboard_port()
    try:
        p = run(["run", SCEN / "case4.toml", "--out", tmp_path / "out", "--scheduler", "local",
                 "--workers", "2"], tmp_path, env=env)
    finally:
        if port is not None:
            port.close()
    assert p.returncode == 0, p.stderr
    assert "Warning" not in p.stderr and "Traceback" not in p.stderr, p.stderr
    assert sorted(os.listdir(tmp)) == []
    p = run(["run", SCEN / "case4.toml", "--out", tmp_path / "out2"], tmp_path, env=env)
    assert p.returncode == 0 and sorted(os.listdir(tmp)) == []


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


def test_a_long_run_says_how_far_it_is_within_2_s_and_stops_on_ctrl_c(tmp_path):
    big = _aged_with(tmp_path, "step_s = 2.0e-4", "step_s = 1e-9")
    proc = subprocess.Popen(CMD + ["run", str(big), "--out", "out", "--yes", "--workers", "2"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    t0 = time.monotonic()
    started = None
    try:
        for line in proc.stderr:
            if ": warning: " in line:
                continue
            if started is None:
                started = time.monotonic()
            assert line.startswith("mat_aged: 0/91"), line  # no run of 2e9 steps has finished
            break
        first = time.monotonic() - t0
    finally:
        os.killpg(proc.pid, signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    assert first < 6.0  # the interpreter's start (~1-2 s) and the 2 s of the first line
    assert proc.returncode == 130 and err.strip().splitlines()[-1].startswith("orthocontact: interrupted")


def test_a_scenario_saved_with_a_byte_order_mark_is_read(tmp_path):
    sc = tmp_path / "bom.toml"
    sc.write_bytes(b"\xef\xbb\xbf" + (SCEN / "case4.toml").read_bytes())
    p = run(["run", sc, "--out", tmp_path / "out", "--workers", "1"], tmp_path)
    assert p.returncode == 0, p.stderr


def test_the_sweeps_refinement_and_recordings_say_they_are_running(tmp_path):
    """After the sweep's last run, the extremum's refinement and the recorded
    trajectories are more runs: a line within 2 s of them too."""
    sc = _aged_with(tmp_path, "step_deg = 1.0", "step_deg = 45.0")
    sc.write_text(sc.read_text().replace("step_s = 2.0e-4", "step_s = 5.0e-7"))  # seconds a run
    p = run(["run", sc, "--out", tmp_path / "out", "--workers", "2"], tmp_path, timeout=300)
    assert p.returncode == 0, p.stderr
    assert "mat_aged extremum and trajectories: " in p.stderr and "runs done" in p.stderr
