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

Fragility studies likewise (:func:`fragility`): one Dask task per run of a record at a
stripe, or per record of an incremental dynamic analysis (its runs depend on each other);
the workers read the study file and its records from their absolute paths.
"""

from __future__ import annotations

from typing import Any, Mapping, Union

from . import FragilityResult, PathLike, Scenario, SweepTable, _core, plan_fragility, plan_sweep


def run_case(plan: _core.Sweep, case: int, check: bool = True) -> str:
    """Compute case ``case`` of ``plan`` to its results row (a line of results.csv)."""
    return plan.run_case(case, check)


def run_cases(plan: _core.Sweep, cases: list[int], check: bool = True) -> list[str]:
    """Compute the cases ``cases`` of ``plan`` one after the other: their results rows."""
    return [plan.run_case(c, check) for c in cases]


def sweep(
    client: Any,
    source: Union[PathLike, Scenario],
    axes: Mapping[str, Any] | None = None,
    *,
    check: bool = True,
    cases_per_task: int = 1,
) -> SweepTable:
    """Run every case of a sweep on the workers of a ``dask.distributed.Client`` and return
    the table :func:`pounding.sweep` returns for the same sweep (rows in case order).

    ``source`` and ``axes`` as for :func:`pounding.sweep`; ``check``: each case's self-check.
    ``cases_per_task``: cases computed by one Dask task (consecutive cases); raise it for
    sweeps of many cheap cases, where Dask's overhead per task (about a millisecond) would
    matter. A failed case is a row with its reason, as in :func:`pounding.sweep`; a sweep none
    of whose cases is a valid scenario raises :class:`pounding.SweepError` before any task.
    """
    if cases_per_task < 1:
        raise ValueError("cases_per_task must be at least 1")
    plan = plan_sweep(source, axes)
    plan.require_valid_case()
    [shared] = client.scatter([plan], broadcast=True)
    n = len(plan)
    if cases_per_task == 1:
        futures = client.map(run_case, [shared] * n, range(n), check=check, pure=False)
        rows = client.gather(futures)
    else:
        chunks = [list(range(i, min(i + cases_per_task, n))) for i in range(0, n, cases_per_task)]
        futures = client.map(run_cases, [shared] * len(chunks), chunks, check=check, pure=False)
        rows = [row for part in client.gather(futures) for row in part]
    return SweepTable(plan.columns(rows))


def run_fragility_task(plan: _core.FragilityPlan, task: int) -> list[str]:
    """Compute task ``task`` of a fragility study's ``plan``: its runs as rows."""
    return plan.run_task(task)


def fragility(
    client: Any,
    path: PathLike,
    *,
    out: PathLike | None = None,
    plots: bool = True,
) -> FragilityResult:
    """Run a fragility study file on the workers of a ``dask.distributed.Client`` and return
    what :func:`pounding.fragility` returns for it (the same tables and fits, to the bit).

    Each task is a run of a record at a stripe, or a record's whole IDA (hunt and fill: its
    runs depend on each other). With ``out``, the files (and the figures unless ``plots`` is
    false) are written there by the client, fit.json last."""
    import os

    plan = plan_fragility(path)
    [shared] = client.scatter([plan], broadcast=True)
    futures = client.map(run_fragility_task, [shared] * len(plan), range(len(plan)), pure=False)
    rows = [row for part in client.gather(futures) for row in part]
    parts = plan.assemble(rows, None if out is None else os.fspath(out), plots)
    return FragilityResult(dict(parts))
