//! Adaptive refinement: solve, estimate, mark, refine, solve again.
//!
//! Each cycle solves a mesh from the start of the load history (no
//! transfer of Gauss-point histories between meshes: simple, and exact for
//! a path-dependent material), takes the Zienkiewicz–Zhu estimate of its
//! solution ([`crate::post::estimate`]) — of a modal analysis, the
//! estimates of the modes it follows and of their frequencies
//! (`measure`) —, and stops when
//!
//! * the relative estimate (modal: the largest estimated relative
//!   frequency error) is below the tolerance,
//! * the next mesh would have more DOF than the budget `max_dof`,
//! * `max_cycles` refinements have been solved,
//! * nothing is left to refine, or
//! * the analysis of a cycle stopped early (not converged, interrupted) or
//!   failed, or a stop was requested: the last finished cycle is the result
//!   (for the first cycle, its last converged state, as for a single run).
//!
//! Otherwise the elements holding the share `fraction` (Dörfler's θ) of
//! `Σ η_e²` (modal: of the unconverged modes' shares summed, `measure`)
//! are marked ([`mark::dorfler`]) and every division interval
//! through a marked element — x, z and axis — is halved for its whole row,
//! column or axis slice ([`mark::intervals`], [`mark::refine`]): the
//! sections are tensor grids swept along the axis, so splitting intervals
//! keeps the mesh conforming — no hanging nodes, no constraints — at the
//! price of refining a whole row where one element asked for it. Sections
//! that are not grids are refined when the marked elements are spread over
//! them or their error lies across them: the counts of the walls or plies
//! holding the section error doubled (a circle: every count), and
//! their axis intervals split only where the error lies along the axis
//! (`mark::local`, `mark::along_axis`); a tube whose marked elements'
//! error lies across the section is refined along the long sides of its
//! largest marked element — the axis, the elements along the walls,
//! through them (`tube::tube_sections`); `quads` and `gmsh` sections are
//! kept ([`crate::setup::SectionPlan`]).
//! The refined model is rebuilt from its own model-file text with the new
//! divisions (`Model::parse_planned`), so every constraint, load, contact,
//! probe and line is resolved on the new mesh by its geometric selection
//! and keeps its name. The solution returned is the last cycle's, with
//! the cycles in [`Solution::adapt`].

pub mod mark;
pub(crate) mod measure;
pub(crate) mod tube;

use std::path::Path;
use std::time::Instant;

use crate::analysis::{self, AdaptCycle, AdaptEnd, Adaptivity, AnalysisError, Progress, RunOptions, Solution};
use crate::setup::{AdaptSettings, Limits, MeshPlan, Model, ModelError};
use crate::solver::stepping::StopReason;

/// Errors of an adaptive run.
#[derive(Debug, thiserror::Error)]
pub enum AdaptError {
    /// A refined model could not be built.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// An analysis could not start or failed outright.
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
    /// The model as given is already over the budget.
    #[error(
        "{key} = {max_dof}: expected at least the model's own {} DOF (the first cycle solves the \
         model as given; raise the budget or coarsen the model)",
        crate::numbers::thousands(*.dof)
    )]
    Budget {
        /// Where the budget was given: `adapt.max_dof`, or the CLI's `--max-dof`.
        key: &'static str,
        /// The budget.
        max_dof: usize,
        /// The model's DOF.
        dof: usize,
    },
}

/// Where the refined models come from: the model file's text, the folder
/// its relative paths start at, and the limits models are read under.
#[derive(Debug, Clone, Copy)]
pub struct Source<'a> {
    /// Model-file text.
    pub text: &'a str,
    /// Folder of relative paths (gmsh sections).
    pub base: &'a Path,
    /// Limits for reading models.
    pub limits: Limits,
}

