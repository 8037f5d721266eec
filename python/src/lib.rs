//! `pounding._core`: the compiled module of the Python package `pounding` (python/pounding/).
//!
//! It only parses Python objects, calls the `pounding` library and converts its results to
//! Python objects (NumPy arrays, dicts, strings): every piece of logic — validating a scenario,
//! setting key paths, listing a sweep's cases, running one, writing a run's files — is a
//! function of the library that the command line uses too. The simulation runs with the GIL
//! released. Errors are Python exceptions carrying the library's message (the text the
//! command line prints after `error: `); a panic of the library is caught and raised as an
//! exception, never carried across the boundary.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use numpy::IntoPyArray;
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use pounding::analysis::simulate::{Report, RunCapture};
use pounding::input::scenario::{Scenario, ScenarioError as LibScenarioError};
use pounding::output::run::Column;
use pounding::study::sweep::Sweep;

mod row;

create_exception!(
    pounding,
    ScenarioError,
    PyValueError,
    "A scenario (or a value given for it) was refused; the message is the command line's: file:line:col, key, allowed range."
);
create_exception!(
    pounding,
    SweepError,
    PyValueError,
    "A sweep (its file, base scenario or axes) was refused; the message is the command line's."
);
create_exception!(
    pounding,
    SolveError,
    PyRuntimeError,
    "A simulation could not be carried out (an unstable step, no time history, …); the message is the command line's."
);
create_exception!(
    pounding,
    OutputError,
    PyOSError,
    "The files of a run could not be written."
);

fn scenario_err(e: LibScenarioError) -> PyErr {
    ScenarioError::new_err(e.to_string())
}

fn sweep_err(e: pounding::study::sweep::SweepError) -> PyErr {
    SweepError::new_err(e.to_string())
}

/// The message of a caught panic.
fn panic_message(p: Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<String>()
        .cloned()
        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}

/// Run `f`, turning a panic of the library into `SolveError` (never across the FFI boundary).
fn no_panic<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).unwrap_or_else(|p| {
        Err(SolveError::new_err(format!(
            "internal error (please report): {}",
            panic_message(p)
        )))
    })
}

// ---------------------------------------------------------------------------------------------
// Python objects → TOML values

/// Deepest nesting of dicts and lists accepted from Python.
const MAX_DEPTH: usize = 32;

/// A key path as the library's messages write it: `structure[2].period`.
fn child(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// Convert a Python value (dict, list/tuple, str, bool, int, float, NumPy scalar or 1-D/2-D
/// array) to a TOML value; anything else is a `ScenarioError` naming `path` in `origin`.
fn to_toml(v: &Bound<'_, PyAny>, path: &str, origin: &str) -> PyResult<toml::Value> {
    let refuse = |what: String| -> PyErr {
        let at = if path.is_empty() {
            String::new()
        } else {
            format!(" `{path}`:")
        };
        ScenarioError::new_err(format!("{origin}:{at} {what}"))
    };
    // (a list that contains itself must not recurse until the stack overflows)
    if path.matches(['.', '[']).count() > MAX_DEPTH {
        return Err(refuse(format!(
            "nested more than {MAX_DEPTH} levels deep: a scenario has a few"
        )));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        return Ok(toml::Value::Table(dict_to_table(d, path, origin)?));
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract::<bool>()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract::<String>()?));
    }
    if v.is_instance_of::<PyInt>() {
        return v
            .extract::<i64>()
            .map(toml::Value::Integer)
            .map_err(|_| refuse(format!("{v} does not fit in a 64-bit integer")));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract::<f64>()?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for (i, x) in v.try_iter()?.enumerate() {
            out.push(to_toml(&x?, &format!("{path}[{}]", i + 1), origin)?);
        }
        return Ok(toml::Value::Array(out));
    }
    // NumPy scalars and arrays, without importing NumPy: by their module and kind
    let ty = v.get_type();
    let module: String = ty
        .getattr("__module__")
        .and_then(|m| m.extract())
        .unwrap_or_default();
    if module == "numpy" {
        let name: String = ty.getattr("__name__")?.extract()?;
        if name == "ndarray" {
            return to_toml(&v.call_method0("tolist")?, path, origin);
        }
        if name == "bool" || name == "bool_" {
            return Ok(toml::Value::Boolean(v.call_method0("__bool__")?.extract()?));
        }
        if name.starts_with("int") || name.starts_with("uint") {
            let i = v.call_method0("__index__")?;
            return i
                .extract::<i64>()
                .map(toml::Value::Integer)
                .map_err(|_| refuse(format!("{v} does not fit in a 64-bit integer")));
        }
        if name.starts_with("float") || name == "longdouble" {
            return Ok(toml::Value::Float(v.call_method0("__float__")?.extract()?));
        }
    }
    let tname: String = ty.getattr("__name__")?.extract()?;
    Err(refuse(format!(
        "a value of type {tname} ({}) cannot be a scenario value: give a dict (table), list, str, bool, int or float (NumPy numbers too)",
        v.repr().map(|r| r.to_string()).unwrap_or_default()
    )))
}

