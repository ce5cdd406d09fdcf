"""tools/cli_fuzz.py: hostile runs of every command end as --help promises
(exit 0, 1 without a traceback, 2 with a line per problem, 74 with one
line), never in a traceback or a hang; and its judge does fail such a run."""
import subprocess
import sys

import cli_fuzz  # tools/ is on sys.path (conftest)
from paths import TOOLS


def test_hostile_runs_of_every_command_end_without_a_traceback():
    """A fixed seed and budget: 40 cases over every command the parser has."""
    p = subprocess.run([sys.executable, str(TOOLS / "cli_fuzz.py"), "--seed", "1", "--cases", "40",
                        "--timeout", "90"], capture_output=True, text=True, timeout=1800)
    summary = [line for line in p.stdout.splitlines() if line.startswith("cli_fuzz: ")]
    assert p.returncode == 0 and summary and summary[0].endswith(", 0 failed"), p.stdout[-3000:] + p.stderr
    seen = {line.split(":")[0].split(" ", 1)[1] for line in p.stdout.splitlines() if "/40 " in line}
    assert seen == set(cli_fuzz.subcommands()), seen   # every command met at least once


def completed(status, stderr):
    return subprocess.CompletedProcess([], status, "", stderr)


def test_the_judge_fails_a_traceback_a_stray_status_a_long_refusal_and_a_hang():
    verdicts = []
    for p in (completed(1, "Traceback (most recent call last):\n  ...\nValueError: x\n"),
              completed(-11, ""),
              completed(2, "orthocontact: warning: unusual\n"),
              completed(74, "orthocontact: error: one\northocontact: error: two\n"),
              None,
              completed(2, "orthocontact: error: expected a number\n"),
              completed(1, "orthocontact: warning: unusual\n")):
        case = cli_fuzz.Case("run", "x", [])
        cli_fuzz.judge(case, p)
        verdicts.append(case.verdict)
    assert verdicts == ["traceback", "exit -11", "exit 2 with no error line", "exit 74 with 2 error lines",
                        "hang: killed at the timeout", "", ""]
