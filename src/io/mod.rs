//! Output files: VTU for ParaView, CSV along lines and per increment,
//! PNG plots and the JSON summary.
//!
//! | file | content |
//! |------|---------|
//! | `summary.json` | DOF, wall time, probes, reactions, contact resultants, solver statistics |
//! | `result.vtu` | the whole 3D field (a VTK Lagrange hexahedron per CUF element, or linear sub-cells: `output.vtu_cells`) |
//! | `line_<name>.csv` | fields sampled along each `[[lines]]` entry |
//! | `history_<name>.csv` | per increment: reaction of a constraint set, or force of a contact |
//! | `history_probes.csv` | per increment: the displacement of every probe |
//! | `history.csv` | per increment: load factor, iterations, plastic points, negative pivots of the tangent; with cohesive interfaces the delaminated area, with ply damage the volume past half damage per mode |
//! | `delamination.png` | transient with cohesive interfaces: the delaminated area against time |
//! | `frame_<k>.vtu`, `frames.pvd` | transient with `analysis.output_interval`: the fields at every output time, and their ParaView time series |
//! | `energy.csv`, `energy.png` | transient: per converged time step, the kinetic energy, the work of the internal, damping, applied, contact and support forces, and their balance |
//! | `mode_<k>.vtu` | buckling and modal: the shape of mode k as the displacement field |
//! | `modes.csv` | modal: per mode, the natural frequency, the effective masses and the estimated errors |
//! | `buckling.csv` | buckling: per mode, the critical load factor and load and the estimated errors |
//! | `error_history.csv` | per step end and frame kept: the estimated discretization error of that state |
//! | `contact_<name>.csv` | final gap, force and pressure of every contact point |
//! | `line_<name>_<quantity>.png` | plots of the quantities listed in a line's `plot` |
//! | `history_<indenter>.png` | force against displacement of each moving indenter |
//! | `report.html` | the run's self-contained page: text, tables, warnings, charts, 3D view (`output.report`); `cufem verify` adds its comparison ([`add_section`]) |

mod csv;
mod delamination;
mod energy;
mod error_history;
mod html;
mod json;
pub mod output;
mod png;
pub mod report;
mod run;
mod section_plot;
mod vtu;

pub use csv::field as csv_field;
pub use html::{Plot, Section, SectionTable, add_section};
pub use json::{ForceSummary, Summary, summary};
pub use png::Series;
pub use run::{Finished, RunError, RunInto, Written, run_into, solved_into, write_into};
pub use section_plot::section_plot;
pub(crate) use vtu::write_gauss_vtu;
pub use vtu::{
    Cells, FieldArray, FieldGrid, GridElement, damage_cells, field_grid, write_contact_vtu, write_point_cloud,
    write_vtu,
};

use std::path::{Path, PathBuf};

use crate::analysis::{Solution, tables};
use crate::setup::Model;

/// Errors while writing results.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    /// File system error.
    #[error("cannot write {path}: {source}")]
    File {
        /// Path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// VTK writer error.
    #[error("cannot write VTU file {path}: {message}")]
    Vtk {
        /// Path.
        path: String,
        /// Cause.
        message: String,
    },
    /// Plotting error.
    #[error("cannot draw plot {path}: {message}")]
    Plot {
        /// Path.
        path: String,
        /// Cause.
        message: String,
    },
    /// The stress recovery of a step's fields failed.
    #[error("cannot recover the stresses of a step: {0}")]
    Recovery(String),
}

/// An I/O error on `path`.
pub fn file_error(path: &Path, source: std::io::Error) -> IoError {
    IoError::File { path: path.display().to_string(), source }
}

