"""Uncertainty propagation (orthocontact.uq.propagate) through the FMU, serial
and on Dask: the band is the delta method's on the closed form, serial and
cluster give the same files, a worker killed mid-run, Ctrl-C."""
import json
import math
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from cli_run import CMD
from orthocontact import closed_forms as cf
from orthocontact.experiment.scenario import load
from orthocontact.uq.estimates import load_estimates
from orthocontact.uq.propagate import propagate
from paths import SCENARIOS
from procs import alive, descendants

BIN = Path(sys.executable).parent


def _small_scenario(tmp_path, start=10.0, stop=70.0, step=30.0) -> Path:
    text = (SCENARIOS / "mat_aged.toml").read_text()
    text = text.replace("start_deg = 0.0", f"start_deg = {start}").replace(
        "stop_deg = 90.0", f"stop_deg = {stop}").replace("step_deg = 1.0", f"step_deg = {step}")
    path = tmp_path / "small.toml"
    path.write_text(text)
    return path


def test_band_matches_the_delta_method_on_the_closed_form(identified, tmp_path):
    """The parameter band's half-width at each angle is 1.96 times the delta
    method's standard deviation of the closed-form steady angle (eq. 22 with
    the coupled rule), for uncertainties this small."""
    est = load_estimates(identified)
    sc = load(_small_scenario(tmp_path))
    res = propagate(est, sc, 3000, seed=3, fmu_path=None, scheduler=None, progress=False)
    v = dict(zip(est.names, est.mean))

    def phi(p, a):
        al, be = sc.geometry.axes(a)
        return math.degrees(math.atan(cf.steady_tan_phi(p[0], p[1], p[2] * p[3], p[3], al, be, "coupled")))
    p0 = [v["mu1"], v["mu2"], v["eps_ratio"], v["eps2"]]
    for k, a in enumerate(res.angles_deg):
        grad = np.zeros(4)
        for j in range(4):
            h = 1e-6 * p0[j]
            up, dn = list(p0), list(p0)
            up[j] += h
            dn[j] -= h
            grad[j] = (phi(up, a) - phi(dn, a)) / (2 * h)
        sd = math.sqrt(grad @ est.cov @ grad)
        lo, hi = np.percentile(res.phi[:, k], [2.5, 97.5])
        assert 0.5 * (hi - lo) == pytest.approx(1.959964 * sd, rel=0.1), a
        assert np.median(res.phi[:, k]) == pytest.approx(phi(p0, a), abs=0.1 * sd + 1e-3)
    assert res.step_check["max_abs_difference_deg"] < 1e-5


def _uq(identified, scenario, out, *extra, timeout=300):
    return subprocess.run(CMD + ["uq", str(identified), "--scenario", str(scenario), "--out", str(out),
                                 *extra], capture_output=True, text=True, timeout=timeout)


def _same_results(a: Path, b: Path):
    for name in ("uq_bands.csv", "samples.csv"):
        assert (a / name).read_bytes() == (b / name).read_bytes(), name
    ja, jb = (json.loads((d / "uq.json").read_text()) for d in (a, b))
    for k in ("engine", "seconds"):
        ja.pop(k), jb.pop(k)
    assert ja == jb


def test_cli_serial_and_local_cluster_give_the_same_files(identified, tmp_path):
    sc = _small_scenario(tmp_path, 0.0, 90.0, 10.0)
    p1 = _uq(identified, sc, tmp_path / "serial", "--samples", "60", "--seed", "5", "--scheduler", "none")
    assert p1.returncode == 0, p1.stderr
    p2 = _uq(identified, sc, tmp_path / "local", "--samples", "60", "--seed", "5", "--workers", "2",
             "--chunk-runs", "100")
    assert p2.returncode == 0, p2.stderr
    assert "LocalCluster, 2 worker processes" in p2.stdout
    _same_results(tmp_path / "serial", tmp_path / "local")
    d = json.loads((tmp_path / "local" / "uq.json").read_text())
    assert d["runs"] == 600 and d["samples"] == 60 and len(d["bands"]) == 10
    assert sorted(p.name for p in (tmp_path / "local").iterdir()) == [
        ".orthocontact-manifest.json", "samples.csv", "uq.json", "uq.png", "uq_bands.csv"]
    assert "100%" in p2.stderr  # the progress


