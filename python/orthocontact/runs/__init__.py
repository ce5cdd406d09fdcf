"""Many rig runs: the executor (serial, a local pool, Dask) and the master
(C, fmpy) of a batch (executors), batches (batch), progress on stderr
(progress), sweeps and step studies of a scenario (sweep), and Dask (cluster)."""
