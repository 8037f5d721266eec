#!/usr/bin/env python3
"""The README's table "Accuracy (paper case T1/T2 = 0.7, 3 modes, 20 s)", measured.

    cargo build --release && python3 scripts/accuracy-table.py
    python3 scripts/accuracy-table.py --stiff

(from the repository's root; `--bin PATH` runs another `pounding` binary, `--keep DIR` keeps
the runs' outputs). Each takes well under a minute of one core. `--stiff` prints instead the
numbers the README gives for issue 9's stiff Hertz case (1000x the paper's stiffness, 6 s):
each method's largest relative error of both peaks, the peak force and the required
separation against the converged run (`adaptive`, rtol 1e-12, dt 1e-4 s), at PGA 0.5 g over
exact-modal's rtol ladder and at 0.4 g and 0.6 g; and how far a 1e-6 change of the gap moves
the converged peak force (with `--keep DIR` it also leaves DIR/stiff-rk4.toml, the case with
rk4 at dt 1 ms, on which the README runs `pounding convergence`).

Each row is `pounding run … --no-check --no-plot -q` on examples/paper-c.toml with
`solver.method` and `dt` replaced (and `rtol` added where the row names one). Every row is
compared with a converged reference, `adaptive` at rtol 1e-11 with observations every 0.1 ms (dt
= 1e-4 s), which is itself checked against an independent one, `rk4` at dt = 2e-5 s, and the
same method at a tenth of the step; their agreement is printed first, and how much the 20 s
peaks move when the gap is 1 um wider (the sensitivity of a sequence of 81 impacts). Columns:
relative errors of the peaks w1, w2 (summary.json `structures[i].peak_displacement`) and of the
peak force (`contact.peak_force`); the largest relative error of the peak force over the first
eight impacts (impacts.csv, matched in order, their starts within 1 ms of the reference's); the
run's own energy-balance error (`solver.energy_relative_error`, the run with contact); and its
steps (`solver.steps`).

Python 3 standard library only.
"""

import argparse
import csv
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "paper-c.toml"
FIRST_IMPACTS = 8

# (label, method, dt, rtol or None for the method's default)
ROWS = [
    ("`rk4` dt = 1 ms (the paper)", "rk4", 1e-3, None),
    ("`rk4` dt = 0.5 ms", "rk4", 5e-4, None),
    ("`exact-modal` dt = 1 ms (default rtol 1e-8)", "exact-modal", 1e-3, None),
    ("`exact-modal` dt = 5 ms (default rtol)", "exact-modal", 5e-3, None),
    ("**`exact-modal` dt = 10 ms (default rtol)**", "exact-modal", 1e-2, None),
    ("`exact-modal` dt = 10 ms, rtol 1e-6", "exact-modal", 1e-2, 1e-6),
    ("`exact-modal` dt = 10 ms, rtol 1e-10", "exact-modal", 1e-2, 1e-10),
    ("`adaptive` dt = 1 ms (default rtol 1e-10)", "adaptive", 1e-3, None),
    ("`adaptive` dt = 10 ms (default rtol)", "adaptive", 1e-2, None),
]
REFERENCE = ("reference", "adaptive", 1e-4, 1e-11)
SECOND = ("rk4 dt = 2e-5 s", "rk4", 2e-5, None)
FINER = ("adaptive rtol 1e-11 dt = 1e-5 s", "adaptive", 1e-5, 1e-11)


def scenario(method, dt, rtol, gap=None):
    """paper-c.toml's text with the method, dt and rtol (and the gap, m) replaced."""
    text = EXAMPLE.read_text()
    if gap is not None:
        text, n = re.subn(r"^gap = 0\.0127$", f"gap = {gap!r}", text, flags=re.MULTILINE)
        if n != 1:
            sys.exit(f"{EXAMPLE}: no line `gap = 0.0127`")
    solver = f'method = "{method}"\ndt = {dt!r}' + ("" if rtol is None else f"\nrtol = {rtol!r}")
    text, n = re.subn(r'^method = "rk4"\ndt = 0\.001$', solver, text, flags=re.MULTILINE)
    if n != 1:
        sys.exit(f"{EXAMPLE}: its [solver] lines are not `method = \"rk4\"`, `dt = 0.001`")
    return text


