"""`python -m orthocontact`: the same as the `orthocontact` command."""
import sys

from .cli import main

sys.exit(main())
