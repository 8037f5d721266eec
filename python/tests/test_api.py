"""Every call of the Python API: scenarios, runs, arrays, pandas, saving, sweeps, pickling."""

from __future__ import annotations

import math
import pickle
try:
    import tomllib
except ImportError:  # Python 3.10
    import tomli as tomllib
from pathlib import Path

import numpy as np
import pytest

import pounding
from conftest import need

HISTORY = ["t", "w1", "w2", "force", "w1_free", "w2_free"]
IMPACTS = ["level", "height", "start", "end", "duration", "peak_force", "impulse",
           "max_penetration", "approach_speed"]


@pytest.fixture(scope="module")
def paper(examples: Path) -> pounding.Scenario:
    return pounding.Scenario.from_file(examples / "paper-c.toml")


@pytest.fixture(scope="module")
def paper_run(paper: pounding.Scenario) -> pounding.RunResult:
    return pounding.run(paper)


def test_scenario_constructors_agree(examples: Path, paper: pounding.Scenario) -> None:
    text = (examples / "paper-c.toml").read_text()
    from_text = pounding.Scenario.from_toml(text, name="paper", base_dir=examples)
    data = tomllib.loads(text)
    from_dict = pounding.Scenario.from_dict(data)
    assert paper.title == from_text.title == from_dict.title
    assert paper.toml == text
    a = pounding.run(paper, check=False).summary
    assert a == pounding.run(from_text, check=False).summary
    assert a == pounding.run(from_dict, check=False).summary


def test_from_dict_takes_numpy_numbers(examples: Path) -> None:
    data = tomllib.loads((examples / "paper-c.toml").read_text())
    plain = pounding.Scenario.from_dict(data)
    data["structure"][1]["period"] = np.float64(data["structure"][1]["period"])
    data["structure"][0]["modes"] = np.int32(data["structure"][0]["modes"])
    data["structure"][0]["damping_ratio"] = np.float32(0.5)  # exact in float32: the same 0.5
    plain = plain.replace({"structure.1.damping_ratio": 0.5})
    data["solver"]["duration"] = np.array(2.0)[()]  # a NumPy 0-d scalar
    sc = pounding.Scenario.from_dict(data)
    assert sc.toml.count("modes = 3") == 2
    plain2 = plain.replace({"solver.duration": 2.0})
    assert pounding.run(sc, check=False).summary["structures"] == \
        pounding.run(plain2, check=False).summary["structures"]


def test_from_dict_refuses_other_objects_naming_the_key(examples: Path) -> None:
    data = tomllib.loads((examples / "paper-c.toml").read_text())
    data["structure"][1]["mass"] = 1 + 2j
    with pytest.raises(pounding.ScenarioError, match=r"<dict>: `structure\[2\]\.mass`: a value of type complex"):
        pounding.Scenario.from_dict(data)
    data["structure"][1]["mass"] = None
    with pytest.raises(pounding.ScenarioError, match=r"`structure\[2\]\.mass`"):
        pounding.Scenario.from_dict(data)
    with pytest.raises(pounding.ScenarioError, match="not a string"):
        pounding.Scenario.from_dict({1: 2})


def test_from_dict_validates_as_a_file(examples: Path) -> None:
    data = tomllib.loads((examples / "paper-c.toml").read_text())
    data["contact"]["gap"] = -1.0
    with pytest.raises(pounding.ScenarioError, match=r"`contact.gap` = -1: must be a finite number ≥ 0 \(m\)"):
        pounding.Scenario.from_dict(data)
    data["contact"]["gap"] = 0.01
    data["contact"]["gapp"] = 0.01
    with pytest.raises(pounding.ScenarioError, match="unknown key `gapp`"):
        pounding.Scenario.from_dict(data)
    assert issubclass(pounding.ScenarioError, ValueError)


def test_replace_sets_key_paths(paper: pounding.Scenario) -> None:
    sc2 = paper.replace({"structure.2.period": 0.5, "ground_motion.pga": 0.4})
    t = tomllib.loads(sc2.toml)
    assert t["structure"][1]["period"] == 0.5
    assert t["ground_motion"]["pga"] == 0.4
    assert "structure.2.period = 0.5" in sc2.title
    # the derived key of sweeps: T1/T2 sets structure 2's period
    r = tomllib.loads(paper.replace({"period_ratio": 0.5}).toml)
    assert r["structure"][1]["period"] == t["structure"][0]["period"] / 0.5
    assert tomllib.loads(paper.toml)["ground_motion"]["pga"] == 0.6  # unchanged
    with pytest.raises(pounding.ScenarioError, match=r"`structure.2.perio`: unknown axis key; did you mean `structure.N.period`"):
        paper.replace({"structure.2.perio": 0.5})
    with pytest.raises(pounding.ScenarioError, match=r"`structure\[2\].period` = -0.5"):
        paper.replace({"structure.2.period": -0.5})


