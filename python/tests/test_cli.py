"""The Python package against the command line of the same sources: the same numbers, bit for
bit, the same files, the same tables and the same error messages."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest

import pounding

SCENARIOS = ["paper-c.toml", "two-levels.toml", "shear-buildings.toml", "loma-prieta.toml"]


@pytest.mark.parametrize("name", SCENARIOS)
def test_summary_is_bit_identical_to_the_cli(cli, examples: Path, tmp_path: Path, name: str) -> None:
    p = cli("run", examples / name, "--out", tmp_path / "cli", "--no-plot", "-q")
    assert p.returncode == 0, p.stderr
    res = pounding.run(pounding.Scenario.from_file(examples / name))
    text = (tmp_path / "cli" / "summary.json").read_text()
    assert res.summary_json == text
    assert res.summary == json.loads(text)
    # the files of save() are the CLI's, byte for byte
    res.save(tmp_path / "py", plots=False)
    for f in ["history.csv", "impacts.csv", "floors.csv", "summary.json"]:
        assert (tmp_path / "py" / f).read_bytes() == (tmp_path / "cli" / f).read_bytes(), f


def read_csv_columns(path: Path) -> dict[str, list[str]]:
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return {k: [r[j] for r in rows[1:]] for j, k in enumerate(rows[0])}


def test_arrays_are_the_csv_files(cli, examples: Path, tmp_path: Path) -> None:
    p = cli("run", examples / "two-levels.toml", "--out", tmp_path, "--no-plot", "-q")
    assert p.returncode == 0, p.stderr
    res = pounding.run(pounding.Scenario.from_file(examples / "two-levels.toml"))
    for name, arrays in [("history.csv", res.history), ("impacts.csv", res.impacts), ("floors.csv", res.floors)]:
        cols = read_csv_columns(tmp_path / name)
        assert list(cols) == list(arrays), name
        for k, text in cols.items():
            expected = np.array([float(x) for x in text])
            np.testing.assert_array_equal(arrays[k], expected, err_msg=f"{name}:{k}")


def typed(values: list[str], like: object) -> object:
    if isinstance(like, list):
        return values
    dtype = like.dtype  # type: ignore[attr-defined]
    if dtype == np.int64:
        return np.array([int(v) for v in values], dtype=np.int64)
    return np.array([float(v) if v != "" else math.nan for v in values])


@pytest.mark.parametrize("sweep_file, args", [
    ("quick-sweep.toml", ["--no-check"]),
    ("quick-sweep.toml", []),
    ("record-sweep.toml", ["--no-check"]),
])
def test_sweep_table_is_results_csv(cli, examples: Path, tmp_path: Path, sweep_file: str, args: list[str]) -> None:
    p = cli("sweep", examples / sweep_file, "--out", tmp_path, "--no-plot", "-q", "-j", "2", *args)
    assert p.returncode == 0, p.stderr
    table = pounding.sweep(examples / sweep_file, jobs=2, check="--no-check" not in args)
    cols = read_csv_columns(tmp_path / "results.csv")
    assert list(cols) == list(table)
    for k, text in cols.items():
        np.testing.assert_array_equal(table[k], typed(text, table[k]), err_msg=k)


def cli_error(p) -> str:
    assert p.returncode == 2, (p.stdout, p.stderr)
    assert p.stderr.startswith("error: ")
    return p.stderr[len("error: "):].rstrip("\n")


BAD_SCENARIOS = {
    "range": ("gap = 0.0127", "gap = -0.5"),
    "unknown key": ("gap = 0.0127", "gapp = 0.0127"),
    "syntax": ("gap = 0.0127", "gap = = 1"),
    "missing": ("gap = 0.0127", ""),
    "type": ("gap = 0.0127", 'gap = "wide"'),
}


@pytest.mark.parametrize("case", sorted(BAD_SCENARIOS))
def test_scenario_errors_carry_the_cli_message(cli, examples: Path, tmp_path: Path, case: str) -> None:
    old, new = BAD_SCENARIOS[case]
    text = (examples / "paper-c.toml").read_text()
    assert old in text
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace(old, new))
    message = cli_error(cli("run", bad, "--out", tmp_path / "out"))
    with pytest.raises(pounding.ScenarioError) as e:
        pounding.Scenario.from_file(bad)
    assert str(e.value) == message
    assert str(bad) in message  # file:line:col
    with pytest.raises(pounding.ScenarioError) as e:
        pounding.Scenario.from_toml(bad.read_text(), name=str(bad))
    assert str(e.value) == message


def test_missing_file_error(cli, tmp_path: Path) -> None:
    message = cli_error(cli("run", tmp_path / "nope.toml", "--out", tmp_path / "out"))
    with pytest.raises(pounding.ScenarioError) as e:
        pounding.Scenario.from_file(tmp_path / "nope.toml")
    assert str(e.value) == message


def test_solve_error_carries_the_cli_message(cli, examples: Path, tmp_path: Path) -> None:
    f = examples / "design-spectrum.toml"
    message = cli_error(cli("run", f, "--out", tmp_path / "out"))
    with pytest.raises(pounding.SolveError) as e:
        pounding.run(pounding.Scenario.from_file(f))
    assert str(e.value) == message


def test_unstable_step_error_carries_the_cli_message(cli, examples: Path, tmp_path: Path) -> None:
    # a contact too stiff for RK4 at 1 ms: refused at its first impact (a SolveError)
    text = (examples / "paper-c.toml").read_text().replace("\nstiffness = 2.808e10", "\nstiffness = 1e17", 1)
    assert "stiffness = 1e17" in text
    f = tmp_path / "stiff.toml"
    f.write_text(text)
    message = cli_error(cli("run", f, "--out", tmp_path / "out"))
    assert "rk4 refused at t = " in message
    with pytest.raises(pounding.SolveError) as e:
        pounding.run(pounding.Scenario.from_file(f))
    assert str(e.value) == message
    assert not (tmp_path / "out").exists()


def test_replace_refuses_an_unstable_step(examples: Path) -> None:
    sc = pounding.Scenario.from_file(examples / "paper-c.toml")
    with pytest.raises(pounding.ScenarioError, match=r"paper-c.toml \(replaced\):\d+:\d+: `solver.dt` = 0.05: time step dt = 0.05 s is beyond rk4's stability limit"):
        sc.replace({"solver.dt": 0.05})


def test_sweep_errors_carry_the_cli_message(cli, examples: Path, tmp_path: Path) -> None:
    bad = tmp_path / "bad-sweep.toml"
    bad.write_text(f'scenario = "{examples / "paper-c.toml"}"\n[[axis]]\nkey = "ground_motion.pgaa"\nvalues = [0.1]\n')
    message = cli_error(cli("sweep", bad, "--out", tmp_path / "out"))
    with pytest.raises(pounding.SweepError) as e:
        pounding.sweep(bad)
    assert str(e.value) == message
