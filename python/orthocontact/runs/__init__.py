"""Many rig runs: local worker processes (pool), batches on either master
(batch), sweeps and step studies of a scenario (sweep), and Dask (cluster)."""