/// Writes every output of a solved model into `dir` (created if needed),
/// `summary.json` last. Returns the paths written. The CLI writes into the
/// staging folder of an [`output::OutputDir`], which makes the set appear
/// as a whole.
pub fn write_results(model: &Model, solution: &Solution, dir: &Path) -> Result<Vec<PathBuf>, IoError> {
    let start = std::time::Instant::now();
    std::fs::create_dir_all(dir).map_err(|e| file_error(dir, e))?;
    let mut written = Vec::new();
    let view = solution.fields(model);
    let mut shown = model.output.report.then(html::View::default);

    if model.output.gauss_points {
        let path = dir.join("gauss.vtu");
        write_gauss_vtu(&path, model, solution)?;
        written.push(path);
    }

    let mut lines = Vec::new();
    for k in 0..model.lines.len() {
        let table = tables::sampled_line(model, &view, k);
        written.push(csv::write_table(&table, dir)?);
        if model.output.plots {
            written.extend(png::line_plots(&model.lines[k], &table, dir)?);
        }
        lines.push(table);
    }

    let histories = tables::histories(model, solution);
    written.extend(csv::write_tables(&histories, dir)?);
    let points: Vec<_> = solution.contact_sets.iter().map(|set| tables::contact_points(model, set)).collect();
    written.extend(csv::write_tables(&points, dir)?);
    if model.output.vtu {
        for (k, set) in solution.contact_sets.iter().enumerate() {
            let path = dir.join(format!("contact_{}.vtu", set.name));
            write_contact_vtu(&path, model, solution, k)?;
            written.push(path);
        }
    }
    if model.output.plots {
        written.extend(png::history_plots(model, &histories, dir)?);
    }
    let modes: Vec<_> =
        [tables::modes(solution), tables::buckling(model, solution), tables::error_history(model, solution)]
            .into_iter()
            .flatten()
            .collect();
    written.extend(csv::write_tables(&modes, dir)?);
    written.extend(write_modes(model, solution, dir, shown.as_mut())?);
    written.extend(energy::write_energy(model, solution, dir)?);
    written.extend(delamination::write_delamination_plot(model, solution, dir)?);
    if let Some(a) = &solution.adapt {
        // the adapted mesh as a model file (`cufem run adapted.toml` solves it again)
        let path = dir.join("adapted.toml");
        std::fs::write(&path, &a.model_file).map_err(|e| file_error(&path, e))?;
        written.push(path);
    }
    // the end of every step: a VTU per step and a .pvd series when the
    // history has several steps; probes and resultants per step in the summary
    let mut steps = Vec::new();
    let mut series = Vec::new();
    for k in 0..solution.steps.len() {
        let snapshot = solution.at_step(model, k).map_err(|e| IoError::Recovery(e.to_string()))?;
        let at_end = snapshot.as_ref().unwrap_or(solution);
        let mut vtu = None;
        if let Some(at) = &snapshot {
            let step = &solution.steps[k];
            let label = format!("end of step {} ({}, λ = {:.4})", k + 1, step.name, step.lambda);
            let name = step_vtu_name(solution, k);
            let path = model.output.vtu.then(|| dir.join(&name));
            write_state(model, at, path.as_deref(), shown.as_mut().map(|v| (v, label, false)))?;
            if let Some(path) = path {
                written.push(path);
                // the series' time: λ, or the time in s of a transient run
                let lambda = step.lambda;
                series.push((model.transient.as_ref().map_or(lambda, |t| t.time(lambda)), name.clone()));
                vtu = Some(name);
            }
        }
        steps.push(json::step_summary(model, solution, k, at_end, vtu));
    }
    if !series.is_empty() {
        let path = dir.join("result.pvd");
        write_pvd(&path, &series)?;
        written.push(path);
    }
    written.extend(write_frames(model, solution, dir, shown.as_mut())?);
    let end = model.output.vtu.then(|| dir.join("result.vtu"));
    let label = format!("end (λ = {:.4})", solution.lambda);
    write_state(model, solution, end.as_deref(), shown.as_mut().map(|v| (v, label, true)))?;
    written.extend(end);
    // last: its presence and its list of files mark a complete result set
    let mut s = summary(model, solution);
    s.steps = steps;
    if let Some(shown) = shown {
        let energy: Vec<_> = tables::energy(solution).into_iter().chain(modes).collect();
        let tables = html::Tables { histories: &histories, lines: &lines, others: &energy };
        let (page, gathering) = (std::time::Instant::now(), shown.spent);
        written.push(html::write(model, solution, dir, &s, tables, shown)?);
        s.timings.report_s = (gathering + page.elapsed()).as_secs_f64();
    }
    s.timings.output_s = start.elapsed().as_secs_f64();
    s.files = written.iter().filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned())).collect();
    let path = dir.join("summary.json");
    json::write(&path, &s)?;
    written.push(path);
    Ok(written)
}

