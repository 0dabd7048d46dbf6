//! The weights of an impulse taken at the end of a time step under
//! Newmark's and Bossak's methods (`crate::dynamics::impulse`): the one
//! recursion the contacts, the cohesive interfaces, a rigid impactor's push
//! and the damaged ply points (`crate::materials::damage_impulse`) share.
//! A foundation of its own so that the material law needs nothing of the
//! dynamics.

/// The weights of the end-of-step impulse over one step: Newmark's `γ` and
/// Bossak's `α` (`crate::dynamics::impulse`, *Bossak*). `g` is the force the velocity
/// update weighs, `f'` the one the residual takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Recursion {
    /// Newmark's γ.
    pub gamma: f64,
    /// Bossak's α (0: Newmark).
    pub alpha: f64,
}

impl Recursion {
    /// `(g, f')` of the step from the physical force `f` at its end and the
    /// committed `g_n`: `g = (f − (1 − γ) g_n) / γ`, `f' = (1 − α) g + α g_n`.
    pub fn step(self, physical: f64, committed: f64) -> (f64, f64) {
        let g = (physical - (1.0 - self.gamma) * committed) / self.gamma;
        (g, (1.0 - self.alpha) * g + self.alpha * committed)
    }

    /// `∂f'/∂f = (1 − α) / γ`, the factor on the forces' stiffness.
    pub fn weight(self) -> f64 {
        (1.0 - self.alpha) / self.gamma
    }
}
