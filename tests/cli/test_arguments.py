"""The command line's arguments as they are read (orthocontact.cli.arguments):
each type refuses a bad value in one line, `expected ..., got ...`; a
parser's error is one line naming the command; --version names the
package's version and every installed FMU's."""
import argparse

import pytest

from orthocontact.cli import arguments as a
from orthocontact.version import __version__


@pytest.mark.parametrize(("parse", "text", "says"), [
    (a.positive_int("worker processes"), "0", "expected a whole number of worker processes >= 1, got 0"),
    (a.positive_int("runs"), "two", "expected a whole number of runs >= 1, got 'two'"),
    (a.positive_float, "1e400", "expected a finite number > 0, got 1e400"),
    (a.positive_float, "-1", "expected a finite number > 0, got -1"),
    (a.count, "-1", "expected a whole number >= 0, got -1"),
    (a.seed, "1.5", "expected a whole number >= 0, got '1.5'"),
    (a.angle_deg, "nan", "expected a finite angle in [-360, 360] degrees, got nan"),
    (a.angle_deg, "400", "expected a finite angle in [-360, 360] degrees, got 400"),
    (a.out_path, " ", "expected a path, got an empty one (an unset shell variable?)"),
])
def test_a_bad_value_is_one_line_saying_what_was_expected(parse, text, says):
    with pytest.raises(argparse.ArgumentTypeError) as e:
        parse(text)
    assert str(e.value).startswith(says) and "\n" not in str(e.value)


def test_a_good_value_is_read_as_its_type():
    assert a.positive_int("runs")("3") == 3 and a.count("0") == 0 and a.seed("7") == 7
    assert a.positive_float("0.5") == 0.5 and a.angle_deg("-360") == -360.0
    assert str(a.out_path("results")) == "results"


def test_a_parsers_error_is_one_line_naming_the_command_and_exit_2(capsys):
    p = a.Parser(prog="orthocontact run")
    p.add_argument("--runs", type=a.positive_int("runs"))
    with pytest.raises(SystemExit) as e:
        p.parse_args(["--runs", "0"])
    err = capsys.readouterr().err
    assert e.value.code == 2 and err.count("\n") == 1
    assert err.startswith("orthocontact: error: orthocontact run: argument --runs: expected a whole number")
    assert err.endswith("(see orthocontact run --help)\n")


def test_the_version_names_the_package_and_each_installed_fmu():
    lines = a.version_text().splitlines()
    assert lines[0] == f"orthocontact {__version__}"
    assert lines[1:] and all(line.startswith("  FMI ") for line in lines[1:])
