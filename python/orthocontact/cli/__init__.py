"""The `orthocontact` command: argument parsing (parser), the commands
(commands), output folders and warnings (output), interrupts (interrupts),
and main/entry (main)."""
from .main import entry, main

__all__ = ["main", "entry"]
