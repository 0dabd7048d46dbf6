//! `cufem._native`: the Rust side of the Python package `cufem`.
//!
//! A thin layer over the library: models are read by the CLI's parser
//! ([`Model::parse_in`], so the schema and every validation message are the
//! CLI's), solved by [`analysis::run`] in a thread of their own with the GIL
//! released, and written by [`cufem::io::write_into`] (the same files,
//! the same atomic replacement as `cufem run`); fields reach Python as
//! numpy arrays. The pure-Python package (`python/cufem/`) wraps these
//! classes into `cufem.Model` and `cufem.Results`.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc;
use std::time::Duration;

use cufem::analysis::{self, RunOptions, Solution, tables};
use cufem::io::output::OutputDir;
use cufem::io::report;
use cufem::setup::{Limits, Model, ModelError as RustModelError};
use cufem::solver::Interrupt;
use numpy::{IntoPyArray, PyArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyKeyError, PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

mod thread;
mod toml_objects;
use thread::{Channel, Message, Stream, kept_state, solve};
use toml_objects::{object_to_toml, toml_to_object};

create_exception!(
    cufem,
    ModelError,
    PyValueError,
    "An invalid model: the message names the model-file key, the value and what is allowed (the CLI's message)."
);

fn model_error(e: RustModelError) -> PyErr {
    match e {
        RustModelError::Io { .. } => PyOSError::new_err(e.to_string()),
        e => ModelError::new_err(e.to_string()),
    }
}

fn limits(max_memory: Option<u64>) -> Limits {
    Limits { max_memory: max_memory.or_else(cufem::size::available_memory) }
}

/// A validated model (immutable; shared with the analysis thread).
#[pyclass(module = "cufem._native", frozen)]
struct NativeModel {
    model: Arc<Model>,
}

/// Reads and validates a model file (relative paths in it start at its folder).
#[pyfunction]
#[pyo3(signature = (path, max_memory=None))]
fn parse_file(py: Python<'_>, path: PathBuf, max_memory: Option<u64>) -> PyResult<NativeModel> {
    let model = py.allow_threads(|| Model::from_file_with(&path, limits(max_memory))).map_err(model_error)?;
    Ok(NativeModel { model: Arc::new(model) })
}

/// Parses and validates model-file text; relative paths start at `base`.
#[pyfunction]
#[pyo3(signature = (text, base=None, max_memory=None))]
fn parse_toml(py: Python<'_>, text: String, base: Option<PathBuf>, max_memory: Option<u64>) -> PyResult<NativeModel> {
    let base = base.unwrap_or_else(|| PathBuf::from("."));
    let model = py.allow_threads(|| Model::parse_in(&text, limits(max_memory), &base)).map_err(model_error)?;
    Ok(NativeModel { model: Arc::new(model) })
}

/// Writes `text`, ending in a newline, to Python's `sys.stdout` or `sys.stderr`
/// (what Jupyter shows, what pytest's `capsys` captures).
fn write_to(py: Python<'_>, stream: Stream, text: &str) -> PyResult<()> {
    let name = match stream {
        Stream::Out => "stdout",
        Stream::Err => "stderr",
    };
    let file = py.import("sys")?.getattr(name)?;
    let line = if text.ends_with('\n') { text.to_string() } else { format!("{text}\n") };
    file.call_method1("write", (line,))?;
    Ok(())
}

fn write_stderr(py: Python<'_>, text: &str) -> PyResult<()> {
    write_to(py, Stream::Err, text)
}

/// The model's or the run's warnings, to stderr as `cufem run` prints them
/// (also with `quiet`: they are in `summary["warnings"]` too).
fn write_warnings<'a>(py: Python<'_>, warnings: impl Iterator<Item = &'a cufem::setup::Warning>) -> PyResult<()> {
    for w in warnings {
        write_stderr(py, &format!("warning: {w}"))?;
    }
    Ok(())
}

/// An output folder's error in the Python arguments' words (the library
/// words it for the CLI: `--out`, `--force`).
fn output_error(e: impl std::fmt::Display) -> PyErr {
    PyOSError::new_err(e.to_string().replacen("--out ", "out = ", 1).replace("add --force", "pass force=True"))
}