fn dict_to_table(d: &Bound<'_, PyDict>, path: &str, origin: &str) -> PyResult<toml::Table> {
    let mut t = toml::Table::new();
    for (k, v) in d.iter() {
        let Ok(key) = k.extract::<String>() else {
            let at = if path.is_empty() {
                "the top level".to_string()
            } else {
                format!("`{path}`")
            };
            return Err(ScenarioError::new_err(format!(
                "{origin}: key {} in {at} is not a string: keys of a scenario are names",
                k.repr()?
            )));
        };
        let value = to_toml(&v, &child(path, &key), origin)?;
        t.insert(key, value);
    }
    Ok(t)
}

// ---------------------------------------------------------------------------------------------
// Scenario

/// A validated scenario: its TOML text, the name it goes by in messages, the directory record
/// files are relative to, and the library's checked `Scenario`.
#[pyclass(frozen, module = "pounding._core", name = "Scenario")]
struct PyScenario {
    text: String,
    origin: String,
    base_dir: PathBuf,
    inner: Arc<Scenario>,
}

/// Appended to the name of a scenario made by `replace` (its text is no longer the file's).
const REPLACED: &str = " (replaced)";

fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

impl PyScenario {
    fn build(text: String, origin: String, base_dir: PathBuf) -> PyResult<PyScenario> {
        let base_dir = absolute(&base_dir);
        let inner =
            no_panic(|| Scenario::from_toml(&text, &origin, &base_dir).map_err(scenario_err))?;
        Ok(PyScenario {
            text,
            origin,
            base_dir,
            inner: Arc::new(inner),
        })
    }

    /// The scenario's path as a sweep names its base: its directory and file name.
    fn path(&self) -> PathBuf {
        let name = Path::new(self.origin.trim_end_matches(REPLACED))
            .file_name()
            .map_or_else(|| "scenario".into(), |n| n.to_string_lossy().into_owned());
        self.base_dir.join(name)
    }
}

#[pymethods]
impl PyScenario {
    /// Read and validate a scenario file (as `pounding run FILE`).
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<PyScenario> {
        let (inner, text) = py
            .detach(|| Scenario::read_file(&path))
            .map_err(scenario_err)?;
        Ok(PyScenario {
            text,
            origin: path.display().to_string(),
            base_dir: absolute(path.parent().unwrap_or(Path::new("."))),
            inner: Arc::new(inner),
        })
    }

    /// Validate scenario TOML text; `name` names it in messages, `base_dir` resolves record files.
    #[staticmethod]
    #[pyo3(signature = (text, name = "<string>".to_string(), base_dir = PathBuf::from(".")))]
    fn from_toml(text: String, name: String, base_dir: PathBuf) -> PyResult<PyScenario> {
        PyScenario::build(text, name, base_dir)
    }

