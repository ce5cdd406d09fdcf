"""The law's parameters as the FMU takes them (ContactParams: angles in rad,
stiffness in N/m) and the sliding rules' numbers (RULES).

ContactParams is source generated from the contact's variable table
(fmu/generated.py, written by tools/make_generated.py: `make generated`):
its fields, their order, types and defaults, its docstring with units and
ranges, the angles' degrees.  Its checks are code that reads the table's
rows as data (fmu/param_checks.py).  Fields up to the first angle are
required; an angle defaults to 0 (its axis along X1), a later parameter to
the table's start."""
from __future__ import annotations

from .generated import LAW, RULES, ContactParams

__all__ = ["ANGLE_LIMIT_RAD", "LAW", "RULES", "ContactParams"]

# The FMU's range of the axis angles [rad] (the table's, the same for every angle).
ANGLE_LIMIT_RAD = max(abs(row.max) for row in LAW if row.is_angle and row.max is not None)
