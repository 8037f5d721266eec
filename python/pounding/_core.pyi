"""Type stubs of the compiled module pounding._core (python/src/lib.rs).

Use the package `pounding` rather than this module: it re-exports Scenario and the exceptions
and wraps the rest (run → RunResult, sweep → SweepTable).
"""

import os
from pathlib import Path
from typing import Any, Mapping, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, os.PathLike[str]]

__version__: str

class ScenarioError(ValueError):
    """A scenario (or a value given for it) was refused; the message is the command line's:
    file:line:col, key, allowed range."""

class SweepError(ValueError):
    """A sweep (its file, base scenario or axes) was refused; the message is the command line's."""

class SolveError(RuntimeError):
    """A simulation could not be carried out (an unstable step, no time history, …); the
    message is the command line's."""

class OutputError(OSError):
    """The files of a run could not be written."""

class Scenario:
    """A validated scenario (immutable). Build it with from_file, from_toml or from_dict; it
    pickles (as its TOML text)."""

    @staticmethod
    def from_file(path: _Path) -> Scenario:
        """Read and validate a scenario file, as `pounding run FILE` does. Record files are
        relative to the file's directory. Raises ScenarioError."""
    @staticmethod
    def from_toml(text: str, name: str = "<string>", base_dir: _Path = ".") -> Scenario:
        """Validate scenario TOML text; `name` names it in messages (with line:col of `text`),
        `base_dir` resolves record files. Raises ScenarioError."""
    @staticmethod
    def from_dict(data: Mapping[str, Any], name: str = "<dict>", base_dir: _Path = ".") -> Scenario:
        """Validate a scenario given as nested dicts/lists with the structure of a scenario
        file (numbers may be NumPy scalars, lists NumPy arrays); validated exactly as a file
        (its positions are line:col of `.toml`). Any other object is a ScenarioError naming
        its key path."""
    def replace(self, values: Mapping[str, Any]) -> Scenario:
        """A new scenario with keys set by the sweep's key paths, e.g.
        {"structure.2.period": 0.5, "ground_motion.pga": 0.4, "period_ratio": 0.7}, with the
        sweep's rules (setting `period` removes `bending_stiffness`, …). Raises ScenarioError."""
    def modes_text(self) -> str:
        """The table `pounding modes` prints."""
    def separation_text(self, codes: list[str] | None = None, spectrum: str | None = None) -> str:
        """The tables `pounding separation` prints (`codes` as --code, `spectrum` as
        --spectrum); GIL released. Raises SolveError, ScenarioError (an unknown code or one
        without factors, a bad spectrum)."""
    @property
    def toml(self) -> str:
        """The scenario's TOML text (what was validated)."""
    @property
    def name(self) -> str:
        """The name in messages: the file, `<dict>`, `<string>` (+ ` (replaced)`)."""
    @property
    def base_dir(self) -> Path:
        """The directory record files are resolved from (absolute)."""
    @property
    def is_row(self) -> bool:
        """Whether the scenario is a row of more than two buildings."""
    @property
    def title(self) -> str:
        """The scenario's title."""
    @property
    def defaults_applied(self) -> list[str]:
        """Keys left out and the defaults used for them (`key = value`)."""
    @property
    def warnings(self) -> list[str]:
        """Plausibility warnings of the scenario."""

class RunOutput:
    """What `run` returns (wrapped by pounding.RunResult)."""

    def summary_json(self) -> str:
        """summary.json's text."""
    def history(self) -> dict[str, npt.NDArray[np.float64]]:
        """history.csv's columns."""
    def impacts(self) -> dict[str, npt.NDArray[Any]]:
        """impacts.csv's columns (`level` int64, the rest float64)."""
    def floors(self) -> dict[str, npt.NDArray[np.float64]]:
        """floors.csv's columns."""
    def summary_text(self) -> str:
        """The summary `pounding run` prints (a suite's report for a suite of records)."""
    def suite_csv(self) -> str | None:
        """suite.csv's text for a suite of records; None for one record."""
    @property
    def warnings(self) -> list[str]:
        """The run's warnings."""
    def save(self, dir: _Path, plots: bool = True) -> list[Path]:
        """Write the files of `pounding run --out DIR`; returns the paths, summary.json last.
        Raises OutputError."""

def run(scenario: Scenario, check: bool = True, max_output_size: int = 1_000_000_000) -> RunOutput:
    """Both runs of a scenario (and its self-check if `check`), GIL released. Raises
    SolveError, ScenarioError (a history above max_output_size)."""

