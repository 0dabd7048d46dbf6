//! `[analysis]` keys of a transient analysis: Newmark's parameters,
//! Rayleigh damping, initial velocities and the treatment of the contacts
//! (`setup::transient` checks them).

use serde::Deserialize;

use super::Exact;
use crate::input::ranges;

/// `analysis.contact_forces`.
#[derive(Debug, Clone, Copy, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub(crate) enum ContactForcesFile {
    /// The contact impulse at the end of the step (the default).
    #[default]
    Implicit,
    /// Newmark's average of the forces at both ends.
    Newmark,
}

/// `analysis.interface_forces`.
#[derive(Debug, Clone, Copy, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub(crate) enum InterfaceForcesFile {
    /// The cohesive interfaces' impulse at the end of the step (the
    /// default).
    #[default]
    Implicit,
    /// Newmark's average of the forces at both ends.
    Newmark,
    /// The impulse of each point's discrete-gradient traction.
    DiscreteGradient,
}

/// `analysis.ply_damage_forces`.
#[derive(Debug, Clone, Copy, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub(crate) enum PlyDamageForcesFile {
    /// Newmark's average of the stresses at both ends (the default).
    #[default]
    Newmark,
    /// The end-of-step stress at damaged and near-onset ply points.
    Implicit,
}

/// `analysis.newmark`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct NewmarkFile {
    /// β (default `¼ (1 − α)²`).
    pub beta: Option<f64>,
    /// γ (default `½ − α`).
    #[schemars(transform = ranges::NEWMARK_GAMMA.schema())]
    pub gamma: Option<f64>,
    /// Bossak's α (default 0: Newmark's method).
    #[schemars(transform = ranges::BOSSAK_ALPHA.schema())]
    pub alpha: Option<f64>,
}

/// `analysis.damping`: `C = mass · M + stiffness · K₀`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct DampingFile {
    /// α_M (1/s).
    #[schemars(transform = ranges::DAMPING_MASS.schema())]
    pub mass: Option<f64>,
    /// β_K (s).
    #[schemars(transform = ranges::DAMPING_STIFFNESS.schema())]
    pub stiffness: Option<f64>,
}

/// `analysis.initial_velocities[]`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub(crate) struct InitialVelocityFile {
    /// The body.
    pub body: String,
    /// Its velocity (m/s).
    #[schemars(transform = ranges::SPEED.items())]
    pub velocity: Exact<f64, 3>,
}

/// `analysis.contact_mass`.
#[derive(Debug, Clone, Copy, Default, Deserialize, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub(crate) enum ContactMassFile {
    /// The contact nodes carry no mass (`dynamics::redistribution`; the default).
    #[default]
    Redistributed,
    /// Every node keeps its share of the mass.
    Kept,
}
