"""Parameter identification with casadi, split by job: the data and their
files (measurements), the strip in the fit's model (strip_model), the
paper's formulas and the joint fit (estimators), statistics (statistics),
the job (job) and its figure and Markdown (report)."""
from .design_inputs import noise_of, paper_prior, prior_from_identified, read_plan
from .design_search import stderr_say
from .estimators import eq1, max_rule
from .export import export as export_calibration
from .export import load_calibration, plausible_calibration, rig_scenario
from .identified import IdentifiedFile
from .identified_file import read_identified
from .job import identify
from .measurements import MeasurementSet, load_data

__all__ = ["noise_of", "paper_prior", "prior_from_identified", "read_plan", "stderr_say", "eq1", "max_rule",
           "export_calibration", "load_calibration", "plausible_calibration", "rig_scenario",
           "IdentifiedFile", "read_identified", "identify", "MeasurementSet", "load_data"]
