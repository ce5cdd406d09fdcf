"""Where a batch of rig runs goes and what runs it (orthocontact.runs.executors):
each executor (here, a local pool; Dask in test_cluster.py) with each master
(the compiled one, the harness on fmpy) gives the same figures."""
from dataclasses import replace

import pytest

from orthocontact.experiment.scenario import load
from orthocontact.fmu.files import find_fmu
from orthocontact.runs.executors import OnDask, Pool, Serial, executor, local_chunk_size, resolve_master
from paths import SCENARIOS


@pytest.fixture(scope="module")
def tasks():
    sc = load(SCENARIOS / "mat_aged.toml")
    return [(sc.params_at(a), replace(sc.rig, travel_m=0.05)) for a in (0, 30, 45, 60, 90)]


def test_every_executor_with_every_master_gives_the_same_figures(tasks):
    fmu = find_fmu()
    done = []
    ref = Serial().map("fmpy", fmu, [[t] for t in tasks], done.append)
    assert len(done) == len(tasks) and all(len(r) == 1 for r in ref)
    ref = [f for part in ref for f in part]
    for ex in (Serial(), Pool(2)):
        for master in ("c", "fmpy"):
            size = ex.chunk_size(len(tasks), master)
            chunks = [tasks[k:k + size] for k in range(0, len(tasks), size)]
            assert [f for part in ex.map(master, fmu, chunks, lambda r: None) for f in part] == ref, \
                (type(ex).__name__, master)


def test_the_two_choices_are_made_apart():
    assert type(executor(1)) is Serial and type(executor(2)) is Pool
    assert type(executor(2, dask=object())) is OnDask
    assert local_chunk_size(1000, 2, "fmpy") == 1                # the harness: a progress step per run
    assert local_chunk_size(1000, 2, "c") == 125                 # 4 chunks per worker
    assert local_chunk_size(10 ** 6, 2, "c") == 256              # at most 256 runs a call
    assert OnDask(None).chunk_size(10 ** 6, "c") == 1000
    with pytest.raises(ValueError, match="a Dask cluster runs the compiled master"):
        OnDask(None).map("fmpy", find_fmu(), [], None)


def test_auto_takes_the_compiled_master_for_fmi_2_only():
    assert resolve_master("auto", find_fmu(fmi_version=2)) == "c"
    assert resolve_master("auto", find_fmu(fmi_version=3)) == "fmpy"
    with pytest.raises(ValueError, match="the compiled master runs FMI 2.0 FMUs"):
        resolve_master("c", find_fmu(fmi_version=3))
    with pytest.raises(ValueError, match="master must be one of"):
        resolve_master("C", None)
