"""Sweeps on a cluster through Dask (optional: ``pip install pounding[dask]``).

Each case of the sweep is one Dask task: the checked sweep (:func:`pounding.plan_sweep`,
which pickles as its text and its base scenario's text) is scattered to the workers once, each
task computes one case to its results row, and the rows come back in case order into the same
table :func:`pounding.sweep` returns. The same code runs on a laptop (``LocalCluster``) and
on a Slurm cluster (``dask_jobqueue.SLURMCluster``)::

    from dask.distributed import Client, LocalCluster
    import pounding, pounding.distributed

    with LocalCluster(n_workers=4, threads_per_worker=1) as cluster, Client(cluster) as client:
        table = pounding.distributed.sweep(client, "examples/quick-sweep.toml")

    # on Slurm:
    # from dask_jobqueue import SLURMCluster
    # cluster = SLURMCluster(cores=32, processes=32, memory="64GB", walltime="02:00:00")
    # cluster.scale(jobs=8); client = Client(cluster)

Record files are read by the workers from their absolute paths: on a cluster they must be
on a shared file system (as for the CLI's Slurm-array route, ``pounding sweep --shard``).
"""

from __future__ import annotations

from typing import Any, Mapping, Union

from . import PathLike, Scenario, SweepTable, _core, plan_sweep


def run_case(plan: _core.Sweep, case: int, check: bool = True) -> str:
    """Compute case ``case`` of ``plan`` to its results row (a line of results.csv)."""
    return plan.run_case(case, check)


def sweep(
    client: Any,
    source: Union[PathLike, Scenario],
    axes: Mapping[str, Any] | None = None,
    *,
    check: bool = True,
) -> SweepTable:
    """Run every case of a sweep on the workers of a ``dask.distributed.Client`` and return
    the table :func:`pounding.sweep` returns for the same sweep (rows in case order)."""
    plan = plan_sweep(source, axes)
    plan.require_valid_case()
    [shared] = client.scatter([plan], broadcast=True)
    futures = client.map(run_case, [shared] * len(plan), range(len(plan)), check=check, pure=False)
    rows = client.gather(futures)
    return SweepTable(plan.columns(rows))
