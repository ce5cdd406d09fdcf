"""The cells of an FMI 2.0 run, which has no arrays: taken from the same run
on the installed FMI 3.0 FMU of its model, and only if that run gives the
FMI 2.0 run's record bit for bit (the two builds compute the same bits).
What the twist, the push and the rolling pad do when their FMU is FMI 2.0."""
from __future__ import annotations

from collections.abc import Callable

from ..fmu import find_fmu


def fmi3_twin(model: str, run: Callable, same: Callable, what: str, compared: str = " at every step",
              differs: str | None = None) -> tuple:
    """(run(the installed FMI 3.0 FMU's path), where it comes from) if
    same(that result) holds, else (None, why not): no FMI 3.0 FMU of `model`
    is installed, or its run is not this one.  `what` names the run
    ("push"), `compared` says where same() compares (" at every step"),
    `differs` what differed (default `what`)."""
    try:
        twin = find_fmu(fmi_version=3, model=model)
    except FileNotFoundError as e:
        return None, f"FMI 2.0 has no arrays, and no FMI 3.0 {model} FMU is installed ({e})"
    again = run(twin)
    if not same(again):
        return None, (f"FMI 2.0 has no arrays, and the installed FMI 3.0 FMU ({twin}) does not give this "
                      f"FMU's {differs or what} bit for bit: its cells would not be this run's")
    return again, (f"the same {what} on the installed FMI 3.0 {model} FMU, equal to this run{compared} "
                   "(FMI 2.0 has no arrays)")
