//! `[analysis]` keys of a transient analysis: Newmark's parameters,
//! Rayleigh damping, initial velocities and the treatment of the contacts
//! (`model::transient` checks them).

use serde::Deserialize;

use super::Exact;

/// `analysis.contact_forces`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactForcesFile {
    /// The contact impulse at the end of the step.
    Implicit,
    /// Newmark's average of the forces at both ends.
    Newmark,
}

/// `analysis.newmark`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NewmarkFile {
    /// β.
    pub beta: f64,
    /// γ.
    pub gamma: f64,
}

/// `analysis.damping`: `C = mass · M + stiffness · K₀`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DampingFile {
    /// α_M (1/s).
    pub mass: Option<f64>,
    /// β_K (s).
    pub stiffness: Option<f64>,
}

/// `analysis.initial_velocities[]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialVelocityFile {
    /// The body.
    pub body: String,
    /// Its velocity (m/s).
    pub velocity: Exact<f64, 3>,
}

/// `analysis.contact_mass`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactMassFile {
    /// The contact nodes carry no mass (`dynamics::redistribution`).
    Redistributed,
    /// Every node keeps its share of the mass.
    Kept,
}
