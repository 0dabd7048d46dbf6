//! Command-line edge: argument parsing, progress, report printing, exit
//! codes. Library errors are typed; here they become `anyhow` messages.
//!
//! Exit codes (also in the README):
//!
//! | code | meaning |
//! |---:|---|
//! | 0 | success |
//! | 1 | invalid model file or command line (the message names the key, the value and what is allowed) |
//! | 2 | the analysis stopped before the full load (not converged); the last converged increment is written |
//! | 3 | a file could not be read or written (output folder unusable or locked, disk full) |
//! | 4 | the model needs more memory than available (`--max-memory` raises the limit) |
//! | 5 | `verify`: CalculiX is missing or did not finish (the cufem results, deck and log are written) |
//! | 130 | interrupted (Ctrl-C or SIGTERM); the last converged increment is written |
// the arguments' doc comments are clap's --help text, written for a terminal
// (`out/<model name>`), not HTML
#![allow(rustdoc::invalid_html_tags)]

mod adapt;
mod bench;
mod report;
mod values;
mod verify;

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::anyhow;
use clap::{Parser, Subcommand};
use cufem::analysis::{self, AnalysisError, IncrementLog, Progress, RunOptions};
use cufem::io::output::OutputDir;
use cufem::setup::{Limits, Model, ModelError};
use cufem::size;
use cufem::solver::Interrupt;
use cufem::solver::stepping::{Cutback, StopReason};
use indicatif::{ProgressBar, ProgressStyle};
use values::{integer_in, parse_memory, parse_refine, parse_repeat, parse_threads};

/// Exit code: success.
const OK: u8 = 0;
/// Exit code: invalid model or command line.
const INPUT: u8 = 1;
/// Exit code: the analysis stopped before the full load.
const NOT_CONVERGED: u8 = 2;
/// Exit code: a file could not be read or written.
const FILES: u8 = 3;
/// Exit code: not enough memory.
const TOO_LARGE: u8 = 4;
/// Exit code: interrupted (128 + SIGINT, as shells report it).
const INTERRUPTED: u8 = 130;

/// Refined 1D (CUF) finite elements for elastoplastic contact.
#[derive(Parser)]
#[command(name = "cufem", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(clap::Args)]
struct Resources {
    /// Worker threads (default: the model's `solver.threads`, else all logical cores; more than the
    /// machine's logical cores are capped at them, with a warning, unless --force-threads).
    #[arg(long, allow_negative_numbers = true, value_parser = parse_threads)]
    threads: Option<usize>,
    /// Allow more threads than logical cores (at most 1024).
    #[arg(long)]
    force_threads: bool,
    /// Largest memory the analysis may need, e.g. 8G or 512MiB (default: the memory available now).
    // allow_hyphen_values: "-5G" reaches the parser, whose message names what is allowed, instead of
    // clap's "unexpected argument '-5'"
    #[arg(long, allow_hyphen_values = true, value_parser = parse_memory)]
    max_memory: Option<u64>,
}

