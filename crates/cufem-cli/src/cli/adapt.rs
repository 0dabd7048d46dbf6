//! `cufem run --adapt TOL`: the options, and the adaptive run into the
//! output folder (`cufem::adapt::run`, then the last cycle written as a
//! single run's results are).

use std::path::Path;

use anyhow::anyhow;
use cufem::adapt::{AdaptError, Source};
use cufem::analysis::{AdaptEnd, AnalysisError, RunOptions, Solution};
use cufem::io::output::OutputDir;
use cufem::io::{RunInto, solved_into};
use cufem::setup::{AdaptSettings, Model, ModelError};

use super::{Failure, INPUT, INTERRUPTED, NOT_CONVERGED, Reporter, TOO_LARGE, fail, model_failure, run_failure};

/// The options of `cufem run` for adaptive refinement.
#[derive(clap::Args)]
pub(super) struct AdaptArgs {
    /// Refine where the error estimate is largest and solve again until the relative estimate (energy
    /// norm, of a transient run's worst kept time; of a modal or buckling analysis, the largest
    /// estimated relative frequency or critical load factor error of the modes followed) is below TOL,
    /// e.g. 0.05 (overrides the model's `adapt.tolerance`).
    #[arg(long, value_name = "TOL", allow_negative_numbers = true, value_parser = parse_tolerance)]
    adapt: Option<f64>,
    /// DOF budget of an adaptive run: no mesh with more DOF is solved (overrides `adapt.max_dof`;
    /// default 50,000).
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = parse_max_dof)]
    max_dof: Option<usize>,
    /// Dörfler's θ of an adaptive run: the marked elements are the fewest, largest first, holding this
    /// share of the squared estimate (overrides `adapt.fraction`; default 0.5).
    #[arg(long, value_name = "THETA", allow_negative_numbers = true, value_parser = parse_fraction)]
    fraction: Option<f64>,
}

fn parse_tolerance(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v < 1.0 => Ok(v),
        _ => Err("expected a relative error between 0 and 1 (e.g. 0.05): in the energy norm, or of the frequencies \
                  of a modal analysis"
            .into()),
    }
}

fn parse_fraction(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v > 0.0 && v <= 1.0 => Ok(v),
        _ => Err("expected Dörfler's θ, a share of the squared estimate in (0, 1] (e.g. 0.5)".into()),
    }
}

fn parse_max_dof(s: &str) -> Result<usize, String> {
    super::integer_in(s, 1, Some(cufem::setup::MAX_BUDGET), "degrees of freedom")
}

impl AdaptArgs {
    /// The settings of an adaptive run (the model's `[adapt]` table
    /// overridden by the options), or `None` for a single run.
    pub(super) fn settings(&self, model: &Model) -> Result<Option<AdaptSettings>, Failure> {
        let mut settings = match (self.adapt, model.adapt) {
            (None, None) if self.max_dof.is_some() || self.fraction.is_some() => {
                let option = if self.max_dof.is_some() { "--max-dof" } else { "--fraction" };
                return Err(fail(
                    INPUT,
                    anyhow!("{option} is an option of an adaptive run: give --adapt TOL or an [adapt] table too"),
                ));
            }
            (None, None) => return Ok(None),
            (_, file) => file.unwrap_or_default(),
        };
        if let Some(t) = self.adapt {
            // (an [adapt] table with another analysis is refused with the model)
            settings.tolerance = t;
            model.check_adaptive().map_err(|e| fail(INPUT, e))?;
        }
        if let Some(n) = self.max_dof {
            settings.max_dof = n;
        }
        if let Some(f) = self.fraction {
            settings.fraction = f;
        }
        // before the output folder is touched (the library checks it too)
        if model.n_dofs() > settings.max_dof {
            let key = if self.max_dof.is_some() { "--max-dof" } else { "adapt.max_dof" };
            return Err(fail(INPUT, AdaptError::Budget { key, max_dof: settings.max_dof, dof: model.n_dofs() }));
        }
        Ok(Some(settings))
    }
}

/// Runs `model` adaptively and writes the last cycle's results into
/// `folder`; returns that cycle's model with what was written.
pub(super) fn run_into(
    model: Model,
    source: Source<'_>,
    settings: &AdaptSettings,
    folder: OutputDir,
    options: &RunOptions,
    progress: &mut Reporter,
    path: &Path,
) -> Result<(Model, RunInto<()>), Failure> {
    progress.line(format!(
        "adaptive run: until the estimate is below {:.2} %, at most {} DOF and {} refinements (θ = {})",
        100.0 * settings.tolerance,
        cufem::io::report::thousands(settings.max_dof),
        settings.max_cycles,
        settings.fraction
    ));
    if model.transient.as_ref().is_some_and(|t| t.output_interval.is_none()) {
        progress.line(
            "a transient run without frames: each cycle is measured by its end alone (the run's largest \
             error, at an impact, may lie before it); set analysis.output_interval to keep frames and \
             measure the worst of them"
                .to_string(),
        );
    }
    let print = progress.printer();
    let result = cufem::adapt::run(model, source, settings, options, progress, &mut |c, _, _| print(cycle_line(c)));
    let (model, solution) = result.map_err(|e| match e {
        AdaptError::Model(e @ ModelError::TooLarge { .. }) => model_failure(e, path),
        AdaptError::Model(e) => fail(INPUT, anyhow!(e).context("refined model")),
        AdaptError::Analysis(e @ AnalysisError::TooLarge { .. }) => fail(TOO_LARGE, e),
        AdaptError::Analysis(e) => fail(INPUT, anyhow!(e).context("analysis failed")),
        e @ AdaptError::Budget { .. } => fail(INPUT, e),
    })?;
    if let Some(a) = &solution.adapt {
        if a.end == AdaptEnd::Done {
            progress.line(format!("adaptive run stopped: {}", a.stop));
        } else {
            // also with --quiet: the results are not those asked for
            eprintln!("adaptive run stopped: {}", a.stop);
        }
    }
    let cycle = solution.adapt.as_ref().and_then(|a| a.cycles.last()).map(|c| c.cycle);
    let written = solved_into(&model, solution, folder, |_| ()).map_err(run_failure)?;
    if let Some(cycle) = cycle {
        println!("the mesh of cycle {cycle} as a model file: {}", written.folder.join("adapted.toml").display());
    }
    Ok((model, written))
}

/// The exit code of an adaptive run that wrote its last finished cycle
/// but did not end as asked: a later cycle stopped or failed (2), or a stop
/// was requested (130); `None` otherwise (the solution's own failure
/// decides, as for a single run).
pub(super) fn exit_code(solution: &Solution) -> Option<u8> {
    match solution.adapt.as_ref().map(|a| a.end) {
        Some(AdaptEnd::Stopped) => Some(NOT_CONVERGED),
        Some(AdaptEnd::Interrupted) => Some(INTERRUPTED),
        _ => None,
    }
}

/// The report line of one cycle.
pub(super) fn cycle_line(c: &cufem::analysis::AdaptCycle) -> String {
    let refined = if c.refined.is_empty() { String::new() } else { format!("  (refined {})", c.refined) };
    let what = match (&c.modes, &c.state) {
        (Some(m), _) => format!("largest {} error estimate", m.quantity.name()),
        (None, Some(state)) => format!("estimate of the worst kept time ({state})"),
        (None, None) => "estimate".to_string(),
    };
    format!(
        "cycle {}: {} DOF, {what} {:.2} %, {:.1} s{refined}",
        c.cycle,
        cufem::io::report::thousands(c.dof),
        100.0 * c.estimate,
        c.time_s
    )
}
