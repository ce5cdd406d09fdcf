"""The paper reproduced: each scenario's tables and figures
(scenario_outputs), the report against the paper's numbers (paper_report),
and the rig's unmeasured assumptions (sensitivity)."""
from .kinds import in_report_order, run_scenario
from .paper_report import calibration_rows, paper_rows, reproduction_report

__all__ = ["in_report_order", "run_scenario", "calibration_rows", "paper_rows", "reproduction_report"]
