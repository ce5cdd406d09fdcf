"""The carriage/block rig of the paper's experiment: the Python harness on
fmpy (harness, the reference the C rig is pinned to), the compiled master
(compiled: the rig loop in C), and every run's self-check (checks)."""
from .harness import MODES, Rig, RigResult, RunFigures, run

__all__ = ["MODES", "Rig", "RigResult", "RunFigures", "run"]