#[derive(Subcommand)]
enum Command {
    /// Run the analysis of a model file and write results.
    Run {
        /// Model file (TOML).
        model: PathBuf,
        /// Output folder (default: out/<model name>). Replaced as a whole when the run ends.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write into an output folder that holds files cufem did not write (they are left alone).
        #[arg(long)]
        force: bool,
        /// Print only the final report.
        #[arg(long)]
        quiet: bool,
        #[command(flatten)]
        adapt: adapt::AdaptArgs,
        #[command(flatten)]
        resources: Resources,
    },
    /// Validate a model file; print its sections' properties, size and memory estimate.
    Check {
        /// Model file (TOML).
        model: PathBuf,
        /// Also draw every body's section mesh to `<model>_section_<body>.png`.
        #[arg(long)]
        plot: bool,
        /// Folder for the --plot drawings (default: the model file's folder).
        #[arg(long)]
        out: Option<PathBuf>,
        #[command(flatten)]
        resources: Resources,
    },
    /// Write a CalculiX deck (3D solid model) of the same problem.
    ExportCcx {
        /// Model file (TOML).
        model: PathBuf,
        /// Hexahedra per Lagrange interval of the CUF mesh, per direction (1 to 8).
        #[arg(long, default_value_t = 2, allow_negative_numbers = true, value_parser = parse_refine)]
        refine: usize,
        /// Solid element: C3D20R or C3D8I.
        #[arg(long, default_value = "C3D20R")]
        element: String,
        /// Output folder (default: out/<model name>-ccx).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Run a model and its CalculiX twin (3D solids) and compare them at the probes, lines and resultants.
    Verify {
        /// Model file (TOML).
        model: PathBuf,
        /// Output folder (default: out/<model name>); the comparison goes to its verify/ folder.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Hexahedra per Lagrange interval of the CUF mesh, per direction (1 to 8).
        #[arg(long, default_value_t = 2, allow_negative_numbers = true, value_parser = parse_refine)]
        refine: usize,
        /// Solid element: C3D20R or C3D8I.
        #[arg(long, default_value = "C3D20R")]
        element: String,
        /// The CalculiX program (default: ccx on the PATH).
        #[arg(long)]
        ccx: Option<PathBuf>,
        /// Compare with the CalculiX results of an earlier verify of the same deck (its verify/ccx folder)
        /// instead of running CalculiX again: e.g. another formulation or recovery on the same mesh.
        #[arg(long)]
        ccx_results: Option<PathBuf>,
        /// Write into an output folder that holds files cufem did not write.
        #[arg(long)]
        force: bool,
        /// Print only the final report.
        #[arg(long)]
        quiet: bool,
        #[command(flatten)]
        resources: Resources,
    },
    /// Time the phases of an analysis (setup, assembly, factorization, solve) over repeated runs.
    Bench {
        /// Model file (TOML).
        model: PathBuf,
        /// Number of timed repetitions (the median is reported; 1 to 1000).
        #[arg(long, default_value_t = 5, allow_negative_numbers = true, value_parser = parse_repeat)]
        repeat: usize,
        /// Time the full analysis instead of one linear solve.
        #[arg(long)]
        full: bool,
        #[command(flatten)]
        resources: Resources,
    },
    /// Print the JSON Schema of the model file, for editors that check and complete it as it is typed
    /// (docs/model-format.md, "Editor support").
    Schema,
}

/// Most worker threads, also with --force-threads.
const MAX_THREADS: usize = 1024;

/// An error with the exit code it maps to.
struct Failure {
    code: u8,
    error: anyhow::Error,
}

fn fail(code: u8, error: impl Into<anyhow::Error>) -> Failure {
    Failure { code, error: error.into() }
}

/// Entry point (see the module docs for the exit codes).
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            // clap uses 2 for usage errors; ours is 1 (2 means "not converged")
            return ExitCode::from(if e.use_stderr() { INPUT } else { OK });
        }
    };
    match dispatch(cli) {
        Ok(code) => ExitCode::from(code),
        Err(f) => {
            eprintln!("error: {:#}", f.error);
            ExitCode::from(f.code)
        }
    }
}

fn dispatch(cli: Cli) -> Result<u8, Failure> {
    match cli.command {
        Command::Run { model, out, force, quiet, adapt, resources } => {
            run(&model, out, force, quiet, &adapt, &resources)
        }
        Command::Check { model, plot, out, resources } => {
            let m = load(&model, &resources)?;
            report::print_check(&m);
            if plot {
                plot_sections(&m, &model, out)?;
            }
            let sizes = analysis::plan(&m).map_err(|e| fail(INPUT, e))?;
            report::print_memory(&sizes, limit(&resources));
            print_warnings(m.warnings.iter());
            Ok(OK)
        }
        Command::Verify { model, out, refine, element, ccx, ccx_results, force, quiet, resources } => {
            verify::run(verify::Args { model, out, refine, element, ccx, ccx_results, force, quiet, resources })
        }
        Command::ExportCcx { model, refine, element, out } => {
            let m = load(&model, &Resources { threads: None, force_threads: false, max_memory: None })?;
            let kind = hex_kind(&element)?;
            let refine = check_refine(refine)?;
            let dir = out.unwrap_or_else(|| default_out(&model, "-ccx"));
            folder_or_new(&dir)?;
            let (mesh, path) = cufem_ccx::export(&m, kind, refine, &dir).map_err(ccx_failure)?;
            println!(
                "wrote {} ({} nodes, {} {} body elements, {} tool elements)",
                path.display(),
                mesh.nodes.len(),
                mesh.parts.iter().filter(|p| matches!(p, cufem_ccx::mesh::Part::Body(_))).count(),
                kind.name(),
                mesh.parts.iter().filter(|p| matches!(p, cufem_ccx::mesh::Part::Tool(_))).count()
            );
            Ok(OK)
        }
        Command::Bench { model, repeat, full, resources } => {
            let m = load(&model, &resources)?;
            configure_threads(resources.threads.or(m.solver.threads), resources.force_threads)?;
            bench::run(&m, repeat, full).map_err(|e| fail(INPUT, e))?;
            Ok(OK)
        }
        Command::Schema => {
            let text = serde_json::to_string_pretty(&cufem::input::json_schema()).map_err(|e| fail(INPUT, e))?;
            println!("{text}");
            Ok(OK)
        }
    }
}

