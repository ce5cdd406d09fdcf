"""Batches of rig runs on a Dask cluster (dask.distributed).

A `DaskRunner` either starts a `distributed.LocalCluster` with one
single-threaded worker process per core, listening on the loopback interface
only, or connects to an existing scheduler (`tcp://HOST:PORT`).  The contact FMU travels to the workers as
bytes (scattered to every worker once; no shared file system is assumed);
each worker process unpacks it once into its own temporary folder and runs
its chunks on the compiled master.  A chunk's result depends on nothing but
its inputs, so the scheduler may run a chunk again (a lost worker's chunks
are recomputed on the others) and the results stay identical to a serial
run.

The workers need this package installed (the compiled master ships with it)."""
from __future__ import annotations

import hashlib
import logging
import os
import shutil
import signal
import sys
import tempfile
from pathlib import Path

from ..errors import InputError

# -- the worker's side ------------------------------------------------------------

_masters: dict = {}  # FMU digest -> CMaster, per worker process


def _master_for(fmu):
    """The compiled master on the FMU `fmu` = (digest, file name, bytes),
    unpacked once per worker process."""
    digest, name, blob = fmu
    if digest not in _masters:
        from ..rig import CMaster
        from ..runtime import temp_folder
        folder = Path(tempfile.mkdtemp(prefix=f"fmu-{digest[:16]}-{os.getpid()}-", dir=temp_folder()))
        try:
            path = folder / name
            path.write_bytes(blob)
            # CMaster unpacks the FMU (removed when this process ends:
            # runtime.temp.remove_unzipped); the archive is not needed after.
            _masters[digest] = CMaster(path)
        finally:
            shutil.rmtree(folder, ignore_errors=True)
    return _masters[digest]


PARENT_ENV = "ORTHOCONTACT_PARENT"  # the pid of the command that started a local cluster


def dask_setup(worker):
    """A local cluster's worker (this module is its preload): Ctrl-C reaches
    the whole process group, and the command, not the worker, decides; the
    worker ends when the command's process ends, however it ends (Dask's own
    watch, a pipe, stays open while any process forked from the command
    holds it)."""
    import threading

    from ..runtime import end_with_parent
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    if os.environ.get(PARENT_ENV, "").isdigit():
        # started by one of the nanny's threads: PR_SET_PDEATHSIG would fire when that thread ends
        end_with_parent(int(os.environ[PARENT_ENV]), forked_by_main_thread=False)


def fmu_payload(fmu_path) -> tuple:
    """(digest, file name, bytes): the FMU as it travels to the workers."""
    path = Path(fmu_path)
    blob = path.read_bytes()
    return hashlib.sha256(blob).hexdigest(), path.name, blob


def run_tasks(fmu, tasks):
    """[(ContactParams, Rig)] -> [RunFigures] on the worker."""
    return _master_for(fmu).run(tasks)


def run_grid(fmu, laws, axes, rig):
    """CMaster.run_grid on the worker: every law at every (alpha, beta)."""
    return _master_for(fmu).run_grid(laws, axes, rig)


# -- the client's side ------------------------------------------------------------

LOOPBACK = "127.0.0.1"  # where a local cluster listens


def check_address(scheduler: str) -> None:
    """InputError unless `scheduler` is 'local' or a Dask address."""
    if scheduler != "local" and not scheduler.startswith(("tcp://", "tls://", "inproc://", "ucx://")):
        raise InputError(f"--scheduler {scheduler}: expected 'local' or a scheduler address "
                         "such as tcp://HOST:PORT")


