//! The end-of-step stress of one damaged ply point over a Newmark step
//! (`analysis.ply_damage_forces = "implicit"`; the scheme and why:
//! `crate::dynamics::ply_forces`).

use super::damage::{DamageState, PlyDamage};
use crate::voigt::{Matrix6, Voigt};

/// The Hashin onset measure `φ` from which a point takes the end-of-step
/// stress at the next step: the onset itself. Half the strength (`0.5`)
/// put every point a stress wave loads past half its strength under the
/// scheme, whose Bregman losses there are those of undamaged, linear
/// points: on the struck strip of crates/cufem-cli/tests/ply_damage_transient.rs
/// at 200 steps `0.105` of the impact energy against `0.063` from the onset,
/// and no step created energy either way.
pub(crate) const NEAR_ONSET: f64 = 1.0;

/// How a transient run integrates a damaging ply point's internal force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PointForces {
    /// Newmark's γ and Bossak's α.
    pub(crate) recursion: crate::newmark::Recursion,
    /// Damaged and near-onset points take the end-of-step stress
    /// (`analysis.ply_damage_forces = "implicit"`); else every point
    /// Newmark's average.
    pub(crate) end_of_step: bool,
}

/// One point's end-of-step stress over a step with the weights of
/// `forces.recursion` (Newmark's γ, Bossak's α): from
/// the committed state `old` and the trial `state` (whose `strain` is the
/// new strain in material axes) of the law `law`, the physical stress
/// `stress` (global) and `local` (material axes). Writes `force_stress`,
/// `implicit` and `scheme` of `state`; returns the factor on the point's
/// tangent (`(1 − α)/γ` under the scheme, else 1).
///
/// `scheme` gains what the forces' work at the point exceeds the change of
/// its stored energy at the new damage, `w − (W(ε_(n+1); d_(n+1)) −
/// W(ε_n; d_(n+1)))`, with `w = σ_(n+1)·Δε` under the scheme (the Bregman
/// distance, ≥ 0) and the trapezoidal `w = ½ (σ_n + σ_(n+1))·Δε` at a point
/// under Newmark's average whose damage grows in this step (every point
/// under `"newmark"`, a point's first damaging step under `"implicit"`;
/// signed: `½ ε_nᵀ (C_n − C_(n+1)) Δε` without a closing crack, and less
/// where a crack closes: the energy Newmark's average creates). With the law's release at fixed strain
/// (`DamageState::released`, `W(ε_n; d_n) − W(ε_n; d_(n+1))`) the point's
/// work is then exactly the change of its stored energy plus both.
pub(crate) fn end_of_step(
    forces: PointForces,
    law: &PlyDamage,
    old: &DamageState,
    state: &mut DamageState,
    (stress, local): (&Voigt, &Voigt),
) -> f64 {
    state.implicit =
        forces.end_of_step && (old.implicit || state.index >= NEAR_ONSET || state.viscous.iter().any(|&d| d > 0.0));
    let delta: Voigt = std::array::from_fn(|k| state.strain[k] - old.strain[k]);
    let dot = |s: &Voigt| s.iter().zip(&delta).map(|(a, b)| a * b).sum::<f64>();
    // W(ε_(n+1); d_(n+1)) − W(ε_n; d_(n+1))
    let stored_change = || state.stored - law.stored(&state.viscous, &old.strain);
    if !old.implicit {
        state.force_stress = *stress;
        state.velocity_stress = *stress;
        state.scheme = old.scheme;
        if (0..4).any(|i| state.viscous[i] > old.viscous[i]) {
            let before = law.stress(&old.viscous, &old.strain);
            let trapezoidal = 0.5 * (dot(&before) + dot(local));
            state.scheme += trapezoidal - stored_change();
        }
        return 1.0;
    }
    for k in 0..6 {
        (state.velocity_stress[k], state.force_stress[k]) = forces.recursion.step(stress[k], old.velocity_stress[k]);
    }
    // B = σ_(n+1)·Δε − (W(ε_(n+1); d_(n+1)) − W(ε_n; d_(n+1))) ≥ 0 (module
    // docs); round-off can leave it a hair below zero
    state.scheme = old.scheme + (dot(local) - stored_change()).max(0.0);
    forces.recursion.weight()
}

