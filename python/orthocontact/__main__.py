"""`python -m orthocontact`: the same as the `orthocontact` command."""
from .cli import entry

entry()