    /// Validate a scenario given as nested dicts and lists (the structure of a scenario file).
    #[staticmethod]
    #[pyo3(signature = (data, name = "<dict>".to_string(), base_dir = PathBuf::from(".")))]
    fn from_dict(
        data: &Bound<'_, PyDict>,
        name: String,
        base_dir: PathBuf,
    ) -> PyResult<PyScenario> {
        let table = dict_to_table(data, "", &name)?;
        let base_dir = absolute(&base_dir);
        let inner =
            no_panic(|| Scenario::from_table(&table, &name, &base_dir).map_err(scenario_err))?;
        let text = pounding::input::scenario::table_to_toml(&table, &name).map_err(scenario_err)?;
        Ok(PyScenario {
            text,
            origin: name,
            base_dir,
            inner: Arc::new(inner),
        })
    }

    /// A new scenario with keys set by the sweep's key paths.
    fn replace(&self, values: &Bound<'_, PyDict>) -> PyResult<PyScenario> {
        let mut list = Vec::new();
        for (k, v) in values.iter() {
            let key: String = k.extract().map_err(|_| {
                ScenarioError::new_err(format!(
                    "replace: key {} is not a string: give key paths such as \"structure.2.period\"",
                    k.repr().map(|r| r.to_string()).unwrap_or_default()
                ))
            })?;
            let value = to_toml(&v, &key, "replace")?;
            list.push((key, value));
        }
        let text = pounding::study::sweep::set_keys(&self.text, &self.path(), list)
            .map_err(|e| ScenarioError::new_err(e.to_string()))?;
        // positions in messages are in the new text, not in the file it came from
        let origin = if self.origin.ends_with(REPLACED) {
            self.origin.clone()
        } else {
            format!("{}{REPLACED}", self.origin)
        };
        PyScenario::build(text, origin, self.base_dir.clone())
    }

    /// The scenario's TOML text (what was validated; positions in messages refer to it).
    #[getter]
    fn toml(&self) -> &str {
        &self.text
    }

    /// The name the scenario goes by in messages (its file, or `<dict>`, `<string>`).
    #[getter]
    fn name(&self) -> &str {
        &self.origin
    }

    /// The directory record files are resolved from.
    #[getter]
    fn base_dir(&self) -> PathBuf {
        self.base_dir.clone()
    }

    /// Whether the scenario is a row of more than two buildings (issue 29).
    #[getter]
    fn is_row(&self) -> bool {
        self.inner.is_row()
    }

    /// The scenario's title.
    #[getter]
    fn title(&self) -> &str {
        &self.inner.title
    }

    /// Keys left out and the defaults used for them (`key = value`).
    #[getter]
    fn defaults_applied(&self) -> Vec<String> {
        self.inner.defaults_applied.clone()
    }

    /// Plausibility warnings of the scenario.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.warnings.clone()
    }

    fn __repr__(&self) -> String {
        format!("Scenario({:?}, title={:?})", self.origin, self.inner.title)
    }

    /// The table `pounding modes` prints for this scenario.
    fn modes_text(&self) -> PyResult<String> {
        no_panic(|| Ok(pounding::output::text::modes_table(&self.inner)))
    }

    /// The tables `pounding separation` prints: every rule and code at every contact level
    /// (`codes`: only these, as `--code`; `spectrum`: a design spectrum for the rules, as
    /// `--spectrum`), with the GIL released during the run without pounding.
    #[pyo3(signature = (codes = None, spectrum = None))]
    fn separation_text(
        &self,
        py: Python<'_>,
        codes: Option<Vec<String>>,
        spectrum: Option<String>,
    ) -> PyResult<String> {
        let sc = self.inner.clone();
        py.detach(|| {
            no_panic(|| {
                let spectrum = spectrum
                    .as_deref()
                    .map(pounding::input::scenario::design::spectrum_from_arg)
                    .transpose()
                    .map_err(scenario_err)?;
                let report = pounding::analysis::gap_report::gap_report(
                    &sc,
                    spectrum.as_ref(),
                    codes.as_deref(),
                )
                .map_err(|e| match e {
                    pounding::analysis::gap_report::GapError::UnknownCode(_)
                    | pounding::analysis::gap_report::GapError::NotInScenario(_) => {
                        ScenarioError::new_err(e.to_string())
                    }
                    _ => SolveError::new_err(e.to_string()),
                })?;
                Ok(pounding::output::text::separation_report(&report))
            })
        })
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, (String, String, PathBuf))> {
        let s = slf.get();
        let ctor = slf.get_type().getattr("from_toml")?;
        Ok((ctor, (s.text.clone(), s.origin.clone(), s.base_dir.clone())))
    }
}

