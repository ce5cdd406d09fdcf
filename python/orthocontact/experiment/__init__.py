"""The experiment described: scenario files (scenario), a lab's rig.toml
(rig_setup), and the experiment at one angle as an SSP package (ssp)."""
from .kinds import (
    KINDS,
    ReportPart,
    RunOptions,
    Section,
    fmu_for,
    kind_of,
    part,
    register,
    require_mat_angles,
    roll_steps,
)
from .rig_setup import RigSetup, load_rig_toml, write_rig_toml
from .scenario import SCHEMA, Scenario, ScenarioError
from .scenario import load as load_scenario
from .ssp import parameter_values_file, write_ssp

__all__ = ["load_scenario", "Scenario", "ScenarioError", "SCHEMA", "KINDS", "ReportPart", "RunOptions",
           "Section", "fmu_for", "kind_of", "part", "register", "require_mat_angles", "roll_steps",
           "RigSetup", "load_rig_toml", "write_rig_toml", "parameter_values_file", "write_ssp"]
