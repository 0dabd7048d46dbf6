//! The analysis driver: model → structure → load stepping → solution.
//!
//! ```text
//! let structure = Structure::of_model(model) // number, order, pattern, symbolic factorization
//! for each increment λ_n → λ_{n+1}:           // solver::stepping (cutbacks, growth)
//!     set λ, prescribe λ ū                     // Incremental::set_load_factor
//!     Newton: evaluate R, K; solve; update     // solver::newton
//!     commit Gauss-point history               // Incremental::commit
//!     record reactions and contact forces      // Recorder
//! ```
//!
//! This file is the driver ([`run`]); the rest by concept: `progress`
//! (what the run reports while it goes), `sizes` (memory planning),
//! `solution` (the result types), `results` (resultants, timings and the
//! solver statistics), `tables` (the result tables the writers serialise).

pub mod buckling;
mod checks;
pub mod concentrated;
mod conditioning;
pub mod modal;
pub mod path;
mod progress;
mod recorder;
mod results;
mod sizes;
pub(crate) mod solution;
mod stages;
pub mod state_errors;
pub mod structure;
pub mod tables;
mod warnings;

pub use path::{PathEnd, PathOutcome};
pub use progress::{IncrementLog, Progress, Setup, Silent};
pub use recorder::Frame;
use recorder::Recorder;
pub use results::{AdaptCycle, AdaptEnd, Adaptivity, FollowedModes, ModeQuantity};
pub(crate) use sizes::{describe_memory, memory_advice, model_sizes};
pub use sizes::{plan, sizes};
pub use solution::{HistoryRow, Solution, StepEnd, StepFields};
pub use structure::{
    ContactKind, ContactPoint, ContactResultant, ContactSet, LeverResultant, Reaction, StateReport, Structure, Timings,
};

use std::time::Instant;

use crate::elements::ElementError;
use crate::setup::Model;
use crate::size::{MemoryEstimate, human_bytes};
use crate::solver::Interrupt;
use crate::solver::linear::LinearError;
use crate::solver::newton::NonlinearProblem;
use crate::solver::stepping::{self, SteppingError};

/// Errors that stop an analysis before it can start (a non-convergence is
/// not an error: it is reported in [`Solution::failure`]).
#[derive(Debug, thiserror::Error)]
pub enum AnalysisError {
    /// Element geometry.
    #[error(transparent)]
    Element(#[from] ElementError),
    /// Linear algebra.
    #[error(transparent)]
    Linear(#[from] LinearError),
    /// The imperfection's mode was not found.
    #[error(
        "analysis.imperfection.mode = {mode}: expected the number of a buckling mode of the model, whose buckling \
         analysis found {found} buckling load factor(s){why}"
    )]
    Imperfection {
        /// The mode asked for.
        mode: usize,
        /// Buckling load factors found.
        found: usize,
        /// Factors found beyond the critical-strain bound (not buckling).
        beyond: Vec<f64>,
        /// Why, when more can be said (`; …`).
        why: String,
    },
    /// A value of the model that the analysis found it cannot take (e.g. an
    /// arc length too long for the model's stiffness).
    #[error(transparent)]
    Model(#[from] crate::setup::ModelError),
    /// The eigenproblem of a buckling or modal analysis.
    #[error("eigenvalue analysis")]
    Eigen(#[from] crate::solver::eigen::EigenError),
    /// The mass matrix of a modal analysis.
    #[error(transparent)]
    Mass(#[from] crate::dynamics::MassError),
    /// The analysis would need more memory than allowed.
    #[error(
        "the analysis needs about {} of memory ({}) but {} is available; {}, or --max-memory to raise the limit",
        human_bytes(.estimate.total()),
        describe_memory(.estimate),
        human_bytes(*.limit),
        memory_advice(.estimate)
    )]
    TooLarge {
        /// The estimate.
        estimate: MemoryEstimate,
        /// The limit (bytes).
        limit: u64,
    },
}

/// Options of an analysis run.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Stops the analysis at the next safe point when requested (the last
    /// converged increment is kept, [`Solution::failure`] says why).
    pub interrupt: Interrupt,
    /// Refuse the analysis if its estimated memory exceeds this (bytes).
    pub max_memory: Option<u64>,
}

/// Drives the structure over the model's load history — by load steps, or
/// along the path by arc length — and returns the ends of the completed
/// steps, the failure that stopped it (if any) and the path's outcome.
type Driven = (Vec<StepEnd>, Option<SteppingError>, Option<PathOutcome>);