/// Writes every result file into `dir` as `cufem run --out dir [--force]` does.
fn write_folder(model: &Model, solution: &Solution, dir: &Path, force: bool) -> PyResult<Vec<String>> {
    let folder = OutputDir::prepare(dir, force).map_err(output_error)?;
    Ok(cufem::io::write_into(model, solution, folder, |_| ()).map_err(output_error)?.files)
}

#[pymethods]
impl NativeModel {
    /// Sizes of the model: per body and in total, and the equations after
    /// the symbolic factorization.
    fn check<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let m = &self.model;
        let d = PyDict::new(py);
        d.set_item("title", &m.title)?;
        let bodies = PyList::empty(py);
        for b in &m.mesh.bodies {
            let e = PyDict::new(py);
            e.set_item("name", &b.name)?;
            e.set_item("material", &m.materials[b.material].name)?;
            e.set_item("section_elements", b.section.n_elements())?;
            e.set_item("section_element", format!("{:?}", b.section.kind))?;
            e.set_item("section_nodes", b.section.n_nodes())?;
            e.set_item("axis_elements", b.axis.n_elements())?;
            e.set_item("axis_element", format!("{:?}", b.axis.kind))?;
            e.set_item("axis_nodes", b.axis.n_nodes())?;
            e.set_item("elements", b.n_elements())?;
            e.set_item("nodes", b.n_nodes())?;
            e.set_item("dof", 3 * b.n_nodes())?;
            bodies.append(e)?;
        }
        d.set_item("bodies", bodies)?;
        d.set_item("elements", m.mesh.n_elements())?;
        d.set_item("nodes", m.mesh.n_nodes())?;
        d.set_item("dof", m.n_dofs())?;
        let model = self.model.clone();
        let sizes = py.allow_threads(|| analysis::plan(&model)).map_err(|e| ModelError::new_err(e.to_string()))?;
        d.set_item("equations", sizes.equations)?;
        d.set_item("factor_nnz", sizes.factor_nnz)?;
        d.set_item("steps", m.steps.iter().map(|s| s.name.clone()).collect::<Vec<_>>())?;
        d.set_item("probes", m.probes.iter().map(|p| p.name.clone()).collect::<Vec<_>>())?;
        d.set_item("lines", m.lines.iter().map(|p| p.name.clone()).collect::<Vec<_>>())?;
        d.set_item("warnings", m.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>())?;
        Ok(d)
    }

    /// Solves the model in a thread of its own (GIL released); the caller's
    /// thread prints what `cufem run` prints (header, a line per increment,
    /// the final report; nothing but the warnings with `quiet`) and watches
    /// for Ctrl-C: a first one stops the analysis at the next safe point
    /// (the last converged increment is kept and, with `out`, written), a
    /// second one raises `KeyboardInterrupt` at once.
    ///
    /// With the model's text and folder (`text`, `base`) a model with an
    /// `[adapt]` table runs its adaptive cycles as `cufem run` does, and the
    /// results are the last finished cycle's.
    #[pyo3(signature = (out=None, force=false, threads=None, quiet=false, text=None, base=None))]
    #[allow(clippy::too_many_arguments)] // the Python keyword arguments
    fn run(
        &self,
        py: Python<'_>,
        out: Option<PathBuf>,
        force: bool,
        threads: Option<usize>,
        quiet: bool,
        text: Option<String>,
        base: Option<PathBuf>,
    ) -> PyResult<NativeResults> {
        let threads = threads.or(self.model.solver.threads);
        if let Some(n) = threads
            && (n == 0 || n > 1024)
        {
            return Err(PyValueError::new_err(format!("threads = {n}: expected an integer from 1 to 1024")));
        }
        write_warnings(py, self.model.warnings.iter())?;
        // the output folder is checked and locked before any computing
        let folder = match &out {
            Some(dir) => Some(OutputDir::prepare(dir, force).map_err(output_error)?),
            None => None,
        };
        if !quiet {
            write_to(py, Stream::Out, &report::header(&self.model))?;
        }
        let mut builder = rayon::ThreadPoolBuilder::new();
        if let Some(n) = threads {
            builder = builder.num_threads(n);
        }
        let pool = builder.build().map_err(|e| PyRuntimeError::new_err(format!("cannot start threads: {e}")))?;
        let interrupt = Interrupt::new();
        let options = RunOptions { interrupt: interrupt.clone(), max_memory: cufem::size::available_memory() };
        let (tx, mut rx) = mpsc::channel();
        let model = self.model.clone();
        let worker = std::thread::Builder::new()
            .name("cufem-analysis".into())
            .spawn(move || {
                let mut sink = Channel { tx: tx.clone(), print: !quiet };
                let result = pool.install(|| solve(&model, text.as_deref().zip(base.as_deref()), &options, &mut sink));
                let _ = tx.send(Message::Done(Box::new(result)));
            })
            .map_err(|e| PyRuntimeError::new_err(format!("cannot start the analysis thread: {e}")))?;
        let result = loop {
            // the receiver goes into the GIL-free closure and back (it is Send, not Sync)
            let (back, message) = py.allow_threads(move || {
                let m = rx.recv_timeout(Duration::from_millis(50));
                (rx, m)
            });
            rx = back;
            match message {
                Ok(Message::Line(stream, text)) => write_to(py, stream, &text)?,
                Ok(Message::Done(result)) => break *result,
                Err(mpsc::RecvTimeoutError::Timeout) => {}
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    break Err("the analysis thread ended without a result".to_string());
                }
            }
            // signals reach Python handlers in the main thread only; elsewhere this is a no-op
            if let Err(e) = py.check_signals() {
                if interrupt.is_requested() || !e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
                    interrupt.request();
                    return Err(e);
                }
                interrupt.request();
                if !quiet {
                    write_stderr(py, "interrupted: stopping at the next safe point (Ctrl-C again to abandon the run)")?;
                }
            }
        };
        let _ = worker.join();
        let (model, solution) = result.map_err(|e| PyRuntimeError::new_err(format!("analysis failed: {e}")))?;
        if !quiet {
            write_to(py, Stream::Out, &report::results(&model, &solution))?;
        }
        write_warnings(py, solution.warnings.iter())?;
        let mut files = None;
        let mut written_to = None;
        let mut kept = false;
        if let Some(folder) = folder {
            let model = model.clone();
            let written =
                py.allow_threads(|| cufem::io::write_into(&model, &solution, folder, |_| ())).map_err(output_error)?;
            if !quiet {
                write_to(py, Stream::Out, &report::wrote_line(written.files.len(), &written.folder))?;
            }
            kept = written.kept_converged;
            files = Some(written.files);
            written_to = Some(written.folder);
        }
        if !quiet {
            let kept = out.as_deref().filter(|_| kept);
            if let Some(text) = report::stopped_early(&model, &solution, written_to.as_deref(), kept) {
                write_stderr(py, &text)?;
            }
        }
        let written_to = written_to.map(|w| w.display().to_string());
        Ok(NativeResults { model, solution: Arc::new(solution), files, written_to })
    }
}

