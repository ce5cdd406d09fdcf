"""InputError (orthocontact.errors): raised by any layer, it reaches the user
as one line and exit status 2, whatever the layer, without a traceback."""
import importlib

import pytest

from orthocontact.errors import InputError
from orthocontact.identification.identified_file import read_identified

cli_main = importlib.import_module("orthocontact.cli.main")   # the package's `main` is the function


def test_an_input_error_is_an_exception_whose_text_is_the_message():
    e = InputError("data/forces.csv: line 3: expected a number, got 'x'")
    assert isinstance(e, Exception) and not isinstance(e, (ValueError, OSError))
    assert str(e) == "data/forces.csv: line 3: expected a number, got 'x'"
    with pytest.raises(InputError, match="nowhere.json: not found"):
        read_identified("nowhere.json")   # a layer below the CLI raises it


def test_the_users_input_errors_are_one_hierarchy():
    """A scenario file's error and a start value the FMU would refuse are
    InputErrors (the CLI catches InputError alone); a failure of an FMU call
    or of a solver is not the user's input and is not one."""
    from orthocontact.experiment.scenario import ScenarioError
    from orthocontact.fmu.contact import FMUError
    from orthocontact.fmu.start_values import StartValueError
    from orthocontact.rig.harness import LateralSolveError
    assert issubclass(ScenarioError, InputError) and issubclass(StartValueError, InputError)
    assert str(ScenarioError("s.toml", "law.mu1", "a number > 0", -1)) == \
        "s.toml: law.mu1: expected a number > 0, got -1"
    assert issubclass(StartValueError, ValueError)   # its callers' `except ValueError` still hold
    assert not issubclass(FMUError, InputError) and not issubclass(LateralSolveError, InputError)


def test_an_input_error_from_any_layer_is_one_line_and_exit_2(tmp_path, capsys, monkeypatch):
    def refuse(args):
        raise InputError("somewhere deep: expected something else")
    args = cli_main.build_parser().parse_args(["run", "x.toml", "--out", str(tmp_path / "o")])
    monkeypatch.setattr(cli_main, "build_parser", lambda: _Fixed(args, refuse))
    assert cli_main.main([]) == 2
    err = capsys.readouterr().err
    assert err == "orthocontact: error: somewhere deep: expected something else\n"
    assert not (tmp_path / "o").exists()


def test_every_problem_of_an_input_error_is_a_line_of_its_own(tmp_path, capsys, monkeypatch):
    """A reader that found several problems (errors.Problems) raises one
    InputError of them: the CLI prints each as its own `orthocontact: error:`
    line, exit 2."""
    from orthocontact.errors import Problems

    def refuse(args):
        problems = Problems()
        problems.add("f.toml: a: expected 1, got 2")
        problems.add("f.toml: b: expected 3, got 4")
        problems.raise_any()
    args = cli_main.build_parser().parse_args(["run", "x.toml", "--out", str(tmp_path / "o")])
    monkeypatch.setattr(cli_main, "build_parser", lambda: _Fixed(args, refuse))
    assert cli_main.main([]) == 2
    assert capsys.readouterr().err == ("orthocontact: error: f.toml: a: expected 1, got 2\n"
                                       "orthocontact: error: f.toml: b: expected 3, got 4\n")
    Problems().raise_any()   # none: nothing raised


class _Fixed:
    """A parser that gives `args` with its command replaced by `func`."""

    def __init__(self, args, func):
        self.args, self.func = args, func

    def parse_args(self, argv):
        self.args.func = self.func
        return self.args
