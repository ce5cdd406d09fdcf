"""Batches of rig runs on either master: the compiled one (C, FMI 2.0 FMUs)
or the Python harness on fmpy, in local worker processes or on Dask.  Each
worker holds its own FMU instance and resets it for every run, so results do
not depend on the number of workers or the order."""
from __future__ import annotations

import os
from concurrent.futures import as_completed

from ..fmu.contact import ContactFMU
from ..fmu.params import ContactParams
from ..rig.harness import Rig, RunFigures, run
from .pool import Progress, process_pool, stop_pool

# -- workers ----------------------------------------------------------------------

_worker_fmu: ContactFMU | None = None


def _init_worker(fmu_path):
    global _worker_fmu
    _worker_fmu = ContactFMU(fmu_path, instance_name=f"worker{os.getpid()}")


def _run_one(task, fmu: ContactFMU | None = None):
    """(index, params, rig) -> (index, RunFigures), on `fmu` or the worker's
    own instance."""
    index, params, rig = task
    return index, run(params, rig, fmu=fmu or _worker_fmu, record_every=1 << 30).figures


MASTERS = ("auto", "c", "fmpy")


def resolve_master(master: str, fmu_path) -> str:
    """"c" or "fmpy": auto takes the compiled master for an FMI 2.0 FMU."""
    if master not in MASTERS:
        raise ValueError(f"master must be one of {', '.join(map(repr, MASTERS))}, got {master!r}")
    from ..fmu.files import find_fmu, fmi_version_of
    version = fmi_version_of(find_fmu(fmu_path))
    if master == "c" and version != 2:
        # checked here, in the main process, not in a worker's initializer
        raise ValueError(f"the compiled master runs FMI 2.0 FMUs, this one is FMI {version}.0; "
                         "use master='fmpy'")
    if master != "auto":
        return master
    return "c" if version == 2 else "fmpy"


_worker_cmaster = None


def _init_cworker(fmu_path):
    global _worker_cmaster
    from ..fmu.files import find_fmu
    from ..rig.compiled import CMaster
    _worker_cmaster = CMaster(find_fmu(fmu_path))


def _run_chunk(chunk):
    """[(index, params, rig)] -> [(index, RunFigures)] on the worker's
    compiled master."""
    res = _worker_cmaster.run([(p, r) for _, p, r in chunk])
    return [(i, figures) for (i, _, _), figures in zip(chunk, res)]


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
        return _run_many(tasks, workers, fmu_path, bar, master, dask)
    finally:
        bar.close()


def _run_many(tasks, workers, fmu_path, bar, master, dask):
    out: list = [None] * len(tasks)
    indexed = [(i, p, r) for i, (p, r) in enumerate(tasks)]
    use_c = resolve_master(master, fmu_path) == "c"
    if dask is not None:
        if not use_c:
            raise ValueError("a Dask cluster runs the compiled master: use master 'c' or 'auto' "
                             "with an FMI 2.0 FMU")
        from ..fmu.files import find_fmu
        from .cluster import run_tasks
        size = max(1, min(1000, -(-len(tasks) // 8)))
        chunks = [tasks[k:k + size] for k in range(0, len(tasks), size)]
        res = dask.map(run_tasks, chunks, find_fmu(fmu_path), lambda i, r: bar.update(len(r)))
        return [RunFigures(*x) for part in res for x in part]
    if use_c:
        # chunks small enough to show progress and balance two workers
        size = max(1, min(256, -(-len(indexed) // (4 * max(workers, 1)))))
        chunks = [indexed[k:k + size] for k in range(0, len(indexed), size)]
    if workers <= 1:
        if use_c:
            from ..fmu.files import find_fmu
            from ..rig.compiled import CMaster
            cm = CMaster(find_fmu(fmu_path))
            try:
                for chunk in chunks:
                    for (i, _, _), res in zip(chunk, cm.run([(p, r) for _, p, r in chunk])):
                        out[i] = res
                    bar.update(len(chunk))
            finally:
                cm.close()
            return out
        fmu = ContactFMU(fmu_path, instance_name="serial")
        try:
            for t in indexed:
                i, out[i] = _run_one(t, fmu)
                bar.update()
        finally:
            fmu.close()
        return out
    from ..fmu.files import find_fmu, unzipped
    unzipped(find_fmu(fmu_path))  # once, here: forked workers share it, and this process removes it
    ex = process_pool(workers, _init_cworker if use_c else _init_worker, fmu_path)
    try:
        if use_c:
            futures = [ex.submit(_run_chunk, c) for c in chunks]
            for fut in as_completed(futures):
                done = fut.result()
                for i, figures in done:
                    out[i] = figures
                bar.update(len(done))
        else:
            futures = [ex.submit(_run_one, t) for t in indexed]
            for fut in as_completed(futures):
                i, figures = fut.result()
                out[i] = figures
                bar.update()
    except BaseException:
        stop_pool(ex)
        raise
    ex.shutdown()
    return out
