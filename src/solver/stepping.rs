//! Incremental load stepping with automatic cutbacks, above Newton.
//!
//! The load factor λ goes from 0 to 1. Each increment sets λ, runs Newton
//! from the last converged state and, on success, commits the state (so
//! path-dependent material history only advances on converged increments).
//! A failed increment is rolled back and retried with `Δλ · cutback_factor`;
//! an increment that converged in at most `easy_iterations` iterations lets
//! the next one grow by `growth_factor` (up to `max_increment`). Before the
//! first cutback of an increment, the same `Δλ` is retried once with the
//! problem's cautious linearization ([`Incremental::cautious`]). When `Δλ`
//! would fall below `min_increment`, the analysis stops with a report and the
//! problem is left at its last converged increment.
//!
//! With a [`StepControl`] (`solver.step_control`) the size of the next
//! increment follows instead what the last one changed, as the problem
//! measures it ([`Incremental::measure`]; rules in `solver::step_control`),
//! and an increment that changed far too much is redone smaller. With its
//! `time_error` (adaptive time steps) the increments also land on the
//! problem's landing points ([`Incremental::landing`], a transient
//! analysis's output times): an increment that would pass one is shortened
//! to end on it, and the next takes up the size it was cut from.

use super::Interrupt;
use super::newton::{self, FirstCorrection, NewtonSettings, NonlinearProblem, Report};
use super::step_control::Verdict;
pub use super::step_control::{StepControl, StepMeasure};

/// A problem that can be driven incrementally.
pub trait Incremental: NonlinearProblem {
    /// Sets the load factor for the next solve (applying prescribed values).
    fn set_load_factor(&mut self, lambda: f64);
    /// Accepts the current (converged) state as the new start point.
    fn commit(&mut self);
    /// Returns to the last committed state.
    fn restore(&mut self);
    /// After a converged solve: updates the problem's constraint
    /// multipliers (augmented Lagrangian); true if it changed them and the
    /// increment must be solved again (the default: nothing to update).
    fn augment(&mut self) -> bool {
        false
    }
    /// Switches to (or back from) a more cautious linearization for a retry
    /// of a failed increment — e.g. elastic tangents at points on their
    /// yield surface when the load reverses. Returns true if that changed
    /// anything (the default: nothing to switch).
    fn cautious(&mut self, _on: bool) -> bool {
        false
    }
    /// True if the load step that starts at `lambda` takes some load back:
    /// its first increment starts with the cautious linearization (the
    /// default: never).
    fn unloads(&self, _lambda: f64) -> bool {
        false
    }
    /// Moves the start of the next solve from the committed state along the
    /// last converged increment, scaled by `ratio` = Δλ_next / Δλ_last (a
    /// linear extrapolation of the path; the default: start at the
    /// committed state). Called only within one step of a load history.
    fn extrapolate(&mut self, _ratio: f64) {}
    /// After a converged solve, before it is committed: what the increment
    /// changed, for the step control (the default: nothing measured).
    fn measure(&self) -> StepMeasure {
        StepMeasure::default()
    }
    /// The first λ after `lambda` that an adaptive increment must land on
    /// (the default: none; the end of the span always is one). Read only
    /// with a step control's `time_error`.
    fn landing(&self, _lambda: f64) -> Option<f64> {
        None
    }
}

/// Controls of the load stepping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepSettings {
    /// First increment of λ.
    pub initial: f64,
    /// Largest increment.
    pub max: f64,
    /// Smallest increment before giving up.
    pub min: f64,
    /// Factor applied to Δλ after a failure (0 < f < 1).
    pub cutback_factor: f64,
    /// Factor applied to Δλ after an easy increment (≥ 1).
    pub(crate) growth_factor: f64,
    /// An increment converging within this many iterations is "easy".
    pub(crate) easy_iterations: usize,
    /// Largest number of converged increments before the analysis is stopped.
    pub max_increments: usize,
    /// Step control by an error measure (`None`: the growth after easy
    /// increments alone).
    pub control: Option<StepControl>,
}

impl Default for StepSettings {
    fn default() -> Self {
        Self {
            initial: 0.1,
            max: 0.1,
            min: 1e-5,
            cutback_factor: 0.5,
            growth_factor: 1.5,
            easy_iterations: 4,
            max_increments: 1000,
            control: None,
        }
    }
}

