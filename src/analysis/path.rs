//! Path following of the finite-element structure (`[solver] control =
//! "arc_length"`): `PathStructure` adapts [`Structure`] to
//! [`solver::arclength::PathProblem`](crate::solver::arclength::PathProblem),
//! and `follow` traces the path from λ = 0, recording each converged point
//! as load stepping records an increment (history rows, increments,
//! cutbacks), until a stop criterion of the model holds.
//!
//! The problem is `R(u, λ) = f_int(u) − λ f − f_c(u)` on the free
//! equations, `f` the model's loads at λ = 1 (`setup::path` refuses any
//! other loading). Each corrector solves two right-hand sides with one
//! factorization of the present tangent (`Structure::solve_columns`, in
//! double precision: `LDLᵀ` once the tangent is indefinite past a limit
//! point). Gauss-point states are committed with each converged point and
//! restored after a failed attempt, as in load stepping.

use super::{Recorder, Structure};
use crate::input::PathSettings;
use crate::setup::Model;
use crate::solver::Interrupt;
use crate::solver::arclength::{self, PathError, PathObserver, PathProblem, PathStep, PathStop};
use crate::solver::linear::LinearError;
use crate::solver::newton::{Failure, Report};
use crate::solver::stepping::{Cutback, Increment, Incremental, Observer, SteppingError, StopReason};

/// The structure as a path-following problem.
pub(crate) struct PathStructure<'s, 'm> {
    structure: &'s mut Structure<'m>,
    /// The reference load by equation.
    load: Vec<f64>,
}

impl<'s, 'm> PathStructure<'s, 'm> {
    /// Wraps `structure` at its committed state.
    pub fn new(structure: &'s mut Structure<'m>) -> Self {
        let load = structure.reference_load();
        structure.start_path_increment();
        Self { structure, load }
    }

    /// The structure, at the last evaluated iterate.
    pub fn structure(&self) -> &Structure<'m> {
        self.structure
    }
}

impl PathProblem for PathStructure<'_, '_> {
    type Error = LinearError;

    fn dimension(&self) -> usize {
        self.structure.n_equations()
    }

    fn reference_load(&self, f: &mut [f64]) {
        f.copy_from_slice(&self.load);
    }

    fn residual(&mut self, lambda: f64, r: &mut [f64]) -> Result<(), LinearError> {
        use crate::solver::newton::NonlinearProblem;
        self.structure.set_path_load_factor(lambda);
        self.structure.evaluate()?;
        r.copy_from_slice(self.structure.residual());
        Ok(())
    }

    fn solve(&mut self, rhs: &mut [&mut [f64]]) -> Result<(), LinearError> {
        self.structure.solve_columns(rhs)
    }

    fn update(&mut self, du: &[f64]) -> Result<(), LinearError> {
        self.structure.add_by_equation(du);
        Ok(())
    }

    fn commit(&mut self) {
        Incremental::commit(self.structure);
        self.structure.start_path_increment();
    }

    fn restore(&mut self) {
        Incremental::restore(self.structure);
        self.structure.start_path_increment();
    }

    fn negative_pivots(&self) -> Option<usize> {
        self.structure.negative_pivots()
    }

    fn pseudo_time_step(&mut self, step: f64) {
        self.structure.set_path_viscous_step(step);
    }
}

/// Why a path following ended as the model asked.
#[derive(Debug, Clone, PartialEq)]
pub enum PathEnd {
    /// λ reached `solver.max_load_factor`.
    LoadFactor(f64),
    /// The probe of `solver.stop` passed its value.
    Displacement {
        /// Probe name.
        probe: String,
        /// 0, 1, 2 for x, y, z.
        component: usize,
        /// Its displacement at the last point (m).
        value: f64,
    },
}

/// How a path following went (`Solution::path`).
#[derive(Debug, Clone, PartialEq)]
pub struct PathOutcome {
    /// The stop criterion met; `None` if the run stopped early
    /// (`Solution::failure` says why).
    pub end: Option<PathEnd>,
    /// The limit points passed: `(increment, λ)` of each converged point
    /// where λ turned (a maximum, then a minimum after a snap-through), the
    /// largest λ of the points around the limit, not interpolated.
    pub limit_points: Vec<(usize, f64)>,
    /// The first arc length `Δl₀` (m).
    pub(crate) first_arc_length: f64,
}