// ---------------------------------------------------------------------------------------------
// One run

/// The outcome of `run`: the scenario, the report and every history sample.
#[pyclass(frozen, module = "pounding._core", name = "RunOutput")]
struct PyRunOutput {
    scenario: Arc<Scenario>,
    /// The scenario's name in reports (its file, `<dict>`, …), as `pounding run` names it.
    name: String,
    report: Report,
    capture: RunCapture,
    floor_columns: Vec<String>,
    /// A suite of records: every record's run (the fields above are the representative
    /// record's, the top level of summary.json).
    suite: Option<Arc<pounding::study::suite::SuiteRun>>,
}

fn float_dict<'py>(py: Python<'py>, cols: Vec<(String, Vec<f64>)>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in cols {
        d.set_item(k, v.into_pyarray(py))?;
    }
    Ok(d)
}

fn column_dict<'py>(py: Python<'py>, cols: Vec<(String, Column)>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, c) in cols {
        match c {
            Column::Int(v) => d.set_item(k, v.into_pyarray(py))?,
            Column::Float(v) => d.set_item(k, v.into_pyarray(py))?,
            Column::Text(v) => d.set_item(k, PyList::new(py, v)?)?,
        }
    }
    Ok(d)
}

#[pymethods]
impl PyRunOutput {
    /// summary.json's text (exactly the file `pounding run` writes).
    fn summary_json(&self) -> PyResult<String> {
        let section = self
            .suite
            .as_deref()
            .map(pounding::study::suite::write::section);
        pounding::output::run::summary_json_with(&self.scenario, &self.report, section.as_ref())
            .map_err(OutputError::new_err)
    }

    /// The summary `pounding run` prints (for a suite of records, the suite's report).
    fn summary_text(&self) -> PyResult<String> {
        no_panic(|| {
            Ok(match self.suite.as_deref() {
                Some(run) => {
                    pounding::study::suite::report::text(run, &self.scenario.title, &self.name)
                }
                None => {
                    pounding::output::text::run_summary(&self.scenario, &self.name, &self.report)
                }
            })
        })
    }

    /// suite.csv's text for a suite of records (`None` for one record).
    fn suite_csv(&self) -> Option<String> {
        self.suite
            .as_deref()
            .map(pounding::study::suite::write::suite_csv)
    }