/// `c / γ` in place (the tangent of the end-of-step stress).
pub(crate) fn scale(c: &mut Matrix6, factor: f64) {
    c.iter_mut().flatten().for_each(|v| *v *= factor);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::anisotropic::Orthotropic;
    use crate::materials::failure::Strengths;

    const IMPLICIT: PointForces =
        PointForces { recursion: crate::newmark::Recursion { gamma: 0.5, alpha: 0.0 }, end_of_step: true };

    fn law() -> PlyDamage {
        let elastic =
            Orthotropic { young: [122.7e9, 10.1e9, 10.1e9], shear: [5.5e9, 5.5e9, 3.7e9], poisson: [0.25, 0.25, 0.45] };
        let strengths = Strengths {
            tension: [2070e6, 86e6, 86e6],
            compression: [1360e6, 196e6, 196e6],
            shear: [147e6, 147e6, 98e6],
        };
        PlyDamage::new(elastic, strengths, [12.5e3, 10e3, 1.0e3, 2.0e3], 1.0 - 1e-9).unwrap()
    }

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
        let held = [3.0, -1.0, 0.0, 0.5, 0.0, 0.0];
        let old = DamageState { implicit: true, force_stress: held, velocity_stress: held, ..Default::default() };
        let mut state = DamageState { index: 0.1, ..Default::default() };
        let stress = [1.0, 2.0, 0.0, 0.0, -1.0, 0.0];
        let factor = end_of_step(IMPLICIT, &law(), &old, &mut state, (&stress, &stress));
        assert_eq!(factor, 2.0);
        for k in 0..6 {
            assert!((0.5 * (old.force_stress[k] + state.force_stress[k]) - stress[k]).abs() < 1e-15);
        }
        assert!(state.implicit, "once under the scheme, always");
        let far = DamageState { index: 0.1, ..Default::default() };
        let mut next = DamageState { index: 0.2, ..Default::default() };
        assert_eq!(end_of_step(IMPLICIT, &law(), &far, &mut next, (&stress, &stress)), 1.0);
        assert_eq!(next.force_stress, stress);
        assert!(!next.implicit);
    }

    /// The per-point identity the energy ledger rests on: over every step
    /// of a point that cracks in matrix tension and shear while its strain
    /// grows, opens and shuts (large steps, so that it passes its softening
    /// within a few), the forces' work `σ_(n+1)·Δε` (`σ_n` and
    /// `σ_(n+1)` averaged at the step where the point still takes Newmark's
    /// average) equals the change of the stored energy plus the law's
    /// release at fixed strain (`released`, per mode) plus the scheme's
    /// `scheme`; the release and, under the scheme, the Bregman term are
    /// never negative. Independent: the work is summed here from the
    /// law's stresses and the strains, the energies from `stored`.
    #[test]
    fn the_work_of_the_forces_is_the_stored_energy_plus_the_release_plus_the_scheme() {
        let law = law();
        let band = [1e-4, 1e-4];
        let direction = [0.0, 1.0, 0.2, 0.6, 0.0, 0.1];
        let path = [0.0, 0.004, 0.009, 0.013, 0.006, -0.004, 0.011, 0.016, 0.02, 0.0, 0.025];
        let mut old = DamageState::default();
        let mut force_old = [0.0; 6];
        for (n, &s) in path.iter().enumerate().skip(1) {
            let strain: Voigt = direction.map(|x| x * s);
            let r = law.update_over(&strain, band, f64::INFINITY, &old);
            let mut state = r.state;
            end_of_step(IMPLICIT, &law, &old, &mut state, (&r.stress, &r.stress));
            let delta: Voigt = std::array::from_fn(|k| strain[k] - old.strain[k]);
            // the force stress's trapezoidal mean is the work's stress
            let mean: Voigt = std::array::from_fn(|k| 0.5 * (force_old[k] + state.force_stress[k]));
            let work: f64 = mean.iter().zip(&delta).map(|(a, b)| a * b).sum();
            let released: f64 = (0..4).map(|i| state.released[i] - old.released[i]).sum();
            let scheme = state.scheme - old.scheme;
            let stored = law.stored(&state.viscous, &strain) - law.stored(&old.viscous, &old.strain);
            let scale = r.stress.iter().zip(&delta).map(|(a, b)| (a * b).abs()).sum::<f64>();
            println!("step {n}: work {work:.4e} stored {stored:.4e} released {released:.4e} scheme {scheme:.4e}");
            assert!((work - stored - released - scheme).abs() <= 1e-9 * scale, "step {n}");
            assert!((0..4).all(|i| state.released[i] >= old.released[i]), "step {n}: a mode's release fell");
            if old.implicit {
                assert!(scheme >= 0.0, "step {n}");
            }
            force_old = state.force_stress;
            old = state;
        }
        assert!(old.viscous[2] > 0.5 && old.implicit, "the point did not crack: {:?}", old.viscous);
        assert!(old.released[2] > 0.0 && old.released[0] == 0.0, "{:?}", old.released);
    }
}
