"""The command line as the tests run it: `python -m orthocontact` in a
subprocess, as a user does, with its output captured."""
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

from paths import SCENARIOS

CMD = [sys.executable, "-m", "orthocontact"]

# The aged mat's law (scenarios/mat_aged.toml) as a scenario's [law] table,
# and the smallest sweep on it: the tests' own scenario files start from these.
AGED_LAW = """[law]
mu1 = 0.408
mu2 = 0.625
eps2 = 1.0e4
eps_ratio = 1.251
"""
MAT_SWEEP = 'name = "m"\nkind = "sweep"\n' + AGED_LAW + "[sweep]\nstep_deg = 45.0\n"

# PYTHONPATH=python (the source tree shadowing the installed package) must
# hold in a command started in another folder (cwd=tmp_path) too.
if os.environ.get("PYTHONPATH"):
    os.environ["PYTHONPATH"] = os.pathsep.join(str(Path(p).resolve()) for p in
                                               os.environ["PYTHONPATH"].split(os.pathsep) if p)


def run_cli(args, cwd, timeout=120, env=None):
    """The finished command (CompletedProcess, text) of `orthocontact ARGS`."""
    return subprocess.run(CMD + [str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=env)


def busy_dashboard_port():
    """Holds 127.0.0.1:8787 (Dask's dashboard port) if it is free (if not,
    someone else does); None then."""
    s = socket.socket()
    try:
        s.bind(("127.0.0.1", 8787))
        s.listen(1)
    except OSError:
        s.close()
        return None
    return s


def timed_run(args, cwd, timeout=120):
    """(run_cli's result, its wall time [s])."""
    t0 = time.monotonic()
    p = run_cli(args, cwd, timeout=timeout)
    return p, time.monotonic() - t0


def one_error_line(p, *says):
    """The command refused its input as the CLI promises: exit 2 and one
    line `orthocontact: error: ...` on stderr, containing each of `says`."""
    lines = p.stderr.strip().splitlines()
    assert p.returncode == 2, p.stderr
    assert len(lines) == 1 and lines[0].startswith("orthocontact: error: "), p.stderr
    for s in says:
        assert s in lines[0], lines[0]


def error_lines(p, *says):
    """The command refused its input with one line per problem: exit 2 and
    each line of stderr `orthocontact: error: ...`.  With `says` given, one
    line each, in order, the i-th containing says[i].  The lines, without
    the prefix."""
    lines = p.stderr.strip().splitlines()
    assert p.returncode == 2, p.stderr
    assert lines and all(line.startswith("orthocontact: error: ") for line in lines), p.stderr
    if says:
        assert len(lines) == len(says), p.stderr
        for line, s in zip(lines, says):
            assert s in line, (s, line)
    return [line[len("orthocontact: error: "):] for line in lines]


def leftovers(folder: Path):
    """The names in `folder`, sorted."""
    return sorted(p.name for p in folder.iterdir())


def scenario_variant(path: Path, old: str, new: str, into: Path) -> Path:
    """The scenario file `path` with its text `old` (which must be there)
    replaced by `new`, written as `into`."""
    text = path.read_text()
    assert old in text, (path, old)
    into.write_text(text.replace(old, new, 1))
    return into


def case4_named(tmp_path: Path, name: str) -> Path:
    """A folder holding Case 4's scenario under the name `name` (s.toml)."""
    folder = tmp_path / "scen"
    folder.mkdir(exist_ok=True)
    scenario_variant(SCENARIOS / "case4.toml", 'name = "case4"', f'name = "{name}"', folder / "s.toml")
    return folder
