"""Hostile runs of every command of the command line: no traceback, ever.

Each case is one `orthocontact` command line, run in a subprocess as a user
runs it, with one thing made hostile: an option's value (empty, not a
number, nan, inf, negative, huge, a folder where a file goes, a missing
path, /dev/null, a binary or empty file), or one value inside an input file
(a scenario's key, an identified.json field, a cell of a data CSV).  The
commands and their options are read from the parser itself, so a new
command or option is fuzzed without anyone remembering.

A case passes when the command ends as its --help promises: exit 0, exit 1
without a traceback (a result that does not match the paper), exit 2 with
a line `orthocontact: error: ...` for each problem of its input, or 74 with
one line; it fails on a traceback, another exit status, a refusal without
its line, or a run past --timeout (killed: a hang).

  .venv/bin/python tools/cli_fuzz.py [--seed S] [--cases N] [--timeout SECONDS] [--json FILE]

prints one line per case and a summary; exit status 1 if any case failed.
It runs the installed package, or the source tree's with PYTHONPATH=$PWD/python."""
from __future__ import annotations

import argparse
import json
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENARIOS = ROOT / "scenarios"
CMD = [sys.executable, "-m", "orthocontact"]

# Values an option or a file's key may be given by mistake or by malice.
HOSTILE_TEXT = ["", " ", "nan", "inf", "-inf", "-1", "0", "1e309", "-1e-320", "abc", "1,5", "0x10",
                "\u2603", "x" * 5000, "../../..", "--out", "-"]
HOSTILE_TOML = ["-1.0", "0", "0.0", "1e308", "-1e308", "nan", "inf", '"abc"', "[]", "[1, 2]", "true",
                "{}", "99999999999999999999", "1e-320", '"\u2603"', "[nan]", "[-1e9, 1e9]", '["x"]']


@dataclass
class Case:
    """One hostile command line and what it did."""
    command: str
    what: str                 # the hostile part, in words
    argv: list
    status: int | None = None
    seconds: float = 0.0
    verdict: str = ""         # "" passed, else why it failed
    stderr_tail: str = ""


def subcommands():
    """{command: [(option or positional dest, its action)]} from the parser."""
    from orthocontact.cli.parser import build_parser
    ap = build_parser()
    sub = next(a for a in ap._actions if isinstance(a, argparse._SubParsersAction))
    return {name: [a for a in p._actions if not isinstance(a, argparse._HelpAction)]
            for name, p in sub.choices.items()}


def small_scenario(into: Path) -> Path:
    """Case 4 at 45 deg steps: a run of about a second."""
    text = (SCENARIOS / "case4.toml").read_text().replace("step_deg = 1.0", "step_deg = 45.0")
    into.write_text(text)
    return into


def short_patch(kind: str, into: Path) -> Path:
    """The bundled twist or towed block, shortened to a second or so."""
    text = (SCENARIOS / f"{kind}.toml").read_text()
    text = text.replace("angles_deg = [15.0, 39.2, 60.0, 75.0]", "angles_deg = [15.0]")
    text = text.replace("duration_s = 3.0", "duration_s = 0.3")
    text = text.replace("angle_deg = 15.0", "angle_deg = 2.0")
    into.write_text(text)
    return into


