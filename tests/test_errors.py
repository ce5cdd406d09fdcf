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


def test_an_input_error_from_any_layer_is_one_line_and_exit_2(tmp_path, capsys, monkeypatch):
    def refuse(args):
        raise InputError("somewhere deep: expected something else")
    args = cli_main.build_parser().parse_args(["run", "x.toml", "--out", str(tmp_path / "o")])
    monkeypatch.setattr(cli_main, "build_parser", lambda: _Fixed(args, refuse))
    assert cli_main.main([]) == 2
    err = capsys.readouterr().err
    assert err == "orthocontact: error: somewhere deep: expected something else\n"
    assert not (tmp_path / "o").exists()


class _Fixed:
    """A parser that gives `args` with its command replaced by `func`."""

    def __init__(self, args, func):
        self.args, self.func = args, func

    def parse_args(self, argv):
        self.args.func = self.func
        return self.args
