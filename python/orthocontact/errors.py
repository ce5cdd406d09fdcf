"""Errors that reach the user as one line (the CLI prints them and exits 2).
Kept apart so that every layer can raise them without importing the CLI.

The one hierarchy of the user's input errors: InputError, and under it
experiment.scenario.ScenarioError (a scenario file) and
fmu.start_values.StartValueError (a start value the FMU would refuse).
Failures that are not the user's input (an FMU call, a solver) are not
InputErrors: they keep their traceback."""


class InputError(Exception):
    """Bad user input (a data file, an argument, an output path): str(e) is the
    one-line message, naming the file or option and what was expected."""
