"""pounding — seismic pounding of adjacent buildings, from Python.

The same library as the ``pounding`` command line (written in Rust), with NumPy arrays::

    import pounding
    sc = pounding.Scenario.from_file("examples/paper-c.toml")
    res = pounding.run(sc)                      # both runs, as `pounding run`
    res.summary["structures"][0]["peak_displacement"]
    res.history["w1"]                           # NumPy float64 arrays, history.csv's columns
    print(res.summary_text())                   # what `pounding run` prints
    print(sc.separation_text())                 # what `pounding separation` prints
    table = pounding.sweep("examples/quick-sweep.toml", jobs=2)   # results.csv's columns

Nothing is computed in Python: every function here parses its arguments, calls the compiled
library (``pounding._core``) and converts its results. Simulations release the GIL, so runs
from a ``concurrent.futures.ThreadPoolExecutor`` use every core. Errors are exceptions carrying
the command line's message: :class:`ScenarioError` and :class:`SweepError` (both
``ValueError``), :class:`SolveError` (``RuntimeError``), :class:`OutputError` (``OSError``).
For a cluster, :mod:`pounding.distributed` runs a sweep through Dask.
"""

from __future__ import annotations

import json
import os
from typing import Any, Mapping, Union

from . import _core
from ._core import OutputError, Scenario, ScenarioError, SolveError, SweepError

__all__ = [
    "Scenario",
    "RunResult",
    "RowResult",
    "SweepTable",
    "run",
    "sweep",
    "plan_sweep",
    "fragility",
    "FragilityResult",
    "laws_text",
    "ScenarioError",
    "SweepError",
    "SolveError",
    "OutputError",
]

__version__: str = _core.__version__

PathLike = Union[str, "os.PathLike[str]"]


class _RunFiles:
    """What a pair's and a row's run have alike: the files ``pounding run --out DIR`` writes, as
    Python objects computed once, on first access (see :class:`RunResult`,
    :class:`RowResult`)."""

    __slots__ = ("_out", "_cache")

    def __init__(self, out: Any) -> None:
        self._out = out
        self._cache: dict[str, Any] = {}

    def _get(self, name: str, make: Any) -> Any:
        if name not in self._cache:
            self._cache[name] = make()
        return self._cache[name]

    @property
    def summary(self) -> dict[str, Any]:
        """summary.json's content (the same text ``pounding run`` writes, parsed)."""
        return self._get("summary", lambda: json.loads(self._out.summary_json()))

    @property
    def summary_json(self) -> str:
        """summary.json's text, byte for byte."""
        return self._out.summary_json()

    @property
    def history(self) -> dict[str, Any]:
        """history.csv's columns: dict of 1-D float64 NumPy arrays (s, m, N)."""
        return self._get("history", self._out.history)

    @property
    def floors(self) -> dict[str, Any]:
        """floors.csv's columns: dict of 1-D float64 NumPy arrays (m, m/s²)."""
        return self._get("floors", self._out.floors)

    @property
    def warnings(self) -> list[str]:
        """The run's warnings."""
        return self._out.warnings

    @property
    def suite(self) -> dict[str, Any] | None:
        """A suite's section of summary.json, or None for one record."""
        return self.summary.get("suite")

    @property
    def statistics(self) -> dict[str, Any]:
        """A suite's statistics across its records (empty for one record)."""
        s = self.suite
        return {} if s is None else s["statistics"]

    def to_pandas(self) -> dict[str, Any]:
        """The tables as pandas DataFrames: ``{"history", "impacts", "floors"}`` (needs pandas)."""
        import pandas as pd  # optional dependency

        return {
            "history": pd.DataFrame(self.history),
            "impacts": pd.DataFrame(self.impacts),
            "floors": pd.DataFrame(self.floors),
        }