/// One converged increment.
#[derive(Debug, Clone, PartialEq)]
pub struct Increment {
    /// 1-based index.
    pub index: usize,
    /// Load factor reached.
    pub lambda: f64,
    /// Its increment.
    pub dlambda: f64,
    /// Newton history of the converged attempt.
    pub newton: Report,
    /// Failed attempts (cutbacks) before it converged.
    pub cutbacks: usize,
    /// What it changed, as the step control measured it (nothing measured
    /// without a step control).
    pub measure: StepMeasure,
}

/// A failed attempt, for logs.
#[derive(Debug, Clone, PartialEq)]
pub struct Cutback {
    /// Index of the increment being attempted.
    pub index: usize,
    /// λ that was attempted.
    pub lambda: f64,
    /// Δλ that failed.
    pub dlambda: f64,
    /// The failed Newton history (converged if the step control rejected it).
    pub newton: Report,
    /// `Some(q)`: the attempt converged, but the step control rejected it,
    /// its measure `q` times the target.
    pub rejected: Option<f64>,
}

/// Callbacks of the stepping loop.
pub trait Observer<P> {
    /// Called after each converged and committed increment.
    fn converged(&mut self, problem: &P, increment: &Increment);
    /// Called after each failed attempt (before the retry).
    fn cut_back(&mut self, _cutback: &Cutback) {}
}

pub use super::stop::{SteppingError, StopReason};

/// Most multiplier updates per increment (augmented Lagrangian); the
/// contact's penetration check then reports what is left.
pub(crate) const MAX_AUGMENTATIONS: usize = 50;

/// Drives `problem` from λ = 0 to 1. Returns the converged increments.
pub fn run<P: Incremental>(
    problem: &mut P,
    steps: &StepSettings,
    newton_settings: &NewtonSettings,
    observer: &mut dyn Observer<P>,
    interrupt: &Interrupt,
) -> Result<Vec<Increment>, Box<SteppingError>> {
    run_span(problem, (0.0, 1.0), 1, steps, newton_settings, observer, interrupt)
}

