"""Suites of records (issue 27): `pounding.run` on a `kind = "suite"` scenario returns the
per-record results and the statistics, and writes what `pounding run` writes."""

from __future__ import annotations

import statistics
from pathlib import Path

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