fn drive(
    structure: &mut Structure<'_>,
    model: &Model,
    options: &RunOptions,
    recorder: &mut Recorder<'_>,
) -> Result<Driven, AnalysisError> {
    // the load history: each step drives λ over [k, k + 1] from the state the
    // previous one left (displacements, plastic history, contact)
    let mut failure = None;
    let mut step_ends = Vec::new();
    let mut path = None;
    if let Some(settings) = &model.solver.path {
        let (outcome, stopped) = path::follow(structure, model, settings, recorder, &options.interrupt)?;
        if stopped.is_none() {
            let StateReport { lambda, reactions, contacts, .. } = structure.report();
            let (name, increment) = (model.steps[0].name.clone(), recorder.increments.len());
            let (fields, damage, delamination) = (None, None, None);
            step_ends.push(StepEnd { name, lambda, increment, reactions, contacts, fields, damage, delamination });
        }
        (path, failure) = (Some(outcome), stopped);
    }
    for (k, step) in model.steps.iter().enumerate().filter(|_| path.is_none()) {
        let span = (k as f64, (k + 1) as f64);
        let first = recorder.increments.len() + 1;
        let newton = &model.solver.newton;
        match stepping::run_span(structure, span, first, &step.settings, newton, recorder, &options.interrupt) {
            Ok(_) => {
                let StateReport { reactions, contacts, .. } = structure.report();
                // the fields (and the ply and interface damage) of every
                // step end of a history of several steps, for its per-step output
                let kept = model.steps.len() > 1;
                step_ends.push(StepEnd {
                    name: step.name.clone(),
                    lambda: span.1,
                    increment: recorder.increments.len(),
                    reactions,
                    contacts,
                    fields: kept.then(|| structure.fields()),
                    damage: kept.then(|| structure.elements().damage.shown()).flatten(),
                    delamination: kept.then(|| structure.interfaces().delamination()).flatten(),
                })
            }
            Err(mut e) => {
                // a transient stop speaks of times
                if let Some(t) = &model.transient {
                    let at = t.time(e.lambda);
                    e.seconds = Some([at, at - t.time(e.lambda - e.dlambda), t.time(e.last_converged)]);
                }
                failure = Some(*e);
                break;
            }
        }
    }
    Ok((step_ends, failure, path))
}

/// Runs the analysis of `model`.
pub fn run(model: &Model, options: &RunOptions, progress: &mut dyn Progress) -> Result<Solution, AnalysisError> {
    let start = Instant::now();
    // a geometric imperfection: the buckling analysis of the model first
    let imperfect = model.imperfection.map(|imp| buckling::imperfection(model, imp)).transpose()?;
    let mut structure = Structure::of_model(model, options.max_memory)?;
    if let Some((u0, _)) = &imperfect {
        structure.set_imperfection(u0.clone());
    }
    let setup = structure.setup();
    progress.start(model, &setup);
    let mut recorder = Recorder::new(model, progress);
    let (step_ends, mut failure, path) = drive(&mut structure, model, options, &mut recorder)?;
    if let Some(f) = failure.as_mut().filter(|f| f.reason == stepping::StopReason::IncrementTooSmall)
        && let Some(why) = conditioning::diagnose(model)
    {
        f.newton.message = Some(f.newton.message.take().map_or(why.clone(), |m| format!("{m}; {why}")));
    }
    if let Some(f) = failure.as_mut().filter(|f| f.reason == stepping::StopReason::IncrementTooSmall)
        && let Some(why) = conditioning::softening(model)
    {
        f.newton.message = Some(f.newton.message.take().map_or(why.clone(), |m| format!("{m}; {why}")));
    }
    if failure.is_some() {
        // refresh forces at the last converged state for reactions and contact output
        structure.evaluate()?;
    }
    let eigen_start = std::time::Instant::now();
    let (buckled, vibration, failure) = stages::eigen(&mut structure, model, &recorder.history, failure)?;
    let eigen_time = eigen_start.elapsed();
    let mut applied = [0.0; 3];
    for (d, f) in structure.external_loads().iter().enumerate() {
        applied[d % 3] += f;
    }
    let StateReport { lambda, reactions, contacts, plastic_points, levers, .. } = structure.report();
    let contact_sets = structure
        .contact_sets()
        .map(|(name, kind, points)| ContactSet { name: name.to_string(), kind, points: points.to_vec() })
        .collect();
    let Setup { equations, factor_nnz, memory } = setup;
    let energy = structure.energies();
    let delamination = structure.interfaces().delamination();
    let (u, elements, stresses, mut timings) = structure.into_parts();
    if model.buckling.is_some() || model.modal.is_some() {
        timings.eigen = eigen_time;
    }
    let mut solution = Solution {
        reactions,
        contacts,
        levers,
        contact_sets,
        applied,
        lambda,
        equations,
        factor_nnz,
        plastic_points,
        timings,
        u,
        states: elements.committed,
        stresses,
        gp_offsets: elements.gp_offsets,
        history: recorder.history,
        increments: recorder.increments,
        cutbacks: recorder.cutbacks,
        failure,
        wall_time: start.elapsed(),
        memory,
        warnings: Vec::new(),
        recovered: None,
        error_estimate: None,
        error_history: Default::default(),
        steps: step_ends,
        adapt: None,
        buckling: buckled.or(imperfect.map(|(_, b)| b)),
        modal: vibration,
        energy,
        frames: recorder.frames,
        path,
        delamination,
        damage: elements.damage.into_result(),
    };
    // the estimate compares the raw stresses with their patch recovery
    // (kept to each ply and zone of a layered body, `post::spr`); the fields
    // show the L2 projection if the model asks for it
    let (mesh, cells, offsets) = (&model.mesh, &model.cells, &solution.gp_offsets);
    solution.error_estimate = Some(crate::post::estimate::of_state(
        mesh,
        cells,
        &model.materials,
        (&solution.stresses, &solution.states),
        offsets,
        model.kinematics.is_nonlinear().then_some(&solution.u[..]),
    ));
    // and every step end and frame the run kept, by the same estimate
    solution.error_history = state_errors::estimate(
        model,
        offsets,
        (&solution.steps, &solution.frames, &solution.history),
        (solution.error_estimate.as_ref(), solution.increments.len()),
    );
    if model.output.recovery == crate::input::Recovery::Projection {
        solution.recovered = Some(crate::post::recovery::project(
            &model.mesh,
            &model.cells,
            &solution.stresses,
            &solution.states,
            &solution.gp_offsets,
        )?);
    }
    solution.warnings = warnings::result_warnings(model, &solution);
    Ok(solution)
}