def test_history_arrays(paper_run: pounding.RunResult, paper: pounding.Scenario) -> None:
    h = paper_run.history
    assert list(h) == HISTORY
    solver = tomllib.loads(paper.toml)["solver"]
    n = round(solver["duration"] / solver["output_interval"]) + 1
    for k, v in h.items():
        assert isinstance(v, np.ndarray) and v.dtype == np.float64 and v.ndim == 1, k
        assert len(v) == n, k
    assert h["t"][0] == 0.0 and h["t"][-1] == pytest.approx(solver["duration"])
    assert np.all(np.diff(h["t"]) > 0)
    assert np.max(np.abs(h["w1"])) <= paper_run.summary["structures"][0]["peak_displacement"]
    assert np.all(h["force"] >= 0) and np.max(h["force"]) > 0


def test_impact_arrays(paper_run: pounding.RunResult) -> None:
    imp = paper_run.impacts
    assert list(imp) == IMPACTS
    n = paper_run.summary["contact"]["impacts"]
    assert n > 0
    assert imp["level"].dtype == np.int64 and set(imp["level"]) == {1}
    for k in IMPACTS[1:]:
        assert imp[k].dtype == np.float64 and len(imp[k]) == n, k
    assert np.array_equal(imp["duration"], imp["end"] - imp["start"])
    assert imp["peak_force"].max() == paper_run.summary["contact"]["peak_force"]


def test_floor_arrays(paper_run: pounding.RunResult) -> None:
    f = paper_run.floors
    assert next(iter(f)) == "t"
    assert np.array_equal(f["t"], paper_run.history["t"])
    cols = list(f)[1:]
    half = len(cols) // 2
    assert cols[half:] == [c + "_free" for c in cols[:half]]
    assert all(v.dtype == np.float64 and len(v) == len(f["t"]) for v in f.values())


def test_several_levels_have_their_forces(examples: Path) -> None:
    r = pounding.run(pounding.Scenario.from_file(examples / "two-levels.toml"), check=False)
    levels = len(r.summary["levels"])
    assert levels > 1
    h = r.history
    assert list(h) == HISTORY + [f"force_{k}" for k in range(1, levels + 1)]
    assert np.array_equal(h["force"], sum(h[f"force_{k}"] for k in range(1, levels + 1)))
    assert set(r.impacts["level"]) <= set(range(1, levels + 1))


def test_to_pandas(paper_run: pounding.RunResult) -> None:
    pd = need("pandas")
    frames = paper_run.to_pandas()
    assert set(frames) == {"history", "impacts", "floors"}
    assert isinstance(frames["history"], pd.DataFrame)
    assert list(frames["history"].columns) == HISTORY
    assert len(frames["impacts"]) == paper_run.summary["contact"]["impacts"]


def test_summary_and_warnings(paper_run: pounding.RunResult) -> None:
    s = paper_run.summary
    assert s["accuracy"]["checked"] is True
    assert paper_run.warnings == s["warnings"]
    assert "structures" in s and "solver" in s


def test_save_writes_the_run(paper_run: pounding.RunResult, tmp_path: Path) -> None:
    files = paper_run.save(tmp_path / "out")
    names = [Path(f).name for f in files]
    assert names[-1] == "summary.json"
    assert names[:3] == ["history.csv", "impacts.csv", "floors.csv"]
    assert {"history.png", "history.svg", "envelopes.png", "envelopes.svg"} <= set(names)
    # without pictures: stale ones removed, as `--no-plot`
    files = paper_run.save(tmp_path / "out", plots=False)
    assert not (tmp_path / "out" / "history.png").exists()
    assert [Path(f).name for f in files] == ["history.csv", "impacts.csv", "floors.csv", "summary.json"]


