#!/usr/bin/env python3
"""The speed/accuracy dial of a large study: a looser exact-modal rtol on bench-10k-fast.

    cargo build --release && python3 scripts/chaos-ladder/sweep_dial.py
    python3 scripts/chaos-ladder/sweep_dial.py --check          # also the self-check at 1e-4

(from the repository's root; `--bin PATH` another `pounding` binary, `--shard K/N` another part
of the sweep (default 1/11: 910 of the 10 000 cases), `--rtols` the other tolerances (default
1e-4 1e-6 1e-10: two looser, and one tighter, which shows how far the default itself is from a
tighter answer on these rows), `--keep DIR` keeps the sweeps' files). The default run takes ~20 s of one core,
`--check` another ~20 s.

Runs `pounding sweep SWEEP --no-plot --no-check --jobs 1 --shard K/N --out D` on a copy of
examples/bench-10k-fast.toml (the paper case c, T1/T2 x T2/Tg = 100 x 100, exact-modal dt 5 ms)
at exact-modal's default rtol (1e-8) and at each other rtol. `solver.rtol` is not a key a
sweep axis may set, so each other sweep points `scenario =` at a copy of examples/paper-c.toml
with `rtol = R` added under `[solver]`. For each: the CPU time of the sweep process (user +
system, from getrusage of the child), and over the rows the distribution (median, 95th
percentile, max) of the relative difference |a - b|/|b| of peak_force, peak_displacement_1,
peak_displacement_2 and sep_time_history against the default's row (b; rows where both are 0
count 0), how many rows change their number of impacts, and how many move by more than 0.5 %
on one of the first three.

With `--check`, the default and then the first looser rtol are swept again with the self-check
on (no `--no-check`):
each row is also run at rtol/100 and says `converged = false` when a number (or the count of
impacts) moved by more than 1 % (README "Every run checks itself"). The script prints how many
rows are flagged, and how many of the rows that moved by more than 0.5 % and by more than 1 %
against the default the flag catches (a row that moved but is not flagged is listed).

Python 3 standard library only. It measures; it changes nothing in the repository.
"""

import argparse
import csv
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile

FIELDS = ["peak_force", "peak_displacement_1", "peak_displacement_2", "sep_time_history"]
BAR = 5e-3


def sweep(args, name, rtol, check):
    """Writes the sweep (and its scenario) for `rtol` (None: the default), runs it, returns
    (cpu seconds, rows by case)."""
    root = os.path.abspath(".")
    base = os.path.join(root, "examples", "paper-c.toml")
    if rtol is not None:
        text = open(base).read()
        if "\n[solver]\n" not in text:
            sys.exit("examples/paper-c.toml has no [solver] table")
        text = text.replace("\n[solver]\n", f"\n[solver]\nrtol = {rtol!r}\n", 1)
        base = os.path.join(args.work, f"paper-c-rtol{rtol:g}.toml")
        with open(base, "w") as f:
            f.write(text)
    sweep_text = open(os.path.join(root, "examples", "bench-10k-fast.toml")).read()
    if 'scenario = "paper-c.toml"' not in sweep_text:
        sys.exit("examples/bench-10k-fast.toml no longer names paper-c.toml")
    sweep_text = sweep_text.replace('scenario = "paper-c.toml"', f"scenario = {json.dumps(base)}")
    path = os.path.join(args.work, name + ".toml")
    with open(path, "w") as f:
        f.write(sweep_text)
    out = os.path.join(args.work, name)
    shutil.rmtree(out, ignore_errors=True)
    cmd = [args.bin, "sweep", path, "--no-plot", "--jobs", "1", "--shard", args.shard, "--out", out]
    if not check:
        cmd.insert(4, "--no-check")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} exited {p.returncode}: {p.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    k, n = args.shard.split("/")
    with open(os.path.join(out, f"results-shard-{k}-of-{n}.csv")) as f:
        rows = {r["case"]: r for r in csv.DictReader(f)}
    return cpu, rows


def rel(a, b):
    a, b = float(a), float(b)
    if a == b:
        return 0.0
    return abs(a - b) / abs(b) if b != 0 else float("inf")


def quantile(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(q * len(xs)))]


