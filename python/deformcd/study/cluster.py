"""Where a study runs: a Dask client for an existing cluster, or a local one made for the study.

Each run uses `threads` CPU threads (deformcd.World's threads, which do not change its results);
a worker runs one task at a time (one Dask thread), so a machine with C cores takes C // threads
workers and is never oversubscribed. Workers are processes: a run that crashes its process
takes only that worker down, and Dask gives its task to another worker (up to
distributed.scheduler.allowed-failures times, 3 by default, before the run becomes a row with a
KilledWorker error).
"""

import contextlib
import logging
import os


def local_worker_count(threads):
    """Workers of threads each that fit this machine's cores (the ones this process may use)."""
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        cores = os.cpu_count() or 1
    return max(1, cores // max(1, threads))


@contextlib.contextmanager
def dask_client(client=None, scheduler=None, workers=None, threads=1, log=print):
    """Yields a distributed.Client: `client` itself; else one connected to `scheduler` (an
    address such as tcp://10.0.0.5:8786) or $DASK_SCHEDULER_ADDRESS; else one of a LocalCluster
    of `workers` processes (local_worker_count(threads) by default) on 127.0.0.1, closed after."""
    import distributed

    if client is not None:
        yield client
        return
    address = scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS")
    if address:
        log(f"study: on the cluster at {address}")
        with distributed.Client(address, timeout="30s") as connected:
            yield connected
        return
    count = workers or local_worker_count(threads)
    log(f"study: on a local cluster of {count} worker processes, {threads} thread(s) per run")
    # No dashboard: it would need bokeh, and a fixed port would clash with another study's.
    with distributed.LocalCluster(n_workers=count, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None,
                                  silence_logs=logging.ERROR) as cluster:
        with distributed.Client(cluster) as local:
            yield local
