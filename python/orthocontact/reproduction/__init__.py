"""The paper reproduced: each scenario's tables and figures
(scenario_outputs), the report against the paper's numbers (paper_report),
and the rig's unmeasured assumptions (sensitivity)."""
