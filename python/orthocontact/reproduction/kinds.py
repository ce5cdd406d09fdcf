"""Every scenario kind's pieces of this layer (experiment.kinds), in reach:
importing this module imports each module that registers one (a kind's
runner, its part of the report), so that a command can ask any scenario's
kind for them.  run_scenario runs a scenario by its kind's runner;
in_report_order orders scenarios as the report shows them."""
from __future__ import annotations

from pathlib import Path

from ..experiment import RunOptions, Scenario, kind_of
from ..fmu import fmi_version_of
from ..output import write_json

# each registers its kinds' pieces
from . import paper_report, planar_outputs, pushed_outputs, rolling_outputs, scenario_outputs  # noqa: F401


def run_scenario(sc: Scenario, out: Path, fmu_path, how: RunOptions) -> dict:
    """Runs the scenario by its kind's runner on the FMU at `fmu_path` (the
    command's: experiment.kinds.fmu_for) and writes its outputs into `out`,
    summary.json with the FMU's FMI version last; the summary (its
    "checks" hold the run's warning line, or None)."""
    summary = kind_of(sc).part("run")(sc, out, fmu_path, how)
    summary["fmi_version"] = fmi_version_of(fmu_path)
    write_json(out / "summary.json", summary)
    return summary


def in_report_order(scenarios: list[Scenario]) -> list[Scenario]:
    """The scenarios by their section of the report (the contact patch's
    before the paper's), each section's in the order given: reproduce runs
    them so, and the figures of those run in this process are drawn while
    the sweeps' workers run."""
    return sorted(scenarios, key=paper_report.section_index)
