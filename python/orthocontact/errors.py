"""Errors that reach the user as one line each (the CLI prints them and
exits 2).  Kept apart so that every layer can raise them without importing
the CLI.

The one hierarchy of the user's input errors: InputError, and under it
experiment.scenario.ScenarioError (a scenario file) and
fmu.start_values.StartValueError (a start value the FMU would refuse).
Failures that are not the user's input (an FMU call, a solver) are not
InputErrors: they keep their traceback.

A file's readers collect every problem they find (Problems) and raise one
InputError naming them all, one line each, so that a file with three
mistakes needs one run, not three."""
from __future__ import annotations


class InputError(Exception):
    """Bad user input (a data file, an argument, an output path): str(e) is
    the message, one line per problem (most often one), each naming the file
    or option and what was expected; the CLI prints each line as
    `orthocontact: error: LINE`."""

    @property
    def lines(self) -> list[str]:
        """The message's problems, one line each."""
        return str(self).splitlines()


class Problems:
    """The problems found in one input, in the order found: add() each (one
    line naming the file and key), then raise_any() raises one `error`
    (an InputError class) of all of them.  A reader stops early only where a
    problem leaves the rest without meaning (a file that is not TOML, an
    unknown scenario kind): raise_any() then, with what it has."""

    def __init__(self, error: type[InputError] = InputError):
        self.error = error
        self.lines: list[str] = []

    def add(self, line: str) -> None:
        self.lines.append(line)

    def extend(self, e: InputError) -> None:
        """Every problem of an InputError raised by a reader this one calls."""
        self.lines.extend(e.lines)

    def __bool__(self) -> bool:
        return bool(self.lines)

    def raise_any(self) -> None:
        """Raises error(every line, one a line) if any problem was added."""
        if self.lines:
            raise self.error("\n".join(self.lines))
