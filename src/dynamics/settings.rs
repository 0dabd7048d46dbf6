//! The settings of a transient analysis (validated by `setup::transient`).

use super::{ContactForces, ContactMass, InterfaceForces, MassKind, PlyDamageForces};

/// The settings of a transient analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct TransientSettings {
    /// Time of each load step (s): step k (λ ∈ [k, k + 1]) lasts
    /// `durations[k]`.
    pub durations: Vec<f64>,
    /// Newmark's β.
    pub beta: f64,
    /// Newmark's γ.
    pub gamma: f64,
    /// Bossak's α: the inertia force `M ((1 − α) a + α a_n)`
    /// (`dynamics::inertia`); 0 for Newmark's method.
    pub alpha: f64,
    /// Rayleigh damping `C = α_M M + β_K K₀`: `(α_M, β_K)`.
    pub damping: (f64, f64),
    /// The mass matrix.
    pub mass: MassKind,
    /// Uniform initial velocity per body index (m/s).
    pub initial_velocities: Vec<(usize, [f64; 3])>,
    /// `analysis.output_interval`: the time (s) between the frames of the
    /// ParaView time series; `None`: the step ends only.
    pub output_interval: Option<f64>,
    /// `analysis.contact_forces`: the contact impulse at the end of the
    /// step, or Newmark's average (`dynamics::impulse`).
    pub contact_forces: ContactForces,
    /// `analysis.contact_mass`: the contact nodes' mass moved to their
    /// neighbours, or kept (`dynamics::redistribution`).
    pub contact_mass: ContactMass,
    /// `analysis.interface_forces`: the cohesive interfaces' impulse at the
    /// end of the step, or Newmark's average (`dynamics::impulse`).
    pub interface_forces: InterfaceForces,
    /// `analysis.ply_damage_forces`: the end-of-step stress at damaged ply
    /// points, or Newmark's average (`dynamics::ply_forces`).
    pub ply_damage_forces: PlyDamageForces,
}

impl TransientSettings {
    /// The weights of the end-of-step impulses (`dynamics::impulse`).
    pub(crate) fn recursion(&self) -> crate::newmark::Recursion {
        crate::newmark::Recursion { gamma: self.gamma, alpha: self.alpha }
    }

    /// The time (s) at analysis time λ: the durations of the steps before
    /// and the elapsed fraction of the present one.
    pub fn time(&self, lambda: f64) -> f64 {
        let n = self.durations.len();
        let k = (lambda.max(0.0).floor() as usize).min(n - 1);
        self.durations[..k].iter().sum::<f64>() + (lambda - k as f64) * self.durations[k]
    }
}
