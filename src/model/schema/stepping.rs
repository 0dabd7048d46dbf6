//! `[solver]` keys of what drives the increments: the path following's
//! control and stop, the load-step control and the line search
//! (`solver::step_control`, `solver::newton`).

use serde::Deserialize;

use super::Axis;

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

/// `solver.control`: what drives the increments.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Control {
    /// λ prescribed increment by increment (load stepping).
    Load,
    /// λ an unknown, each increment a fixed length of the path (Crisfield).
    ArcLength,
}

/// `solver.stop = { probe, component, beyond }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StopFile {
    pub probe: String,
    pub component: Axis,
    pub beyond: f64,
}