/// Drives `problem` from λ = `span.0` to `span.1` (one step of a load
/// history; the problem starts from its committed state at `span.0`), the
/// increments numbered from `first_index`. The increment controls are
/// lengths in λ. Returns the converged increments.
pub fn run_span<P: Incremental>(
    problem: &mut P,
    span: (f64, f64),
    first_index: usize,
    steps: &StepSettings,
    newton_settings: &NewtonSettings,
    observer: &mut dyn Observer<P>,
    interrupt: &Interrupt,
) -> Result<Vec<Increment>, Box<SteppingError>> {
    let (mut lambda, end) = span;
    let mut history: Vec<Increment> = Vec::new();
    let mut dlambda = steps.initial.min(steps.max);
    let mut cutbacks = 0;
    // the present increment was already rejected once by the step control
    let mut rejected = false;
    let lands = steps.control.is_some_and(|c| c.time_error.is_some());
    while lambda < end - 1e-12 * end.abs().max(1.0) {
        if history.len() >= steps.max_increments {
            return Err(stop_before(StopReason::TooManyIncrements, first_index + history.len(), lambda, dlambda));
        }
        if interrupt.is_requested() {
            return Err(stop_before(StopReason::Interrupted, first_index + history.len(), lambda, dlambda));
        }
        dlambda = dlambda.min(end - lambda);
        let mut target = if dlambda >= end - lambda { end } else { lambda + dlambda };
        let planned = if lands { land(problem, lambda, &mut dlambda, &mut target) } else { None };
        problem.set_load_factor(target);
        if let Some(last) = history.last() {
            // within a step the loads are linear in λ: start Newton on the
            // secant of the last increment instead of the committed state
            problem.extrapolate((target - lambda) / last.dlambda);
        }
        // an increment that converged within two corrections was about linear:
        // the next one's first correction is solved far enough to be its last
        let first = match history.last().map(|last| last.newton.iterations) {
            Some(0 | 1) => FirstCorrection::Last,
            Some(2) => FirstCorrection::Finishing,
            _ => FirstCorrection::Plain,
        };
        if history.is_empty() && cutbacks == 0 && problem.unloads(lambda) {
            problem.cautious(true); // not the loading branch at points on their yield surface
        }
        let report = solve_increment(problem, newton_settings, first, interrupt);
        if report.failure == Some(newton::Failure::Interrupted) {
            problem.restore();
            problem.set_load_factor(lambda);
            return Err(Box::new(SteppingError {
                reason: StopReason::Interrupted,
                increment: first_index + history.len(),
                lambda: target,
                dlambda,
                last_converged: lambda,
                newton: report,
                seconds: None,
            }));
        }
        if report.converged() {
            let easy = report.iterations <= steps.easy_iterations;
            let mut next = None;
            let mut measure = StepMeasure::default();
            if let Some(control) = &steps.control {
                let growth = if easy { steps.growth_factor } else { 1.0 };
                measure = problem.measure();
                match control.verdict(&measure, dlambda, growth, steps.min, rejected) {
                    Verdict::Reject { factor, q } => {
                        problem.restore();
                        let index = first_index + history.len();
                        let rejection = Cutback { index, lambda: target, dlambda, newton: report, rejected: Some(q) };
                        observer.cut_back(&rejection);
                        (cutbacks, rejected, dlambda) = (cutbacks + 1, true, dlambda * factor);
                        continue;
                    }
                    Verdict::Accept(factor) => next = Some(factor),
                }
            }
            problem.cautious(false);
            problem.commit();
            lambda = target;
            let inc =
                Increment { index: first_index + history.len(), lambda, dlambda, newton: report, cutbacks, measure };
            observer.converged(problem, &inc);
            history.push(inc);
            cutbacks = 0;
            rejected = false;
            if let Some(factor) = next {
                dlambda = (dlambda * factor).clamp(steps.min, steps.max);
                if let Some(planned) = planned.filter(|_| factor >= 1.0) {
                    dlambda = dlambda.max(planned);
                }
            } else if easy {
                dlambda = (dlambda * steps.growth_factor).min(steps.max);
            }
        } else {
            problem.restore();
            let index = first_index + history.len();
            observer.cut_back(&Cutback { index, lambda: target, dlambda, newton: report.clone(), rejected: None });
            cutbacks += 1;
            if problem.cautious(true) {
                // retry the same Δλ with the cautious linearization first
                continue;
            }
            let next = dlambda * steps.cutback_factor;
            if next < steps.min {
                problem.set_load_factor(lambda);
                return Err(Box::new(SteppingError {
                    reason: StopReason::IncrementTooSmall,
                    increment: index,
                    lambda: target,
                    dlambda,
                    last_converged: lambda,
                    newton: report,
                    seconds: None,
                }));
            }
            dlambda = next;
        }
    }
    Ok(history)
}

/// The stop before an increment is attempted (the problem at its last
/// converged state, λ).
fn stop_before(reason: StopReason, increment: usize, lambda: f64, dlambda: f64) -> Box<SteppingError> {
    Box::new(SteppingError {
        reason,
        increment,
        lambda,
        dlambda,
        last_converged: lambda,
        newton: Report::default(),
        seconds: None,
    })
}

/// An adaptive time step lands on the problem's next landing point: the
/// increment from `lambda` to `target` is cut short to end on it, and the
/// size it was cut from is returned (for the next increment).
fn land<P: Incremental>(problem: &P, lambda: f64, dlambda: &mut f64, target: &mut f64) -> Option<f64> {
    let stop = problem.landing(lambda)?;
    if stop > lambda + 1e-9 * *dlambda && stop < *target - 1e-9 * *dlambda {
        let planned = *dlambda;
        (*dlambda, *target) = (stop - lambda, stop);
        return Some(planned);
    }
    None
}

/// Newton on the present increment, solved again after each multiplier
/// update of an augmented Lagrangian until the problem is satisfied (or
/// Newton fails); the reports joined.
fn solve_increment<P: Incremental>(
    problem: &mut P,
    newton_settings: &NewtonSettings,
    first: FirstCorrection,
    interrupt: &Interrupt,
) -> Report {
    let mut report = newton::solve_from(problem, newton_settings, first, interrupt);
    let mut augmentations = 0;
    while report.converged() && augmentations < MAX_AUGMENTATIONS && problem.augment() {
        augmentations += 1;
        let again = newton::solve(problem, newton_settings, interrupt);
        report.iterations += again.iterations;
        report.residuals.extend(again.residuals);
        report.corrections.extend(again.corrections);
        report.line_searches += again.line_searches;
        report.failure = again.failure;
        report.message = again.message;
    }
    report
}

#[cfg(test)]
#[path = "stepping_tests.rs"]
mod tests;