class Workspace:
    """The inputs the cases start from, made once in a temporary folder."""

    def __init__(self, root: Path, timeout: float):
        self.root = root
        self.scen = root / "scen"
        self.scen.mkdir()
        self.case4 = small_scenario(self.scen / "case4.toml")
        self.twist = short_patch("twist", root / "twist.toml")
        self.towed = short_patch("towed_block", root / "towed.toml")
        self.data = Path(shutil.copytree(SCENARIOS / "example_identification", root / "data"))
        ident = root / "identified"
        p = subprocess.run(CMD + ["identify", str(self.data), "--out", str(ident), "--no-validate"],
                           capture_output=True, text=True, timeout=timeout, cwd=root)
        if p.returncode != 0:
            raise SystemExit(f"cli_fuzz: the base identification failed:\n{p.stderr}")
        self.identified = ident / "identified.json"
        (root / "empty.toml").write_text("")
        (root / "binary.bin").write_bytes(bytes(range(256)) * 8)
        self.n = 0

    def out(self) -> str:
        self.n += 1
        return str(self.root / "out" / f"o{self.n}")

    def base(self, command: str) -> list:
        """A valid command line of `command` that runs in about a second."""
        return {
            "run": [str(self.case4), "--out", self.out()],
            "reproduce": ["--scenarios", str(self.scen), "--out", self.out()],
            "identify": [str(self.data), "--out", self.out(), "--no-validate"],
            "export": [str(self.identified), "--out", self.out(), "--angle", "40"],
            "uq": [str(self.identified), "--scenario", str(SCENARIOS / "mat_aged.toml"), "--samples", "2",
                   "--scheduler", "none", "--out", self.out()],
            "ssp": [str(self.case4), "--angle", "40", "--out", self.out() + ".ssp"],
            "sensitivity": [str(SCENARIOS / "mat_aged.toml"), "--out", self.out()],
            "design": ["--runs", "3", "--no-strip", "--out", self.out()],
        }[command]

    def paths(self) -> list:
        return [str(self.root), str(self.root / "missing" / "x"), "/dev/null", str(self.root / "empty.toml"),
                str(self.root / "binary.bin"), "/proc/self", "/"]


def option_cases(ws: Workspace, command: str, actions, rng: random.Random) -> Case:
    """The command's valid line with one option's (or positional's) value hostile."""
    argv = ws.base(command)
    takes_value = [a for a in actions if a.nargs != 0 and a.dest != "func"]
    a = rng.choice(takes_value)
    value = rng.choice(HOSTILE_TEXT + ws.paths())
    if a.option_strings:
        opt = a.option_strings[-1]
        if opt in argv:
            i = argv.index(opt)
            argv = argv[:i + 1] + [value] + argv[i + 2:]
        else:
            argv = argv + [opt, value]
        what = f"{opt} {value[:40]!r}"
    else:
        argv = [value] + argv[1:]
        what = f"{a.dest} {value[:40]!r}"
    return Case(command, what, [command] + argv)


def toml_value_case(ws: Workspace, rng: random.Random) -> Case:
    """A bundled-style scenario with one key's value hostile, run or made an SSP."""
    src = rng.choice([ws.case4, ws.twist, ws.towed])
    lines = src.read_text().splitlines()
    keyed = [i for i, line in enumerate(lines) if re.match(r"^\s*[a-z_0-9]+\s*=", line)]
    i = rng.choice(keyed)
    key = lines[i].split("=")[0].strip()
    value = rng.choice(HOSTILE_TOML)
    lines[i] = f"{key} = {value}"
    f = ws.root / f"mut{ws.n}.toml"
    f.write_text("\n".join(lines) + "\n")
    command = "ssp" if src == ws.case4 and rng.random() < 0.2 else "run"
    argv = ([str(f), "--angle", "40", "--out", ws.out() + ".ssp"] if command == "ssp"
            else [str(f), "--out", ws.out()])
    return Case(command, f"{src.name}: {key} = {value[:40]}", [command] + argv)


def identified_case(ws: Workspace, rng: random.Random) -> Case:
    """identified.json with one field hostile, given to export or uq."""
    d = json.loads(ws.identified.read_text())
    path, node = [], d
    while isinstance(node, dict) and node:
        k = rng.choice(sorted(node))
        path.append(k)
        if not isinstance(node[k], (dict,)) or rng.random() < 0.3:
            break
        node = node[k]
    value = rng.choice([None, -1.0, 0, 1e308, "x", [], {}, True, float("nan")])
    target = d
    for k in path[:-1]:
        target = target[k]
    target[path[-1]] = value
    folder = ws.root / f"ident{ws.n}"
    folder.mkdir()
    f = folder / "identified.json"
    f.write_text(json.dumps(d))
    command = rng.choice(["export", "uq"])
    argv = ws.base(command)
    argv[0] = str(f)
    return Case(command, f"identified.json: {'.'.join(path)} = {value!r}", [command] + argv)