def run(binary, work, row, gap=None):
    """Runs one row; returns its summary.json and impacts.csv rows."""
    label, method, dt, rtol = row
    name = f"{method}-{dt!r}-{rtol!r}-{gap!r}"
    toml = work / f"{name}.toml"
    toml.write_text(scenario(method, dt, rtol, gap))
    out = work / name
    subprocess.run(
        [str(binary), "run", str(toml), "--out", str(out), "--no-check", "--no-plot", "-q"],
        check=True,
        stderr=subprocess.DEVNULL,
    )
    summary = json.loads((out / "summary.json").read_text())
    with open(out / "impacts.csv", newline="") as f:
        impacts = list(csv.DictReader(f))
    return summary, impacts


def rel(a, b):
    return abs(a - b) / abs(b)


def errors(result, reference):
    """(peak w1, peak w2, peak force, per impact) relative errors of `result`."""
    (s, imp), (rs, rimp) = result, reference
    peaks = [
        rel(s["structures"][i]["peak_displacement"], rs["structures"][i]["peak_displacement"])
        for i in range(2)
    ]
    force = rel(s["contact"]["peak_force"], rs["contact"]["peak_force"])
    if len(imp) < FIRST_IMPACTS or len(rimp) < FIRST_IMPACTS:
        sys.exit("fewer than eight impacts")
    per_impact = 0.0
    for a, b in zip(imp[:FIRST_IMPACTS], rimp[:FIRST_IMPACTS]):
        if abs(float(a["start"]) - float(b["start"])) > 1e-3:
            sys.exit(f"impacts out of step: {a['start']} against {b['start']}")
        per_impact = max(per_impact, rel(float(a["peak_force"]), float(b["peak_force"])))
    return peaks + [force, per_impact]


def fmt(x):
    """1.2e-3 rather than 1.2e-03."""
    if x == 0.0:
        return "0"
    mantissa, exponent = f"{x:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


# Issue 9's stiff Hertz case (1000x the paper's k_h, 3 modes, Tg = 0.8 s, 6 s), as
# tests/error_control.rs builds it; `pga` in g, `solver` the [solver] lines before `duration`.
STIFF = """[[structure]]
length = 10.0
mass = 2.273e6
period = 0.3
modes = 3
damping_ratio = 0.01
[[structure]]
length = 10.0
mass = 2.273e6
period = 0.6
modes = 3
damping_ratio = 0.01
[contact]
law = "hertz"
stiffness = 2.808e13
gap = 0.0127
[ground_motion]
kind = "harmonic"
pga = {pga}
period = 0.8
[solver]
{solver}
duration = 6.0
"""


def run_text(binary, work, name, text):
    """Runs a scenario given as text; returns its summary.json."""
    toml = work / f"{name}.toml"
    toml.write_text(text)
    out = work / name
    subprocess.run(
        [str(binary), "run", str(toml), "--out", str(out), "--no-check", "--no-plot", "-q"],
        check=True,
        stderr=subprocess.DEVNULL,
    )
    return json.loads((out / "summary.json").read_text())


def headline(s):
    """Both peaks, the peak force and the required separation (time history)."""
    return [
        s["structures"][0]["peak_displacement"],
        s["structures"][1]["peak_displacement"],
        s["contact"]["peak_force"],
        s["separation"]["time_history"],
    ]


