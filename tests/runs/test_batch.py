"""Batches of rig runs (orthocontact.runs.batch): the same figures with
either master and any number of workers, a master chosen by name."""
from dataclasses import replace

from orthocontact.experiment.scenario import load
from orthocontact.runs.batch import run_many
from paths import SCENARIOS


def test_run_many_same_with_either_master_and_any_workers():
    sc = load(SCENARIOS / "mat_aged.toml")
    tasks = [(sc.params_at(a), replace(sc.rig, travel_m=0.05)) for a in range(0, 91, 10)]
    ref = run_many(tasks, 1, None, "t", progress=False, master="fmpy")
    assert run_many(tasks, 1, None, "t", progress=False, master="c") == ref
    assert run_many(tasks, 2, None, "t", progress=False, master="c") == ref
