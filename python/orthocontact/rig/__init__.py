"""The carriage/block rig of the paper's experiment: the Python harness on
fmpy (harness, the reference the C rig is pinned to), the compiled master
(compiled: the rig loop in C), and every run's self-check (checks)."""
from .checks import (
    SETTLE_TOL_DEG,
    STEADY_TOL_DEG,
    RunChecks,
    angle_list,
    check_runs,
    remedy,
    system_settling_warning,
    warning_line,
)
from .compiled import CMaster
from .harness import MODES, Rig, RigResult, RunFigures, run
from .planar import steady_yaw
from .pushed import fit_steps_problem

__all__ = ["MODES", "Rig", "RigResult", "RunFigures", "run", "SETTLE_TOL_DEG", "STEADY_TOL_DEG", "RunChecks",
           "angle_list", "check_runs", "remedy", "system_settling_warning", "warning_line", "CMaster",
           "fit_steps_problem", "steady_yaw"]
