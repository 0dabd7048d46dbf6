//! The energy the ply damage law dissipates over one update
//! ([`super::PlyDamage::update`]): `∫ (Y_I + Y_s ∂d_s/∂d_I) dd_I` along the
//! update's strain path, taken straight from the committed strain to the
//! trial one. The rule sums it by trapezoids over steps of that path in
//! each of which no mode's damage grows by more than [`GROWTH_PER_STEP`];
//! an update that grows less is one trapezoid of its two ends, as it
//! always was.
//!
//! One trapezoid over a large growth books far more than the path
//! dissipates: a point of a linear softening law that goes from onset to
//! `d → 1` within one update (its band's strain jumping past `δf`) has
//! `Y = ½ E ε²` at `ε0` and at `εf`, so the trapezoid books `¼ E εf²`
//! where the path dissipates `½ σ0 εf` (`G/L`): `εf/(2 ε0)` times too
//! much, the excess a static damage run with coarse increments reported.
//! Within a step the strain, the damage the law reaches and its viscous
//! regularisation (`d_v = (1 − s) d_v,n + s d`, `s` the share of the
//! step's time so far) follow the path; the last step ends on the update's
//! own state, so the sums close on it.

use super::{DamageState, PlyDamage};
use crate::voigt::{Voigt, mat_vec};

/// Largest growth of a mode's damage over one trapezoid of an update's
/// dissipation.
const GROWTH_PER_STEP: f64 = 0.02;

/// Most trapezoids of one update (a growth from 0 to `max_damage` takes
/// 50).
const MOST_STEPS: usize = 64;

impl PlyDamage {
    /// The energy release rates `[Y_FT, Y_FC, Y_MT, Y_MC, Y_s]` (J/m³) of
    /// the stress `stress` at the damage `d` (`ds` its shear damage), the
    /// normal stresses' modes `normal` (module docs of [`super`],
    /// "Dissipation").
    pub(super) fn release_rates(&self, d: &[f64; 4], ds: f64, normal: [usize; 3], stress: &Voigt) -> [f64; 5] {
        let mut release = [0.0; 5];
        for k in 0..3 {
            let (mode, young) = (normal[k], self.elastic.young[k]);
            release[mode] += 0.5 * stress[k] * stress[k] / ((1.0 - d[mode]).powi(2) * young);
        }
        let [g12, g13, g23] = self.elastic.shear;
        release[4] = 0.5 * (stress[3] * stress[3] / g12 + stress[4] * stress[4] / g13 + stress[5] * stress[5] / g23)
            / (1.0 - ds).powi(2);
        release
    }

    /// Adds to `state.dissipated` what the update from `old` to `state`
    /// (at the material strain `strain`, crack bands `band`, viscous step
    /// `step`, its growing modes `[fibre, matrix]` on the branches
    /// `tension`) dissipates (module docs).
    pub(super) fn book_dissipation(
        &self,
        (strain, band, step): (&Voigt, [f64; 2], f64),
        ([fibre, matrix], tension): ([usize; 2], [bool; 2]),
        old: &DamageState,
        state: &mut DamageState,
    ) {
        let grown = (0..4).map(|m| state.viscous[m] - old.viscous[m]).fold(0.0, f64::max);
        if !(grown > 0.0) {
            return;
        }
        let steps = ((grown / GROWTH_PER_STEP).ceil() as usize).clamp(1, MOST_STEPS);
        let mut path = *old;
        let (mut d_before, mut y_before) = (old.viscous, old.release);
        for k in 1..=steps {
            let (d, y) = if k == steps {
                (state.viscous, state.release)
            } else {
                let t = k as f64 / steps as f64;
                let eps: Voigt = std::array::from_fn(|i| old.strain[i] + t * (strain[i] - old.strain[i]));
                let effective = mat_vec(&self.stiffness, &eps);
                let [fibre_ratio, matrix_ratio] = self.strengths.hashin_ratios(&effective, tension, self.fibre_shear);
                for (mode, ratio, length) in [(fibre, fibre_ratio, band[0]), (matrix, matrix_ratio, band[1])] {
                    self.soften(mode, 1.0 / ratio, length, &eps, &effective, &mut path);
                }
                let share = self.share(t * step);
                // between the update's ends (which round-off may order
                // either way where a mode sits at its cap)
                let d: [f64; 4] = std::array::from_fn(|i| {
                    let (a, b) = (old.viscous[i], state.viscous[i]);
                    ((1.0 - share) * a + share * path.damage[i]).clamp(a.min(b), a.max(b))
                });
                let ds = 1.0 - d.iter().map(|x| 1.0 - x).product::<f64>();
                let (normal, _, stress) = self.closed_or_open(&d, ds, &eps, &effective);
                (d, self.release_rates(&d, ds, normal, &stress))
            };
            for mode in 0..4 {
                let growth = d[mode] - d_before[mode];
                if growth > 0.0 {
                    let others = |v: &[f64; 4]| (0..4).filter(|&j| j != mode).map(|j| 1.0 - v[j]).product::<f64>();
                    let coupling = 0.5 * (others(&d_before) + others(&d));
                    let rate = 0.5 * (y_before[mode] + y[mode]) + 0.5 * (y_before[4] + y[4]) * coupling;
                    state.dissipated[mode] += rate * growth;
                }
            }
            (d_before, y_before) = (d, y);
        }
    }
}
