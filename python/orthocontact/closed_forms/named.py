"""The table of closed forms a scenario can name (geometry.closed_form): each
name with its description, the law and axes it holds for, and its scalar and
array forms.  A form joins the table where it is written, with `named` (see
closed_forms.paper); the scenario schema, the sweep and the report read the
table, so adding a form touches its module and its test only.

A form is f(law, alpha, beta) -> tan(phi) of steady sliding, law anything
with the attributes mu1, mu2, eps1, eps2 and rule (a ContactParams), alpha
and beta the axes' angles [rad]: numbers for the scalar form, arrays of
equal shape for the array form."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np


@dataclass(frozen=True)
class NamedForm:
    """One row of the table.  scalar(law, alpha, beta) -> tan(phi) for
    numbers, array(law, alpha, beta) the same for arrays of angles [rad];
    refusal(law, beta_minus_alpha_deg) -> why the form does not hold for
    the law and axes (one phrase), or None where it holds."""
    name: str
    description: str
    scalar: Callable
    array: Callable
    refusal: Callable

    def phi_deg(self, law, alpha: float, beta: float) -> float:
        """The steady trajectory angle [deg] at one pair of axes [rad]."""
        return math.degrees(math.atan(self.scalar(law, alpha, beta)))

    def phi_deg_array(self, law, alpha, beta) -> np.ndarray:
        """The steady trajectory angles [deg] at arrays of axes [rad]."""
        return np.degrees(np.arctan(self.array(law, alpha, beta)))


FORMS: dict[str, NamedForm] = {}


def holds_always(law, beta_minus_alpha_deg: float) -> None:
    """The refusal of a form that holds for any law and axes: none."""
    return None


def named(name: str, description: str, refusal: Callable = holds_always, array: Callable | None = None):
    """Decorator: puts the form f(law, alpha, beta) into FORMS under `name`.
    f serves numbers and arrays alike unless a separate `array` form is
    given.  A name given twice is an error (two forms would answer to it)."""
    def register(f):
        if name in FORMS:
            raise ValueError(f"closed form {name!r} is named twice")
        FORMS[name] = NamedForm(name, description, f, array or f, refusal)
        return f
    return register