def data_case(ws: Workspace, rng: random.Random) -> Case:
    """A copy of the reduced example set with one CSV cell or rig.toml key hostile."""
    folder = Path(shutil.copytree(ws.data, ws.root / f"data{ws.n}"))
    ws.n += 1
    files = sorted(folder.glob("*.csv")) + [folder / "rig.toml"]
    f = rng.choice(files)
    lines = f.read_text().splitlines()
    if f.suffix == ".csv":
        r = rng.randrange(1, len(lines))
        cells = lines[r].split(",")
        c = rng.randrange(len(cells))
        cells[c] = rng.choice(HOSTILE_TEXT[:13])
        lines[r] = ",".join(cells)
        what = f"{f.name} row {r} cell {c} = {cells[c]!r}"
    else:
        keyed = [i for i, line in enumerate(lines) if re.match(r"^\s*[a-z_0-9]+\s*=", line)]
        i = rng.choice(keyed)
        key = lines[i].split("=")[0].strip()
        value = rng.choice(HOSTILE_TOML)
        lines[i] = f"{key} = {value}"
        what = f"rig.toml: {key} = {value[:40]}"
    f.write_text("\n".join(lines) + "\n")
    return Case("identify", what, ["identify", str(folder), "--out", ws.out(), "--no-validate"])


def judge(case: Case, p: subprocess.CompletedProcess | None) -> None:
    if p is None:
        case.verdict = "hang: killed at the timeout"
        return
    err = p.stderr
    case.status = p.returncode
    case.stderr_tail = err[-600:]
    said = [line for line in err.splitlines() if line.startswith("orthocontact: error:")]
    if "Traceback" in err:
        case.verdict = "traceback"
    elif p.returncode not in (0, 1, 2, 74):
        case.verdict = f"exit {p.returncode}"
    elif p.returncode == 74 and len(said) != 1:
        case.verdict = f"exit 74 with {len(said)} error lines"
    elif p.returncode == 2 and not said:   # a bad file: one line for each of its problems
        case.verdict = "exit 2 with no error line"


def run_cases(seed: int, count: int, timeout: float, progress=print) -> list[Case]:
    rng = random.Random(seed)
    commands = subcommands()
    with tempfile.TemporaryDirectory(prefix="cli_fuzz-") as tmp:
        ws = Workspace(Path(tmp), timeout)
        cases = []
        for k in range(count):
            kind = rng.random()
            if k < len(commands) or kind < 0.45:   # every command first, then at random
                command = sorted(commands)[k] if k < len(commands) else rng.choice(sorted(commands))
                case = option_cases(ws, command, commands[command], rng)
            elif kind < 0.75:
                case = toml_value_case(ws, rng)
            elif kind < 0.88:
                case = identified_case(ws, rng)
            else:
                case = data_case(ws, rng)
            t0 = time.monotonic()
            try:
                p = subprocess.run(CMD + case.argv, capture_output=True, text=True, timeout=timeout,
                                   cwd=tmp, stdin=subprocess.DEVNULL)
            except subprocess.TimeoutExpired:
                p = None
            case.seconds = time.monotonic() - t0
            judge(case, p)
            cases.append(case)
            progress(f"{k + 1}/{count} {case.command}: {case.what}: exit {case.status} "
                     f"({case.seconds:.1f} s){' FAILED: ' + case.verdict if case.verdict else ''}")
    return cases


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--cases", type=int, default=100)
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds a case may take [s]")
    ap.add_argument("--json", type=Path, default=None, help="write every case as JSON here")
    a = ap.parse_args(argv)
    cases = run_cases(a.seed, a.cases, a.timeout)
    failed = [c for c in cases if c.verdict]
    by_status = {}
    for c in cases:
        by_status[c.status] = by_status.get(c.status, 0) + 1
    print(f"cli_fuzz: {len(cases)} cases (seed {a.seed}), exit statuses {by_status}, {len(failed)} failed")
    for c in failed:
        print(f"  FAILED {c.command} ({c.what}): {c.verdict}\n    {' '.join(c.argv)[:300]}\n"
              f"    {c.stderr_tail.strip()[-400:]}")
    if a.json:
        a.json.write_text(json.dumps([asdict(c) for c in cases], indent=1))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