/// The solution of a run, with its model.
#[pyclass(module = "cufem._native", frozen)]
struct NativeResults {
    model: Arc<Model>,
    solution: Arc<Solution>,
    /// The files written by `run(out=…)`, if any.
    files: Option<Vec<String>>,
    /// The folder they went to (`out`, or `out.partial` beside a converged
    /// set the run did not replace).
    written_to: Option<String>,
}

#[pymethods]
impl NativeResults {
    /// The content of `summary.json` as JSON text (`files`: those written
    /// by `run(out=…)`, else empty).
    fn summary_json(&self, py: Python<'_>) -> PyResult<String> {
        let (model, solution) = (self.model.clone(), self.solution.clone());
        let mut s = py
            .allow_threads(|| cufem::io::full_summary(&model, &solution))
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        if let Some(files) = &self.files {
            s.files = files.iter().filter(|f| *f != "summary.json").cloned().collect();
        }
        serde_json::to_string(&s).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// The files written by `run(out=…)` (None if nothing was written).
    #[getter]
    fn files(&self) -> Option<Vec<String>> {
        self.files.clone()
    }

    /// The folder `run(out=…)` wrote to (None if nothing was written).
    #[getter]
    fn written_to(&self) -> Option<String> {
        self.written_to.clone()
    }

    /// Every quantity at probe `name` (`x, y, z`, `u_x` … `peeq`, `e_xx` …):
    /// its row of the probe table, as in summary.json.
    fn probe(&self, py: Python<'_>, name: &str) -> PyResult<Vec<(String, f64)>> {
        let (model, solution) = (self.model.clone(), self.solution.clone());
        let table = py.allow_threads(|| tables::probes(&model, &solution.fields(&model)));
        let names = table.text("probe").unwrap_or_default();
        let i = names
            .iter()
            .position(|p| p == name)
            .ok_or_else(|| PyKeyError::new_err(format!("probe {name:?}: expected one of {names:?}")))?;
        Ok(table.row(i).0)
    }

    /// The columns of `line_<name>.csv`: `s, x, y, z` and every quantity
    /// (points outside every body left out).
    fn line(&self, py: Python<'_>, name: &str) -> PyResult<Vec<TypedColumn>> {
        let k = self.model.lines.iter().position(|l| l.name == name).ok_or_else(|| {
            let names: Vec<&str> = self.model.lines.iter().map(|p| p.name.as_str()).collect();
            PyKeyError::new_err(format!("line {name:?}: expected one of {names:?}"))
        })?;
        let (model, solution) = (self.model.clone(), self.solution.clone());
        columns(py, &py.allow_threads(|| tables::sampled_line(&model, &solution.fields(&model), k)))
    }

    /// The columns of `history_<name>.csv` (a constraint set: prescribed
    /// displacement and reaction; an indenter or contact: displacement,
    /// force, penetration, plastic points; cut by symmetry planes, the full
    /// structure's force too; `"probes"`: every probe's displacement), one
    /// row per converged increment; an absent value is NaN.
    fn history(&self, py: Python<'_>, name: &str) -> PyResult<Vec<TypedColumn>> {
        let (m, solution) = (&self.model, &self.solution);
        if let Some(ci) = m.constraints.iter().position(|c| c.name == name) {
            return columns(py, &tables::constraint_history(m, solution, ci));
        }
        if let Some(set) = solution.contact_sets.iter().find(|s| s.name == name) {
            return columns(py, &tables::contact_history(m, solution, set));
        }
        if name == "probes" && !m.probes.is_empty() {
            return columns(py, &tables::probe_history(m, solution));
        }
        let mut names: Vec<&str> = m.constraints.iter().map(|c| c.name.as_str()).collect();
        names.extend(solution.contact_sets.iter().map(|s| s.name.as_str()));
        if !m.probes.is_empty() {
            names.push("probes");
        }
        Err(PyKeyError::new_err(format!(
            "history {name:?}: expected a constraint, indenter or contact, one of {names:?}"
        )))
    }

    /// The columns of `modes.csv` (`analysis.type = "modal"`: `mode`,
    /// `frequency_hz`, `effective_mass_*`) or, with `buckling`, of
    /// `buckling.csv` (`mode`, `load_factor`, `critical_load_*`, cut by
    /// symmetry planes `full_critical_load_*`), one row per mode.
    fn modes(&self, py: Python<'_>, buckling: bool) -> PyResult<Vec<TypedColumn>> {
        let (m, solution) = (&self.model, &self.solution);
        let table = if buckling { tables::buckling(m, solution) } else { tables::modes(solution) };
        let (file, kind) = if buckling { ("buckling.csv", "buckling") } else { ("modes.csv", "modal") };
        let table = table.ok_or_else(|| {
            PyKeyError::new_err(format!(
                "{file}: this run has no {kind} analysis (analysis.type = \"{kind}\" computes one)"
            ))
        })?;
        columns(py, &table)
    }

    /// The probe table (`analysis::tables::probes`, summary.json's
    /// `probes`): one row per probe, its name (`probe`), its point `x, y, z`
    /// and every quantity there.
    fn probes(&self, py: Python<'_>) -> PyResult<Vec<TypedColumn>> {
        let (model, solution) = (self.model.clone(), self.solution.clone());
        columns(py, &py.allow_threads(|| tables::probes(&model, &solution.fields(&model))))
    }

    /// The stems of every CSV file a run writes (`line_top`, `history_clamp`,
    /// `history`, `contact_load`, `energy`, `modes` …), in the order
    /// `cufem run` writes them.
    fn table_names(&self) -> Vec<String> {
        let (m, solution) = (&self.model, &self.solution);
        let mut names: Vec<String> = m.lines.iter().map(|l| format!("line_{}", l.name)).collect();
        names.extend(tables::histories(m, solution).into_iter().map(|t| t.name));
        names.extend(other_tables(m, solution).into_iter().map(|t| t.name));
        names
    }

    /// The columns of `<stem>.csv`, any CSV file a run writes
    /// ([`NativeResults::table_names`]), with their CSV headers (`kinetic_J`).
    fn table(&self, py: Python<'_>, stem: &str) -> PyResult<Vec<TypedColumn>> {
        let (m, solution) = (&self.model, &self.solution);
        if let Some(k) = m.lines.iter().position(|l| stem.strip_prefix("line_") == Some(l.name.as_str())) {
            let (model, solution) = (self.model.clone(), self.solution.clone());
            return columns(py, &py.allow_threads(|| tables::sampled_line(&model, &solution.fields(&model), k)));
        }
        let mut all = tables::histories(m, solution);
        all.extend(other_tables(m, solution));
        match all.iter().find(|t| t.name == stem) {
            Some(t) => columns(py, t),
            None => Err(PyKeyError::new_err(format!(
                "table {stem:?}: this run writes no {stem}.csv; expected one of {:?}",
                self.table_names()
            ))),
        }
    }

    /// How many states beside the final one the run kept: `(frames, steps,
    /// modes)`: a transient run's frames, the step ends that kept their
    /// fields, the mode shapes of a modal or buckling analysis.
    fn kept(&self) -> (usize, usize, usize) {
        let s = &self.solution;
        let modes = s.buckling.as_ref().map(|b| b.modes.len()).or(s.modal.as_ref().map(|m| m.modes.len()));
        // a history of one step keeps no fields (its end is the final state);
        // one of several keeps them at each completed step's end
        let steps = s.steps.iter().take_while(|end| end.fields.is_some()).count();
        (s.frames.len(), steps, modes.unwrap_or(0))
    }

    /// The results of one kept state (`kind` `"frame"`, `"step"` or
    /// `"mode"`, `k` from 0): its fields as `frame_<k>.vtu`,
    /// `result_<k>_<name>.vtu` or `mode_<k>.vtu` hold them.
    fn state(&self, py: Python<'_>, kind: &str, k: usize) -> PyResult<NativeResults> {
        let (model, s) = (self.model.clone(), self.solution.clone());
        let (frames, steps, modes) = self.kept();
        let count = match kind {
            "frame" => frames,
            "step" => steps,
            "mode" => modes,
            _ => return Err(PyValueError::new_err(format!("{kind:?}: expected \"frame\", \"step\" or \"mode\""))),
        };
        if k >= count {
            return Err(PyKeyError::new_err(format!("{kind} {k}: this run kept {count} (numbered from 0)")));
        }
        let state = py
            .allow_threads(|| kept_state(&model, &s, kind, k))
            .map_err(PyRuntimeError::new_err)?
            .ok_or_else(|| PyKeyError::new_err(format!("step {k}: its end kept no fields")))?;
        Ok(NativeResults { model, solution: Arc::new(state), files: None, written_to: None })
    }

    /// The 3D field of `result.vtu` as numpy arrays, computed here rather
    /// than read back from a file: `points` (n, 3), `connectivity` (cells,
    /// 8, the linear VTK hexahedra of `output.vtu_cells = "linear"`), `point_data` (name → (n,) or (n, components)) and
    /// `cell_data` (`body`, `element` and, with ply damage, `d_ft d_fc d_mt d_mc`: (cells,)).
    fn fields<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (model, solution) = (self.model.clone(), self.solution.clone());
        let g = py.allow_threads(|| cufem::io::field_grid(&model, &solution));
        let n = g.points.len() / 3;
        let table = |values: Vec<f64>, columns: usize| -> PyResult<Bound<'py, PyAny>> {
            let a = values.into_pyarray(py);
            Ok(if columns == 1 { a.into_any() } else { a.reshape([n, columns])?.into_any() })
        };
        let d = PyDict::new(py);
        // linear hexahedra, 8 points each: one array for any mix of orders
        let c = g.cells(cufem::input::VtuCells::Linear);
        d.set_item("points", table(g.points, 3)?)?;
        let cells = c.body.len();
        let connectivity: Vec<i64> = c.connectivity.iter().map(|&i| i as i64).collect();
        d.set_item("connectivity", connectivity.into_pyarray(py).reshape([cells, 8])?)?;
        let point_data = PyDict::new(py);
        for a in g.point_data {
            point_data.set_item(a.name, table(a.values, a.components)?)?;
        }
        d.set_item("point_data", point_data)?;
        let cell_data = PyDict::new(py);
        let damage = cufem::io::damage_cells(&model, &solution, &c.body, &c.element);
        cell_data.set_item("body", c.body.into_pyarray(py))?;
        cell_data.set_item("element", c.element.into_pyarray(py))?;
        for (name, values) in damage {
            cell_data.set_item(name, values.into_pyarray(py))?;
        }
        d.set_item("cell_data", cell_data)?;
        Ok(d)
    }

    /// Writes every result file into `dir` as `cufem run --out dir` does;
    /// returns the file names.
    #[pyo3(signature = (dir, force=false))]
    fn write(&self, py: Python<'_>, dir: PathBuf, force: bool) -> PyResult<Vec<String>> {
        let (model, solution) = (self.model.clone(), self.solution.clone());
        // the error as it is (its text again inside an OSError read "OSError: OSError: …")
        py.allow_threads(|| write_folder(&model, &solution, &dir, force))
    }
}

