//! Load-step control by an error measure (`solver.step_control`): the size
//! of the next increment from what the last one changed, instead of a fixed
//! count.
//!
//! After each converged increment (before it is committed) the problem
//! measures what changed (`Incremental::measure` of `solver::stepping`): the
//! largest increment of the equivalent plastic strain at any point, the
//! largest increment of a damage variable at any point (ply damage modes,
//! cohesive interfaces), and the fraction of the discrete contact set whose
//! status changed. Each is divided by its target ([`StepControl`]); `q` is
//! the largest ratio.
//!
//! * `q` > `REJECT` (plastic strain, damage or time error): the increment is rejected,
//!   rolled back and redone with `Δλ · max(SAFETY/q, 1/4)` (the time
//!   error: `(SAFETY/q)^(1/3)`) — once per
//!   increment, and not below the smallest increment. The plastic strain
//!   and the damage are measures of the error of integrating the path in one increment;
//!   a change of the contact set is not an error of a converged state
//!   (frictionless contact is path-independent), so it only steers the
//!   next size.
//! * otherwise the next `Δλ` is `Δλ · clamp(SAFETY/q, 1/2, g)`, `g` the
//!   growth factor after an easy increment (Newton within
//!   `easy_iterations`) and 1 after a hard one, bounded by the step's
//!   smallest and largest increment.
//!
//! Both measures grow about linearly with `Δλ` along a smooth path, so
//! `SAFETY/q` is the increment that would have met the target with a margin.
//!
//! The third measure, `time_error`, is the local error estimate of a time
//! step of a transient analysis (`dynamics::time_error`), relative to the
//! displacement scale: it grows like `Δt³`, so its factor is
//! `(SAFETY/q)^(1/3)` (Zienkiewicz & Xie 1991). It is an error of the
//! converged step, so above `REJECT` times its target it rejects the step
//! like the plastic strain does; the next step takes the smaller of the
//! measures' factors, within the same bounds.
//!
//! Stepping knows nothing of plasticity, contact or dynamics: the measures
//! are numbers the problem reports (the default: nothing measured, `q` = 0,
//! the increment grows like an easy one).

/// Targets of the step control. `None`: that measure is not controlled.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepControl {
    /// Largest increment of the equivalent plastic strain at any point
    /// per load increment.
    pub plastic_strain: Option<f64>,
    /// Largest fraction of the contact points, of those active before or
    /// after the increment, that open or close in one increment.
    pub contact_set: Option<f64>,
    /// Largest local error of a time step (`dynamics::time_error`) relative
    /// to the displacement scale (transient analyses only).
    pub time_error: Option<f64>,
    /// Largest increment of a damage variable at any point per increment:
    /// a ply damage mode's or a cohesive interface's, the damage the
    /// stiffness takes (the viscous one under Duvaut–Lions).
    pub damage: Option<f64>,
}

/// What a converged increment changed (reported by the problem).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepMeasure {
    /// Largest increment of the equivalent plastic strain at any point.
    pub plastic_strain: f64,
    /// Points whose contact status changed, as a fraction of those active
    /// before or after (the larger count); `None` when no point was active
    /// before the increment (a first touch is no rate: any `Δλ` gives 1).
    pub contact_set: Option<f64>,
    /// The local error estimate of the time step relative to the
    /// displacement scale (`dynamics::time_error`; 0: not measured).
    pub time_error: f64,
    /// Largest increment of a damage variable at any point (ply damage
    /// modes and cohesive interfaces; 0: none damages).
    pub damage: f64,
}

/// A measure above `REJECT` times its target rejects the increment.
pub(crate) const REJECT: f64 = 2.0;

/// The next increment aims at this fraction of the target.
pub const SAFETY: f64 = 0.8;

/// The order of the time error in `Δt`: the local error of a Newmark step
/// is `O(Δt³)` (`dynamics::time_error`).
pub(crate) const TIME_ERROR_ORDER: f64 = 3.0;

/// The smallest factor of a rejected increment.
const SHRINK_REJECTED: f64 = 0.25;

/// The control's verdict on a converged increment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Verdict {
    /// Keep the increment; the next one is `Δλ` times this factor.
    Accept(f64),
    /// Redo the increment with `Δλ` times this factor; `q` is the ratio
    /// of its measure to its target.
    Reject {
        /// Factor on `Δλ` for the retry.
        factor: f64,
        /// Largest ratio of measure to target.
        q: f64,
    },
}