class RunResult(_RunFiles):
    """The outcome of :func:`run`: what ``pounding run --out DIR`` writes, as Python objects.

    Attributes are computed from the run once, on first access:

    - ``summary``: dict, exactly the content of summary.json;
    - ``history``: dict of 1-D float64 arrays keyed by history.csv's columns (``t``, ``w1``,
      ``w2``, ``force``, ``w1_free``, ``w2_free``, and ``force_1 … force_k`` with several
      contact levels);
    - ``impacts``: dict of 1-D arrays keyed by impacts.csv's columns (``level`` int64, 1-based;
      ``height``, ``start``, ``end``, ``duration``, ``peak_force``, ``impulse``,
      ``max_penetration``, ``approach_speed`` float64), one entry per impact;
    - ``floors``: dict of 1-D float64 arrays keyed by floors.csv's columns (``t``, then
      ``w1_<h>``, ``a1_<h>``, … with pounding, then the same with ``_free``);
    - ``warnings``: list of the run's warnings (as ``pounding run`` prints them).

    For a suite of records (``[ground_motion] kind = "suite"``) the tables and the top level of
    ``summary`` are the representative record's run (as ``pounding run`` writes them), and

    - ``suite``: dict, summary.json's ``suite`` section (``records``, ``scaling``,
      ``statistics``, ``design``, ``representative``), ``None`` for one record;
    - ``records``: list of dicts, one per record (file, component, factor, headline numbers);
    - ``statistics``: dict, per headline number its ``mean``, ``median``, ``p84``, ``min``,
      ``max`` and ``design`` value across the records.
    """

    __slots__ = ()

    @property
    def impacts(self) -> dict[str, Any]:
        """impacts.csv's columns: dict of 1-D NumPy arrays, one entry per impact."""
        return self._get("impacts", self._out.impacts)

    @property
    def records(self) -> list[dict[str, Any]]:
        """A suite's records with their headline numbers (empty for one record)."""
        s = self.suite
        return [] if s is None else s["records"]

    def summary_text(self) -> str:
        """The summary ``pounding run`` prints on screen, the same text (for a suite of records,
        the suite's report): the peaks with and without pounding, the impacts, the required
        separation, the energy balance and the self-check."""
        return self._out.summary_text()

    def save(self, dir: PathLike, plots: bool = True) -> list[str]:
        """Write the files ``pounding run --out DIR`` writes (history.csv, impacts.csv,
        floors.csv, the pictures unless ``plots`` is false, summary.json last; each file
        atomically). Returns the paths written, in order."""
        return [str(p) for p in self._out.save(os.fspath(dir), plots)]

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"RunResult({s['title']!r}: peaks {s['structures'][0]['peak_displacement']:.4g} m, "
            f"{s['structures'][1]['peak_displacement']:.4g} m, {s['contact']['impacts']} impacts)"
        )


