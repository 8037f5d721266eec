"""Suites of records (issue 27): `pounding.run` on a `kind = "suite"` scenario returns the
per-record results and the statistics, and writes what `pounding run` writes."""

from __future__ import annotations

import statistics
from pathlib import Path

import pytest

import pounding


def test_suite_run_gives_records_and_statistics(examples: Path, tmp_path: Path, cli) -> None:
    sc = pounding.Scenario.from_file(examples / "suite-ec8.toml")
    r = pounding.run(sc, check=False)
    assert r.suite is not None
    assert len(r.records) == 5
    assert r.suite["scaling"]["rule"] == "ec8"
    # the statistics are those of the records' numbers (mean and max computed here)
    key = "level1_required_separation"
    values = [rec[key] for rec in r.records]
    s = r.statistics[key]
    assert abs(s["mean"] - statistics.fmean(values)) <= 1e-12 * s["mean"]
    assert s["max"] == max(values)
    # fewer than 7 records under EN 1998-1: the design value is the most unfavourable
    assert r.suite["design"]["statistic"] == "max"
    assert r.suite["design"]["levels"][0]["required"] == max(values)
    # the top level is the representative record's run
    rep = r.suite["representative"] - 1
    assert r.summary["levels"][0]["required_gap"] == r.records[rep][key]
    # save writes the command line's files, summary.json byte for byte
    written = r.save(tmp_path / "py", plots=False)
    assert Path(written[-1]).name == "summary.json"
    assert (tmp_path / "py" / "suite.csv").read_text() == r._out.suite_csv()
    out = cli("run", examples / "suite-ec8.toml", "--out", tmp_path / "cli", "--no-check", "--no-plot")
    assert out.returncode == 0, out.stderr
    for f in ("summary.json", "suite.csv"):
        assert (tmp_path / "py" / f).read_text() == (tmp_path / "cli" / f).read_text(), f
    # the suite's report, as `pounding run` prints it before the files it wrote
    assert out.stdout.startswith(r.summary_text() + "\nwrote ")


def test_one_record_has_no_suite(examples: Path) -> None:
    r = pounding.run(pounding.Scenario.from_file(examples / "two-levels.toml"), check=False)
    assert r.suite is None and r.records == [] and r.statistics == {}


def _csv_rows(path: Path) -> list[dict[str, str]]:
    import csv

    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_sweep_over_a_suite_gives_the_suite_rows(examples: Path, tmp_path: Path, cli) -> None:
    """`pounding.sweep` over a suite scenario: one row per case with the suite's answer, the
    same fields as `pounding sweep`'s results.csv (the binary), the design value unchanged
    along the gap axis and the verdict gap ≥ design value at every level."""
    sc = pounding.Scenario.from_file(examples / "suite-ec8.toml")
    axes = {"contact.level.1.gap": [0.1, 0.4]}
    table = pounding.sweep(sc, axes=axes, check=False, jobs=2)
    assert table["statistic"] == ["max", "max"]  # EC8, 5 records: the most unfavourable
    assert list(table["records"]) == [5.0, 5.0]
    req = table["level1_required_separation"]
    assert req[0] == req[1]  # the runs without contact give it: the gap does not move it
    for i, gap in enumerate(axes["contact.level.1.gap"]):
        levels = [k for k in table if k.endswith("_required_separation")]
        ok = all(
            table[k.replace("required_separation", "gap")][i] >= table[k][i] for k in levels
        )
        assert table["sufficient"][i] == str(ok).lower()
        assert table["level1_gap"][i] == gap
    assert "peak_displacement_1" not in table  # a suite's row, not a single run's
    sweep_file = tmp_path / "s.toml"
    sweep_file.write_text(
        f'scenario = "{(examples / "suite-ec8.toml").as_posix()}"\n'
        '[[axis]]\nkey = "contact.level.1.gap"\nvalues = [0.1, 0.4]\n'
    )
    out = cli("sweep", sweep_file, "--out", tmp_path / "o", "--no-check", "--no-plot", "-q")
    assert out.returncode == 0, out.stderr
    rows = _csv_rows(tmp_path / "o" / "results.csv")
    assert list(rows[0]) == list(table)
    for i, row in enumerate(rows):
        for k, v in row.items():
            got = table[k][i]
            if isinstance(got, str):
                assert got == v, k
            else:
                if v in ("", "NaN"):  # check_max_change unchecked, the ratio of rule none
                    assert got != got, k
                else:
                    assert float(v) == got, k


def test_dask_sweep_over_a_suite(examples: Path) -> None:
    """The Dask route computes the same suite rows as `pounding.sweep`."""
    import numpy as np

    from conftest import need

    distributed = need("dask.distributed")
    import pounding.distributed as pd_dask

    sc = pounding.Scenario.from_file(examples / "suite-ec8.toml")
    axes = {"contact.level.1.gap": [0.1, 0.4]}
    local = pounding.sweep(sc, axes=axes, check=False, jobs=1)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        table = pd_dask.sweep(client, sc, axes=axes, check=False)
    assert list(table) == list(local)
    for k in local:
        np.testing.assert_array_equal(table[k], local[k], err_msg=k)


