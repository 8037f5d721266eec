"""A record scaled to a target spectral acceleration through the scenario key (issue 27):
`[ground_motion] scale_to_sa = { period, sa }` from Python, checked against an oscillator
written here and against the run of an explicitly scaled copy of the record."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import pounding

G = 9.80665
RECORD = "records/RSN753_LOMAP_CLS000.AT2"


def scenario(ground: dict) -> dict:
    return {
        "title": "scale_to_sa",
        "structure": [
            {"name": "a", "length": 10.0, "mass": 2.273e6, "period": 0.42, "modes": 2,
             "damping_ratio": 0.02},
            {"name": "b", "length": 10.0, "mass": 2.273e6, "period": 0.6, "modes": 2,
             "damping_ratio": 0.02},
        ],
        "contact": {"law": "hertz", "stiffness": 2.808e10, "gap": 0.02},
        "ground_motion": ground,
        "solver": {"method": "exact-modal", "dt": 0.005, "duration": 8.0},
    }


def read_at2(path: Path) -> tuple[float, list[float]]:
    """The AT2 file read here (four header lines, then values in g), in m/s²."""
    lines = path.read_text().splitlines()
    dt = float(lines[3].split("DT=")[1].split()[0])
    values = [float(x) * G for line in lines[4:] for x in line.split()]
    return dt, values


def psa_rk4(accel: list[float], dt: float, period: float, zeta: float, m: int) -> float:
    """ω²·max|u| by classical RK4 on m sub-steps per sample interval (a linear between samples,
    0 after the end, 3 periods of free vibration), the peak over the sub-step ends."""
    w = 2 * math.pi / period
    h = dt / m
    c, k = 2 * zeta * w, w * w
    u = v = peak = 0.0

    def step(a0: float, am: float, a1: float) -> None:
        nonlocal u, v, peak
        k1u, k1v = v, -a0 - c * v - k * u
        u2, v2 = u + 0.5 * h * k1u, v + 0.5 * h * k1v
        k2u, k2v = v2, -am - c * v2 - k * u2
        u3, v3 = u + 0.5 * h * k2u, v + 0.5 * h * k2v
        k3u, k3v = v3, -am - c * v3 - k * u3
        u4, v4 = u + h * k3u, v + h * k3v
        k4u, k4v = v4, -a1 - c * v4 - k * u4
        u += h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u)
        v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        peak = max(peak, abs(u))

    for a0, a1 in zip(accel, accel[1:]):
        for j in range(m):
            s, ds = j / m, 1 / m
            step(a0 + (a1 - a0) * s, a0 + (a1 - a0) * (s + ds / 2), a0 + (a1 - a0) * (s + ds))
    for _ in range(math.ceil(3 * period / h)):
        step(0.0, 0.0, 0.0)
    return k * peak


def test_scale_to_sa_through_the_scenario_key(examples: Path, tmp_path: Path) -> None:
    period, sa = 0.6, 0.5
    ground = {"kind": "record", "file": str(examples / RECORD),
              "scale_to_sa": {"period": period, "sa": sa}}
    r = pounding.run(pounding.Scenario.from_dict(scenario(ground)), check=False)
    g = r.summary["ground_motion"]
    assert g["kind"] == "record"
    assert g["scale_to_sa"]["period"] == period
    assert g["scale_to_sa"]["sa_g"] == sa
    assert g["scale_to_sa"]["damping"] == 0.05
    f = g["scale_factor"]

    # the factor brings the record's PSA at T to the target, by the oscillator written above.
    # Tolerance 2e-5: 10 sub-steps of 0.5 ms (ωh = 5.2e-3) miss the true peak by at most
    # (ωh/2)²/2 = 3.4e-6 of it; RK4's own error is O((ωh)⁴), negligible.
    dt, accel = read_at2(examples / RECORD)
    psa = psa_rk4(accel, dt, period, 0.05, 10)
    assert abs(f * psa / (sa * G) - 1) < 2e-5
    assert abs(g["scale_to_sa"]["psa_before"] / psa - 1) < 2e-5

    # the same run as the record multiplied by that factor (read by the program, written out
    # with round-trip decimals): every number of the run, bit for bit
    raw = pounding.run(pounding.Scenario.from_dict(
        scenario({"kind": "record", "file": str(examples / RECORD)})), check=False)
    copy = tmp_path / "copy.txt"
    # (the samples as the program reads them: the AT2 values × 9.80665 to m/s², then × f)
    copy.write_text("".join(f"{float(x) * G * f!r}\n" for x in _at2_values(examples / RECORD)))
    c = pounding.run(pounding.Scenario.from_dict(scenario(
        {"kind": "record", "file": str(copy), "units": "m/s2", "dt": dt})), check=False)
    for key in ("structures", "contact", "levels", "separation", "energy", "impact_log"):
        assert r.summary[key] == c.summary[key], key
    assert r.summary["contact"]["impacts"] > 0
    assert c.summary["ground_motion"]["scale_factor"] == 1.0
    assert raw.summary["ground_motion"]["scale_factor"] == 1.0
    assert "scaled ×" in r.summary_text()


def _at2_values(path: Path) -> list[str]:
    return [x for line in path.read_text().splitlines()[4:] for x in line.split()]


def test_scale_to_sa_errors_name_the_key(examples: Path) -> None:
    base = {"kind": "record", "file": str(examples / RECORD)}
    for extra, key in [
        ({"scale_to_sa": {"period": 1.0, "sa": 0.4}, "scale_to_pga": 0.3},
         "ground_motion.scale_to_sa"),
        ({"scale_to_sa": {"period": 0.0, "sa": 0.4}}, "ground_motion.scale_to_sa.period"),
        ({"scale_to_sa": {"period": 1.0, "sa": -1.0}}, "ground_motion.scale_to_sa.sa"),
        ({"scale_to_sa": {"period": 1.0, "sa": 0.4, "damping": 1.5}},
         "ground_motion.scale_to_sa.damping"),
    ]:
        with pytest.raises(pounding.ScenarioError) as e:
            pounding.Scenario.from_dict(scenario({**base, **extra}))
        assert key in str(e.value)
