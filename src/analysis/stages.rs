//! The eigenvalue analyses after the static solution (`analysis.type =
//! "buckling"` or `"modal"`). Their failure no longer discards the
//! converged static state: it is kept and written, and the run stops with
//! the reason (exit 2, as any analysis that stopped before its end) — a
//! modal analysis about a state past a critical load, whose pre-stressed
//! tangent is indefinite, above all.

use super::{AnalysisError, HistoryRow, Structure, buckling, modal};
use crate::setup::Model;
use crate::solver::eigen::EigenError;
use crate::solver::newton::Report;
use crate::solver::stepping::{SteppingError, StopReason};

/// The buckling or modal results, and the run's failure.
type Eigen = (Option<buckling::Buckling>, Option<modal::Modal>, Option<SteppingError>);

/// Runs the model's eigenvalue analysis about the converged static state
/// (none after a static run that stopped early). An eigenproblem that
/// cannot be solved becomes the run's failure, the static state kept.
pub(super) fn eigen(
    structure: &mut Structure<'_>,
    model: &Model,
    history: &[HistoryRow],
    failure: Option<SteppingError>,
) -> Result<Eigen, AnalysisError> {
    if failure.is_some() {
        return Ok((None, None, failure));
    }
    let lambda = structure.load_factor();
    if let Some(b) = model.buckling {
        return match buckling::solve(structure, b.modes) {
            Ok(b) => Ok((Some(b), None, None)),
            Err(AnalysisError::Eigen(e)) => Ok((None, None, Some(stop("buckling", &e, lambda, history, model)))),
            Err(e) => Err(e),
        };
    }
    if let Some(settings) = model.modal {
        return match modal::solve(structure, model, settings) {
            Ok(m) => Ok((None, Some(m), None)),
            Err(AnalysisError::Eigen(e)) => Ok((None, None, Some(stop("modal", &e, lambda, history, model)))),
            Err(e) => Err(e),
        };
    }
    Ok((None, None, None))
}

/// The stop of a `what` analysis whose eigenproblem failed with `e` about
/// the converged state at `lambda`.
fn stop(what: &str, e: &EigenError, lambda: f64, history: &[HistoryRow], model: &Model) -> SteppingError {
    let why = match e {
        EigenError::NotPositiveDefinite => {
            let pivots = history.last().and_then(|r| r.negative_pivots).filter(|&n| n > 0);
            let count =
                pivots.map_or(String::new(), |n| format!(" ({n} negative pivot{})", if n == 1 { "" } else { "s" }));
            let geometry = if model.kinematics.is_nonlinear() { "pre-stressed tangent" } else { "stiffness" };
            format!(
                "its {geometry} there is not positive definite{count}: the structure is unstable at that state (past \
                 a buckling or limit load, or free to move rigidly) and has no {} about it; lower the loads below the \
                 first critical load (analysis.type = \"buckling\" finds it), or give analysis.imperfection",
                if what == "modal" { "natural frequencies" } else { "buckling loads" }
            )
        }
        other => other.to_string(),
    };
    let n = history.len();
    SteppingError {
        reason: StopReason::Eigenproblem,
        increment: n + 1,
        lambda,
        dlambda: 0.0,
        last_converged: lambda,
        seconds: None,
        newton: Report {
            message: Some(format!(
                "the {what} analysis (analysis.type = \"{what}\") about the converged static state at load factor \
                 {lambda:.6} failed: {why}; the static results are written"
            )),
            ..Report::default()
        },
    }
}