/// `--out` of a command that writes into a folder: refused, naming the
/// option as `cufem run` does, when it is an existing file (the OS error
/// named only the path).
fn folder_or_new(dir: &Path) -> Result<(), Failure> {
    if dir.exists() && !dir.is_dir() {
        return Err(fail(INPUT, cufem::io::output::OutputError::NotAFolder(dir.display().to_string())));
    }
    Ok(())
}

/// `cufem check --plot`: one PNG per body, `<model stem>_section_<body>.png`.
fn plot_sections(m: &Model, model: &Path, out: Option<PathBuf>) -> Result<(), Failure> {
    let dir = out.unwrap_or_else(|| model.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf));
    folder_or_new(&dir)?;
    std::fs::create_dir_all(&dir).map_err(|e| fail(FILES, anyhow!("cannot create {}: {e}", dir.display())))?;
    let stem = model.file_stem().map_or_else(|| "model".into(), |s| s.to_string_lossy().into_owned());
    for b in &m.mesh.bodies {
        let path = dir.join(format!("{stem}_section_{}.png", b.name));
        let p = b.section.properties();
        let title = format!(
            "{}: {} × {:?}, {} nodes, A = {:.4} mm²",
            b.name,
            b.section.n_elements(),
            b.section.kind,
            b.section.n_nodes(),
            p.area * 1e6
        );
        cufem::io::section_plot(&path, &title, &b.section).map_err(|e| fail(FILES, e))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// An export error: a model the deck cannot represent is invalid input for
/// this command (exit 1); anything else is a file error (exit 3).
fn ccx_failure(e: cufem_ccx::CcxError) -> Failure {
    match e {
        cufem_ccx::CcxError::Unsupported { .. }
        | cufem_ccx::CcxError::PreStressed { .. }
        | cufem_ccx::CcxError::Transient { .. } => fail(INPUT, e),
        e => fail(FILES, e),
    }
}

fn hex_kind(element: &str) -> Result<cufem_ccx::HexKind, Failure> {
    cufem_ccx::HexKind::parse(element)
        .ok_or_else(|| fail(INPUT, anyhow!("--element = {element:?}: expected \"C3D20R\" or \"C3D8I\"")))
}

fn check_refine(refine: usize) -> Result<usize, Failure> {
    if (1..=8).contains(&refine) {
        Ok(refine)
    } else {
        Err(fail(
            INPUT,
            anyhow!("--refine = {refine}: expected an integer from 1 to 8 (hexahedra per Lagrange interval)"),
        ))
    }
}

/// `out/<model file stem><suffix>`.
fn default_out(path: &Path, suffix: &str) -> PathBuf {
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "model".into());
    PathBuf::from("out").join(format!("{stem}{suffix}"))
}

fn limit(r: &Resources) -> Option<u64> {
    r.max_memory.or_else(size::available_memory)
}

fn load(path: &Path, resources: &Resources) -> Result<Model, Failure> {
    Model::from_file_with(path, Limits { max_memory: limit(resources) }).map_err(|e| model_failure(e, path))
}

