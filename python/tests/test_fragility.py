"""Fragility studies (issue 28): `pounding.fragility` returns the tables and fits of
`pounding fragility`, the same numbers as the files the command line writes."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

import pounding

STUDY = """scenario = "{scenario}"
[ground_motion]
records = [
  {{ file = "{records}/RSN753_LOMAP_CLS000.AT2" }},
  {{ file = "{records}/RSN753_LOMAP_CLS090.AT2" }},
  {{ file = "{records}/RSN786_LOMAP_PAE055.AT2" }},
]
[intensity]
measure = "pga"
[[limit_state]]
kind = "pounding"
[[limit_state]]
kind = "drift_ratio"
value = 0.005
[fragility]
stripes = [0.1, 0.3]
gaps = [0.0, 0.05, 0.1, 0.2]
target = {{ im = 0.3, probability = 0.3 }}
bootstrap = 20
"""


def _study(tmp_path: Path, examples: Path) -> Path:
    # a short base scenario: the example's buildings, 8 s of motion
    base = (examples / "fragility-frames.toml").read_text().replace("duration = 30.0", "duration = 8.0")
    base = base.replace('file = "records/', f'file = "{examples}/records/')
    (tmp_path / "base.toml").write_text(base)
    p = tmp_path / "study.toml"
    p.write_text(STUDY.format(scenario="base.toml", records=examples / "records"))
    return p


def test_fragility_tables_equal_the_files(tmp_path: Path, examples: Path, cli) -> None:
    study = _study(tmp_path, examples)
    r = pounding.fragility(study, jobs=2, out=tmp_path / "py", plots=False)
    assert isinstance(r, pounding.FragilityResult)
    # 3 records × 2 stripes
    assert r.fit["runs"] == 6 and len(r.runs["record"]) == 6
    # pounding with and without contact, drift with and without: 4 curves × 2 stripes
    assert len(r.fragility["im"]) == 8
    assert set(r.fragility["model"]) == {"with", "without"}
    np.testing.assert_array_equal(r.fragility["fraction"], r.fragility["exceedances"] / r.fragility["runs"])
    # P(pounding) is the fraction of records whose critical gap (runs.csv) exceeds the gap
    for im, gap, p in zip(r.p_pounding["im"], r.p_pounding["gap"], r.p_pounding["p_pounding"]):
        at = r.runs["im"] == im
        assert p == pytest.approx(np.mean(r.runs["critical_gap"][at] > gap), abs=1e-15)
    assert r.target_gap is not None and r.target_gap["records"] == 3
    # the files written are these tables; the command line writes the same numbers
    assert json.loads((tmp_path / "py" / "fit.json").read_text()) == r.fit
    out = cli("fragility", study, "--out", tmp_path / "cli", "--no-plot", "-j", "1")
    assert out.returncode == 0, out.stderr
    for f in ("fragility.csv", "p_pounding.csv", "runs.csv", "fit.json"):
        assert (tmp_path / "py" / f).read_text() == (tmp_path / "cli" / f).read_text(), f
    with open(tmp_path / "cli" / "fragility.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [float(x["exceedances"]) for x in rows] == list(r.fragility["exceedances"])


def test_fragility_bad_study_raises_scenario_error(tmp_path: Path) -> None:
    p = tmp_path / "study.toml"
    p.write_text('scenario = "nothere.toml"\n')
    with pytest.raises(pounding.ScenarioError, match="`scenario`"):
        pounding.fragility(p)