/// Runs `model` (read from `source`) adaptively under `settings`, calling
/// `report` after each cycle with the cycle, its model and its solution
/// (which a caller may sample: each cycle's results are otherwise
/// dropped). Returns the last finished cycle's model and solution.
///
/// Every exit after the first cycle keeps the last finished one: a later
/// cycle whose mesh exceeds the memory allowed ends the run as the DOF
/// budget does ([`AdaptEnd::Done`]); one whose analysis stops early, fails,
/// or whose refined model cannot be built ends it [`AdaptEnd::Stopped`]; a
/// stop request (Ctrl-C) [`AdaptEnd::Interrupted`] — each with the last
/// finished cycle's solution and the reason in [`Adaptivity::stop`]. Only
/// the first cycle's errors are errors (nothing was finished).
pub fn run(
    model: Model,
    source: Source<'_>,
    settings: &AdaptSettings,
    options: &RunOptions,
    progress: &mut dyn Progress,
    report: &mut dyn FnMut(&AdaptCycle, &Model, &Solution),
) -> Result<(Model, Solution), AdaptError> {
    model.check_adaptive()?;
    if model.n_dofs() > settings.max_dof {
        return Err(AdaptError::Budget { key: "adapt.max_dof", max_dof: settings.max_dof, dof: model.n_dofs() });
    }
    let mut run = Cycles { settings, text: source.text, cycles: Vec::new(), last: None };
    let (mut model, mut refined, mut start) = (model, String::new(), Instant::now());
    loop {
        let k = run.cycles.len();
        if k > 0 && options.interrupt.is_requested() {
            return Ok(run.end(format!("interrupted before cycle {k}"), AdaptEnd::Interrupted));
        }
        let mut solution = match analysis::run(&model, options, progress) {
            Err(e) if k == 0 => return Err(e.into()),
            Err(AnalysisError::TooLarge { estimate, limit }) => {
                let why = format!(
                    "the mesh of cycle {k} ({} DOF) would need {} of memory, more than the {} allowed",
                    model.n_dofs(),
                    crate::size::human_bytes(estimate.total()),
                    crate::size::human_bytes(limit)
                );
                return Ok(run.end(why, AdaptEnd::Done));
            }
            Err(e) => {
                let why = format!("the analysis of cycle {k} ({} DOF) failed: {e}", model.n_dofs());
                return Ok(run.end(why, AdaptEnd::Stopped));
            }
            Ok(s) => match &s.failure {
                Some(f) if k > 0 => {
                    let end =
                        if f.reason == StopReason::Interrupted { AdaptEnd::Interrupted } else { AdaptEnd::Stopped };
                    return Ok(
                        run.end(format!("the analysis of cycle {k} ({} DOF) stopped early: {f}", model.n_dofs()), end)
                    );
                }
                _ => s,
            },
        };
        let measure = measure::Measure::of(&solution, settings);
        let cycle = AdaptCycle {
            cycle: k,
            dof: model.n_dofs(),
            estimate: measure.estimate,
            modes: measure.modes.clone(),
            state: measure.state.clone(),
            time_s: start.elapsed().as_secs_f64(),
            refined: std::mem::take(&mut refined),
            probes: analysis::tables::probes(&model, &solution.fields(&model)),
        };
        report(&cycle, &model, &solution);
        run.cycles.push(cycle);
        start = Instant::now();
        let next = match stop_before_refining(&solution, &measure, settings, k) {
            Some(reason) => Err((reason, AdaptEnd::Done)),
            None => match next_model(&model, &measure, source, settings) {
                Ok(next) => next.map_err(|reason| (reason, AdaptEnd::Done)),
                Err(e) => {
                    Err((format!("the refined model of cycle {} could not be built: {e}", k + 1), AdaptEnd::Stopped))
                }
            },
        };
        match next {
            Ok(next) => {
                refined = mark::describe(&model.mesh, &model.plan, &next.plan);
                run.last = Some((std::mem::replace(&mut model, next), solution));
            }
            Err((stop, end)) => {
                solution.adapt = Some(run.adaptivity(stop, end, &model.plan));
                return Ok((model, solution));
            }
        }
    }
}

/// The cycles of an adaptive run so far and the last finished one's model
/// and solution (once a refinement follows it).
struct Cycles<'a> {
    settings: &'a AdaptSettings,
    text: &'a str,
    cycles: Vec<AdaptCycle>,
    last: Option<(Model, Solution)>,
}

impl Cycles<'_> {
    /// The run's record, the results being on `plan`'s mesh.
    fn adaptivity(&mut self, stop: String, end: AdaptEnd, plan: &MeshPlan) -> Adaptivity {
        let (tolerance, max_dof) = (self.settings.tolerance, self.settings.max_dof);
        // the plan was made from this text and its models were built from it
        let about = self.cycles.last().map_or_else(String::new, |c| {
            format!(
                "cycle {} ({} DOF, estimate {:.2} %)",
                c.cycle,
                crate::numbers::thousands(c.dof),
                100.0 * c.estimate
            )
        });
        let model_file = crate::setup::adapted_text(self.text, plan, &about).unwrap_or_else(|e| format!("# {e}\n"));
        Adaptivity { cycles: std::mem::take(&mut self.cycles), stop, tolerance, max_dof, end, model_file }
    }

    /// The end of the run after a later cycle could not finish: the last
    /// finished cycle's model and solution, with why.
    fn end(mut self, why: String, end: AdaptEnd) -> (Model, Solution) {
        let (model, mut solution) = self.last.take().expect("a cycle finished before a refinement");
        let k = self.cycles.len() - 1;
        let stop = format!("{why}; the results are cycle {k}'s, the last finished");
        solution.adapt = Some(self.adaptivity(stop, end, &model.plan));
        (model, solution)
    }
}