class RowOutput:
    """What `run_row` returns (wrapped by pounding.RowResult)."""

    def summary_json(self) -> str:
        """summary.json's text of a row."""
    def summary_text(self) -> str:
        """The summary `pounding run` prints for a row (for a suite of records, its report)."""
    def suite_csv(self) -> str | None:
        """suite.csv's text for a suite of records on the row (None for one record)."""
    def history(self) -> dict[str, npt.NDArray[np.float64]]:
        """history.csv's columns."""
    def structures(self) -> dict[str, dict[str, npt.NDArray[np.float64]]]:
        """Per structure: `t`, `w`, `w_free`."""
    def pairs(self) -> list[tuple[str, str, dict[str, npt.NDArray[np.float64]]]]:
        """Per pair: left, right, and `t`, `force` (and `force_k` with several levels)."""
    def impacts(self) -> dict[str, Any]:
        """impacts.csv's columns (`pair`, `level` int64; `left`, `right` lists of str)."""
    def floors(self) -> dict[str, npt.NDArray[np.float64]]:
        """floors.csv's columns."""
    @property
    def warnings(self) -> list[str]:
        """The run's warnings."""
    def save(self, dir: _Path, plots: bool = True) -> list[Path]:
        """Write the files of `pounding run --out DIR` for a row; summary.json last."""

def run_row(scenario: Scenario, check: bool = True, max_output_size: int = 1_000_000_000) -> RowOutput:
    """Both runs of a row (and its self-check if `check`), GIL released. Raises SolveError,
    ScenarioError (a history above max_output_size)."""

class Sweep:
    """A checked sweep (immutable, picklable): its cases and how to compute each."""

    @staticmethod
    def from_file(path: _Path) -> Sweep:
        """Read and check a sweep file (as `pounding sweep FILE`). Raises SweepError."""
    @staticmethod
    def from_scenario(scenario: Scenario, axes: Mapping[str, Any]) -> Sweep:
        """A sweep of `scenario` along `axes`: key path → list of values, or → dict with
        `from`, `to`, `steps` (and `scale`), as a sweep file's [[axis]]. Raises SweepError."""
    @staticmethod
    def from_sources(text: str, path: _Path, base_text: str, base_path: _Path) -> Sweep:
        """The sweep `sources()` describes (used by pickling)."""
    def sources(self) -> tuple[str, Path, str, Path]:
        """(sweep text, sweep path, base scenario text, base scenario path)."""
    def __len__(self) -> int:
        """The number of cases."""
    @property
    def axes(self) -> list[str]:
        """The axis keys, first (slowest) first."""
    @property
    def header(self) -> str:
        """results.csv's header line."""
    def label(self, case: int) -> str:
        """`key = value, …` of a case."""
    def case_toml(self, case: int) -> str:
        """The scenario TOML of a case (`pounding sweep FILE --case N`)."""
    def run_case(self, case: int, check: bool = True) -> str:
        """Compute one case to its results row (a line of results.csv), GIL released."""
    def run_all(self, jobs: int, check: bool = True) -> list[str]:
        """Compute every case on `jobs` threads, GIL released; rows in case order. Raises
        SweepError when no case is a valid scenario."""
    def require_valid_case(self) -> None:
        """Raise SweepError when no case is a valid scenario (as `pounding sweep`)."""
    def columns(self, rows: list[str]) -> dict[str, Union[npt.NDArray[Any], list[str]]]:
        """The typed columns of results rows (see pounding.SweepTable)."""

def laws_text(speed: float = 0.5) -> str:
    """The table `pounding laws --speed SPEED` prints; GIL released. Raises ValueError for a
    speed that is not a finite number > 0."""

def available_parallelism() -> int:
    """The number of threads the machine offers."""

def fragility(
    path: _Path, jobs: int | None = None, out: _Path | None = None, plots: bool = True
) -> list[tuple[str, str]]:
    """Run a fragility study file (`pounding fragility`): (name, text) pairs fragility_csv,
    p_pounding_csv, runs_csv (ida.csv in an IDA), capacities_csv, fit_json, report; with `out`,
    the files written there too."""

class FragilityPlan:
    """A checked fragility study split into tasks (immutable; pickles as its study file's
    absolute path)."""

    @staticmethod
    def from_file(path: _Path) -> FragilityPlan:
        """Read and check a study file. Raises ScenarioError."""
    def __len__(self) -> int:
        """The number of tasks (runs of records × stripes, or records of an IDA)."""
    def run_task(self, task: int) -> list[str]:
        """Compute one task, GIL released: its runs as rows. Raises SolveError."""
    def assemble(
        self, rows: list[str], out: _Path | None = None, plots: bool = True
    ) -> list[tuple[str, str]]:
        """The tables (as `fragility`) from the rows of every task; with `out` the files."""
