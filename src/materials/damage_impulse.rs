//! The end-of-step stress of one damaged ply point over a Newmark step
//! (`analysis.ply_damage_forces = "implicit"`; the scheme and why:
//! `crate::dynamics::ply_forces`).

use super::damage::DamageState;
use crate::voigt::{Matrix6, Voigt};

/// The Hashin onset measure `φ` from which a point takes the end-of-step
/// stress at the next step: the onset itself. Half the strength (`0.5`)
/// put every point a stress wave loads past half its strength under the
/// scheme, whose Bregman losses there are those of undamaged, linear
/// points: on the struck strip of crates/cufem-cli/tests/ply_damage_transient.rs
/// at 200 steps `0.105` of the impact energy against `0.063` from the onset,
/// and no step created energy either way.
pub(crate) const NEAR_ONSET: f64 = 1.0;

/// One point's end-of-step stress over a step with Newmark's `gamma`: from
/// the committed state `old` and the trial `state` (whose `strain` is the
/// new strain in material axes), the physical stress `stress` (global)
/// and `local` (material axes) and the law's stored energy at the old
/// strain with the new damage `stored_before` (`PlyDamage::stored`).
/// Writes `force_stress`, `implicit` and `scheme` of `state`; returns the
/// factor on the point's tangent (`1/γ` under the scheme, else 1).
pub(crate) fn end_of_step(
    gamma: f64,
    old: &DamageState,
    state: &mut DamageState,
    (stress, local): (&Voigt, &Voigt),
    stored_before: impl FnOnce() -> f64,
) -> f64 {
    state.implicit = old.implicit || state.index >= NEAR_ONSET || state.viscous.iter().any(|&d| d > 0.0);
    if !old.implicit {
        state.force_stress = *stress;
        state.scheme = old.scheme;
        return 1.0;
    }
    state.force_stress = std::array::from_fn(|k| (stress[k] - (1.0 - gamma) * old.force_stress[k]) / gamma);
    let work: f64 = local.iter().zip(state.strain.iter().zip(&old.strain)).map(|(s, (e, e0))| s * (e - e0)).sum();
    // B = σ_(n+1)·Δε − (W(ε_(n+1); d_(n+1)) − W(ε_n; d_(n+1))) ≥ 0 (module
    // docs); round-off can leave it a hair below zero
    state.scheme = old.scheme + (work - state.stored + stored_before()).max(0.0);
    1.0 / gamma
}

/// `c / γ` in place (the tangent of the end-of-step stress).
pub(crate) fn scale(c: &mut Matrix6, factor: f64) {
    c.iter_mut().flatten().for_each(|v| *v *= factor);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point of a 1D damaged bar with the open/closed kink
    /// `W = ½ E_±ε²` (E₊ = (1 − d) E where ε > 0, E₋ = E): a step that
    /// opens the crack from compression crosses the kink, one that closes
    /// it stops at the kink, then compresses. The end-of-step stress's work
    /// per step is never below ΔW (its excess is the Bregman distance of
    /// the convex W); the trapezoidal work of an opening step falls short
    /// of ΔW by ½ (E − E₊) |ε_n| ε_(n+1), so over the cycles it books less
    /// work than the energy stored: energy from nothing. An independent
    /// calculation of both works.
    #[test]
    fn the_end_of_step_stress_cannot_create_energy_across_a_closing_crack() {
        let (e, d) = (100.0, 0.9);
        let sigma = |x: f64| if x > 0.0 { (1.0 - d) * e * x } else { e * x };
        let w = |x: f64| 0.5 * sigma(x) * x;
        // closed, opened across the kink, closed to it, …
        let path = [0.0, -1.0, 1.0, 0.0, -1.0, 1.0, 0.0];
        let (mut trapezoidal, mut implicit) = (0.0, 0.0);
        for p in path.windows(2) {
            let (a, b) = (p[0], p[1]);
            let dw = w(b) - w(a);
            let end = sigma(b) * (b - a);
            let bregman = w(a) - w(b) - sigma(b) * (a - b);
            assert!(end >= dw - 1e-12, "{a} → {b}: {end} < {dw}");
            assert!((end - dw - bregman).abs() < 1e-12);
            trapezoidal += 0.5 * (sigma(a) + sigma(b)) * (b - a) - dw;
            implicit += end - dw;
        }
        // the trapezoidal rule books less work than the energy stored: per
        // opening ½ (σ₋ + σ₊)·2 − (W₊ − W₋) = −½ (E − E₊) = −45 (energy
        // from nothing); the end-of-step stress books more
        println!("work less ΔW over the path: trapezoidal {trapezoidal}, end of step {implicit}");
        assert!((trapezoidal + 90.0).abs() < 1e-9 && implicit > 0.0, "{trapezoidal} {implicit}");
    }

    /// The recursion: with γ = ½ the mean of the algorithmic stresses of
    /// both ends is the end-of-step stress, whatever the point held before.
    #[test]
    fn the_algorithmic_stress_makes_the_mean_the_end_of_step_stress() {
        let old = DamageState { implicit: true, force_stress: [3.0, -1.0, 0.0, 0.5, 0.0, 0.0], ..Default::default() };
        let mut state = DamageState { index: 0.1, ..Default::default() };
        let stress = [1.0, 2.0, 0.0, 0.0, -1.0, 0.0];
        let factor = end_of_step(0.5, &old, &mut state, (&stress, &stress), || 0.0);
        assert_eq!(factor, 2.0);
        for k in 0..6 {
            assert!((0.5 * (old.force_stress[k] + state.force_stress[k]) - stress[k]).abs() < 1e-15);
        }
        assert!(state.implicit, "once under the scheme, always");
        let far = DamageState { index: 0.1, ..Default::default() };
        let mut next = DamageState { index: 0.2, ..Default::default() };
        assert_eq!(end_of_step(0.5, &far, &mut next, (&stress, &stress), || 0.0), 1.0);
        assert_eq!(next.force_stress, stress);
        assert!(!next.implicit);
    }
}
