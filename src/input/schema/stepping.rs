//! `[solver]` keys of what drives the increments: the path following's
//! control and stop, the load-step control and the line search
//! (`solver::step_control`, `solver::newton`).

use serde::Deserialize;

use super::Axis;
use crate::input::ranges;

/// `solver.step_control = { plastic_strain = 2e-3, contact_set = 0.2, time_error = 1e-3 }`:
/// the targets per increment of the adaptive load stepping (at least one).
#[derive(Debug, Clone, Copy, Default, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct StepControlFile {
    /// Largest increment of the equivalent plastic strain at any Gauss point.
    #[schemars(transform = ranges::PLASTIC_STRAIN_STEP.schema())]
    pub plastic_strain: Option<f64>,
    /// Largest fraction of the active contact points that open or close.
    #[schemars(transform = ranges::FRACTION.schema())]
    pub contact_set: Option<f64>,
    /// Largest local error of a time step relative to the largest
    /// displacement so far (`analysis.type = "transient"`: adaptive time steps).
    #[schemars(transform = ranges::TIME_ERROR.schema())]
    pub time_error: Option<f64>,
    /// Largest increment of a damage variable (a ply damage mode's, a
    /// cohesive interface's) at any point per increment.
    #[schemars(transform = ranges::FRACTION.schema())]
    pub damage: Option<f64>,
}

/// `solver.control`: what drives the increments.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub(crate) enum Control {
    /// λ prescribed increment by increment (load stepping; the default).
    #[default]
    Load,
    /// λ an unknown, each increment a fixed length of the path (Crisfield).
    ArcLength,
}

/// `solver.constraint`: what holds each path increment's length.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub(crate) enum PathConstraint {
    /// The cylinder of the displacements' change (Crisfield; the default).
    #[default]
    Cylinder,
    /// The energy dissipated per increment once the structure dissipates
    /// (Gutiérrez 2004; Verhoosel, Remmers & Gutiérrez 2009), the cylinder
    /// before.
    Dissipation,
}

/// `solver.stop = { probe, component, beyond }`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct StopFile {
    /// Name of a `[[probes]]` entry.
    pub probe: String,
    /// The displacement component watched.
    pub component: Axis,
    /// The run ends once the component is at or beyond this (m, ≠ 0).
    pub beyond: f64,
}
