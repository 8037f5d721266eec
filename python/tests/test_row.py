"""A row of buildings from Python (issue 29): `pounding.run` on a row gives a RowResult with
arrays per structure and per pair."""

from __future__ import annotations

import json

import numpy as np

import pounding


def building(name: str, n: int, k: float) -> str:
    return (
        f'[[structure]]\nname = "{name}"\nkind = "shear-building"\nstoreys = {n}\n'
        f"storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\n"
        f"damping_ratio = 0.05\nmodes = {n}\n"
    )


def contact(a: str, b: str, h: float, gap: float) -> str:
    return (
        f'[[contact]]\nbetween = ["{a}", "{b}"]\nlaw = "hertz"\nstiffness = 2.0e10\n'
        f"height = {h}\ngap = {gap}\n"
    )


HARMONIC = '[ground_motion]\nkind = "harmonic"\npga = 0.35\nperiod = 0.8\n'
SOLVER = '[solver]\nmethod = "exact-modal"\ndt = 0.002\nduration = 6.0\n'


def test_a_row_whose_second_gap_never_closes_gives_the_pairs_arrays(tmp_path):
    # A (4 storeys, 14 m) and B (5, 17.5 m) pound at 14 m, B's highest contact level; the gap
    # B–C (10 m) never closes: the first pair's arrays are the pair's, to the last digit (the
    # same arithmetic; the Rust test tests/row_outputs.rs checks the files)
    ab = building("A", 4, 3.0e8) + building("B", 5, 1.6e8)
    row = pounding.Scenario.from_toml(
        ab + building("C", 3, 1.0e8) + contact("A", "B", 14.0, 0.01)
        + contact("B", "C", 10.5, 10.0) + HARMONIC + SOLVER,
        "row.toml",
        str(tmp_path),
    )
    pair = pounding.Scenario.from_toml(
        ab + contact("A", "B", 14.0, 0.01) + HARMONIC + SOLVER, "pair.toml", str(tmp_path)
    )
    assert row.is_row and not pair.is_row
    r = pounding.run(row, check=False)
    p = pounding.run(pair, check=False)
    assert isinstance(r, pounding.RowResult) and isinstance(p, pounding.RunResult)
    assert p.summary["contact"]["impacts"] > 0
    assert list(r.structures) == ["A", "B", "C"]
    a, b = r.structures["A"], r.structures["B"]
    for got, want in [
        (a["t"], p.history["t"]),
        (a["w"], p.history["w1"]),
        (b["w"], p.history["w2"]),
        (a["w_free"], p.history["w1_free"]),
        (b["w_free"], p.history["w2_free"]),
    ]:
        assert got.dtype == np.float64
        np.testing.assert_array_equal(got, want)
    first, second = r.pairs
    assert first["between"] == ("A", "B") and second["between"] == ("B", "C")
    np.testing.assert_array_equal(first["force"], p.history["force"])
    assert not second["force"].any()
    assert len(second["impacts"]["start"]) == 0
    for k in ["start", "end", "peak_force", "impulse", "approach_speed"]:
        np.testing.assert_array_equal(first["impacts"][k], p.impacts[k])
    assert set(r.impacts["left"]) == {"A"} and set(r.impacts["right"]) == {"B"}
    # the history columns are history.csv's, named after the structures and pairs
    assert list(r.history)[:5] == ["t", "w_A", "w_B", "w_C", "force_A_B_1"]
    np.testing.assert_array_equal(r.history["w_C"], r.structures["C"]["w"])
    assert "w_C_10.5" in r.floors and "a_B_17.5_free" in r.floors
    # the text and the summary are the command line's
    text = r.summary_text()
    assert "a row of 3 structures" in text and "NOT self-checked" in text
    s = r.summary
    assert [x["name"] for x in s["structures"]] == ["A", "B", "C"]
    assert s["accuracy"]["checked"] is False
    # saved: the files of `pounding run`, summary.json last, history.csv the arrays' numbers
    files = r.save(tmp_path / "out", plots=False)
    assert files[-1].endswith("summary.json")
    assert json.loads((tmp_path / "out" / "summary.json").read_text()) == s
    lines = (tmp_path / "out" / "history.csv").read_text().splitlines()
    assert lines[0].split(",") == list(r.history)
    assert len(lines) - 1 == len(a["t"])


def test_a_row_is_self_checked(tmp_path):
    row = pounding.Scenario.from_toml(
        building("A", 3, 3.0e8) + building("B", 5, 1.6e8) + building("C", 4, 2.2e8)
        + contact("A", "B", 10.5, 0.004) + contact("B", "C", 14.0, 0.006) + HARMONIC
        + '[solver]\nduration = 3.0\n',
        "row.toml",
        str(tmp_path),
    )
    r = pounding.run(row)
    assert r.summary["accuracy"]["converged"] is True
    assert "self-check: converged" in r.summary_text()
    assert "peak_force_A_B" in r.summary["accuracy"]["quantities"]