/// Records the converged points and checks the stop criteria.
struct Watch<'r, 'a> {
    recorder: &'r mut Recorder<'a>,
    model: &'r Model,
    settings: &'r PathSettings,
    end: Option<PathEnd>,
    limit_points: Vec<(usize, f64)>,
    /// `Δλ` of the previous point.
    last_dlambda: f64,
    first_arc: f64,
}

fn report(step: &PathStep) -> Report {
    let failure = step.failure.map(|f| match f {
        arclength::PathFailure::Diverged => Failure::Diverged,
        arclength::PathFailure::Problem | arclength::PathFailure::ComplexRoots => Failure::Problem,
        arclength::PathFailure::Turned => Failure::Rejected,
        arclength::PathFailure::Interrupted => Failure::Interrupted,
        arclength::PathFailure::MaxIterations => Failure::MaxIterations,
    });
    let complex = step.failure == Some(arclength::PathFailure::ComplexRoots);
    let message =
        if complex { Some("the arc-length constraint has no real root".into()) } else { step.message.clone() };
    Report {
        iterations: step.iterations,
        residuals: step.residuals.clone(),
        corrections: Vec::new(),
        failure,
        message,
        line_searches: 0,
    }
}

impl<'s, 'm> PathObserver<PathStructure<'s, 'm>> for Watch<'_, '_> {
    fn converged(&mut self, p: &PathStructure<'s, 'm>, step: &PathStep) -> bool {
        if self.first_arc == 0.0 {
            self.first_arc = step.arc_length * 2f64.powi(step.cutbacks as i32);
        }
        let inc = Increment {
            index: step.index,
            lambda: step.lambda,
            dlambda: step.dlambda,
            newton: report(step),
            cutbacks: step.cutbacks,
            measure: Default::default(),
        };
        self.recorder.converged(p.structure(), &inc);
        if step.dlambda * self.last_dlambda < 0.0 {
            let previous = self.recorder.history.len().checked_sub(2).map(|k| &self.recorder.history[k]);
            self.limit_points.extend(previous.map(|row| (row.increment, row.lambda)));
        }
        self.last_dlambda = step.dlambda;
        if step.lambda >= self.settings.max_load_factor {
            self.end = Some(PathEnd::LoadFactor(step.lambda));
        } else if let Some(stop) = self.settings.stop {
            let u = self.recorder.history.last().map_or([0.0; 3], |row| row.probes[stop.probe]);
            if stop.passed(u) {
                let probe = self.model.probes[stop.probe].name.clone();
                self.end = Some(PathEnd::Displacement { probe, component: stop.component, value: u[stop.component] });
            }
        }
        self.end.is_none()
    }

    fn cut_back(&mut self, step: &PathStep) {
        let index = self.recorder.increments.len() + 1;
        self.recorder.cut_back(&Cutback {
            index,
            lambda: step.lambda,
            dlambda: step.dlambda,
            newton: report(step),
            rejected: None,
        });
    }
}

