"""Where a batch of rig runs goes and what runs it: two independent choices.

The master: the compiled one ("c": the rig loop in C over an FMI 2.0 FMU, a
chunk of runs in one call) or the Python harness on fmpy ("fmpy": one run at
a time, FMI 2.0 or 3.0).  The executor: here (Serial), a local pool of
worker processes (Pool, runtime.processes), or a Dask cluster (OnDask,
cluster.DaskRunner).  An executor opens the master once in each process
that runs chunks and hands it the chunks of (params, rig); each process
holds its own FMU instance and resets it for every run, so the results do
not depend on the executor, the chunks or their order."""
from __future__ import annotations

import os
from concurrent.futures import as_completed

from ..fmu import ContactFMU, find_fmu, fmi_version_of
from ..rig import RunFigures, run
from ..runtime import process_pool, stop_pool, unzipped

MASTERS = ("auto", "c", "fmpy")


def resolve_master(master: str, fmu_path) -> str:
    """"c" or "fmpy": auto takes the compiled master for an FMI 2.0 FMU."""
    if master not in MASTERS:
        raise ValueError(f"master must be one of {', '.join(map(repr, MASTERS))}, got {master!r}")
    version = fmi_version_of(find_fmu(fmu_path))
    if master == "c" and version != 2:
        # checked here, in the main process, not in a worker's initializer
        raise ValueError(f"the compiled master runs FMI 2.0 FMUs, this one is FMI {version}.0; "
                         "use master='fmpy'")
    if master != "auto":
        return master
    return "c" if version == 2 else "fmpy"


class FmpyMaster:
    """The Python harness on one ContactFMU instance."""

    def __init__(self, fmu_path, instance_name: str):
        self.fmu = ContactFMU(fmu_path, instance_name=instance_name)

    def run(self, tasks) -> list[RunFigures]:
        """The RunFigures of each (params, rig), in order."""
        return [run(p, r, fmu=self.fmu, record_every=1 << 30).figures for p, r in tasks]

    def close(self) -> None:
        self.fmu.close()


def open_master(master: str, fmu_path, instance_name: str = "serial"):
    """The master `master` ("c" or "fmpy") on the FMU file `fmu_path`:
    .run([(params, rig)]) -> [RunFigures], .close()."""
    if master == "c":
        from ..rig import CMaster
        return CMaster(fmu_path)
    return FmpyMaster(fmu_path, instance_name)


def local_chunk_size(runs: int, workers: int, master: str) -> int:
    """Runs per chunk here or in a local pool: one for the harness (each its
    own progress step), else small enough to show progress and balance the
    workers (4 chunks each, at most 256 runs)."""
    if master == "fmpy":
        return 1
    return max(1, min(256, -(-runs // (4 * max(workers, 1)))))


class Serial:
    """Every chunk in this process, in order."""

    def __init__(self, workers: int = 1):
        self.workers = workers

    def chunk_size(self, runs: int, master: str) -> int:
        return local_chunk_size(runs, self.workers, master)

    def map(self, master: str, fmu, chunks: list, on_done) -> list:
        m = open_master(master, fmu)
        try:
            out = []
            for chunk in chunks:
                out.append(m.run(chunk))
                on_done(out[-1])
            return out
        finally:
            m.close()


_worker_master = None  # a pool worker's master (Pool)


def _open_in_worker(master: str, fmu) -> None:
    global _worker_master
    _worker_master = open_master(master, fmu, f"worker{os.getpid()}")


def _run_in_worker(chunk) -> list[RunFigures]:
    return _worker_master.run(chunk)


class Pool:
    """The chunks in `workers` local worker processes (process_pool), each
    with its own master; stopped at once by an error or an interrupt."""

    def __init__(self, workers: int):
        self.workers = workers

    def chunk_size(self, runs: int, master: str) -> int:
        return local_chunk_size(runs, self.workers, master)

    def map(self, master: str, fmu, chunks: list, on_done) -> list:
        unzipped(fmu)  # once, here: forked workers share it, and this process removes it
        ex = process_pool(self.workers, _open_in_worker, master, fmu)
        out: list = [None] * len(chunks)
        try:
            futures = {ex.submit(_run_in_worker, c): k for k, c in enumerate(chunks)}
            for fut in as_completed(futures):
                out[futures[fut]] = fut.result()
                on_done(out[futures[fut]])
        except BaseException:
            stop_pool(ex)
            raise
        ex.shutdown()
        return out


class OnDask:
    """The chunks on a Dask cluster (a cluster.DaskRunner), the compiled
    master on each of its workers."""

    def __init__(self, runner):
        self.runner = runner

    def chunk_size(self, runs: int, master: str) -> int:
        return max(1, min(1000, -(-runs // 8)))

    def map(self, master: str, fmu, chunks: list, on_done) -> list:
        if master != "c":
            raise ValueError("a Dask cluster runs the compiled master: use master 'c' or 'auto' "
                             "with an FMI 2.0 FMU")
        from .cluster import run_tasks
        res = self.runner.map(run_tasks, chunks, fmu, lambda i, r: on_done(r))
        return [[RunFigures(*x) for x in part] for part in res]


def executor(workers: int, dask=None):
    """OnDask(dask) if a Dask runner is given, else Serial for at most one
    worker, else a Pool of `workers`."""
    if dask is not None:
        return OnDask(dask)
    return Serial(workers) if workers <= 1 else Pool(workers)