/// A model that could not be read: too large (4), else invalid input (1).
fn model_failure(e: ModelError, path: &Path) -> Failure {
    match e {
        ModelError::Io { .. } | ModelError::NotText { .. } | ModelError::TooBig { .. } => fail(INPUT, e),
        ModelError::TooLarge { .. } => fail(TOO_LARGE, anyhow!(e).context(format!("model {}", path.display()))),
        e => fail(INPUT, anyhow!(e).context(format!("invalid model {}", path.display()))),
    }
}

/// Sets the worker threads (`--threads`, else the model's
/// `solver.threads`): more than the machine's logical cores are capped at
/// them with a warning (oversubscription only slows a solver down: 1000
/// threads turned a 0.4 s run into minutes), unless forced, and never more
/// than [`MAX_THREADS`].
fn configure_threads(threads: Option<usize>, force: bool) -> Result<(), Failure> {
    let Some(n) = threads else { return Ok(()) };
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    if n == 0 {
        return Err(fail(INPUT, anyhow!("--threads = 0: expected an integer ≥ 1 (worker threads)")));
    }
    let n = if force {
        if n > MAX_THREADS {
            return Err(fail(
                INPUT,
                anyhow!(
                    "--threads = {n} (or the model's solver.threads) with --force-threads: expected an integer from 1 \
                     to {MAX_THREADS} (--force-threads allows more threads than the {cores} logical cores, up to \
                     {MAX_THREADS})"
                ),
            ));
        }
        n
    } else if n > cores {
        eprintln!(
            "warning: {n} threads requested but this machine has {cores} logical cores; using {cores} \
             (--force-threads to insist, up to {MAX_THREADS})"
        );
        cores
    } else {
        n
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build_global()
        .map_err(|e| fail(INPUT, anyhow!("cannot configure {n} worker threads: {e}")))
}

fn print_warnings<'a>(warnings: impl Iterator<Item = &'a cufem::setup::Warning>) {
    for w in warnings {
        eprintln!("warning: {w}");
    }
}

/// Installs the Ctrl-C/SIGTERM handling: the first signal requests a stop
/// at the next safe point; a second one removes the staging folders and
/// lock files of the output folders being written
/// (`io::output::remove_unfinished`) and exits at once with code 130 — the
/// output folders keep their previous results.
fn install_interrupt() -> Result<Interrupt, Failure> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let interrupt = Interrupt::new();
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM])
        .map_err(|e| fail(INPUT, anyhow!("cannot install the Ctrl-C handler: {e}")))?;
    let flag = interrupt.clone();
    std::thread::spawn(move || {
        for _ in signals.forever() {
            if flag.is_requested() {
                cufem::io::output::remove_unfinished();
                eprintln!("\ninterrupted again: stopped at once; the output folder keeps its previous results");
                std::process::exit(i32::from(INTERRUPTED));
            }
            flag.request();
            eprintln!("\ninterrupt: stopping at the next safe point (Ctrl-C again stops at once, writing nothing)");
        }
    });
    Ok(interrupt)
}

/// Exit for an interrupt that came before the analysis started: nothing
/// was computed, so nothing is written and any earlier results stay.
fn interrupted_before_start() -> Result<u8, Failure> {
    eprintln!("interrupted before the analysis started: nothing written");
    Ok(INTERRUPTED)
}

