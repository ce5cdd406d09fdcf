"""Batches of rig runs: the figures of each (params, rig) in order, on the
master and executor of runs.executors, with a progress bar."""
from __future__ import annotations

from ..fmu import ContactParams, find_fmu
from ..rig import Rig, RunFigures
from .executors import executor, resolve_master
from .progress import Progress


def run_many(tasks: list[tuple[ContactParams, Rig]], workers: int, fmu_path, label: str,
             progress: bool = True, master: str = "auto", dask=None) -> list[RunFigures]:
    """The RunFigures (phi_deg, drive_mean_N, phi_head_deg, phi_tail_deg) of
    each (params, rig), in order.  master: "c"
    (the compiled master, FMI 2.0 FMUs), "fmpy" (the Python harness), or
    "auto" (c where it applies); both give the same angles.  dask: a
    cluster.DaskRunner to run the compiled master's chunks on (else local
    processes)."""
    bar = Progress(len(tasks), label, progress)
    try:
        chosen = resolve_master(master, fmu_path)
        ex = executor(workers, dask)
        size = ex.chunk_size(len(tasks), chosen)
        chunks = [tasks[k:k + size] for k in range(0, len(tasks), size)]
        parts = ex.map(chosen, find_fmu(fmu_path), chunks, lambda done: bar.update(len(done)))
        return [figures for part in parts for figures in part]
    finally:
        bar.close()
