//! Command-line edge: argument parsing, progress and report printing.
//! Library errors are typed; here they become `anyhow` messages.

mod bench;
mod report;

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use cufem::analysis::{self, IncrementLog, Progress};
use cufem::model::Model;
use cufem::solver::stepping::Cutback;
use indicatif::{ProgressBar, ProgressStyle};

/// Refined 1D (CUF) finite elements for elastoplastic contact.
#[derive(Parser)]
#[command(name = "cufem", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run the analysis of a model file and write results.
    Run {
        /// Model file (TOML).
        model: PathBuf,
        /// Output directory (default: out/<model name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Worker threads (default: the model's `solver.threads`, else all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Print only the final report.
        #[arg(long)]
        quiet: bool,
    },
    /// Validate a model file and print its size.
    Check {
        /// Model file (TOML).
        model: PathBuf,
    },
    /// Time the phases of an analysis (setup, assembly, factorization, solve) over repeated runs.
    Bench {
        /// Model file (TOML).
        model: PathBuf,
        /// Number of timed repetitions (the median is reported).
        #[arg(long, default_value_t = 5)]
        repeat: usize,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Time the full analysis instead of one linear solve.
        #[arg(long)]
        full: bool,
    },
}

/// Entry point: exit code 0 on success, 1 on an input or I/O error, 2 when
/// the analysis stopped before reaching the full load.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    match dispatch(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(1)
        }
    }
}

fn dispatch(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Run { model, out, threads, quiet } => run(&model, out, threads, quiet),
        Command::Check { model } => {
            let m = load(&model)?;
            report::print_check(&m);
            Ok(ExitCode::SUCCESS)
        }
        Command::Bench { model, repeat, threads, full } => {
            let m = load(&model)?;
            configure_threads(threads.or(m.solver.threads))?;
            bench::run(&m, repeat.max(1), full)?;
            Ok(ExitCode::SUCCESS)
        }
    }
}

fn load(path: &Path) -> Result<Model> {
    Model::from_file(path).with_context(|| format!("invalid model {}", path.display()))
}

fn configure_threads(threads: Option<usize>) -> Result<()> {
    if let Some(n) = threads {
        anyhow::ensure!(n >= 1, "--threads = {n}: expected an integer ≥ 1");
        rayon::ThreadPoolBuilder::new().num_threads(n).build_global().context("cannot configure the thread pool")?;
    }
    Ok(())
}

fn run(path: &Path, out: Option<PathBuf>, threads: Option<usize>, quiet: bool) -> Result<ExitCode> {
    let model = load(path)?;
    configure_threads(threads.or(model.solver.threads))?;
    let out = out.unwrap_or_else(|| {
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "model".into());
        PathBuf::from("out").join(stem)
    });
    if !quiet {
        report::print_header(&model);
    }
    let mut progress = Reporter::new(quiet);
    let solution = analysis::run(&model, &mut progress).context("analysis failed")?;
    progress.finish();
    let written = cufem::io::write_results(&model, &solution, &out).context("cannot write results")?;
    report::print_results(&model, &solution);
    println!("\nwrote {} files to {}", written.len(), out.display());
    if let Some(f) = &solution.failure {
        eprintln!("\nthe analysis stopped early: {f}");
        eprintln!(
            "results of the last converged increment (load factor {:.4}) are in {}",
            solution.lambda,
            out.display()
        );
        return Ok(ExitCode::from(2));
    }
    Ok(ExitCode::SUCCESS)
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
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} λ = {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            b
        });
        Self { bar, quiet }
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
    fn start(&mut self, _model: &Model, equations: usize) {
        self.line(format!("solving {equations} equations"));
    }

    fn increment(&mut self, log: &IncrementLog) {
        self.line(report::increment_line(log));
        if let Some(b) = &self.bar {
            b.set_position((log.lambda * 1000.0).round() as u64);
            b.set_message(format!("{:.4}", log.lambda));
        }
    }

    fn cutback(&mut self, c: &Cutback) {
        let res: Vec<String> = c.newton.residuals.iter().map(|r| format!("{r:.1e}")).collect();
        self.line(format!(
            "  cutback: increment {} (λ = {:.4}, Δλ = {:.3e}) failed ({:?}) after {} iterations, residuals [{}]{}",
            c.index,
            c.lambda,
            c.dlambda,
            c.newton.failure.unwrap_or(cufem::solver::newton::Failure::MaxIterations),
            c.newton.iterations,
            res.join(" "),
            c.newton.message.as_ref().map(|m| format!(": {m}")).unwrap_or_default()
        ));
    }
}