class DaskRunner:
    """Runs chunks of rig work on Dask.  scheduler: "local" (a LocalCluster
    of `workers` processes, one thread each) or an address tcp://HOST:PORT.

        with DaskRunner("local", 2) as dr:
            results = dr.map(fn, chunks, fmu_path, on_done)

    fn(fmu, chunk) runs on a worker, where fmu is what _master_for takes."""

    def __init__(self, scheduler: str, workers: int):
        check_address(scheduler)
        self.scheduler, self.workers = scheduler, workers
        self._client = self._cluster = self._scratch = None
        self._scattered = {}  # FMU path -> future of its payload

    @property
    def description(self) -> str:
        if self._cluster is not None:
            return f"Dask LocalCluster, {self.workers} worker processes"
        return f"Dask cluster at {self.scheduler}"

    def __enter__(self):
        try:
            return self._enter()
        except BaseException:  # an error or Ctrl-C while it starts: stop what started
            self.__exit__(None, None, None)
            raise

    def _enter(self):
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            raise InputError("--scheduler: Dask is not installed; pip install 'dask[distributed]'") \
                from None
        if self.scheduler == "local":
            self._cluster = self._local_cluster(LocalCluster)
            self._client = Client(self._cluster)
        else:
            try:
                self._client = Client(self.scheduler, timeout=15)
            except OSError as e:
                raise InputError(f"--scheduler {self.scheduler}: cannot reach the scheduler ({e})") \
                    from None
        return self

    def _local_cluster(self, LocalCluster):
        import dask

        from ..runtime import TEMP_ENV, check_workers, temp_folder
        check_workers(self.workers)
        self._scratch = tempfile.mkdtemp(prefix="dask-", dir=temp_folder())
        # Ctrl-C reaches the whole process group; the command decides (it
        # stops the cluster and says one line).  A worker ignores SIGINT from
        # its preload on (dask_setup); one interrupted while it starts would
        # print tracebacks, so the workers' stderr is the null device (a
        # task's error reaches the command through its future, not there).
        sys.stderr.flush()
        saved = os.dup(2)
        try:
            with open(os.devnull, "w") as null:
                os.dup2(null.fileno(), 2)
            # Every scratch folder of the cluster (the scheduler's too) in
            # one of ours, removed when the cluster stops; the workers unpack
            # the FMU in the command's temporary folder (TEMP_ENV).  No
            # dashboard: nobody looks at it during a command; the
            # scheduler's HTTP server (health, metrics) listens anyway, on a
            # free port, as 8787 may be busy (a UserWarning).  A local
            # cluster serves this machine only: the scheduler, its HTTP
            # server and the workers listen on the loopback interface.
            with dask.config.set({"temporary-directory": self._scratch}):
                return LocalCluster(n_workers=self.workers, threads_per_worker=1, processes=True,
                                    host=LOOPBACK, dashboard_address=None,
                                    scheduler_kwargs={"dashboard": False,
                                                      "dashboard_address": f"{LOOPBACK}:0"},
                                    silence_logs=logging.CRITICAL + 1, local_directory=self._scratch,
                                    preload=[__name__],
                                    env={TEMP_ENV: str(temp_folder()), PARENT_ENV: str(os.getpid())})
        finally:
            os.dup2(saved, 2)
            os.close(saved)

    def _fmu(self, fmu_path):
        key = str(Path(fmu_path).resolve())
        if key not in self._scattered:
            # On every worker: a worker that dies takes only its own copy.
            self._scattered[key] = self._client.scatter(fmu_payload(fmu_path), broadcast=True,
                                                        hash=True)
        return self._scattered[key]

    def map(self, fn, chunks: list, fmu_path, on_done=None) -> list:
        """fn(fmu, chunk) for every chunk, on the cluster; the results in the
        order of `chunks`.  on_done(i, result) as each one arrives."""
        from distributed import as_completed
        fmu = self._fmu(fmu_path)
        futures = [self._client.submit(fn, fmu, c, pure=False) for c in chunks]
        index = {f.key: i for i, f in enumerate(futures)}
        out = [None] * len(chunks)
        try:
            for fut in as_completed(futures):
                i = index[fut.key]
                out[i] = fut.result()
                if on_done:
                    on_done(i, out[i])
        except BaseException:
            self._client.cancel(futures)
            raise
        return out

    def __exit__(self, kind, value, tb):
        if self._client is not None:
            self._client.close()
        if self._cluster is not None:
            self._cluster.close()
        if self._scratch is not None:
            shutil.rmtree(self._scratch, ignore_errors=True)
        return False
