//! The stress of damaged ply points at the end of the time step
//! (`analysis.ply_damage_forces = "implicit"`): the impulse of their
//! internal force over a Newmark step is `Δt f(u_(n+1))`, as the contacts'
//! and the cohesive interfaces' (`dynamics::impulse`), instead of Newmark's
//! average of both ends.
//!
//! **Why.** With the trapezoidal rule the inertia forces' work over a step
//! is exactly `ΔT`, so the step's energy balance charges each Gauss point
//! the trapezoidal work `½ (σ_n + σ_(n+1)) · Δε`. A damaged ply point's
//! stored energy `W(ε; d)` is piecewise quadratic: its crack carries
//! `(1 − d) E` open and the full `E` closed (`materials::damage`). Where a
//! point crosses that kink within a step the trapezoidal work differs from
//! the change of `W`, and a crack that opens and shuts within steps pumps
//! energy into the motion: the kinetic energy of a drop weight on a damaging
//! laminate grows past the impact's (docs/limitations.md).
//!
//! **The scheme.** A point that has damaged, or whose Hashin onset measure
//! `φ` reached `materials::damage_impulse::NEAR_ONSET` (1, the onset) at a converged step, takes
//! from the next step on the algorithmic stress
//!
//! ```text
//! σ'_(n+1) = (σ(ε_(n+1), d_(n+1)) − (1 − γ) σ'_n) / γ,     ∂σ'/∂ε = C_(n+1) / γ
//! ```
//!
//! in its internal force (`σ'_n = σ_n` where the point took the average
//! before; with Bossak's α the recursion of `crate::newmark::Recursion`,
//! `g` starting from `σ_n` there, exact for α = 0 only, and the tangent
//! `(1 − α) C_(n+1) / γ`). In small strain the internal force is linear in the stress, so
//! this is the impulse recursion of `dynamics::impulse` point by point:
//! with the trapezoidal rule the step charges the point
//! `σ_(n+1) · Δε`. At fixed damage `W(·; d)` is convex with a continuous
//! gradient (the Legendre conjugate of `½ σᵀ S(d, sign σ) σ`, each normal
//! compliance switching with the sign of its own stress), and it falls as
//! the damage grows, so
//!
//! ```text
//! σ_(n+1) · Δε = W(ε_(n+1); d_(n+1)) − W(ε_n; d_(n+1)) + B ≥ W(ε_(n+1); d_(n+1)) − W(ε_n; d_n),
//! B = W(ε_n; d_(n+1)) − W(ε_(n+1); d_(n+1)) − σ_(n+1) · (ε_n − ε_(n+1)) ≥ 0
//! ```
//!
//! (the Bregman distance of the convex `W`): **a point under the scheme
//! cannot create energy**. It dissipates `B` per step, `½ Δε·C Δε` on a
//! branch (first order in Δt, as backward Euler); the point keeps the sum
//! (`DamageState::scheme`, J/m³) and the energy ledger books it as its own
//! column, `damage_scheme` (`dynamics::energy`), beside the damage's release
//! at fixed strain `W(ε_n; d_n) − W(ε_n; d_(n+1))`, per mode
//! (`DamageState::released`): the point's work is the change of its stored
//! energy plus both, exactly, and the ledger's `plastic` in a body without
//! plasticity is zero to round-off (crates/cufem-cli/tests/ply_damage_transient.rs).
//! At a point's first damaging step, still under Newmark's average, the
//! trapezoidal work's excess over the change at fixed `d_(n+1)` is booked
//! in `damage_scheme` the same way (`materials::damage_impulse::end_of_step`;
//! under `"newmark"` at every damaging point). Points far from onset keep Newmark's average
//! (linear elastic, where the trapezoidal work is exact and the scheme adds
//! nothing). The set of points is fixed within a step (taken from the
//! committed states), so the residual does not switch between Newton
//! iterations (the point's update: `materials::damage_impulse`).
//! `"newmark"` averages the stresses of every point.

/// How a transient analysis integrates the internal force of damaged ply
/// points (`analysis.ply_damage_forces`, module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PlyDamageForces {
    /// Newmark's average of the stresses at both ends of the step.
    #[default]
    Newmark,
    /// The end-of-step stress at damaged and near-onset points (cannot
    /// create energy).
    Implicit,
}