/// A column for Python: its CSV header, its kind (`"real"`, `"count"`,
/// `"optional_count"`, `"text"`), its values (a float64 array with NaN
/// where absent, an int64 array of counts, or a list of text) and its SI
/// unit (`tables::Column::unit`, `""` for counts and ratios).
type TypedColumn = (String, &'static str, PyObject, &'static str);

/// A result table as typed columns named by their CSV headers
/// ([`tables::Table::header`]: `kinetic_J` in `energy.csv`).
fn columns(py: Python<'_>, table: &tables::Table) -> PyResult<Vec<TypedColumn>> {
    use tables::Values;
    let column = |c: &tables::Column| -> PyResult<TypedColumn> {
        let (kind, values) = match &c.values {
            Values::Count(v) => {
                let v: Vec<i64> = v.iter().map(|&n| n as i64).collect();
                ("count", v.into_pyarray(py).into_any().unbind())
            }
            Values::Text(v) => ("text", PyList::new(py, v)?.into_any().unbind()),
            Values::OptionalCount(_) => ("optional_count", c.values.to_f64().into_pyarray(py).into_any().unbind()),
            Values::Real(_) | Values::Optional(_) => ("real", c.values.to_f64().into_pyarray(py).into_any().unbind()),
        };
        Ok((table.header(c), kind, values, c.unit))
    };
    table.columns.iter().map(column).collect()
}

/// The tables after the lines and histories, in the order `cufem run`
/// writes them: each contact's points, the modes, the buckling modes, the
/// estimated error of each kept state, the energy balance.
fn other_tables(m: &Model, solution: &Solution) -> Vec<tables::Table> {
    let mut out: Vec<_> = solution.contact_sets.iter().map(|set| tables::contact_points(m, set)).collect();
    let error_history = tables::error_history(m, solution);
    out.extend(
        [tables::modes(solution), tables::buckling(m, solution), error_history, tables::energy(solution)]
            .into_iter()
            .flatten(),
    );
    out
}

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ModelError", m.py().get_type::<ModelError>())?;
    m.add_class::<NativeModel>()?;
    m.add_class::<NativeResults>()?;
    m.add_function(wrap_pyfunction!(parse_file, m)?)?;
    m.add_function(wrap_pyfunction!(parse_toml, m)?)?;
    m.add_function(wrap_pyfunction!(toml_to_object, m)?)?;
    m.add_function(wrap_pyfunction!(object_to_toml, m)?)?;
    Ok(())
}