def stiff(binary, work):
    """The stiff case's rtol ladder and its chaotic neighbours (README, "Solver methods")."""
    def solver(method, dt, rtol):
        return f'method = "{method}"\ndt = {dt!r}' + ("" if rtol is None else f"\nrtol = {rtol!r}")

    # what `pounding convergence` is shown on in the README: the case with rk4 at dt = 1 ms
    (work / "stiff-rk4.toml").write_text(STIFF.format(pga=0.5, solver=solver("rk4", 1e-3, None)))
    converged = STIFF.format(pga=0.5, solver=solver("adaptive", 1e-4, 1e-12))
    ref = run_text(binary, work, "stiff-0.5-ref", converged)
    wider = converged.replace("gap = 0.0127", "gap = 0.0127000127")
    moved = run_text(binary, work, "stiff-0.5-gap", wider)
    print(
        f"stiff Hertz, PGA 0.5 g: the converged run with the gap 1e-6 of it wider: peak force changes by "
        f"{fmt(rel(moved['contact']['peak_force'], ref['contact']['peak_force']))}, impacts "
        f"{ref['contact']['impacts']} -> {moved['contact']['impacts']}"
    )
    for pga, rows in [
        (0.5, [
            ("adaptive", 1e-4, 3e-12),
            ("adaptive", 1e-3, None),
            ("adaptive", 1e-3, 1e-10),
            ("exact-modal", 1e-3, None),
            ("exact-modal", 1e-3, 2e-8),
            ("exact-modal", 1e-3, 4e-8),
            ("exact-modal", 1e-2, None),
            ("exact-modal", 1e-3, 1e-10),
        ]),
        (0.4, [("adaptive", 1e-3, None), ("exact-modal", 1e-3, None)]),
        (0.6, [("adaptive", 1e-4, 3e-12), ("adaptive", 1e-3, None), ("exact-modal", 1e-3, None)]),
    ]:
        converged = STIFF.format(pga=pga, solver=solver("adaptive", 1e-4, 1e-12))
        ref = run_text(binary, work, f"stiff-{pga}-ref", converged)
        print(f"stiff Hertz, PGA {pga} g, 6 s: converged (adaptive, rtol 1e-12, dt 1e-4 s): "
              f"{ref['contact']['impacts']} impacts, peak force {ref['contact']['peak_force']:.4e} N")
        for method, dt, rtol in rows:
            name = f"stiff-{pga}-{method}-{dt!r}-{rtol!r}"
            s = run_text(binary, work, name, STIFF.format(pga=pga, solver=solver(method, dt, rtol)))
            e = [rel(a, b) for a, b in zip(headline(s), headline(ref))]
            print(f"  {method} dt {dt!r} rtol {'default' if rtol is None else repr(rtol)}: "
                  f"peak force {fmt(e[2])}, largest of peaks, force, separation {fmt(max(e))}, "
                  f"impacts {s['contact']['impacts']}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bin", default=str(ROOT / "target" / "release" / "pounding"))
    parser.add_argument("--keep", help="keep the runs' outputs in this directory")
    parser.add_argument("--stiff", action="store_true", help="the stiff Hertz case's rtol ladder instead")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(args.keep) if args.keep else Path(tmp)
        work.mkdir(parents=True, exist_ok=True)
        if args.stiff:
            return stiff(args.bin, work)
        reference = run(args.bin, work, REFERENCE)
        second = run(args.bin, work, SECOND)
        for other, label in [(second, SECOND[0]), (run(args.bin, work, FINER), FINER[0])]:
            agree = errors(other, reference)
            print(
                f"reference (adaptive, rtol 1e-11, dt 1e-4 s) against {label}: "
                f"peak w1 {fmt(agree[0])}, peak w2 {fmt(agree[1])}, peak force {fmt(agree[2])}, "
                f"first {FIRST_IMPACTS} impacts' peak force {fmt(agree[3])}; impacts "
                f"{reference[0]['contact']['impacts']} and {other[0]['contact']['impacts']}"
            )
        # how sensitive the 20 s peaks are: the reference with the gap 1 um wider
        moved = run(args.bin, work, REFERENCE, gap=0.012701)
        e = errors(moved, reference)
        print(
            f"the reference with gap = 0.012701 m (+1 um): peaks change by {fmt(e[0])}, {fmt(e[1])}, "
            f"peak force {fmt(e[2])}; impacts {moved[0]['contact']['impacts']}"
        )
        print()
        print("| run | peak w1 | peak w2 | peak force | per impact | energy | steps |")
        print("|---|---|---|---|---|---|---|")
        for row in ROWS:
            result = run(args.bin, work, row)
            e = errors(result, reference)
            solver = result[0]["solver"]
            cells = [fmt(x) for x in e] + [fmt(solver["energy_relative_error"]), str(solver["steps"])]
            print(f"| {row[0]} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
