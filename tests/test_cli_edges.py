"""The edges a newcomer meets first, through the real command in a
subprocess: bad output paths and options refused before any work, interrupts
that stop every worker and leave nothing behind, --version, python -m."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from procs import alive, children

from orthocontact.cli.parser import build_parser

ROOT = Path(__file__).resolve().parents[1]
CMD = [sys.executable, "-m", "orthocontact"]
SCEN = str(ROOT / "scenarios" / "case4.toml")


def run(args, cwd, timeout=120):
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
    p, seconds = run(["reproduce", "--out", out], tmp_path)
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and f"--out {out}" in lines[0] and says in lines[0], p.stderr
    assert "partial" not in p.stderr and "Traceback" not in p.stderr
    assert leftovers(tmp_path) == before and (tmp_path / "afile").read_text() == "keep me"
    assert seconds < 10  # no sweep ran (measured: ~0.3 s, the interpreter's start)


@pytest.mark.parametrize("value", ["0", "-3", "two"])
def test_bad_workers_names_the_option(tmp_path, value):
    p, _ = run(["run", SCEN, "--out", "o", "--workers", value], tmp_path)
    assert p.returncode == 2 and "argument --workers" in p.stderr and "worker processes >= 1" in p.stderr
    assert leftovers(tmp_path) == []


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_signal_to_the_main_process_stops_everything_and_writes_nothing(tmp_path, sig):
    """As an IDE's stop button or a job runner does: the signal goes to the
    main process only, while its workers are busy."""
    proc = subprocess.Popen(CMD + ["reproduce", "--out", "results", "--workers", "2"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    kids = []
    t0 = time.monotonic()
    while time.monotonic() - t0 < 60:  # wait until the sweep's workers are running
        kids = [k for k in children(proc.pid)]
        if len(kids) >= 2:
            break
        time.sleep(0.1)
    assert len(kids) >= 2, "the sweep's workers did not start"
    time.sleep(0.5)
    os.kill(proc.pid, sig)
    t_sig = time.monotonic()
    out, err = proc.communicate(timeout=60)
    stopped_after = time.monotonic() - t_sig
    assert proc.returncode == 130, err
    assert "Traceback" not in err
    assert err.strip().splitlines()[-1] == "orthocontact: interrupted; nothing written to results"
    assert stopped_after < 10
    assert leftovers(tmp_path) == []  # no results/, no .results.partial-*
    time.sleep(0.2)
    assert [k for k in kids if alive(k)] == []


def test_version_names_the_package_and_both_fmus(tmp_path):
    from orthocontact import __version__
    p, _ = run(["--version"], tmp_path)
    assert p.returncode == 0
    assert p.stdout.splitlines()[0] == f"orthocontact {__version__}"
    assert "FMI 2.0 FMU:" in p.stdout and "FMI 3.0 FMU:" in p.stdout and "not found" not in p.stdout


def test_every_command_and_argument_has_help():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    assert set(sub.choices) == {"run", "reproduce", "identify", "ssp", "uq", "sensitivity", "export"}
    for name, p in sub.choices.items():
        for action in p._actions:
            assert action.help, f"{name}: {action.option_strings or action.dest} has no help"
    for action in parser._actions:
        assert action.help or action.dest == "cmd"
    texts = {name: p.format_help() for name, p in sub.choices.items()}
    assert all("degrees" in texts[n] for n in ("run", "identify"))  # units are said
    assert "N/m" in texts["identify"] and "[m]" in texts["identify"] or "x1_m" in texts["identify"]


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")  # the swallowing, expected
def test_an_interrupt_swallowed_by_a_finalizer_still_stops_and_writes_nothing(tmp_path):
    """Python reports a KeyboardInterrupt raised inside __del__ as "Exception
    ignored" and runs on (this happened to the CLI, in ContactFMU.__del__);
    the run must still end as interrupted, with nothing committed."""
    from orthocontact.cli import interrupts, output

    class SignalledDuringFinalization:
        def __del__(self):
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.05)  # the handler runs here, inside __del__

    old = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    try:
        interrupts.install_signal_handlers()
        with pytest.raises(KeyboardInterrupt):
            with output.staged_output(tmp_path / "results") as stage:
                (stage / "summary.json").write_text("{}")
                SignalledDuringFinalization()  # dropped at once: __del__ runs
                # reaching here means the interrupt was swallowed
    finally:
        signal.signal(signal.SIGINT, old[0])
        signal.signal(signal.SIGTERM, old[1])
        interrupts.install_signal_handlers()  # forgets the interrupt
        signal.signal(signal.SIGINT, old[0])
        signal.signal(signal.SIGTERM, old[1])
    assert leftovers(tmp_path) == []
