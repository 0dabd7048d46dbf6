//! What the path following reports: each increment ([`PathStep`], why one
//! failed: [`PathFailure`]), the observer of the converged ones
//! ([`PathObserver`]) and why a path stopped ([`PathError`]).

/// Why an increment failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathFailure {
    /// The iteration limit was reached.
    MaxIterations,
    /// The residual grew past the divergence ratio or became non-finite.
    Diverged,
    /// The constraint's quadratic had complex roots.
    ComplexRoots,
    /// The problem failed (e.g. a singular tangent); see the message.
    Problem,
    /// A stop was requested through the [`Interrupt`](crate::solver::Interrupt).
    Interrupted,
    /// The increment converged but turned from its predictor by more than
    /// `ArcLengthSettings::min_cosine` allows (a jump along the path).
    Turned,
}

/// One increment, converged or failed.
#[derive(Debug, Clone, PartialEq)]
pub struct PathStep {
    /// 1-based index of the increment.
    pub index: usize,
    /// Load factor reached (or, failed, last iterated).
    pub lambda: f64,
    /// Its change over the increment.
    pub dlambda: f64,
    /// The arc length `Δl` of the increment.
    pub arc_length: f64,
    /// Corrections made.
    pub iterations: usize,
    /// `‖R‖/‖f‖` at each evaluation.
    pub residuals: Vec<f64>,
    /// True if the increment converged (and was committed).
    pub converged: bool,
    /// Why it failed, if it did.
    pub failure: Option<PathFailure>,
    /// The problem's error message, if any.
    pub message: Option<String>,
    /// Failed attempts before this one (for a converged increment).
    pub cutbacks: usize,
    /// Negative pivots of the tangent at the converged point, if known.
    pub negative_pivots: Option<usize>,
}

/// Callbacks of the path following.
pub trait PathObserver<P> {
    /// After each converged and committed increment; false ends the run.
    fn converged(&mut self, problem: &P, step: &PathStep) -> bool;
    /// After each failed attempt (before the retry with half the arc length).
    fn cut_back(&mut self, _step: &PathStep) {}
}

/// Why the path following stopped with an error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathStop {
    /// The first tangent could not be formed or solved, or `f = 0`.
    Start,
    /// A cutback would bring `Δl` below its minimum.
    ArcTooSmall,
    /// A stop was requested through the [`Interrupt`](crate::solver::Interrupt).
    Interrupted,
}

/// The path following stopped (the problem is left at its last converged
/// increment).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}", describe(self))]
pub struct PathError {
    /// Why.
    pub reason: PathStop,
    /// The last converged load factor.
    pub(crate) last_lambda: f64,
    /// Converged increments before the stop.
    pub increments: usize,
    /// The last attempt, if any.
    pub attempt: Option<PathStep>,
    /// The problem's message (at the start).
    pub message: Option<String>,
}

fn describe(e: &PathError) -> String {
    let at = format!("after {} increments, at load factor {:.6}", e.increments, e.last_lambda);
    match e.reason {
        PathStop::Start => format!(
            "the path following could not start: {}",
            e.message.as_deref().unwrap_or("the reference load is zero")
        ),
        PathStop::Interrupted => format!("path following interrupted {at}"),
        PathStop::ArcTooSmall => {
            let why = e.attempt.as_ref().map_or(String::new(), |s| {
                let res: Vec<String> = s.residuals.iter().map(|r| format!("{r:.2e}")).collect();
                format!(
                    ": {:?} after {} iterations, relative residuals [{}]{}",
                    s.failure.unwrap_or(PathFailure::MaxIterations),
                    s.iterations,
                    res.join(", "),
                    s.message.as_ref().map(|m| format!("; {m}")).unwrap_or_default()
                )
            });
            format!("the arc length fell below its minimum {at}{why}")
        }
    }
}