impl StepControl {
    /// The largest ratio of a measure to its target, and the largest of
    /// the plastic strain's and the damage's (the ones that may reject).
    pub fn ratios(&self, m: &StepMeasure) -> (f64, f64) {
        let plastic = self.plastic_strain.map_or(0.0, |t| m.plastic_strain / t);
        let damage = self.damage.map_or(0.0, |t| m.damage / t);
        let contact = match (self.contact_set, m.contact_set) {
            (Some(t), Some(c)) => c / t,
            _ => 0.0,
        };
        let path = plastic.max(damage);
        (path.max(contact), path)
    }

    /// The verdict on an increment of `dlambda` with measure `m`: `growth`
    /// is the largest factor allowed (1 after a hard increment), `min` the
    /// smallest increment, `retried` true if this increment was already
    /// rejected once.
    pub(crate) fn verdict(&self, m: &StepMeasure, dlambda: f64, growth: f64, min: f64, retried: bool) -> Verdict {
        let (q, path) = self.ratios(m);
        let time = self.time_error.map_or(0.0, |t| m.time_error / t);
        // the factor on Δλ that meets each measure's target with the margin
        let linear = if q > 0.0 { SAFETY / q } else { f64::INFINITY };
        let cubic = if time > 0.0 { (SAFETY / time).powf(1.0 / TIME_ERROR_ORDER) } else { f64::INFINITY };
        if !retried {
            let rejecting = [(path, SAFETY / path), (time, cubic)];
            let worst = rejecting.iter().filter(|(r, _)| *r > REJECT).min_by(|a, b| a.1.total_cmp(&b.1));
            if let Some(&(ratio, factor)) = worst {
                let factor = factor.max(SHRINK_REJECTED);
                if dlambda * factor >= min {
                    return Verdict::Reject { factor, q: ratio };
                }
            }
        }
        Verdict::Accept(linear.min(cubic).clamp(0.5, growth.max(0.5)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(plastic_strain: f64, contact_set: Option<f64>) -> StepMeasure {
        StepMeasure { plastic_strain, contact_set, time_error: 0.0, damage: 0.0 }
    }

    #[test]
    fn grows_below_the_target_and_shrinks_above_it() {
        let c = StepControl { plastic_strain: Some(1e-3), contact_set: Some(0.2), time_error: None, damage: None };
        // nothing changed: the full growth
        assert_eq!(c.verdict(&m(0.0, None), 0.1, 1.5, 1e-5, false), Verdict::Accept(1.5));
        // a fifth of the target: 0.8 / 0.2 = 4, capped at the growth
        assert_eq!(c.verdict(&m(2e-4, Some(0.0)), 0.1, 1.5, 1e-5, false), Verdict::Accept(1.5));
        // after a hard increment: no growth, but no forced shrink either
        assert_eq!(c.verdict(&m(2e-4, None), 0.1, 1.0, 1e-5, false), Verdict::Accept(1.0));
        // the contact set at 2 × its target: 0.4, bounded to 0.5
        assert_eq!(c.verdict(&m(0.0, Some(0.4)), 0.1, 1.5, 1e-5, false), Verdict::Accept(0.5));
        // plastic strain at 1.25 × its target: accepted, 0.64
        let Verdict::Accept(f) = c.verdict(&m(1.25e-3, None), 0.1, 1.5, 1e-5, false) else { panic!() };
        assert!((f - 0.64).abs() < 1e-12, "{f}");
    }

    #[test]
    fn rejects_a_plastic_strain_far_above_its_target_once() {
        let c = StepControl { plastic_strain: Some(1e-3), contact_set: Some(0.2), time_error: None, damage: None };
        let Verdict::Reject { factor, q } = c.verdict(&m(2.5e-3, None), 0.1, 1.5, 1e-5, false) else { panic!() };
        assert!((factor - 0.32).abs() < 1e-12 && (q - 2.5).abs() < 1e-12, "{factor} {q}");
        // at most by a quarter
        let Verdict::Reject { factor, .. } = c.verdict(&m(1.0, None), 0.1, 1.5, 1e-5, false) else { panic!() };
        assert_eq!(factor, 0.25);
        // not twice, and not below the smallest increment
        assert_eq!(c.verdict(&m(4e-3, None), 0.1, 1.5, 1e-5, true), Verdict::Accept(0.5));
        assert_eq!(c.verdict(&m(4e-3, None), 0.1, 1.5, 0.05, false), Verdict::Accept(0.5));
        // the contact set never rejects
        assert_eq!(c.verdict(&m(0.0, Some(1.0)), 0.1, 1.5, 1e-5, false), Verdict::Accept(0.5));
    }

    fn t(time_error: f64) -> StepMeasure {
        StepMeasure { time_error, ..m(0.0, None) }
    }

    /// The time error grows like Δt³ (`dynamics::time_error`): the factor
    /// `(0.8/q)^(1/3)` brings a step at `q` times its target to 0.8 of
    /// it, `q · factor³ = 0.8`, when accepted (q ≤ 2) or redone (q > 2).
    #[test]
    fn the_time_error_sets_the_step_by_its_cube_root() {
        let c = StepControl { plastic_strain: None, contact_set: None, time_error: Some(1e-3), damage: None };
        for q in [0.2, 0.5, 1.0, 1.6, 2.0] {
            let Verdict::Accept(f) = c.verdict(&t(q * 1e-3), 0.1, 3.0, 1e-5, false) else { panic!("{q}") };
            assert!((q * f.powi(3) - 0.8).abs() < 1e-12, "q = {q}: {f}");
        }
        let Verdict::Reject { factor, q } = c.verdict(&t(3.2e-3), 0.1, 3.0, 1e-5, false) else { panic!() };
        assert!((q - 3.2).abs() < 1e-12 && (3.2 * factor.powi(3) - 0.8).abs() < 1e-12, "{factor}");
        // redone once only (then accepted with the same factor), and the
        // growth and shrink bounds still apply
        assert_eq!(c.verdict(&t(3.2e-3), 0.1, 3.0, 1e-5, true), Verdict::Accept(0.25f64.cbrt()));
        assert_eq!(c.verdict(&t(0.1), 0.1, 3.0, 1e-5, true), Verdict::Accept(0.5));
        assert_eq!(c.verdict(&t(1e-6), 0.1, 1.5, 1e-5, false), Verdict::Accept(1.5));
        // with the plastic strain: the smaller factor
        let both = StepControl { plastic_strain: Some(1e-3), ..c };
        let measure = StepMeasure { plastic_strain: 1e-3, ..t(0.1e-3) };
        assert_eq!(both.verdict(&measure, 0.1, 3.0, 1e-5, false), Verdict::Accept(0.8));
    }

    /// The damage increment steers the next step like the plastic strain
    /// (linear in Δλ) and, far above its target, rejects the increment.
    #[test]
    fn the_damage_increment_shrinks_and_rejects_like_the_plastic_strain() {
        let c = StepControl { damage: Some(0.1), ..Default::default() };
        let d = |damage: f64| StepMeasure { damage, ..m(0.0, None) };
        // half its target: 0.8 / 0.5 = 1.6, capped at the growth
        assert_eq!(c.verdict(&d(0.05), 0.1, 1.5, 1e-5, false), Verdict::Accept(1.5));
        // 1.6 × its target: 0.5, accepted
        let Verdict::Accept(f) = c.verdict(&d(0.16), 0.1, 1.5, 1e-5, false) else { panic!() };
        assert!((f - 0.5).abs() < 1e-12, "{f}");
        // 3 × its target: redone at 0.8 / 3
        let Verdict::Reject { factor, q } = c.verdict(&d(0.3), 0.1, 1.5, 1e-5, false) else { panic!() };
        assert!((factor - 0.8 / 3.0).abs() < 1e-12 && (q - 3.0).abs() < 1e-12, "{factor} {q}");
        // with the plastic strain: the worse of the two
        let both = StepControl { plastic_strain: Some(1e-3), ..c };
        let measure = StepMeasure { plastic_strain: 0.5e-3, ..d(0.2) };
        assert_eq!(both.verdict(&measure, 0.1, 1.5, 1e-5, false), Verdict::Accept(0.5));
        // uncontrolled, the damage changes nothing
        assert_eq!(StepControl::default().verdict(&d(0.9), 0.1, 1.5, 1e-5, false), Verdict::Accept(1.5));
    }

    #[test]
    fn an_uncontrolled_measure_is_ignored() {
        let c = StepControl { plastic_strain: None, contact_set: Some(0.2), time_error: None, damage: None };
        assert_eq!(c.verdict(&m(1.0, Some(0.04)), 0.1, 2.0, 1e-5, false), Verdict::Accept(2.0));
        let c = StepControl { plastic_strain: Some(1e-3), contact_set: None, time_error: None, damage: None };
        assert_eq!(c.ratios(&m(5e-4, Some(1.0))), (0.5, 0.5));
    }
}