fn run(
    path: &Path,
    out: Option<PathBuf>,
    force: bool,
    quiet: bool,
    adapt: &adapt::AdaptArgs,
    resources: &Resources,
) -> Result<u8, Failure> {
    // first: a Ctrl-C from now on is ours (a signal that killed the process
    // between preparing the folder and installing the handler would leave
    // its lock and staging folder behind)
    let interrupt = install_interrupt()?;
    let (text, base) = cufem::input::read_text(path).map_err(|e| model_failure(e, path))?;
    let limits = Limits { max_memory: limit(resources) };
    let model = Model::parse_in(&text, limits, &base).map_err(|e| model_failure(e, path))?;
    let settings = adapt.settings(&model)?;
    print_warnings(model.warnings.iter());
    configure_threads(resources.threads.or(model.solver.threads), resources.force_threads)?;
    let out = out.unwrap_or_else(|| default_out(path, ""));
    if interrupt.is_requested() {
        return interrupted_before_start();
    }
    // the output folder is checked and locked before any computing
    let folder = OutputDir::prepare(&out, force).map_err(|e| fail(FILES, e))?;
    if !quiet {
        print!("{}", cufem::io::report::header(&model));
    }
    let mut progress = Reporter::new(quiet);
    let options = RunOptions { interrupt: interrupt.clone(), max_memory: limit(resources) };
    let (model, run) = match settings {
        None => {
            let run = cufem::io::run_into(&model, folder, &options, &mut progress, |_| ()).map_err(run_failure)?;
            (model, run)
        }
        Some(settings) => {
            let source = cufem::adapt::Source { text: &text, base: &base, limits };
            adapt::run_into(model, source, &settings, folder, &options, &mut progress, path)?
        }
    };
    progress.finish();
    let (solution, dest) = (&run.solution, &run.folder);
    print!("{}", cufem::io::report::results(&model, solution));
    print_warnings(solution.warnings.iter());
    println!("{}", cufem::io::report::wrote_line(run.files.len(), dest));
    match &solution.failure {
        None if adapt::exit_code(solution).is_some() => Ok(adapt::exit_code(solution).unwrap_or(OK)),
        None => {
            if interrupt.is_requested() {
                eprintln!("(the interrupt came after the analysis had finished: the results are complete)");
            }
            Ok(OK)
        }
        Some(f) => {
            let kept = run.kept_converged.then_some(out.as_path());
            if let Some(text) = cufem::io::report::stopped_early(&model, solution, Some(dest), kept) {
                eprintln!("{text}");
            }
            Ok(if f.reason == StopReason::Interrupted { INTERRUPTED } else { NOT_CONVERGED })
        }
    }
}

/// The exit code of a run into a folder that failed: too large (4), a file
/// (3), or the analysis refused the model (1).
fn run_failure(e: cufem::io::RunError) -> Failure {
    use cufem::io::RunError;
    match e {
        RunError::Analysis(e @ AnalysisError::TooLarge { .. }) => fail(TOO_LARGE, e),
        RunError::Analysis(e) => fail(INPUT, anyhow!(e).context("analysis failed")),
        e @ (RunError::Io(_) | RunError::Output(_)) => fail(FILES, e),
    }
}

/// Progress: a bar on a terminal, one plain line per increment otherwise.
struct Reporter {
    bar: Option<ProgressBar>,
    quiet: bool,
}

impl Reporter {
    fn new(quiet: bool) -> Self {
        let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
            let b = ProgressBar::new(1000);
            b.set_style(
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} λ = {msg} (about {eta} left)")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            b
        });
        Self { bar, quiet }
    }

    /// Prints like [`Reporter::line`], from where the reporter itself is
    /// borrowed (an adaptive run's cycle reports).
    fn printer(&self) -> impl Fn(String) + 'static {
        let (bar, quiet) = (self.bar.clone(), self.quiet);
        move |text| match &bar {
            Some(b) => b.println(text),
            None if !quiet => eprintln!("{text}"),
            None => {}
        }
    }

    fn line(&self, text: String) {
        match &self.bar {
            Some(b) => b.println(text),
            None if !self.quiet => eprintln!("{text}"),
            None => {}
        }
    }

    fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

impl Progress for Reporter {
    fn start(&mut self, model: &Model, setup: &analysis::Setup) {
        if let Some(b) = &self.bar {
            // λ runs over [0, number of steps]
            b.set_length(1000 * model.steps.len() as u64);
        }
        self.line(cufem::io::report::start_line(setup));
    }

    fn increment(&mut self, log: &IncrementLog) {
        self.line(cufem::io::report::increment_line(log));
        if let Some(b) = &self.bar {
            b.set_position((log.lambda * 1000.0).round() as u64);
            b.set_message(format!("{:.4}", log.lambda));
        }
    }

    fn cutback(&mut self, c: &Cutback) {
        self.line(cufem::io::report::cutback_line(c));
    }
}
