"""Runs from threads use the cores (the GIL is released during a simulation), and a sweep
through Dask gives exactly the table of `pounding.sweep`."""

from __future__ import annotations

import os
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import pounding
from conftest import need


def heavy(examples: Path) -> pounding.Scenario:
    # the paper case at a 20x finer step: about 0.7 s per run (with its self-check) on one core
    return pounding.Scenario.from_file(examples / "paper-c.toml").replace({"solver.dt": 5e-5})


def two_processes(cli, toml: Path, out: Path) -> tuple[float, float]:
    """Wall times of two runs of the `pounding` binary one after the other, then at once."""
    args = lambda k: [toml, "--out", out / str(k), "--no-plot", "-q"]  # noqa: E731
    start = time.perf_counter()
    for k in range(2):
        assert cli("run", *args(k)).returncode == 0
    sequential = time.perf_counter() - start
    start = time.perf_counter()
    with ThreadPoolExecutor(max_workers=2) as pool:  # each thread waits on its own process
        assert all(p.returncode == 0 for p in pool.map(lambda k: cli("run", *args(k)), range(2)))
    return sequential, time.perf_counter() - start


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="needs 2 cores")
def test_threads_scale_with_the_cores(cli, examples: Path, tmp_path: Path) -> None:
    sc = heavy(examples)
    toml = tmp_path / "heavy.toml"
    toml.write_text(sc.toml)
    start = time.perf_counter()
    first = pounding.run(sc).summary
    one = time.perf_counter() - start
    assert one > 0.5, f"the scenario is too light for a timing ({one:.2f} s)"
    threads = processes = 0.0
    # Two runs one after the other, then two at once on two threads; best of up to eight such
    # windows (a few seconds each). Beside them, the same with two processes of the binary: what
    # the machine gives two independent runs at that moment (other work may be using a core).
    for _ in range(8):
        start = time.perf_counter()
        for _ in range(2):
            pounding.run(sc)
        sequential = time.perf_counter() - start
        start = time.perf_counter()
        with ThreadPoolExecutor(max_workers=2) as pool:
            results = list(pool.map(pounding.run, [sc] * 2))
        parallel = time.perf_counter() - start
        assert all(r.summary == first for r in results)  # threads change nothing
        threads = max(threads, sequential / parallel)
        seq_p, par_p = two_processes(cli, toml, tmp_path)
        processes = max(processes, seq_p / par_p)
        if threads > 1.6:
            break
    print(f"speedup on 2 threads: {threads:.2f}x (2 processes: {processes:.2f}x; one run {one:.2f} s)")
    if processes > 1.6:
        # the machine gave two runs two cores: so must two threads
        assert threads > 1.6, f"2 threads ran only {threads:.2f}x faster than 1 (2 processes: {processes:.2f}x)"
    else:
        # a busy machine (two processes got less than 1.6x): threads must scale as processes do
        assert threads > 0.85 * processes, f"2 threads {threads:.2f}x, 2 processes {processes:.2f}x"


def spin_while(future) -> tuple[int, float]:
    """Count the iterations of a Python loop until `future` is done: (count, seconds)."""
    start = time.perf_counter()
    n = 0
    while not future.done():
        n += 1
    return n, time.perf_counter() - start


def test_the_gil_is_released_during_a_run(examples: Path) -> None:
    # While a run computes in another thread, this thread keeps running Python. With the GIL
    # held for the run, the loop would stop as soon as the run enters the library (after at
    # most one switch interval, 5 ms) until it ended, i.e. for nearly all of the run; its rate
    # is compared with the same loop beside a thread that only sleeps.
    sc = heavy(examples)
    with ThreadPoolExecutor(max_workers=1) as pool:
        idle, idle_s = spin_while(pool.submit(time.sleep, 0.2))
        future = pool.submit(pounding.run, sc, check=False)
        n, elapsed = spin_while(future)
        future.result()
    assert elapsed > 0.1, f"the run was too short to tell ({elapsed:.3f} s)"
    ratio = (n / elapsed) / (idle / idle_s)
    assert ratio > 0.1, f"Python ran at {ratio:.1%} of its pace during a run: the GIL was held"


def test_dask_sweep_equals_pounding_sweep(examples: Path) -> None:
    distributed = need("dask.distributed")
    import pounding.distributed as pd_dask

    expected = pounding.sweep(examples / "quick-sweep.toml", jobs=2)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        table = pd_dask.sweep(client, examples / "quick-sweep.toml")
        sc = pounding.Scenario.from_file(examples / "paper-c.toml")
        axes = {"contact.gap": [0.0127, -1.0], "ground_motion.pga": [0.3, 0.6]}
        by_axes = pd_dask.sweep(client, sc, axes=axes, check=False)
        chunked = pd_dask.sweep(client, examples / "quick-sweep.toml", cases_per_task=5)
    assert list(table) == list(expected)
    for k in expected:
        np.testing.assert_array_equal(table[k], expected[k], err_msg=k)
        np.testing.assert_array_equal(chunked[k], expected[k], err_msg=k)
    local = pounding.sweep(sc, axes=axes, check=False, jobs=1)
    assert by_axes["status"][2].startswith("failed: ")  # failed cases come back as rows too
    for k in local:
        np.testing.assert_array_equal(by_axes[k], local[k], err_msg=k)
