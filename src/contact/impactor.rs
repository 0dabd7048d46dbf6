//! A rigid impactor: an indenter with its own mass and initial velocity
//! (a drop weight, `[[indenters]] mass, velocity` in a transient analysis).
//! Its motion along the velocity is an unknown of the analysis, driven by
//! its inertia, its contact force and an optional applied force
//! (`analysis::structure::force`).

/// The mass and initial velocity of a rigid impactor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impactor {
    /// Mass (kg).
    pub mass: f64,
    /// Initial velocity (m/s); the impactor moves along it.
    pub velocity: [f64; 3],
}
