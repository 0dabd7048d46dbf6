//! `cufem verify`: run a model and its CalculiX twin, compare them.

use std::path::{Path, PathBuf};

use cufem::analysis::RunOptions;
use cufem::io::Finished;
use cufem::io::output::OutputDir;
use cufem_ccx::verify;
use cufem_ccx::{self as ccx, CcxError};

use super::{FILES, Failure, NOT_CONVERGED, OK, Reporter, Resources, fail};

/// Exit code: CalculiX is missing or did not finish.
pub const CCX_FAILED: u8 = 5;

/// Options of `cufem verify`.
pub struct Args {
    pub model: PathBuf,
    pub out: Option<PathBuf>,
    pub refine: usize,
    pub element: String,
    pub ccx: Option<PathBuf>,
    pub ccx_results: Option<PathBuf>,
    pub force: bool,
    pub quiet: bool,
    pub resources: Resources,
}

/// `program` as given with a path, or found on `PATH`.
fn find_program(program: &Path) -> Option<PathBuf> {
    if program.components().count() > 1 {
        return program.is_file().then(|| program.to_path_buf());
    }
    std::env::var_os("PATH")?.to_str()?.split(':').map(|d| Path::new(d).join(program)).find(|p| p.is_file())
}

/// Adds the whole-field rows and the zones left out (of a modal model: the
/// frequencies mode by mode; of a transient one: the probe histories) to
/// the run's `summary.json` (key `verify`),
/// beside the table in `verify/`.
fn add_to_summary(path: &Path, c: &verify::Comparison) -> Result<(), cufem::io::IoError> {
    let error = |e: std::io::Error| cufem::io::file_error(path, e);
    let text = std::fs::read_to_string(path).map_err(error)?;
    let mut summary: serde_json::Value = serde_json::from_str(&text).map_err(|e| error(e.into()))?;
    summary["verify"] = if !c.modes.is_empty() {
        serde_json::json!({ "solid": c.solid, "modes": c.modes })
    } else if !c.probe_histories.is_empty() {
        serde_json::json!({ "solid": c.solid, "probe_histories": c.probe_histories })
    } else {
        serde_json::json!({ "solid": c.solid, "fields": c.fields, "excluded": c.excluded })
    };
    std::fs::write(path, serde_json::to_string_pretty(&summary).unwrap_or_default()).map_err(error)
}

/// `--ccx-results FOLDER`: checked before anything is computed — a folder
/// holding the deck and results of an earlier CalculiX run (`model.inp`,
/// `model.frd`), as `cufem verify` leaves them in `<out>/verify/ccx`.
fn earlier_run(from: &Path) -> Result<(), Failure> {
    let expected = "the verify/ccx folder of an earlier `cufem verify` of the same model (holding its CalculiX deck \
                    model.inp and results model.frd)";
    let problem = if !from.exists() {
        Some("no such folder".to_string())
    } else if !from.is_dir() {
        Some("not a folder".to_string())
    } else {
        let missing: Vec<&str> = ["model.inp", "model.frd"].into_iter().filter(|f| !from.join(f).is_file()).collect();
        (!missing.is_empty()).then(|| format!("the folder holds no {}", missing.join(" and no ")))
    };
    match problem {
        None => Ok(()),
        Some(p) => {
            Err(fail(super::INPUT, anyhow::anyhow!("--ccx-results {}: {p}; expected {expected}", from.display())))
        }
    }
}

pub fn run(a: Args) -> Result<u8, Failure> {
    let interrupt = super::install_interrupt()?;
    let model = super::load(&a.model, &a.resources)?;
    let kind = super::hex_kind(&a.element)?;
    let refine = super::check_refine(a.refine)?;
    // a model without a CalculiX twin is refused before the analysis
    ccx::check_supported(&model).map_err(super::ccx_failure)?;
    // CalculiX must be there before anything is computed
    let requested = a.ccx.clone().unwrap_or_else(|| PathBuf::from("ccx"));
    let program = match &a.ccx_results {
        // reusing earlier results needs no CalculiX, but those results
        Some(from) => {
            earlier_run(from)?;
            requested.clone()
        }
        None => find_program(&requested)
            .ok_or_else(|| fail(CCX_FAILED, CcxError::Missing { program: requested.display().to_string() }))?,
    };
    super::print_warnings(model.warnings.iter());
    let threads = a.resources.threads.or(model.solver.threads);
    super::configure_threads(threads, a.resources.force_threads)?;
    let out = a.out.clone().unwrap_or_else(|| super::default_out(&a.model, ""));
    if interrupt.is_requested() {
        return super::interrupted_before_start();
    }
    let folder = OutputDir::prepare(&out, a.force).map_err(|e| fail(FILES, e))?;
    if !a.quiet {
        print!("{}", cufem::io::report::header(&model));
    }
    let mut progress = Reporter::new(a.quiet);
    let options = RunOptions { interrupt, max_memory: super::limit(&a.resources) };
    let n_threads = threads.unwrap_or_else(rayon::current_num_threads);
    // the comparison goes into the staging folder's verify/ before the
    // cufem results are committed (with them, whether CalculiX ran or not)
    let compare = |done: Finished<'_>| -> Result<String, Failure> {
        let dir = done.staging.join("verify");
        let ccx_dir = dir.join("ccx");
        let (mesh, _) = ccx::export(&model, kind, refine, &ccx_dir).map_err(super::ccx_failure)?;
        if !a.quiet {
            eprintln!(
                "running CalculiX on {} {} hexahedra ({} nodes) in {}",
                mesh.elements.len(),
                kind.name(),
                mesh.nodes.len(),
                out.join("verify").join("ccx").display()
            );
        }
        let ccx_run = match &a.ccx_results {
            Some(from) => ccx::reuse(from, &ccx_dir),
            None => ccx::run(&program.display().to_string(), &ccx_dir, n_threads),
        };
        let ccx_run = ccx_run.map_err(|e| {
            let _ = std::fs::write(dir.join("ccx_failed.txt"), e.to_string());
            fail(CCX_FAILED, e)
        })?;
        let (comparison, curves, whole) = verify::compare(&model, done.solution, &mesh, &ccx_run, done.analysis_peak);
        comparison.write(&dir, &curves, &whole).map_err(|e| fail(FILES, e))?;
        add_to_summary(&done.staging.join("summary.json"), &comparison).map_err(|e| fail(FILES, e))?;
        // the run's page (unless `output.report = false`) shows the comparison too
        let page = done.staging.join("report.html");
        if page.exists() {
            cufem::io::add_section(&page, &comparison.section(&curves)).map_err(|e| fail(FILES, e))?;
        }
        Ok(comparison.table())
    };
    let run = cufem::io::run_into(&model, folder, &options, &mut progress, compare).map_err(super::run_failure)?;
    progress.finish();
    match run.extra {
        Some(Ok(table)) => {
            println!("{table}");
            println!("wrote the comparison to {}", out.join("verify").display());
            Ok(OK)
        }
        Some(Err(e)) => {
            eprintln!("cufem results and the CalculiX deck and log are in {}", out.display());
            Err(e)
        }
        // `extra` runs for every finished analysis: this one stopped early
        None => {
            let f = run.solution.failure.as_ref();
            let why = f.map(ToString::to_string).unwrap_or_default();
            eprintln!(
                "the cufem analysis stopped early ({why}); nothing to compare: results in {}",
                run.folder.display()
            );
            let interrupted = f.is_some_and(|f| f.reason == cufem::solver::stepping::StopReason::Interrupted);
            Ok(if interrupted { super::INTERRUPTED } else { NOT_CONVERGED })
        }
    }
}
