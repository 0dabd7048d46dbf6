//! `[solver]` keys of the load-step control and the line search
//! (`solver::step_control`, `solver::newton`).

use serde::Deserialize;

/// `solver.step_control = { plastic_strain = 2e-3, contact_set = 0.2 }`:
/// the targets per increment of the adaptive load stepping (at least one).
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepControlFile {
    /// Largest increment of the equivalent plastic strain at any Gauss point.
    pub plastic_strain: Option<f64>,
    /// Largest fraction of the active contact points that open or close.
    pub contact_set: Option<f64>,
}
