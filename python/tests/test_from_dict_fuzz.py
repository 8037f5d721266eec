"""`Scenario.from_dict` on randomly mutated scenarios (issue 15's fuzzing of `from_dict`, from
the Python side: the conversion of Python objects in `pounding._core` as well as the library
entry behind it, which `fuzz/fuzz_targets/from_dict.rs` fuzzes with libFuzzer). Every input must
give a `Scenario` or a `ScenarioError` — no other exception, no crash of the interpreter."""

from __future__ import annotations

import copy
import math
import random
from pathlib import Path

import numpy as np

import pounding

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib  # type: ignore[no-redef]

# values a notebook may put anywhere: wrong types, non-finite and extreme numbers, NumPy kinds
ODD_VALUES = [
    None, math.nan, math.inf, -math.inf, -1, 0, 1, -0.0, 1e308, 5e-324, 2**70, -(2**63),
    "", "x", "hertz", "rk4", "adaptive", "bouc-wen", True, False, [], {}, [1.0, 2.0], [[1.0]],
    {"a": 1}, np.float32(np.nan), np.float64(-1e300), np.int64(-5), np.uint64(2**64 - 1),
    np.bool_(True), np.array([1.0, 2.0]), np.array([[1.0, 2.0], [3.0, 4.0]]), np.zeros(0),
    1 + 2j, object(), b"bytes", (1, 2),
]


def _odd(rng: random.Random):
    """One of ODD_VALUES, a copy of its own (a shared list or dict, mutated later, could come to
    contain itself)."""
    return copy.deepcopy(rng.choice(ODD_VALUES))


def _containers(node, out):
    """Every (container, key) pair of a nested dict/list structure."""
    if isinstance(node, dict):
        for k in list(node):
            out.append((node, k))
            _containers(node[k], out)
    elif isinstance(node, list):
        for i, x in enumerate(node):
            out.append((node, i))
            _containers(x, out)
    return out


def _mutate(data, rng: random.Random):
    for _ in range(rng.randint(1, 3)):
        places = _containers(data, [])
        if not places:
            return
        parent, key = rng.choice(places)
        action = rng.random()
        value = parent[key]
        if action < 0.45 and isinstance(value, (int, float)) and not isinstance(value, bool):
            # a number moved, often within its range, sometimes far outside
            factor = rng.choice([0.5, 0.9, 1.1, 2.0, -1.0, 0.0, 1e-12, 1e12, 1e300])
            parent[key] = type(value)(value * factor) if isinstance(value, float) else value * int(factor)
        elif action < 0.75:
            parent[key] = _odd(rng)
        elif action < 0.85 and isinstance(parent, dict):
            del parent[key]
        elif action < 0.92 and isinstance(parent, dict):
            parent[rng.choice(["gapp", "hysteresis", "modes", "level", "kind", "1"])] = _odd(rng)
        else:
            parent[key] = [value] * rng.randint(0, 3)


def test_mutated_scenarios_give_a_scenario_or_a_scenario_error(examples: Path) -> None:
    bases = []
    for f in sorted(examples.glob("*.toml")):
        data = tomllib.loads(f.read_text())
        if "scenario" not in data:  # not a sweep file
            pounding.Scenario.from_dict(data, base_dir=examples)  # each base is valid as it is
            bases.append(data)
    assert len(bases) >= 10
    rng = random.Random(20261123)
    accepted = refused = 0
    for _ in range(20000):
        data = copy.deepcopy(rng.choice(bases))
        _mutate(data, rng)
        try:
            pounding.Scenario.from_dict(data, base_dir=examples)
            accepted += 1
        except pounding.ScenarioError as e:
            assert str(e), "an error must say what is wrong"
            refused += 1
    # the mutations reach both outcomes, or the test proves nothing
    assert accepted > 600 and refused > 10000, (accepted, refused)
