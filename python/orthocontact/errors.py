"""Errors that reach the user as one line (the CLI prints them and exits 2).
Kept apart so that every layer can raise them without importing the CLI."""



class InputError(Exception):
    """Bad user input (a data file, an argument, an output path): str(e) is the
    one-line message, naming the file or option and what was expected."""
