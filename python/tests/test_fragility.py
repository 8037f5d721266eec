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


ROW_STUDY = """scenario = "row.toml"
[ground_motion]
records = [
  {{ file = "{records}/RSN753_LOMAP_CLS000.AT2" }},
  {{ file = "{records}/RSN786_LOMAP_PAE055.AT2" }},
  {{ file = "{records}/INGLEWOO.V2", component = 1 }},
]
[intensity]
measure = "sa"
structure = 2
[[limit_state]]
kind = "pounding"
[[limit_state]]
kind = "ductility"
value = 2.0
[fragility]
stripes = [0.05, 0.2]
gaps = [0.0, 0.02, 0.05, 0.1, 0.2]
target = {{ im = 0.2, probability = 0.4 }}
bootstrap = 20
"""


def test_fragility_of_a_row_is_per_pair_and_per_structure(tmp_path: Path, examples: Path) -> None:
    # the bundled row (A4, B8 yielding, C5), 8 s of motion
    base = (examples / "fragility-row-frames.toml").read_text().replace("duration = 20.0", "duration = 8.0")
    base = base.replace('file = "records/', f'file = "{examples}/records/')
    (tmp_path / "row.toml").write_text(base)
    study = tmp_path / "study.toml"
    study.write_text(ROW_STUDY.format(records=examples / "records"))
    r = pounding.fragility(study, jobs=2, plots=False)
    assert r.structures == ["A4", "B8", "C5"]
    # the row's pounding, then each pair's; the ductility of B8, the one yielding building
    names = [f["limit_state"] for f in r.fits if f["model"] == "without"]
    assert names == ["pounding", "pounding(1-2)", "pounding(2-3)", "ductility>2", "ductility>2(2)"]
    assert len(r.pairs) == 2
    for q in r.pairs:
        p = q["pair"]
        assert q["between"] == r.structures[p - 1 : p + 1]
        assert [f["limit_state"] for f in q["fits"]] == [f"pounding({p}-{p + 1})"] * 2
        # each pair's P(pounding | IM, gap): the fraction of records whose critical gap of that
        # pair (runs.csv) exceeds the gap
        crit = r.runs[f"pair{p}_critical_gap"]
        for im, gap, pp in zip(q["p_pounding"]["im"], q["p_pounding"]["gap"], q["p_pounding"]["p_pounding"]):
            assert pp == np.mean(crit[r.runs["im"] == im] > gap)
        # the critical gap is the largest required separation over the pair's levels
        req = np.maximum(r.runs[f"pair{p}_level1_required_separation"], r.runs[f"pair{p}_level2_required_separation"])
        np.testing.assert_array_equal(crit, req)
        # the target: ⌊0.4 · 3⌋ = 1 record may pound: the second largest critical gap at 0.2 g
        t = q["target_gap"]
        assert t["pair"] == p and t["records"] == 3
        assert t["empirical"] == sorted(crit[r.runs["im"] == 0.2])[-2]
        # with contact, pounding of the pair is an impact of the pair (runs.csv)
        f = next(f for f in q["fits"] if f["model"] == "with")
        for j, im in enumerate((0.05, 0.2)):
            assert f["exceedances"][j] == int(np.sum(r.runs[f"pair{p}_impacts"][r.runs["im"] == im] > 0))
    # the row pounds when some pair pounds (with contact: some pair has an impact)
    row = next(f for f in r.fits if f["limit_state"] == "pounding" and f["model"] == "with")
    for j, im in enumerate((0.05, 0.2)):
        at = r.runs["im"] == im
        assert row["exceedances"][j] == int(np.sum((r.runs["pair1_impacts"][at] > 0) | (r.runs["pair2_impacts"][at] > 0)))
