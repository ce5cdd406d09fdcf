"""Every scenario kind's reproduction pieces in reach (orthocontact.reproduction.kinds):
a scenario runs by its kind's runner, the report orders scenarios by its sections."""
import json

from cli_run import scenario_variant
from orthocontact.experiment.kinds import KINDS, RunOptions, fmu_for
from orthocontact.experiment.scenario import load
from orthocontact.reproduction import kinds, pad_report, paper_report, patch_report
from paths import SCENARIOS


def test_every_kind_runs_by_its_runner_and_reports_in_its_section():
    for k in KINDS.values():
        assert callable(k.part("run")) and k.part("report").section in paper_report.sections()
    assert paper_report.sections() == [patch_report.PATCH, pad_report.PAD, paper_report.SCENARIOS]


def test_reproduce_runs_the_patch_section_first_each_section_in_file_order():
    names = ["case1", "pushed_block", "step_study", "towed_block", "twist", "mat_aged"]
    ordered = kinds.in_report_order([load(SCENARIOS / f"{n}.toml") for n in names])
    assert [sc.name for sc in ordered] == ["towed_block", "twist", "pushed_block", "case1", "step_study",
                                           "mat_aged"]


def test_a_scenario_run_writes_its_summary_with_the_fmus_version(tmp_path):
    """A short twist on the FMI 3.0 patch FMU, by its kind's runner: its
    outputs and summary.json, whose fmi_version is the FMU's."""
    sc = load(scenario_variant(SCENARIOS / "twist.toml", "angle_deg = 15.0", "angle_deg = 0.5",
                               tmp_path / "t.toml"))
    out = tmp_path / "out"
    out.mkdir()
    summary = kinds.run_scenario(sc, out, fmu_for(sc, 3), RunOptions(workers=1, progress=False))
    written = json.loads((out / "summary.json").read_text())
    assert written["fmi_version"] == 3 and written["kind"] == "twist" == summary["kind"]
    assert (out / "twist.csv").stat().st_size > 0 and "warning" in written["checks"]