class RowResult(_RunFiles):
    """The outcome of :func:`run` on a row of buildings (more than two ``[[structure]]``
    tables, README "Rows of buildings"): what ``pounding run --out DIR`` writes for a row, as
    Python objects (computed once, on first access):

    - ``summary``: dict, exactly the content of summary.json (``structures``, ``pairs``,
      ``verdict``, ``accuracy``, …);
    - ``history``: dict of 1-D float64 arrays keyed by history.csv's columns (``t``,
      ``w_<name>`` per structure at its highest contact level, ``force_<left>_<right>_<k>`` per
      pair and level, ``w_<name>_free``);
    - ``structures``: dict keyed by structure name (row order) of dicts of 1-D float64 arrays
      ``t`` (s), ``w`` and ``w_free`` (m, with and without pounding, at the structure's highest
      contact level);
    - ``pairs``: list (row order) of dicts: ``between`` (the two names), ``t`` (s), ``force``
      (N, the sum over the pair's levels, as a pair's history.csv ``force``) and with several
      levels ``force_1 … force_k``, and ``impacts`` (the pair's rows of impacts.csv);
    - ``impacts``: dict of impacts.csv's columns (``pair``, ``level`` int64, 1-based; ``left``,
      ``right`` lists of str; the rest float64);
    - ``floors``: dict of floors.csv's columns (``t``, ``w_<name>_<h>``, ``a_<name>_<h>``, then
      the same with ``_free``);
    - ``warnings``: list of the run's warnings.

    For a suite of records on the row (``[ground_motion] kind = "suite"``) the tables and the
    top level of ``summary`` are the representative record's run of the row (as ``pounding
    run`` writes them), and, as for a pair's suite,

    - ``suite``: dict, summary.json's ``suite`` section (``records``, ``scaling``,
      ``statistics``, ``design`` with ``pairs`` — per pair and level the design value, the gap,
      the verdict — ``governing_pair``, ``governing_level``, ``representative``,
      ``record_dirs``), ``None`` for one record;
    - ``records``: list of dicts, one per record (file, component, factor, the numbers per
      structure ``structure{i}_…`` and per pair ``pair{p}_…``);
    - ``statistics``: dict, per such number its ``mean``, ``median``, ``p84``, ``min``, ``max``
      and ``design`` value across the records.
    """

    __slots__ = ()

    @property
    def structures(self) -> dict[str, dict[str, Any]]:
        """Per structure (row order): ``t``, ``w``, ``w_free`` arrays (s, m)."""
        return self._get("structures", self._out.structures)

    @property
    def pairs(self) -> list[dict[str, Any]]:
        """Per adjacent pair (row order): ``between``, ``t``, ``force`` (N), ``force_k`` with
        several levels, and ``impacts`` (its rows of impacts.csv)."""

        def make() -> list[dict[str, Any]]:
            out = []
            imp = self.impacts
            for p, (left, right, cols) in enumerate(self._out.pairs()):
                mine = imp["pair"] == p + 1
                rows = {
                    k: (v[mine] if not isinstance(v, list) else [x for x, m in zip(v, mine) if m])
                    for k, v in imp.items()
                }
                out.append({"between": (left, right), **cols, "impacts": rows})
            return out

        return self._get("pairs", make)

    @property
    def impacts(self) -> dict[str, Any]:
        """impacts.csv's columns: dict of 1-D NumPy arrays (names as lists), one per impact."""
        return self._get("impacts", self._out.impacts)

    @property
    def records(self) -> list[dict[str, Any]]:
        """A suite's records with their numbers per structure and pair (empty for one record)."""
        s = self.suite
        return [] if s is None else s["records"]

    def summary_text(self) -> str:
        """The summary ``pounding run`` prints for a row: every structure's peaks with and
        without pounding, every pair's impacts and required separation, the row's verdict, the
        energy balance and the self-check (for a suite of records, the suite's report per
        pair)."""
        return self._out.summary_text()

    def save(self, dir: PathLike, plots: bool = True) -> list[str]:
        """Write the files ``pounding run --out DIR`` writes for a row (history.csv,
        impacts.csv, floors.csv, the pictures unless ``plots`` is false, summary.json last).
        Returns the paths written, in order."""
        return [str(p) for p in self._out.save(os.fspath(dir), plots)]

    def __repr__(self) -> str:
        s = self.summary
        names = ", ".join(x["name"] for x in s["structures"])
        impacts = sum(p["contact"]["impacts"] for p in s["pairs"])
        return f"RowResult({s['title']!r}: {names}; {impacts} impacts)"


def run(
    scenario: Scenario, *, check: bool = True, max_output_size: int = 1_000_000_000
) -> Union[RunResult, RowResult]:
    """Simulate ``scenario`` with and without pounding, as ``pounding run`` does.

    ``check``: also run the self-check (a second run at a 100× tighter tolerance; summary's
    ``accuracy``), as the command line does unless ``--no-check``. ``max_output_size``: the
    largest history (bytes, as history.csv would hold it) the run may keep (``--max-output-size``).
    The GIL is released during the simulation. Raises :class:`SolveError` (e.g. an
    unstable step, a scenario whose ground motion is a design spectrum) and
    :class:`ScenarioError` (a history above ``max_output_size``).

    A row of buildings (more than two structures) gives a :class:`RowResult`, with arrays per
    structure and per pair; a pair gives a :class:`RunResult`.
    """
    if not isinstance(scenario, Scenario):
        raise TypeError(f"run() takes a pounding.Scenario, not {type(scenario).__name__}")
    if scenario.is_row:
        return RowResult(_core.run_row(scenario, check, max_output_size))
    return RunResult(_core.run(scenario, check, max_output_size))


def laws_text(speed: float = 0.5) -> str:
    """The table ``pounding laws --speed SPEED`` prints: the restitution each contact law that
    takes a target e achieves on an isolated two-body impact at ``speed`` m/s (> 0)."""
    return _core.laws_text(float(speed))


