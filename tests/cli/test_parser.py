"""The command line (orthocontact.cli.parser): every option has help and
units, a bad argument is one line and exit 2 before any work."""
import os
import time
from pathlib import Path

import pytest

from cli_run import leftovers, one_error_line, timed_run
from cli_run import run_cli as run
from orthocontact.cli.parser import build_parser
from paths import SCENARIOS

CASE4 = str(SCENARIOS / "case4.toml")
DATA = SCENARIOS / "example_identification"


@pytest.mark.parametrize("value", ["0", "-3", "two"])
def test_bad_workers_names_the_option(tmp_path, value):
    p, _ = timed_run(["run", CASE4, "--out", "o", "--workers", value], tmp_path)
    assert p.returncode == 2 and "argument --workers" in p.stderr and "worker processes >= 1" in p.stderr
    assert leftovers(tmp_path) == []


def test_every_command_and_argument_has_help():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    assert set(sub.choices) == {"run", "reproduce", "identify", "ssp", "uq", "sensitivity", "export",
                                 "design"}
    for name, p in sub.choices.items():
        for action in p._actions:
            assert action.help, f"{name}: {action.option_strings or action.dest} has no help"
    for action in parser._actions:
        assert action.help or action.dest == "cmd"
    texts = {name: p.format_help() for name, p in sub.choices.items()}
    assert all("degrees" in texts[n] for n in ("run", "identify"))  # units are said
    assert "N/m" in texts["identify"] and "[m]" in texts["identify"] or "x1_m" in texts["identify"]


def bad_arguments(identified):
    aged = SCENARIOS / "mat_aged.toml"
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
