"""The command line as the tests run it: `python -m orthocontact` in a
subprocess, as a user does, with its output captured."""
import socket
import subprocess
import sys

CMD = [sys.executable, "-m", "orthocontact"]


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