def test_row_suite_run_gives_per_pair_results(examples: Path, tmp_path: Path, cli) -> None:
    """A suite of records on a row of buildings (examples/suite-row.toml): a RowResult with the
    suite's records, statistics and per-pair design values (EN 1998-1 with 3 records: the
    largest per pair and level, computed here), the row's verdict at the least margin, and
    the command line's files byte for byte."""
    sc = pounding.Scenario.from_file(examples / "suite-row.toml")
    r = pounding.run(sc, check=False)
    assert isinstance(r, pounding.RowResult)
    assert r.suite is not None and len(r.records) == 3
    design = r.suite["design"]
    assert design["statistic"] == "max"
    least = None
    for pair in design["pairs"]:
        p = pair["pair"]
        for level in pair["levels"]:
            key = f"pair{p}_level{level['level']}_required_separation"
            values = [rec[key] for rec in r.records]
            assert level["required"] == max(values)
            assert r.statistics[key]["mean"] == pytest.approx(statistics.fmean(values), rel=1e-12)
            margin = level["gap"] - max(values)
            if least is None or margin < least[0]:
                least = (margin, p, level["level"])
    assert (design["governing_pair"], design["governing_level"]) == least[1:]
    # the top level is the representative record's run of the row, with every pair
    assert len(r.summary["pairs"]) == 2 and len(r.summary["structures"]) == 3
    written = r.save(tmp_path / "py", plots=False)
    assert Path(written[-1]).name == "summary.json"
    out = cli("run", examples / "suite-row.toml", "--out", tmp_path / "cli", "--no-check", "--no-plot")
    assert out.returncode == 0, out.stderr
    for f in ("summary.json", "suite.csv", "history.csv", "records/01/summary.json"):
        assert (tmp_path / "py" / f).read_text() == (tmp_path / "cli" / f).read_text(), f
    assert out.stdout.startswith(r.summary_text() + "\nwrote ")


def test_row_suite_sweep_columns_have_their_dtypes_and_equal_results_csv(
    examples: Path, tmp_path: Path, cli
) -> None:
    """A sweep over a suite of records on a row (examples/suite-row-sweep.toml: a row of three,
    pair 1 with two levels, pair 2 with one; 3 stiffnesses x 3 gaps): the suite-on-a-row
    columns in the documented order, each of its documented type (the verdicts, `statistic`
    and `converged` lists of str, every other column float64, `case` int64), the margins
    gap - design value exactly as the file's, and every field equal to results.csv of
    `pounding sweep` (numbers read back bit for bit; an empty field is NaN)."""
    import numpy as np

    table = pounding.sweep(examples / "suite-row-sweep.toml", check=False, jobs=2)
    axes = ["structure.2.stiffness_scale", "contact.2.gap"]
    own = ["structures", "records", "statistic", "min_mean_to_target_ratio", "sufficient",
           "governing_pair", "governing_height", "governing_margin"]
    per_pair = ["sufficient", "governing_height", "required", "margin", "peak_force"]
    for p, levels in ((1, 2), (2, 1)):
        own += [f"pair{p}_{c}" for c in per_pair]
        own += [f"pair{p}_level{k}_required_separation" for k in range(1, levels + 1)]
    own += ["check_max_change", "converged"]
    assert list(table) == ["case", *axes, "status", *own]
    text = {"status", "statistic", "sufficient", "converged", "pair1_sufficient",
            "pair2_sufficient"}
    n = 9
    assert table["case"].dtype == np.int64 and list(table["case"]) == list(range(n))
    for k, v in table.items():
        if k == "case":
            continue
        if k in text:
            assert isinstance(v, list) and len(v) == n, k
            assert all(isinstance(x, str) for x in v), k
        else:
            assert isinstance(v, np.ndarray) and v.dtype == np.float64 and v.shape == (n,), k
    assert table["status"] == ["ok"] * n
    assert table["statistic"] == ["max"] * n  # EN 1998-1 with 3 records: the largest
    assert table["converged"] == ["unchecked"] * n
    assert np.isnan(table["check_max_change"]).all()
    assert (table["structures"] == 3.0).all() and (table["records"] == 3.0).all()
    for i in range(n):
        # pair 2's one level is the swept gap: its margin is gap - design value, as computed
        gap = table["contact.2.gap"][i]
        assert table["pair2_margin"][i] == gap - table["pair2_required"][i]
        assert table["pair2_required"][i] == table["pair2_level1_required_separation"][i]
        assert table["pair2_sufficient"][i] == str(bool(gap >= table["pair2_required"][i])).lower()
        margins = [table["pair1_margin"][i], table["pair2_margin"][i]]
        assert table["governing_margin"][i] == min(margins)
        assert table["governing_pair"][i] == 1 + margins.index(min(margins))
        ok = all(table[f"pair{p}_sufficient"][i] == "true" for p in (1, 2))
        assert table["sufficient"][i] == str(ok).lower()
    out = cli("sweep", examples / "suite-row-sweep.toml", "--out", tmp_path / "o", "--no-check",
              "--no-plot", "-q")
    assert out.returncode == 0, out.stderr
    rows = _csv_rows(tmp_path / "o" / "results.csv")
    assert len(rows) == n and list(rows[0]) == list(table)
    for i, row in enumerate(rows):
        for k, v in row.items():
            got = table[k][i]
            if isinstance(got, str):
                assert got == v, k
            elif v in ("", "NaN"):
                assert np.isnan(got), k
            else:
                assert float(v) == got, k
