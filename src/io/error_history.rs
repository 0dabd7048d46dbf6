//! summary.json's `error_history`: the rows of
//! `analysis::tables::error_history` (the estimated error of every kept
//! step end and frame) as objects.

use serde::Serialize;

use crate::analysis::{Solution, tables};
use crate::setup::Model;

/// The estimated error of one kept state (a row of
/// `analysis::tables::error_history`).
#[derive(Debug, Clone, Serialize)]
pub struct StateErrorSummary {
    /// `"step"` (a step's end) or `"frame"` (a transient run's output time).
    pub state: String,
    /// The step's name, or the frame's (`frame_<k>`, its VTU's stem).
    pub name: String,
    /// The increment it was reached at.
    pub increment: usize,
    /// Its analysis time λ.
    pub load_factor: f64,
    /// A transient run's time (s); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_s: Option<f64>,
    /// Estimated relative error in the energy norm (0–1).
    pub relative_energy_norm: f64,
    /// The estimated error in the energy norm (√J).
    pub error: f64,
    /// The energy norm of the state's stresses (√J).
    pub energy: f64,
}

/// The rows of `error_history` in summary.json.
pub(crate) fn rows(model: &Model, solution: &Solution) -> Vec<StateErrorSummary> {
    let Some(t) = tables::error_history(model, solution) else { return Vec::new() };
    let (state, name) = (t.text("state").unwrap_or_default(), t.text("name").unwrap_or_default());
    (0..t.rows())
        .map(|i| StateErrorSummary {
            state: state[i].clone(),
            name: name[i].clone(),
            increment: t.at("increment", i) as usize,
            load_factor: t.at("lambda", i),
            time_s: t.column("time").map(|c| c.values.get(i)),
            relative_energy_norm: t.at("estimate", i),
            error: t.at("error", i),
            energy: t.at("energy", i),
        })
        .collect()
}
