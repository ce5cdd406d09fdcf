"""The compiled master advances two runs in turn (master_src/rig_master.c,
lanes): a batch gives each run's figures exactly as that run alone, whatever
the runs' lengths and modes, and a run that fails stops the batch with its
own message."""
import math
from dataclasses import replace
from pathlib import Path

import pytest

from orthocontact.experiment.scenario import load
from orthocontact.fmu.contact import FMUError
from orthocontact.fmu.files import find_fmu
from orthocontact.rig.compiled import CMaster

ROOT = Path(__file__).resolve().parents[1]


def same(a, b) -> bool:
    return all((math.isnan(x) and math.isnan(y)) or x == y for x, y in zip(a, b, strict=True))


@pytest.fixture
def master():
    cm = CMaster(find_fmu())
    yield cm
    cm.close()


def test_a_batch_gives_each_runs_figures_as_alone(master):
    sc = load(ROOT / "scenarios/mat_aged.toml")
    short, long_ = replace(sc.rig, travel_m=0.03), replace(sc.rig, travel_m=0.07)
    quasi = replace(short, mode="quasistatic", step_s=1e-3)
    # lengths and modes differ, so the two lanes finish runs at different
    # steps and take the next set in an order no single lane would
    tasks = [(sc.params_at(0.0), long_), (sc.params_at(30.0), short), (sc.params_at(45.0), quasi),
             (sc.params_at(60.0), short), (sc.params_at(39.2), replace(long_, mu_strip=0.1)),
             (sc.params_at(90.0), long_), (sc.params_at(11.3), quasi)]
    batch = master.run(tasks)
    alone = [master.run([t])[0] for t in tasks]
    assert len(batch) == len(tasks)
    for k, (b, a) in enumerate(zip(batch, alone)):
        assert same(b, a), (k, b, a)
    # and in reverse order: no figure depends on which lane ran it
    assert all(same(b, a) for b, a in zip(master.run(tasks[::-1]), alone[::-1]))


def test_a_failing_run_stops_the_batch_with_its_message(master):
    sc = load(ROOT / "scenarios/mat_aged.toml")
    ok = replace(sc.rig, travel_m=0.03)
    endless = replace(ok, travel_m=1e10, velocity_m_s=1e-10, step_s=1e-10)  # 1e30 steps
    tasks = [(sc.params_at(0.0), ok), (sc.params_at(10.0), ok), (sc.params_at(20.0), endless),
             (sc.params_at(30.0), ok)]
    with pytest.raises(FMUError, match="not a whole number of steps"):
        master.run(tasks)
    # the master is usable after the failure, its instances freed
    assert same(master.run(tasks[:1])[0], master.run([tasks[0]])[0])
