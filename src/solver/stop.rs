//! Why the load stepping stopped before the end of its load history, and
//! the message that says so: in load factors, or in seconds for a
//! transient analysis (`solver::stepping`).

use super::newton::{self, Report};

/// Why the load stepping stopped before λ = 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// A cutback would take Δλ below the minimum increment.
    IncrementTooSmall,
    /// The limit on the number of increments was reached.
    TooManyIncrements,
    /// A stop was requested through the [`crate::solver::Interrupt`].
    Interrupted,
    /// Path following (`solver::arclength`) stopped before its end: the
    /// arc length fell below its minimum, or the increments ran out
    /// (`SteppingError::newton` carries the message).
    PathFollowing,
    /// The eigenvalue analysis after the converged static solution
    /// (buckling, modal) could not be made; the static state is kept
    /// (`SteppingError::newton` carries the message).
    Eigenproblem,
}

/// The analysis could not reach λ = 1 (the problem is left at its last
/// converged increment).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct SteppingError {
    /// Why it stopped.
    pub reason: StopReason,
    /// Index of the increment that failed (or was not attempted).
    pub increment: usize,
    /// λ attempted.
    pub lambda: f64,
    /// Last Δλ tried.
    pub dlambda: f64,
    /// Last converged λ (the state the problem is left in).
    pub(crate) last_converged: f64,
    /// Newton history of the last attempt.
    pub newton: Report,
    /// A transient analysis's times (s): attempted, the last time step
    /// tried, and the last converged one; the message then speaks of
    /// times instead of load factors. `None` for a static analysis.
    pub seconds: Option<[f64; 3]>,
}

impl std::fmt::Display for SteppingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if let Some([t, dt, last]) = self.seconds {
            return match self.reason {
                StopReason::IncrementTooSmall => write!(
                    f,
                    "time step {} did not converge at t = {t:.6e} s (Δt = {dt:.3e} s) and a cutback would go below \
                     solver.min_increment: {}",
                    self.increment,
                    describe(&self.newton)
                ),
                StopReason::TooManyIncrements => write!(
                    f,
                    "stopped at t = {last:.6e} s after {} converged time steps of this load step: the limit \
                     solver.max_increments = {} was reached (raise it to go on)",
                    self.increment - 1,
                    self.increment - 1
                ),
                StopReason::Interrupted => write!(f, "interrupted at t = {last:.6e} s (the last converged time step)"),
                StopReason::PathFollowing | StopReason::Eigenproblem => {
                    f.write_str(self.newton.message.as_deref().unwrap_or("path following stopped"))
                }
            };
        }
        match self.reason {
            StopReason::IncrementTooSmall => write!(
                f,
                "increment {} did not converge at load factor {:.6} and a cutback would bring Δλ = {:.3e} below \
                 solver.min_increment: {}",
                self.increment,
                self.lambda,
                self.dlambda,
                describe(&self.newton)
            ),
            StopReason::TooManyIncrements => write!(
                f,
                "stopped at load factor {:.6} after {} converged increments: the limit solver.max_increments = {} \
                 was reached (raise it, or max_increment, to go on)",
                self.last_converged,
                self.increment - 1,
                self.increment - 1
            ),
            StopReason::Interrupted => {
                write!(f, "interrupted at load factor {:.6} (the last converged increment)", self.last_converged)
            }
            StopReason::PathFollowing | StopReason::Eigenproblem => {
                f.write_str(self.newton.message.as_deref().unwrap_or("path following stopped"))
            }
        }
    }
}

fn describe(r: &Report) -> String {
    let res: Vec<String> = r.residuals.iter().map(|v| format!("{v:.2e}")).collect();
    let what = match r.failure {
        Some(newton::Failure::Diverged) => format!("Newton diverged after {} iterations", r.iterations),
        Some(newton::Failure::Problem) => format!("the linear solve failed after {} iterations", r.iterations),
        Some(newton::Failure::Rejected) => format!("converged in {} iterations but rejected", r.iterations),
        Some(newton::Failure::Stagnated) => {
            format!("Newton's residual stopped decreasing ({} iterations)", r.iterations)
        }
        _ => format!("Newton did not converge in {} iterations", r.iterations),
    };
    format!(
        "{what}; relative residuals [{}]{}",
        res.join(", "),
        r.message.as_ref().map(|m| format!("; {m}")).unwrap_or_default()
    )
}