/// Why no refinement follows this cycle's solution, if it is done.
fn stop_before_refining(
    solution: &Solution,
    measure: &measure::Measure,
    settings: &AdaptSettings,
    cycle: usize,
) -> Option<String> {
    if let Some(f) = &solution.failure {
        Some(format!("the analysis of cycle {cycle} stopped early: {f}"))
    } else if measure.estimate < settings.tolerance {
        Some(measure.below(settings.tolerance))
    } else if cycle >= settings.max_cycles {
        Some(format!("max_cycles = {} refinements done", settings.max_cycles))
    } else {
        None
    }
}

/// The refined model after a solution measured by `measure`, or why there
/// is none (nothing to refine, over the DOF budget or the memory limit).
/// When the refinement of every marked element would exceed the budget (or
/// the memory allowed), the largest of them that fit are refined — the
/// longest run of the marked elements, largest first, whose refined mesh
/// stays within it — so a run spends its budget where the estimate is
/// largest instead of stopping one refinement short of it; the run stops
/// when not even the largest element's refinement fits.
fn next_model(
    model: &Model,
    measure: &measure::Measure,
    source: Source<'_>,
    settings: &AdaptSettings,
) -> Result<Result<Model, String>, AdaptError> {
    if measure.element.is_empty() {
        return Ok(Err("no error estimate to refine by".into()));
    }
    let marked = mark::dorfler(&measure.element, settings.fraction);
    let nothing = || Ok(Err("nothing left to refine (the marked elements' sections are kept as given)".into()));
    // the longest prefix of `marked` whose refinement fits: all of it
    // first, then a bisection between the longest known to fit (`low`)
    // and the shortest known to be too large (`high`)
    let (mut low, mut high, mut n) = (0, marked.len() + 1, marked.len());
    let (mut best, mut over) = (None, None);
    while n > low && n < high {
        match refined(model, measure, source, settings, &marked[..n])? {
            Refined::Same if n == marked.len() => return nothing(),
            Refined::Same => low = n,
            Refined::Fits(next) => (low, best) = (n, Some(*next)),
            Refined::Over(why) => (high, over) = (n, Some(why)),
        }
        n = (low + high) / 2;
    }
    match (best, over) {
        (Some(next), _) => Ok(Ok(next)),
        (None, Some(why)) => Ok(Err(why)),
        (None, None) => nothing(),
    }
}

/// A refinement of the elements `marked`.
enum Refined {
    /// The refined model, within the budget.
    Fits(Box<Model>),
    /// The plan did not change.
    Same,
    /// Over the budget or the memory allowed: why.
    Over(String),
}

/// The model refined at the elements `marked` (largest first).
fn refined(
    model: &Model,
    measure: &measure::Measure,
    source: Source<'_>,
    settings: &AdaptSettings,
    marked: &[usize],
) -> Result<Refined, AdaptError> {
    let mut marks = mark::intervals(&model.mesh, &model.plan, marked);
    let parts = (&measure.element[..], &measure.section[..]);
    mark::across_sections(&model.mesh, &model.plan, marked, parts, &mut marks);
    mark::along_axis(&model.mesh, &model.plan, marked, parts, &mut marks);
    mark::by_direction(&model.mesh, &model.plan, marked, &measure.direction, &mut marks);
    let weights = if measure.section.len() == measure.element.len() { &measure.section } else { &measure.element };
    mark::local(&model.mesh, &model.plan, weights, &mut marks);
    tube::tube_sections(&model.mesh, &model.plan, marked, parts, &mut marks);
    let plan: MeshPlan = mark::refine(&model.plan, &marks);
    if plan == model.plan {
        return Ok(Refined::Same);
    }
    let next = match Model::parse_planned(source.text, source.limits, source.base, &plan) {
        Ok(m) => m,
        Err(ModelError::TooLarge { dofs, .. }) => {
            return Ok(Refined::Over(format!(
                "the next mesh ({} DOF) would not fit in the memory allowed",
                crate::numbers::thousands(usize::try_from(dofs).unwrap_or(usize::MAX))
            )));
        }
        Err(e) => return Err(e.into()),
    };
    if next.n_dofs() > settings.max_dof {
        return Ok(Refined::Over(format!(
            "the next mesh ({} DOF) would exceed the budget max_dof = {}",
            crate::numbers::thousands(next.n_dofs()),
            crate::numbers::thousands(settings.max_dof)
        )));
    }
    Ok(Refined::Fits(Box::new(next)))
}