def moved(row, ref):
    return max(rel(row[k], ref[k]) for k in FIELDS[:3])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default="target/release/pounding")
    ap.add_argument("--shard", default="1/11")
    ap.add_argument("--rtols", type=float, nargs="+", default=[1e-4, 1e-6, 1e-10])
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--keep")
    args = ap.parse_args()
    args.bin = os.path.abspath(args.bin)
    if args.keep:
        args.work = os.path.abspath(args.keep)
        os.makedirs(args.work, exist_ok=True)
        tmp = None
    else:
        tmp = tempfile.TemporaryDirectory(prefix="sweep-dial-")
        args.work = tmp.name

    cpu0, ref = sweep(args, "default", None, False)
    bad = [c for c, r in ref.items() if r["status"] != "ok"]
    print(
        f"bench-10k-fast shard {args.shard}: {len(ref)} rows, exact-modal dt 5 ms; "
        f"default rtol 1e-8: {cpu0:.2f} s CPU ({len(bad)} rows not ok)"
    )
    print(
        f"{'rtol':>6} {'CPU s':>6} {'x default':>9}  "
        + "  ".join(f"{k + ' med/p95/max':>34}" for k in FIELDS)
        + f"  {'impacts changed':>15} {'moved > 0.5 %':>13}"
    )
    loose = {}
    for rt in args.rtols:
        cpu, rows = sweep(args, f"rtol{rt:g}", rt, False)
        loose[rt] = rows
        if rows.keys() != ref.keys():
            sys.exit(f"rtol {rt:g}: not the same cases as the default")
        cells = []
        for k in FIELDS:
            d = [rel(rows[c][k], ref[c][k]) for c in ref if ref[c]["status"] == "ok"]
            cells.append(
                f"{quantile(d, 0.5):10.2e} {quantile(d, 0.95):10.2e} {max(d):10.2e}  "
            )
        ok = [c for c in ref if ref[c]["status"] == "ok"]
        changed = sum(rows[c]["impacts"] != ref[c]["impacts"] for c in ok)
        over = sum(moved(rows[c], ref[c]) > BAR for c in ok)
        print(
            f"{rt:6g} {cpu:6.2f} {cpu / cpu0:9.2f}  " + "".join(cells) + f"{changed:15d} {over:13d}"
        )

    if args.check:
        ok = [c for c in ref if ref[c]["status"] == "ok"]
        cpu_d, rows_d = sweep(args, "default-checked", None, True)
        flagged_d = sum(rows_d[c]["converged"] == "false" for c in ok)
        print(
            f"\ndefault rtol 1e-8 with the self-check: {cpu_d:.2f} s CPU ({cpu_d / cpu0:.2f}x "
            f"without it); flagged converged = false: {flagged_d} of {len(ok)}"
        )
        rt = args.rtols[0]
        cpu, rows = sweep(args, f"rtol{rt:g}-checked", rt, True)
        same = sum(
            all(rows[c][k] == loose[rt][c][k] for k in FIELDS + ["impacts"]) for c in ok
        )
        flagged = {c for c in ok if rows[c]["converged"] == "false"}
        by_count = sum(rows[c]["impacts"] != ref[c]["impacts"] for c in flagged)
        print(
            f"rtol {rt:g} with the self-check: {cpu:.2f} s CPU ({cpu / cpu0:.2f}x the default "
            f"without it); rows identical to the unchecked sweep's: {same} of {len(ok)}; "
            f"flagged converged = false: {len(flagged)} ({by_count} of them with a number of "
            f"impacts unlike the default's); rerunning those at the default would add "
            f"~{len(flagged) / len(ok) * cpu0:.1f} s ({len(flagged) / len(ok):.2f}x)"
        )
        for bar in (BAR, 1e-2):
            m = [c for c in ok if moved(rows[c], ref[c]) > bar]
            caught = [c for c in m if c in flagged]
            print(
                f"  rows that moved > {bar:g} against the default: {len(m)}, flagged {len(caught)}"
            )
        false_alarm = [c for c in flagged if moved(rows[c], ref[c]) <= BAR]
        print(f"  flagged rows that moved <= {BAR:g}: {len(false_alarm)}")
        missed = sorted(
            (c for c in ok if moved(rows[c], ref[c]) > BAR and c not in flagged),
            key=lambda c: -moved(rows[c], ref[c]),
        )
        if missed:
            print(
                "  moved > 0.5 % but not flagged (case, T1/T2, T2/Tg, moved, its "
                "check_max_change, impacts default/loose):"
            )
            for c in missed:
                r = rows[c]
                print(
                    f"    {c:>5} {float(r['period_ratio']):.3f} "
                    f"{float(r['ground_period_ratio']):.3f} {moved(r, ref[c]):.2e} "
                    f"{float(r['check_max_change']):.2e} {ref[c]['impacts']}/{r['impacts']}"
                )
    if tmp:
        tmp.cleanup()


if __name__ == "__main__":
    main()
