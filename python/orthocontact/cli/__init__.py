"""The `orthocontact` command: argument parsing (parser), the commands
(commands), and main/entry (main); its output folder and warning lines are
output's (folder, lines), its interrupts runtime's (interrupts)."""
from .main import entry, main

__all__ = ["main", "entry"]