def test_bad_scheduler_and_samples_are_refused_before_any_work(identified, tmp_path):
    p = _uq(identified, SCENARIOS / "mat_aged.toml", tmp_path / "o", "--samples", "10",
            "--scheduler", "127.0.0.1:1")
    assert p.returncode == 2 and "--scheduler 127.0.0.1:1: expected" in p.stderr
    p = _uq(identified, SCENARIOS / "mat_aged.toml", tmp_path / "o", "--samples", "0")
    assert p.returncode == 2 and "--samples" in p.stderr
    p = _uq(identified, SCENARIOS / "step_study.toml", tmp_path / "o", "--samples", "3")
    assert p.returncode == 2 and "expected a sweep scenario" in p.stderr
    assert not (tmp_path / "o").exists()


# -- a real Dask cluster: a scheduler and two worker processes on 127.0.0.1 --------

def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _stop(procs):
    for p in procs:
        if p.poll() is None:
            p.terminate()
    for p in procs:
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait(timeout=10)


def test_on_a_real_scheduler_with_a_worker_killed_mid_run(identified, tmp_path):
    from distributed import Client
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = dict(os.environ)
    procs = []
    try:
        procs.append(subprocess.Popen([str(BIN / "dask"), "scheduler", "--host", "127.0.0.1", "--port",
                                       str(port), "--no-dashboard"], stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL, env=env))
        workers = []
        for k in range(2):
            # Each worker its own temporary folder: the FMU must reach it as
            # bytes, not as a path into ours.
            wenv = dict(env, TMPDIR=str(tmp_path / f"w{k}"))
            (tmp_path / f"w{k}").mkdir()
            w = subprocess.Popen([str(BIN / "dask"), "worker", address, "--nthreads", "1", "--no-nanny",
                                  "--no-dashboard", "--host", "127.0.0.1", "--name", f"w{k}"],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=wenv,
                                 cwd=tmp_path / f"w{k}")
            procs.append(w)
            workers.append(w)
        with Client(address, timeout=30) as c:
            c.wait_for_workers(2, timeout=60)

        sc = SCENARIOS / "mat_aged.toml"
        args = ["--samples", "160", "--seed", "11", "--chunk-runs", "273"]  # 54 chunks of 3 sets
        run = subprocess.Popen(CMD + ["uq", str(identified), "--scenario", str(sc), "--out",
                                      str(tmp_path / "cluster"), "--scheduler", address, *args],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        killed_while_running = False
        for line in run.stderr:
            if line.startswith("uq mat_aged:") and int(line.split("(")[1].split("%")[0]) >= 20:
                killed_while_running = run.poll() is None and "(100%" not in line
                workers[0].send_signal(signal.SIGKILL)
                break
        assert killed_while_running, "the run ended before the worker could be killed"
        out, err = run.communicate(timeout=300)
        assert run.returncode == 0, err
        assert workers[0].wait(timeout=10) == -signal.SIGKILL
        assert f"Dask cluster at {address}" in out
        # The killed worker had unpacked the FMU into its own temporary folder
        # (its process's orthocontact-* folder, which a SIGKILL leaves for the
        # next command to remove); the FMU reached it as bytes.
        w0 = tmp_path / "w0"
        assert list(w0.glob("orthocontact-*/fmu-*/binaries")), [str(p) for p in w0.rglob("*")][:20]
        # the archive itself (fmu-<digest>-<pid>-*/<name>.fmu): removed at once
        assert not list(w0.glob("orthocontact-*/fmu-*/*.fmu"))
    finally:
        _stop(procs)
    # The other worker, if it stopped on SIGTERM within _stop's 20 s (on a busy
    # machine it may not, and is killed), leaves nothing of ours in its
    # temporary folder (dask-scratch-space is the user's `dask worker`'s own).
    if workers[1].returncode != -signal.SIGKILL:
        assert [x for x in os.listdir(tmp_path / "w1") if x != "dask-scratch-space"] == []
    p = _uq(identified, sc, tmp_path / "serial", *args, "--scheduler", "none")
    assert p.returncode == 0, p.stderr
    _same_results(tmp_path / "serial", tmp_path / "cluster")


def test_ctrl_c_stops_the_local_cluster_and_writes_nothing(identified, tmp_path):
    run = subprocess.Popen(CMD + ["uq", str(identified), "--scenario", str(SCENARIOS / "mat_aged.toml"),
                                  "--samples", "3000", "--out", str(tmp_path / "o")],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    for line in run.stderr:
        if line.startswith("uq mat_aged:") and "(0%" not in line:
            break
    kids = descendants(run.pid)
    assert kids, "the cluster's processes were not found"
    run.send_signal(signal.SIGINT)
    out, err = run.communicate(timeout=60)
    assert run.returncode == 130, err
    assert err.strip().splitlines()[-1] == f"orthocontact: interrupted; nothing written to {tmp_path / 'o'}"
    assert not (tmp_path / "o").exists() and list(tmp_path.iterdir()) == []
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and [k for k in kids if alive(k)]:
        time.sleep(0.2)
    assert [k for k in kids if alive(k)] == []


def test_a_step_too_long_to_fit_is_named_and_no_nan_is_printed(identified, tmp_path):
    """uq --step-s 0.5 on the 0.5 m dynamic rig: 3 steps in the fitted path,
    one of 0.122 m against a settling length of 0.022 m.  It warned "differ
    by up to nan deg" with numpy's RuntimeWarning and told a travel the rig
    has; the remedy is the step."""
    sc = _small_scenario(tmp_path, 10.0, 70.0, 30.0)
    p = _uq(identified, sc, tmp_path / "o", "--samples", "5", "--scheduler", "none", "--step-s", "0.5")
    assert p.returncode == 0, p.stderr
    assert "nan" not in p.stderr and "RuntimeWarning" not in p.stderr
    lines = [x for x in p.stderr.splitlines() if x.startswith("orthocontact: warning:")]
    runs = next(x for x in lines if "not steady sliding" in x)
    assert "3 have too few steps in a half of the fitted path to fit an angle" in runs
    assert "remedy: --step-s <= 0.012 s (the step 0.5 s leaves 3 steps in the fitted path" in runs
    assert "rig.travel_m" not in runs
    d = json.loads((tmp_path / "o" / "uq.json").read_text())
    assert d["step_check"]["not_fitted"] == {"uq_step": 0, "scenario_step": 0}
    assert d["step_check"]["max_abs_difference_deg"] > 1.0


def test_the_step_check_says_what_failed_instead_of_nan():
    from orthocontact.uq.propagate import step_check, step_warning
    nan = float("nan")
    chk = step_check(2e-4, 1.5, [nan, nan], [-10.5, -11.0])
    assert chk["max_abs_difference_deg"] is None and chk["not_fitted"] == {"uq_step": 2, "scenario_step": 0}
    assert step_warning(chk) == ("at the estimates, at the uq step 1.5 s, 2 of 2 runs gave no angle (too "
                                 "few steps in the fitted path to fit one); choose --step-s")
    chk = step_check(2e-4, 4e-3, [-10.5, nan], [-10.52, -11.0])
    assert chk["max_abs_difference_deg"] == pytest.approx(0.02)
    assert "1 of 2 runs gave no angle" in step_warning(chk) and "by 0.02 deg" in step_warning(chk)
    assert step_warning(step_check(2e-4, 4e-3, [-10.5], [-10.5])) is None
