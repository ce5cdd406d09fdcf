"""Uncertainty propagation on Dask: the identification's estimates and their
draws (estimates), the rig over the draws (propagate), bands and figure
(outputs)."""
from .estimates import Estimates, draw, load_estimates
from .outputs import write_outputs
from .propagate import (
    DEFAULT_STEP_S,
    STEP_CHECK_WARN_DEG,
    UQResult,
    bands,
    check_geometry,
    propagate,
    step_warning,
    uq_step,
)
from .source import read_source

__all__ = ["Estimates", "draw", "load_estimates", "write_outputs", "DEFAULT_STEP_S",
           "STEP_CHECK_WARN_DEG", "UQResult", "bands", "check_geometry", "propagate", "step_warning",
           "uq_step", "read_source"]