    /// history.csv's columns: dict of float64 arrays.
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        float_dict(py, self.capture.history_columns())
    }

    /// impacts.csv's columns: dict of arrays (`level` int64, the rest float64).
    fn impacts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let cols = pounding::output::run::impact_columns(&self.report)
            .into_iter()
            .map(|(k, c)| (k.to_string(), c))
            .collect();
        column_dict(py, cols)
    }

    /// floors.csv's columns: dict of float64 arrays.
    fn floors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        float_dict(py, self.capture.floor_columns(&self.floor_columns))
    }

    /// The run's warnings (as printed by `pounding run`).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.report.warnings.clone()
    }

    /// Write the files of `pounding run --out DIR` (pictures unless `plots` is false);
    /// returns the paths written, summary.json last.
    #[pyo3(signature = (dir, plots = true))]
    fn save(&self, py: Python<'_>, dir: PathBuf, plots: bool) -> PyResult<Vec<PathBuf>> {
        py.detach(|| {
            no_panic(|| {
                if let Some(run) = self.suite.as_deref() {
                    let draw = plots.then(|| pounding::figures::suite::suite_pictures(run));
                    return pounding::study::suite::write::write(&dir, run, draw, |_| None)
                        .map_err(|e| OutputError::new_err(e.to_string()));
                }
                let draw = plots
                    .then(|| pounding::figures::run::run_pictures(&self.scenario, &self.report));
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

/// Run a scenario with and without pounding (and its self-check unless `check` is false), as
/// `pounding run` does, with the GIL released.
#[pyfunction]
#[pyo3(signature = (scenario, check = true, max_output_size = 1_000_000_000))]
fn run(
    py: Python<'_>,
    scenario: &Bound<'_, PyScenario>,
    check: bool,
    max_output_size: u64,
) -> PyResult<PyRunOutput> {
    let sc = scenario.get().inner.clone();
    let name = scenario.get().origin.clone();
    py.detach(|| {
        no_panic(|| {
            if sc.suite.is_some() {
                // every record (issue 27); the representative record's run is the top level
                use pounding::study::suite::SuiteError as E;
                let run = pounding::study::suite::run(&sc, check).map_err(|e| match e {
                    E::Solve { .. } => SolveError::new_err(e.to_string()),
                    _ => ScenarioError::new_err(e.to_string()),
                })?;
                let rep = &run.records[run.representative];
                return Ok(PyRunOutput {
                    scenario: Arc::new(rep.scenario.clone()),
                    name,
                    report: rep.report.clone(),
                    capture: rep.capture.clone(),
                    floor_columns: pounding::output::run::floor_columns(&rep.scenario),
                    suite: Some(Arc::new(run)),
                });
            }
            pounding::analysis::simulate::require_time_history(&sc)
                .map_err(|e| SolveError::new_err(e.to_string()))?;
            pounding::output::budget::check_run(&sc, max_output_size)
                .map_err(|e| ScenarioError::new_err(e.to_string()))?;
            let mut capture = RunCapture::new();
            let report = pounding::analysis::simulate::simulate_streaming(&sc, check, &mut capture)
                .map_err(|e| SolveError::new_err(e.to_string()))?;
            let floor_columns = pounding::output::run::floor_columns(&sc);
            Ok(PyRunOutput {
                scenario: sc.clone(),
                name,
                report,
                capture,
                floor_columns,
                suite: None,
            })
        })
    })
}

// ---------------------------------------------------------------------------------------------
// Sweeps

/// (sweep text, sweep path, base scenario text, base scenario path): a sweep, for pickling.
type SweepSources = (String, PathBuf, String, PathBuf);

/// A checked sweep: its cases, each computed to a results row.
#[pyclass(frozen, module = "pounding._core", name = "Sweep")]
struct PySweep {
    inner: Sweep,
}

/// One axis given from Python: `key -> [values]` or `key -> {"from": …, "to": …, "steps": …}`.
fn axis_table(key: &str, spec: &Bound<'_, PyAny>) -> PyResult<toml::Table> {
    let mut t = toml::Table::new();
    t.insert("key".into(), toml::Value::String(key.to_string()));
    match to_toml(spec, key, "axes")? {
        toml::Value::Table(range) => t.extend(range),
        toml::Value::Array(values) => {
            t.insert("values".into(), toml::Value::Array(values));
        }
        other => {
            t.insert("values".into(), toml::Value::Array(vec![other]));
        }
    }
    Ok(t)
}

#[pymethods]
impl PySweep {
    /// Read and check a sweep file (as `pounding sweep FILE`).
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<PySweep> {
        let inner = py.detach(|| Sweep::from_file(&path)).map_err(sweep_err)?;
        Ok(PySweep { inner })
    }

    /// A sweep over `scenario` along `axes` (dict: key path -> list of values, or -> dict
    /// with `from`, `to`, `steps` and optionally `scale`), as a sweep file would give them.
    #[staticmethod]
    fn from_scenario(
        py: Python<'_>,
        scenario: &Bound<'_, PyScenario>,
        axes: &Bound<'_, PyDict>,
    ) -> PyResult<PySweep> {
        let sc = scenario.get();
        let mut list = Vec::new();
        for (k, v) in axes.iter() {
            let key: String = k.extract().map_err(|_| {
                SweepError::new_err(format!(
                    "axes: key {} is not a string: give key paths such as \"ground_motion.pga\"",
                    k.repr().map(|r| r.to_string()).unwrap_or_default()
                ))
            })?;
            list.push(axis_table(&key, &v)?);
        }
        let path = sc.path();
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        let text = pounding::study::sweep::sweep_text(&name, list).map_err(sweep_err)?;
        let sweep_path = sc.base_dir.join("<axes>");
        let inner = py
            .detach(|| Sweep::from_toml_with_base(&text, &sweep_path, Some((&sc.text, &path))))
            .map_err(sweep_err)?;
        Ok(PySweep { inner })
    }

    /// The same sweep from what `sources()` gave (e.g. in another process).
    #[staticmethod]
    fn from_sources(
        py: Python<'_>,
        text: String,
        path: PathBuf,
        base_text: String,
        base_path: PathBuf,
    ) -> PyResult<PySweep> {
        let inner = py
            .detach(|| Sweep::from_toml_with_base(&text, &path, Some((&base_text, &base_path))))
            .map_err(sweep_err)?;
        Ok(PySweep { inner })
    }

    /// (sweep text, sweep path, base scenario text, base scenario path).
    fn sources(&self) -> SweepSources {
        let (a, b, c, d) = self.inner.sources();
        (
            a.to_string(),
            b.to_path_buf(),
            c.to_string(),
            d.to_path_buf(),
        )
    }

    fn __len__(&self) -> usize {
        self.inner.len()
    }

    /// The axis keys, first (slowest) first.
    #[getter]
    fn axes(&self) -> Vec<String> {
        self.inner.axes.iter().map(|a| a.key.clone()).collect()
    }

    /// The results header (results.csv's first line).
    #[getter]
    fn header(&self) -> String {
        pounding::study::sweep::results::header(&self.inner)
    }

    /// `key = value, …` of a case.
    fn label(&self, case: usize) -> PyResult<String> {
        self.check_case(case)?;
        Ok(self.inner.label(case))
    }

    /// The scenario TOML of a case (`pounding sweep FILE --case N`).
    fn case_toml(&self, case: usize) -> PyResult<String> {
        self.check_case(case)?;
        self.inner.case_toml(case).map_err(ScenarioError::new_err)
    }

    /// Compute one case to its results row (a line of results.csv), GIL released.
    #[pyo3(signature = (case, check = true))]
    fn run_case(&self, py: Python<'_>, case: usize, check: bool) -> PyResult<String> {
        self.check_case(case)?;
        Ok(py.detach(|| pounding::study::sweep::run::compute_case(&self.inner, case, check).line))
    }

    /// Compute every case on `jobs` threads (GIL released); the rows in case order.
    #[pyo3(signature = (jobs, check = true))]
    fn run_all(&self, py: Python<'_>, jobs: usize, check: bool) -> PyResult<Vec<String>> {
        let rows = py
            .detach(|| pounding::study::sweep::run::compute_all(&self.inner, jobs, check))
            .map_err(sweep_err)?;
        Ok(rows.into_iter().map(|r| r.line).collect())
    }

    /// Refuse a sweep none of whose cases is a valid scenario (as `pounding sweep` does).
    fn require_valid_case(&self, py: Python<'_>) -> PyResult<()> {
        let cases: Vec<usize> = (0..self.inner.len()).collect();
        py.detach(|| pounding::study::sweep::run::require_valid_case(&self.inner, &cases))
            .map_err(sweep_err)
    }

    /// The typed columns of results rows (dict: int64/float64 arrays, lists of str).
    fn columns<'py>(&self, py: Python<'py>, rows: Vec<String>) -> PyResult<Bound<'py, PyDict>> {
        let cols =
            pounding::study::sweep::results::columns(&self.inner, &rows).map_err(sweep_err)?;
        column_dict(py, cols)
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, SweepSources)> {
        let ctor = slf.get_type().getattr("from_sources")?;
        Ok((ctor, slf.get().sources()))
    }

    fn __repr__(&self) -> String {
        format!(
            "Sweep({:?}, {} cases, axes={:?})",
            self.inner.path.display().to_string(),
            self.inner.len(),
            self.axes()
        )
    }
}

impl PySweep {
    fn check_case(&self, case: usize) -> PyResult<()> {
        if case >= self.inner.len() {
            return Err(pyo3::exceptions::PyIndexError::new_err(format!(
                "case {case}: the sweep has {} cases, numbered 0 to {}",
                self.inner.len(),
                self.inner.len().saturating_sub(1)
            )));
        }
        Ok(())
    }
}

/// Threads the machine offers (the default of `jobs`).
#[pyfunction]
fn available_parallelism() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

// ---------------------------------------------------------------------------------------------
// Fragility studies (issue 28)

/// A fragility study's tables as CSV text (`fragility_csv`, `p_pounding_csv`, `runs_csv` —
/// `ida.csv` in an IDA — and `capacities_csv`), `fit_json` and `report`; with `out`, the files
/// (and with `plots` the figures) are written there too, `fit.json` last.
fn fragility_parts(
    run: &pounding::study::fragility::FragilityRun,
    out: Option<&Path>,
    plots: bool,
) -> PyResult<Vec<(String, String)>> {
    use pounding::study::fragility as fr;
    if let Some(dir) = out {
        let mut failed = None;
        fr::write::write(run, dir, || {
            if !plots {
                return Vec::new();
            }
            pounding::figures::fragility::pictures(run, dir).unwrap_or_else(|e| {
                failed = Some(e.to_string());
                Vec::new()
            })
        })
        .map_err(|e| OutputError::new_err(e.to_string()))?;
        if let Some(e) = failed {
            return Err(OutputError::new_err(format!("the figures: {e}")));
        }
    }
    Ok(vec![
        ("fragility_csv".into(), fr::write::fragility_csv(run)),
        ("p_pounding_csv".into(), fr::write::p_pounding_csv(run)),
        ("runs_csv".into(), fr::write::runs_csv(run)),
        ("capacities_csv".into(), fr::write::capacities_csv(run)),
        ("fit_json".into(), fr::write::fit_json_text(run)),
        ("report".into(), fr::report::report(run)),
    ])
}

fn fragility_err(e: pounding::study::fragility::FragilityError) -> PyErr {
    use pounding::study::fragility::FragilityError as E;
    match e {
        E::Solve { .. } => SolveError::new_err(e.to_string()),
        _ => ScenarioError::new_err(e.to_string()),
    }
}

/// Run a fragility study file, as `pounding fragility` does, with the GIL released: a dict
/// of its tables ([`fragility_parts`]).
#[pyfunction]
#[pyo3(signature = (path, jobs = None, out = None, plots = true))]
fn fragility(
    py: Python<'_>,
    path: PathBuf,
    jobs: Option<usize>,
    out: Option<PathBuf>,
    plots: bool,
) -> PyResult<Vec<(String, String)>> {
    use pounding::study::fragility as fr;
    py.detach(|| {
        no_panic(|| {
            let study = pounding::input::fragility::FragilityStudy::from_file(&path)
                .map_err(|e| ScenarioError::new_err(e.to_string()))?;
            let run = fr::run(&study, jobs).map_err(fragility_err)?;
            fragility_parts(&run, out.as_deref(), plots)
        })
    })
}

/// A checked fragility study split into tasks (a run at a stripe, or a record's whole IDA),
/// each computed to journal rows anywhere (a Dask worker), the rows joined into the study's
/// tables. Pickles as its study file's absolute path (workers read the study and its records
/// from there).
#[pyclass(frozen, module = "pounding._core", name = "FragilityPlan")]
struct PyFragilityPlan {
    path: PathBuf,
    study: pounding::input::fragility::FragilityStudy,
    record_im: Vec<f64>,
}

#[pymethods]
impl PyFragilityPlan {
    /// Read and check a study file.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<PyFragilityPlan> {
        py.detach(|| {
            no_panic(|| {
                let path = std::path::absolute(&path).unwrap_or(path);
                let study = pounding::input::fragility::FragilityStudy::from_file(&path)
                    .map_err(|e| ScenarioError::new_err(e.to_string()))?;
                let record_im =
                    pounding::study::fragility::record_ims(&study).map_err(fragility_err)?;
                Ok(PyFragilityPlan {
                    path,
                    study,
                    record_im,
                })
            })
        })
    }

    /// The number of tasks.
    fn __len__(&self) -> usize {
        pounding::study::fragility::tasks(&self.study)
    }

    /// Compute task `task` (GIL released): its runs as journal rows.
    fn run_task(&self, py: Python<'_>, task: usize) -> PyResult<Vec<String>> {
        let n = self.__len__();
        if task >= n {
            return Err(pyo3::exceptions::PyIndexError::new_err(format!(
                "task {task}: the study has {n} tasks, numbered 0 to {}",
                n.saturating_sub(1)
            )));
        }
        py.detach(|| {
            no_panic(|| {
                pounding::study::fragility::journal::task_rows(&self.study, &self.record_im, task)
                    .map_err(fragility_err)
            })
        })
    }

    /// The study's tables from the rows of every task (as `pounding.fragility` returns them);
    /// with `out` the files are written too.
    #[pyo3(signature = (rows, out = None, plots = true))]
    fn assemble(
        &self,
        py: Python<'_>,
        rows: Vec<String>,
        out: Option<PathBuf>,
        plots: bool,
    ) -> PyResult<Vec<(String, String)>> {
        py.detach(|| {
            no_panic(|| {
                let run = pounding::study::fragility::journal::assemble_rows(&self.study, &rows)
                    .map_err(fragility_err)?;
                fragility_parts(&run, out.as_deref(), plots)
            })
        })
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (PathBuf,))> {
        let ctor = slf.get_type().getattr("from_file")?;
        Ok((ctor, (slf.get().path.clone(),)))
    }

    fn __repr__(&self) -> String {
        format!(
            "FragilityPlan({:?}, {} tasks)",
            self.path.display().to_string(),
            self.__len__()
        )
    }
}

/// The table `pounding laws` prints: the restitution each contact law that takes a target e
/// achieves on an isolated impact at approach speed `speed` (m/s), GIL released.
#[pyfunction]
#[pyo3(signature = (speed = 0.5))]
fn laws_text(py: Python<'_>, speed: f64) -> PyResult<String> {
    if !(speed.is_finite() && speed > 0.0) {
        return Err(PyValueError::new_err(format!(
            "speed must be a finite number > 0 (m/s), got {speed}"
        )));
    }
    py.detach(|| {
        no_panic(|| {
            let table = pounding::analysis::restitution::restitution_table(speed)
                .map_err(|e| SolveError::new_err(e.to_string()))?;
            Ok(pounding::output::text::laws_table(&table))
        })
    })
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ScenarioError", py.get_type::<ScenarioError>())?;
    m.add("SweepError", py.get_type::<SweepError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    m.add("OutputError", py.get_type::<OutputError>())?;
    m.add_class::<PyScenario>()?;
    m.add_class::<PyRunOutput>()?;
    m.add_class::<row::PyRowOutput>()?;
    m.add_class::<PySweep>()?;
    m.add_class::<PyFragilityPlan>()?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(row::run_row, m)?)?;
    m.add_function(wrap_pyfunction!(fragility, m)?)?;
    m.add_function(wrap_pyfunction!(available_parallelism, m)?)?;
    m.add_function(wrap_pyfunction!(laws_text, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