/// Traces the path of `structure` (at its committed state, λ = 0) with the
/// model's settings. Returns how it went and, if it stopped before a stop
/// criterion, why (the structure is then at its last converged point); an
/// error for an arc length too long for the model (below).
///
/// Every arc length is at most the length of the linear path to
/// `solver.max_load_factor` at the start's stiffness (`max_load_factor ·
/// ‖K₀⁻¹ f‖`): a longer first arc would reach past the whole requested path
/// in one increment, so `solver.arc_length` beyond it is refused by key.
pub(super) fn follow(
    structure: &mut Structure<'_>,
    model: &Model,
    settings: &PathSettings,
    recorder: &mut Recorder<'_>,
    interrupt: &Interrupt,
) -> Result<(PathOutcome, Option<SteppingError>), super::AnalysisError> {
    let mut problem = PathStructure::new(structure);
    let mut arc = settings.arc;
    arc.max_lambda = settings.max_load_factor;
    let mut start = None;
    match linear_length(&mut problem) {
        Ok(norm) if norm > 0.0 && norm.is_finite() => {
            arc.max_length = settings.max_load_factor * norm;
            if let Some(length) = settings.arc_length {
                if length > arc.max_length {
                    return Err(too_long(length, norm, settings.max_load_factor).into());
                }
                // Δλ of the first predictor from the requested Δl₀
                arc.initial_dlambda = length / norm;
            }
        }
        Ok(_) => {}
        Err(e) => start = Some(e.to_string()),
    }
    let mut watch =
        Watch { recorder, model, settings, end: None, limit_points: Vec::new(), last_dlambda: 0.0, first_arc: 0.0 };
    let traced = match start {
        Some(message) => Err(Box::new(PathError {
            reason: PathStop::Start,
            last_lambda: 0.0,
            increments: 0,
            attempt: None,
            message: Some(message),
        })),
        None => arclength::trace(&mut problem, 0.0, &arc, &mut watch, interrupt),
    };
    let (n, lambda) = (watch.recorder.increments.len(), watch.recorder.history.last().map_or(0.0, |r| r.lambda));
    let failure = match traced {
        Ok(_) if watch.end.is_some() => None,
        Ok(_) => Some(stopped(
            n,
            lambda,
            format!(
                "the path following stopped at load factor {lambda:.6} after {n} increments: solver.max_increments = \
                 {n} was reached before solver.max_load_factor = {}{} (raise max_increments, or the arc length, to go on)",
                settings.max_load_factor,
                if settings.stop.is_some() { " or solver.stop" } else { "" }
            ),
        )),
        Err(e) if e.reason == PathStop::Interrupted => {
            let mut s = stopped(n, lambda, e.to_string());
            s.reason = StopReason::Interrupted;
            Some(s)
        }
        Err(e) => {
            let mut s = stopped(n, lambda, e.to_string());
            if let Some(a) = &e.attempt {
                (s.lambda, s.dlambda) = (a.lambda, a.dlambda);
            }
            Some(s)
        }
    };
    let outcome = PathOutcome { end: watch.end, limit_points: watch.limit_points, first_arc_length: watch.first_arc };
    Ok((outcome, failure))
}

/// `‖K₀⁻¹ f‖` at the start: the length of the linear predictor of Δλ = 1.
fn linear_length(p: &mut PathStructure<'_, '_>) -> Result<f64, LinearError> {
    let mut r = vec![0.0; p.dimension()];
    p.residual(0.0, &mut r)?;
    let mut df = p.load.clone();
    p.solve(&mut [&mut df[..]])?;
    Ok(p.dot(&df, &df).sqrt())
}

/// The refusal of `solver.arc_length = length` longer than the linear path
/// to `max_load_factor` (`norm` = `‖K₀⁻¹ f‖`).
fn too_long(length: f64, norm: f64, max_load_factor: f64) -> crate::setup::ModelError {
    use crate::numbers::limit;
    crate::setup::ModelError::Invalid {
        key: "solver.arc_length".into(),
        value: format!("{} m", crate::numbers::number(length)),
        allowed: format!(
            "at most {} m for this model, the length of its linear path to solver.max_load_factor = {} at the \
             start's stiffness: this first increment alone would carry λ to {} by the linear prediction and could \
             jump over limit points; a tenth of that or less follows them (or give solver.increments instead: 10 \
             makes the first increment a tenth of the load)",
            limit(max_load_factor * norm),
            crate::numbers::number(max_load_factor),
            limit(length / norm)
        ),
    }
}

/// The early stop after `n` converged points at `lambda`.
fn stopped(n: usize, lambda: f64, message: String) -> SteppingError {
    SteppingError {
        reason: StopReason::PathFollowing,
        increment: n + 1,
        lambda,
        dlambda: 0.0,
        last_converged: lambda,
        newton: Report { message: Some(message), ..Report::default() },
        seconds: None,
    }
}