def test_save_error_is_an_exception(paper_run: pounding.RunResult, tmp_path: Path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(pounding.OutputError, match="cannot write"):
        paper_run.save(blocker / "out", plots=False)


def test_spectrum_cannot_run(examples: Path) -> None:
    sc = pounding.Scenario.from_file(examples / "design-spectrum.toml")
    with pytest.raises(pounding.SolveError, match="design spectrum"):
        pounding.run(sc)
    assert issubclass(pounding.SolveError, RuntimeError)


def test_output_size_guard(paper: pounding.Scenario) -> None:
    with pytest.raises(pounding.ScenarioError, match="solver.output_interval"):
        pounding.run(paper, max_output_size=1000)


def test_sweep_file_table(examples: Path) -> None:
    t = pounding.sweep(examples / "quick-sweep.toml", jobs=2, check=False)
    assert list(t)[:4] == ["case", "period_ratio", "ground_motion.pga", "status"]
    assert list(t["case"]) == list(range(21))
    assert t["case"].dtype == np.int64 and t["period_ratio"].dtype == np.float64
    assert t["status"] == ["ok"] * 21 and t["converged"] == ["unchecked"] * 21
    assert np.all(np.isnan(t["check_max_change"]))
    assert all(len(v) == 21 for v in t.values())


def test_sweep_of_a_scenario_equals_the_sweep_file(examples: Path, paper: pounding.Scenario) -> None:
    by_file = pounding.sweep(examples / "quick-sweep.toml", jobs=2, check=False)
    by_axes = pounding.sweep(
        paper,
        axes={"period_ratio": {"from": 0.4, "to": 1.0, "steps": 7}, "ground_motion.pga": [0.2, 0.5, 0.8]},
        jobs=1,
        check=False,
    )
    assert list(by_file) == list(by_axes)
    for k in by_file:
        np.testing.assert_array_equal(by_file[k], by_axes[k], err_msg=k)


def test_sweep_errors(examples: Path, paper: pounding.Scenario, tmp_path: Path) -> None:
    with pytest.raises(pounding.SweepError, match="unknown axis key"):
        pounding.sweep(paper, axes={"ground_motion.pgaa": [0.1]})
    with pytest.raises(pounding.SweepError, match="cannot read"):
        pounding.sweep(tmp_path / "missing.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text(f'scenario = "{examples / "paper-c.toml"}"\n[[axis]]\nkey = "contact.gap"\nvalues = [-1.0]\n')
    with pytest.raises(pounding.SweepError, match="no case of the sweep is a valid scenario"):
        pounding.sweep(bad)


def test_a_failed_case_is_a_row(paper: pounding.Scenario) -> None:
    t = pounding.sweep(paper, axes={"contact.gap": [0.0127, -1.0]}, check=False, jobs=1)
    assert t["status"][0] == "ok"
    assert t["status"][1].startswith("failed: `contact.gap` = -1")
    assert math.isnan(t["peak_force"][1]) and math.isnan(t["impacts"][1])


def test_pickles(paper: pounding.Scenario, examples: Path) -> None:
    sc = pickle.loads(pickle.dumps(paper))
    assert sc.toml == paper.toml and sc.name == paper.name
    plan = pounding.plan_sweep(examples / "quick-sweep.toml")
    again = pickle.loads(pickle.dumps(plan))
    assert len(again) == len(plan) == 21
    assert again.run_case(5, False) == plan.run_case(5, False)
    assert again.case_toml(5) == plan.case_toml(5)


def test_installed_not_from_the_source_tree() -> None:
    here = Path(pounding.__file__).resolve()
    source = Path(__file__).resolve().parents[1] / "pounding"
    assert source not in here.parents, f"pounding imported from the source tree: {here}"
    assert "site-packages" in here.parts


def test_sweep_table_to_pandas(paper: pounding.Scenario) -> None:
    need("pandas")
    t = pounding.sweep(paper, axes={"contact.gap": [0.0127, -1.0]}, check=False, jobs=1)
    df = t.to_pandas()
    assert list(df.columns) == list(t)
    assert str(df["impacts"].dtype) == "Int64"
    assert df["impacts"][0] == t["impacts"][0] and df["impacts"].isna()[1]
    np.testing.assert_array_equal(df["peak_force"].to_numpy(), t["peak_force"])


def test_from_dict_refuses_a_list_containing_itself() -> None:
    loop: list = []
    loop.append(loop)
    with pytest.raises(pounding.ScenarioError, match="nested more than"):
        pounding.Scenario.from_dict({"structure": loop})
    d: dict = {}
    d["contact"] = d
    with pytest.raises(pounding.ScenarioError, match="nested more than"):
        pounding.Scenario.from_dict(d)