class SweepTable(dict):
    """A sweep's results: dict of columns in results.csv's order, rows in case order.

    ``case`` int64; an axis of numbers float64 (of whole numbers int64, of text or lists: a list
    of str as results.csv writes them); ``status`` and ``converged`` lists of str; every other
    column float64 — the same numbers results.csv holds (an empty field, e.g. of a failed case,
    is NaN; ``impacts`` is float64 for that reason). A sweep over a suite of records has the
    suite's columns instead (README, "Sweeps over a suite of records"): ``statistic``,
    ``sufficient``, ``levelK_sufficient`` and ``converged`` lists of str, the others float64;
    over a suite on a row of buildings, per pair and level (``statistic``, ``sufficient``,
    ``pairP_sufficient`` and ``converged`` lists of str, the others float64).
    """

    def to_pandas(self) -> Any:
        """The table as a pandas DataFrame (needs pandas); ``impacts`` as pandas' nullable
        ``Int64`` (``<NA>`` for a failed case)."""
        import pandas as pd  # optional dependency

        df = pd.DataFrame(dict(self))
        if "impacts" in df:
            df["impacts"] = df["impacts"].astype("Int64")
        return df


def plan_sweep(source: Union[PathLike, Scenario], axes: Mapping[str, Any] | None = None) -> _core.Sweep:
    """The checked sweep of a sweep file, or of a :class:`Scenario` along ``axes``.

    ``axes``: key path → list of values, or → dict with ``from``, ``to``, ``steps`` (and
    ``scale = "log"``), exactly as a sweep file's ``[[axis]]`` tables, first axis slowest.
    The result lists the cases and runs any one of them to its results row (what
    :mod:`pounding.distributed` sends to workers; it pickles)."""
    if isinstance(source, Scenario):
        if not axes:
            raise SweepError("sweep of a Scenario: give axes={key path: values, …}")
        return _core.Sweep.from_scenario(source, dict(axes))
    if axes is not None:
        raise SweepError("axes= goes with a Scenario; a sweep file gives its own [[axis]] tables")
    return _core.Sweep.from_file(os.fspath(source))


def sweep(
    source: Union[PathLike, Scenario],
    axes: Mapping[str, Any] | None = None,
    *,
    jobs: int | None = None,
    check: bool = True,
) -> SweepTable:
    """Run every case of a sweep on ``jobs`` threads (default: every core), as ``pounding
    sweep`` does, and return its results table (:class:`SweepTable`), equal to results.csv.

    ``source``: a sweep file, or a :class:`Scenario` with ``axes`` (see :func:`plan_sweep`).
    ``check``: each case's self-check (``--no-check`` when false; ``converged`` then says
    ``unchecked``). A failed case is a row with ``status`` ``failed: …``; a sweep none of whose
    cases is a valid scenario raises :class:`SweepError`. Nothing is written to disk.
    """
    plan = plan_sweep(source, axes)
    jobs = _core.available_parallelism() if jobs is None else int(jobs)
    rows = plan.run_all(jobs, check)
    return SweepTable(plan.columns(rows))


def _columns(text: str) -> dict[str, Any]:
    """CSV text → dict of columns: numbers as float64 arrays (an empty field NaN, ``inf``
    infinity), other columns as lists of str."""
    import csv
    import io

    import numpy as np

    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        return {}
    head, body = rows[0], rows[1:]
    out: dict[str, Any] = {}
    for k, name in enumerate(head):
        col = [r[k] for r in body]
        try:
            out[name] = np.array([float(v) if v != "" else np.nan for v in col], dtype=np.float64)
        except ValueError:
            out[name] = col
    return out


