"""The `orthocontact` command (orthocontact.cli.main, python -m orthocontact):
--version, and an error is one line with exit 2."""
import subprocess
import sys
import time
CMD = [sys.executable, "-m", "orthocontact"]


def run(args, cwd, timeout=120):
    t0 = time.monotonic()
    p = subprocess.run(CMD + args, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    return p, time.monotonic() - t0


def test_version_names_the_package_and_both_fmus(tmp_path):
    from orthocontact import __version__
    p, _ = run(["--version"], tmp_path)
    assert p.returncode == 0
    assert p.stdout.splitlines()[0] == f"orthocontact {__version__}"
    assert "FMI 2.0 FMU:" in p.stdout and "FMI 3.0 FMU:" in p.stdout and "not found" not in p.stdout
