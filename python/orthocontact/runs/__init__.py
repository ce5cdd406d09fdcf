"""Many rig runs: the executor (serial, a local pool, Dask) and the master
(C, fmpy) of a batch (executors), batches (batch), progress on stderr
(progress), sweeps and step studies of a scenario (sweep), and Dask (cluster)."""
from .batch import run_many
from .cluster import DaskRunner, check_address, run_grid
from .progress import Heartbeat, Progress, status_lines
from .size import Work, check_scenario_size, check_uq_size, check_work, scenario_work, steps_per_run
from .sweep import StepStudyResult, SweepResult, closed_form_phi_deg_array, run_step_study, run_sweep

__all__ = ["run_many", "DaskRunner", "check_address", "run_grid", "Heartbeat", "Progress", "status_lines",
           "Work", "check_scenario_size", "check_uq_size", "check_work", "scenario_work", "steps_per_run",
           "StepStudyResult", "SweepResult", "closed_form_phi_deg_array", "run_step_study", "run_sweep"]
