"""Fragility studies through Dask (issue 28): `pounding.distributed.fragility` on a local
cluster returns exactly what `pounding.fragility` returns — multi-stripe and IDA — and the
plan pickles."""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np

import pounding
from conftest import need

STUDY = """scenario = "base.toml"
[ground_motion]
records = [
  {{ file = "{records}/RSN753_LOMAP_CLS000.AT2" }},
  {{ file = "{records}/RSN786_LOMAP_PAE055.AT2" }},
  {{ file = "{records}/INGLEWOO.V2", component = 1 }},
]
[intensity]
measure = "pga"
[[limit_state]]
kind = "pounding"
[[limit_state]]
kind = "ductility"
value = 2.0
structure = 2
[fragility]
{method}
gaps = [0.0, 0.05, 0.1, 0.2]
target = {{ im = 0.3, probability = 0.3 }}
bootstrap = 20
"""


def _study(tmp_path: Path, examples: Path, method: str, name: str) -> Path:
    # the bundled frames, 6 s of motion
    base = (examples / "fragility-frames.toml").read_text().replace("duration = 30.0", "duration = 6.0")
    base = base.replace('file = "records/', f'file = "{examples}/records/')
    (tmp_path / "base.toml").write_text(base)
    p = tmp_path / name
    p.write_text(STUDY.format(records=examples / "records", method=method))
    return p


def _same(a: pounding.FragilityResult, b: pounding.FragilityResult) -> None:
    assert a.fit == b.fit
    assert a.report == b.report
    for t in ("fragility", "p_pounding", "runs", "capacities"):
        x, y = getattr(a, t), getattr(b, t)
        assert list(x) == list(y), t
        for k in x:
            if isinstance(x[k], np.ndarray):
                np.testing.assert_array_equal(x[k], y[k], err_msg=f"{t}.{k}")
            else:
                assert x[k] == y[k], f"{t}.{k}"


def test_dask_fragility_equals_pounding_fragility(tmp_path: Path, examples: Path) -> None:
    distributed = need("dask.distributed")
    import pounding.distributed as pd_dask

    stripes = _study(tmp_path, examples, "stripes = [0.1, 0.3]", "stripes.toml")
    ida = _study(
        tmp_path,
        examples,
        "ida = { start = 0.1, step = 0.1, tolerance = 0.02, max_runs = 10 }",
        "ida.toml",
    )
    expected = {p: pounding.fragility(p, jobs=2) for p in (stripes, ida)}
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        got = {p: pd_dask.fragility(client, p) for p in (stripes, ida)}
    for p in (stripes, ida):
        _same(got[p], expected[p])
    # 3 records × 2 stripes; an IDA: capacities of 3 records × 4 curves (pounding and ductility,
    # with and without contact)
    assert len(got[stripes].runs["record"]) == 6 and len(got[stripes].capacities["record"]) == 0
    assert len(got[ida].capacities["record"]) == 3 * 4


def test_fragility_plan_pickles_and_refuses_a_bad_task(tmp_path: Path, examples: Path) -> None:
    p = _study(tmp_path, examples, "stripes = [0.1, 0.3]", "s.toml")
    plan = pounding.plan_fragility(p)
    assert len(plan) == 6
    again = pickle.loads(pickle.dumps(plan))
    assert len(again) == 6 and repr(again) == repr(plan)
    import pytest

    with pytest.raises(IndexError, match="6 tasks"):
        plan.run_task(6)
    # the rows of every task, in any order, make the tables of pounding.fragility
    rows = [r for t in reversed(range(len(plan))) for r in again.run_task(t)]
    _same(pounding.FragilityResult(dict(plan.assemble(rows))), pounding.fragility(p, jobs=1))


def test_dask_fragility_of_a_row_equals_pounding_fragility(tmp_path: Path, examples: Path) -> None:
    # the Dask path is generic: a row's journal rows (per pair and per structure) travel too
    distributed = need("dask.distributed")
    import pounding.distributed as pd_dask

    base = (examples / "fragility-row-frames.toml").read_text().replace("duration = 20.0", "duration = 6.0")
    base = base.replace('file = "records/', f'file = "{examples}/records/')
    (tmp_path / "base.toml").write_text(base)
    study = tmp_path / "row.toml"
    study.write_text(STUDY.format(records=examples / "records", method="stripes = [0.1, 0.3]"))
    expected = pounding.fragility(study, jobs=2)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        got = pd_dask.fragility(client, study)
    _same(got, expected)
    assert [q["between"] for q in got.pairs] == [["A4", "B8"], ["B8", "C5"]]
    assert set(got.p_pounding["pair"]) == {1.0, 2.0}