/// `mode_<k>.vtu` for every buckling or vibration mode: the mode shape
/// (largest component 1, dimensionless) as the `displacement` field of the
/// mesh, strains and stresses those of the shape at that scale (where the
/// mode strains);
/// the shapes the report's view takes go to `shown`, from the same grid.
fn write_modes(
    model: &Model,
    solution: &Solution,
    dir: &Path,
    mut shown: Option<&mut html::View>,
) -> Result<Vec<PathBuf>, IoError> {
    let (modes, labels): (&[Vec<f64>], Vec<String>) = match (&solution.buckling, &solution.modal) {
        (Some(b), _) => (&b.modes, b.factors.iter().map(|f| format!("critical load factor {f:.5e}")).collect()),
        (None, Some(m)) => (&m.modes, m.frequencies.iter().map(|f| format!("{f:.5e} Hz")).collect()),
        (None, None) => return Ok(Vec::new()),
    };
    let mut written = Vec::new();
    if !model.output.vtu && shown.is_none() {
        return Ok(written);
    }
    let mut shape = solution.clone();
    for (k, (mode, label)) in modes.iter().zip(labels).enumerate() {
        let path = model.output.vtu.then(|| dir.join(json::mode_vtu_name(k + 1)));
        let view = shown.as_deref_mut().filter(|v| v.takes_mode());
        if path.is_none() && view.is_none() {
            continue;
        }
        shape.u.clone_from(mode);
        // a mode's own error estimate (`post::mode_error`) as its `error` field
        let errors = match (&solution.buckling, &solution.modal) {
            (Some(b), _) => &b.errors,
            (None, Some(m)) => &m.errors,
            (None, None) => unreachable!("returned above without modes"),
        };
        shape.error_estimate = errors.get(k).map(|e| e.estimate.clone());
        let grid = field_grid(model, &shape);
        if let Some(v) = view {
            v.add_mode(format!("mode {}: {label}", k + 1), &grid);
        }
        if let Some(path) = path {
            vtu::write_grid_vtu(&path, model, &shape, grid)?;
            written.push(path);
        }
    }
    Ok(written)
}

/// `frame_<k>.vtu` for every frame of a transient run
/// (`analysis.output_interval`) and `frames.pvd`, their ParaView time
/// series in seconds; the frames the report's slider takes go to `shown`.
fn write_frames(
    model: &Model,
    solution: &Solution,
    dir: &Path,
    mut shown: Option<&mut html::View>,
) -> Result<Vec<PathBuf>, IoError> {
    let mut written = Vec::new();
    let mut series = Vec::new();
    let n = solution.frames.len();
    for (k, frame) in solution.frames.iter().enumerate() {
        let report = shown.is_some() && html::View::wants(k, n);
        if !model.output.vtu && !report {
            continue;
        }
        let snapshot = solution.at_frame(model, k).map_err(|e| IoError::Recovery(e.to_string()))?;
        let name = format!("frame_{:04}.vtu", k + 1);
        let path = model.output.vtu.then(|| dir.join(&name));
        let view = shown.as_deref_mut().filter(|_| report).map(|v| (v, format!("t = {:.4e} s", frame.time), false));
        write_state(model, &snapshot, path.as_deref(), view)?;
        if let Some(path) = path {
            written.push(path);
            series.push((frame.time, name));
        }
    }
    if !series.is_empty() {
        let path = dir.join("frames.pvd");
        write_pvd(&path, &series)?;
        written.push(path);
    }
    Ok(written)
}

/// Writes the VTU of the state `at` (to `vtu`, if given) and adds it to
/// the report's 3D view (`view`: the view, the frame's label, whether it
/// is the run's end), both from one field grid: the grid is the costly part
/// of either.
fn write_state(
    model: &Model,
    at: &Solution,
    vtu: Option<&Path>,
    view: Option<(&mut html::View, String, bool)>,
) -> Result<(), IoError> {
    let view = match view {
        Some((v, _, last)) if !v.takes(at.lambda, last) => {
            v.skip(last);
            None
        }
        view => view,
    };
    if vtu.is_none() && view.is_none() {
        return Ok(());
    }
    let grid = field_grid(model, at);
    if let Some((v, label, _)) = view {
        v.add_grid(label, model, at, &grid);
    }
    match vtu {
        Some(path) => vtu::write_grid_vtu(path, model, at, grid),
        None => Ok(()),
    }
}

/// The file name of step `k`'s VTU.
fn step_vtu_name(solution: &Solution, k: usize) -> String {
    format!("result_{}_{}.vtu", k + 1, solution.steps[k].name)
}

/// The content of `summary.json` for results kept in memory (the Python
/// package): what [`write_results`] writes, per-step entries included,
/// with an empty `files` list.
pub fn full_summary(model: &Model, solution: &Solution) -> Result<Summary, IoError> {
    let mut s = summary(model, solution);
    for k in 0..solution.steps.len() {
        let snapshot = solution.at_step(model, k).map_err(|e| IoError::Recovery(e.to_string()))?;
        let vtu = (model.output.vtu && snapshot.is_some()).then(|| step_vtu_name(solution, k));
        s.steps.push(json::step_summary(model, solution, k, snapshot.as_ref().unwrap_or(solution), vtu));
    }
    Ok(s)
}

/// A ParaView collection: one dataset per step end, its time the analysis
/// time λ (ParaView plays the steps in order).
fn write_pvd(path: &Path, series: &[(f64, String)]) -> Result<(), IoError> {
    let mut text =
        String::from("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n");
    for (t, file) in series {
        text.push_str(&format!("  <DataSet timestep=\"{t}\" part=\"0\" file=\"{file}\"/>\n"));
    }
    text.push_str("</Collection>\n</VTKFile>\n");
    std::fs::write(path, text).map_err(|e| file_error(path, e))
}