class FragilityResult:
    """The outcome of :func:`fragility`: the tables ``pounding fragility`` writes.

    ``fragility`` (fragility.csv: ``limit_state``, ``model``, ``im``, ``runs``,
    ``exceedances``, ``fraction``), ``p_pounding`` (p_pounding.csv: ``im``, ``gap`` [m],
    ``p_pounding``), ``runs`` (runs.csv, one row per record and stripe) — each a dict of
    columns (float64 arrays; text columns lists of str); ``fit`` (fit.json as a dict) and
    ``fits`` (its list: per limit state and model ``theta``, ``beta``, ``theta_interval``,
    ``beta_interval``, …); ``target_gap`` (the gap for the target probability, or None);
    ``report`` (the printed text).

    A row of buildings (more than two structures): ``structures`` (the names, row order; None
    for a pair), ``p_pounding`` with a ``pair`` column (1-based), ``target_gap`` one entry per
    pair (with ``pair`` and ``between``), the fits of each pair's and each structure's limit
    states (``pounding(1-2)``, ``ductility>4(2)``, … with ``pair`` / ``structure``), and
    ``pairs``: per pair its ``p_pounding``, ``target_gap`` and ``fits`` (one entry for a pair).
    """

    def __init__(self, parts: dict[str, str]) -> None:
        self.report: str = parts["report"]
        self.fit: dict[str, Any] = json.loads(parts["fit_json"])
        self.fits: list[dict[str, Any]] = self.fit["fits"]
        self.target_gap: dict[str, Any] | None = self.fit.get("target_gap")
        self.fragility: dict[str, Any] = _columns(parts["fragility_csv"])
        self.p_pounding: dict[str, Any] = _columns(parts["p_pounding_csv"])
        self.runs: dict[str, Any] = _columns(parts["runs_csv"])
        # an IDA: ``runs`` is ida.csv (``run`` for ``stripe``, rows by record and IM) and
        # ``capacities`` capacities.csv (``record``, ``file``, ``limit_state``, ``model``,
        # ``im_lo``, ``im_hi``, ``capacity``); no rows for stripes
        self.capacities: dict[str, Any] = _columns(parts.get("capacities_csv", ""))
        # a row (more than two structures): the structures' names, ``p_pounding`` with a
        # ``pair`` column, ``target_gap`` a list (one per pair); ``pairs`` gathers each pair's
        self.structures: list[str] | None = self.fit.get("structures")
        self.pairs: list[dict[str, Any]] = self._pairs()

    def _pairs(self) -> list[dict[str, Any]]:
        """Per adjacent pair (row order; one for a pair of structures): ``pair`` (1-based),
        ``between`` (the two names; None for a pair of structures), ``p_pounding`` (its
        P(pounding | IM, gap): ``im``, ``gap``, ``p_pounding``), ``target_gap`` (or None) and
        ``fits`` (the fits of its pair's limit states: pounding, contact force)."""
        if self.structures is None:
            fits = [f for f in self.fits if f["kind"] in ("pounding", "contact_force")]
            return [
                {"pair": 1, "between": None, "p_pounding": self.p_pounding, "target_gap": self.target_gap, "fits": fits}
            ]
        targets = {t["pair"]: t for t in (self.target_gap or [])}
        out = []
        for q in self.fit["pairs"]:
            p = q["pair"]
            at = self.p_pounding["pair"] == p
            out.append(
                {
                    "pair": p,
                    "between": q["between"],
                    "p_pounding": {k: v[at] for k, v in self.p_pounding.items() if k != "pair"},
                    "target_gap": targets.get(p),
                    "fits": [f for f in self.fits if f.get("pair") == p],
                }
            )
        return out

    def to_pandas(self, table: str = "fragility") -> Any:
        """One table (``fragility``, ``p_pounding``, ``runs`` or ``capacities``) as a pandas
        DataFrame (needs pandas)."""
        import pandas as pd  # optional dependency

        if table not in ("fragility", "p_pounding", "runs", "capacities"):
            raise ValueError(
                f"table must be 'fragility', 'p_pounding', 'runs' or 'capacities', not {table!r}"
            )
        return pd.DataFrame(getattr(self, table))

    def __repr__(self) -> str:
        return f"FragilityResult({self.fit['title']!r}: {self.fit['runs']} runs, {len(self.fits)} fits)"


def fragility(
    path: PathLike,
    *,
    jobs: int | None = None,
    out: PathLike | None = None,
    plots: bool = True,
) -> FragilityResult:
    """Run a fragility study file, as ``pounding fragility`` does (README, "Fragility"), on
    ``jobs`` threads (default: every core), with the GIL released, and return its tables and
    fits (:class:`FragilityResult`). With ``out``, also write the files there (the figures
    unless ``plots`` is false; fit.json last). Raises :class:`ScenarioError` (the study or its
    scenario refused), :class:`SolveError` (a run failed), :class:`OutputError`."""
    parts = _core.fragility(
        os.fspath(path), None if jobs is None else int(jobs), None if out is None else os.fspath(out), plots
    )
    return FragilityResult(dict(parts))


def plan_fragility(path: PathLike) -> _core.FragilityPlan:
    """The checked study of a fragility study file, split into tasks (a run of a record at a
    stripe, or a record's whole IDA), each computed to rows anywhere and the rows joined into
    the tables (what :mod:`pounding.distributed` sends to workers; it pickles as the study
    file's absolute path)."""
    return _core.FragilityPlan.from_file(os.fspath(path))
