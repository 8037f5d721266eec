//! A row of buildings from Python (issue 29): `pounding.run` on a row returns a `RowOutput`
//! (wrapped by `pounding.RowResult`), with arrays per structure and per pair. As for a pair,
//! everything is the library's: the row's run (`simulate_row_streaming`), its tables
//! (`output::row`), its text (`output::text::row_summary`) and its files (`output::run::
//! write_run`).

use std::path::PathBuf;
use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use pounding::analysis::simulate::{RowReport, RunCapture};
use pounding::input::scenario::Scenario;

use super::{
    OutputError, PyScenario, ScenarioError, SolveError, column_dict, float_dict, no_panic,
};

/// The outcome of `run_row`: the scenario, the row's report and every history sample.
#[pyclass(frozen, module = "pounding._core", name = "RowOutput")]
pub(crate) struct PyRowOutput {
    scenario: Arc<Scenario>,
    name: String,
    report: RowReport,
    capture: RunCapture,
    /// A suite of records on the row: every record's run (the fields above are the
    /// representative record's, the top level of summary.json).
    suite: Option<Arc<pounding::study::suite::row::RowSuiteRun>>,
}

#[pymethods]
impl PyRowOutput {
    /// summary.json's text (exactly the file `pounding run` writes for a row).
    fn summary_json(&self) -> PyResult<String> {
        let section = self
            .suite
            .as_deref()
            .map(pounding::study::suite::write::section);
        pounding::output::row::row_summary_json_with(&self.scenario, &self.report, section.as_ref())
            .map_err(OutputError::new_err)
    }

    /// suite.csv's text for a suite of records on the row (`None` for one record).
    fn suite_csv(&self) -> Option<String> {
        self.suite
            .as_deref()
            .map(pounding::study::suite::write::suite_csv)
    }

    /// The summary `pounding run` prints for a row.
    fn summary_text(&self) -> PyResult<String> {
        no_panic(|| {
            if let Some(run) = self.suite.as_deref() {
                return Ok(pounding::study::suite::report::text(
                    run,
                    &self.scenario.title,
                    &self.name,
                ));
            }
            Ok(pounding::output::text::row_summary(
                &self.scenario,
                &self.name,
                &self.report,
            ))
        })
    }

    /// history.csv's columns: dict of float64 arrays.
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        float_dict(
            py,
            pounding::output::row::row_history_table(&self.scenario, &self.capture),
        )
    }

    /// Per structure (row order): dict name → dict of float64 arrays `t`, `w`, `w_free`.
    fn structures<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (name, cols) in
            pounding::output::row::row_structure_series(&self.scenario, &self.capture)
        {
            d.set_item(name, float_dict(py, cols)?)?;
        }
        Ok(d)
    }

    /// Per adjacent pair (row order): list of (left, right, dict of float64 arrays `t`,
    /// `force`, and `force_1 … force_k` with several levels).
    fn pairs<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyTuple>>> {
        pounding::output::row::row_pair_series(&self.scenario, &self.capture)
            .into_iter()
            .map(|([l, r], cols)| {
                let d = float_dict(py, cols)?;
                PyTuple::new(
                    py,
                    [
                        l.into_pyobject(py)?.into_any(),
                        r.into_pyobject(py)?.into_any(),
                        d.into_any(),
                    ],
                )
            })
            .collect()
    }

    /// impacts.csv's columns: dict of arrays (`pair`, `level` int64; `left`, `right` lists of
    /// str; the rest float64).
    fn impacts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let cols = pounding::output::row::row_impact_columns(&self.report)
            .into_iter()
            .map(|(k, c)| (k.to_string(), c))
            .collect();
        column_dict(py, cols)
    }

    /// floors.csv's columns: dict of float64 arrays.
    fn floors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let columns = pounding::output::row::row_floor_columns(&self.scenario);
        float_dict(py, self.capture.floor_columns(&columns))
    }

    /// The run's warnings (as printed by `pounding run`).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.report.warnings.clone()
    }

    /// Write the files of `pounding run --out DIR` for a row (pictures unless `plots` is
    /// false); returns the paths written, summary.json last.
    #[pyo3(signature = (dir, plots = true))]
    fn save(&self, py: Python<'_>, dir: PathBuf, plots: bool) -> PyResult<Vec<PathBuf>> {
        py.detach(|| {
            no_panic(|| {
                if let Some(run) = self.suite.as_deref() {
                    use pounding::figures::suite::{row_suite_pictures, row_suite_record_pictures};
                    let draw = plots.then(|| row_suite_pictures(run));
                    return pounding::study::suite::write::write(&dir, run, draw, |i| {
                        plots.then(|| row_suite_record_pictures(run, i))
                    })
                    .map_err(|e| OutputError::new_err(e.to_string()));
                }
                let draw = plots
                    .then(|| pounding::figures::row::row_pictures(&self.scenario, &self.report));
                pounding::output::writer::write_run(
                    &dir,
                    &self.scenario,
                    &self.report,
                    &self.capture,
                    draw,
                )
                .map_err(|e| OutputError::new_err(e.to_string()))
            })
        })
    }
}

/// Run a row of buildings with and without pounding (and its self-check unless `check` is
/// false), as `pounding run` does, with the GIL released.
#[pyfunction]
#[pyo3(signature = (scenario, check = true, max_output_size = 1_000_000_000))]
pub(crate) fn run_row(
    py: Python<'_>,
    scenario: &Bound<'_, PyScenario>,
    check: bool,
    max_output_size: u64,
) -> PyResult<PyRowOutput> {
    let sc = scenario.get().inner.clone();
    let name = scenario.get().origin.clone();
    py.detach(|| {
        no_panic(|| {
            if sc.suite.is_some() {
                // every record through the row's driver; the representative's run is the top
                use pounding::study::suite::SuiteError as E;
                let run =
                    pounding::study::suite::row::run_row(&sc, check).map_err(|e| match e {
                        E::Solve { .. } => SolveError::new_err(e.to_string()),
                        _ => ScenarioError::new_err(e.to_string()),
                    })?;
                let rep = &run.records[run.representative];
                return Ok(PyRowOutput {
                    scenario: Arc::new(rep.scenario.clone()),
                    name,
                    report: rep.report.clone(),
                    capture: rep.capture.clone(),
                    suite: Some(Arc::new(run)),
                });
            }
            pounding::analysis::simulate::require_time_history(&sc)
                .map_err(|e| SolveError::new_err(e.to_string()))?;
            pounding::output::budget::check_run(&sc, max_output_size)
                .map_err(|e| ScenarioError::new_err(e.to_string()))?;
            let mut capture = RunCapture::new();
            let report =
                pounding::analysis::simulate::simulate_row_streaming(&sc, check, &mut capture)
                    .map_err(|e| SolveError::new_err(e.to_string()))?;
            Ok(PyRowOutput {
                scenario: sc.clone(),
                name,
                report,
                capture,
                suite: None,
            })
        })
    })
}
