//! What an adaptive cycle is measured and refined by: the static
//! estimate, or in a modal analysis the estimates of the modes it follows.
//!
//! * **Static** (and any solution without modes): the Zienkiewicz–Zhu
//!   estimate of the stresses ([`crate::post::estimate`]): the relative
//!   error in the energy norm, and each element's `η_e` and section part.
//! * **Modal**: the modes followed are the lowest `adapt.modes` (all those
//!   computed by default); the cycle's estimate is the largest estimated
//!   relative frequency error `(f_h − f) / f` among them
//!   ([`crate::post::mode_error::ModeError::frequency`]), so the tolerance
//!   is a frequency error. The indicators refined by are those of the
//!   followed modes still above the tolerance, each normalised by its own
//!   total and summed: `η_e² = Σ_i η_{e,i}² / Σ_e' η_{e',i}²` (and the
//!   section parts alike) — every unconverged mode counts equally,
//!   whatever its frequency or the scale of its shape, so a cycle refines
//!   where each of them holds its error (the walls of a local mode, the
//!   axis of a bending mode) rather than where only the worst one does.
//!   The bulk of that sum is marked as the static estimate's is
//!   ([`super::mark`]).
//!
//! * **Buckling**: as modal, with the estimated relative errors of the
//!   critical load factors `(μ_h − μ) / μ_h`
//!   ([`crate::post::mode_error::ModeError::eigenvalue`]) in place of the
//!   frequencies': the tolerance is an error of the critical load.
//!
//! * **Transient**: the static estimate of its worst kept time — of the
//!   frames (`analysis.output_interval`) and the end, the state whose
//!   estimated error `η` is largest (`analysis::state_errors`), measured
//!   relative to its own energy and refined by its indicators. Without
//!   frames only the end is seen.

use crate::analysis::{FollowedModes, ModeQuantity, Solution};
use crate::post::mode_error::ModeError;
use crate::setup::AdaptSettings;

/// One cycle's measure.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Measure {
    /// The relative estimate compared with the tolerance.
    pub(crate) estimate: f64,
    /// The indicators to mark by: per element `η_e` (√ of the squared
    /// share), and the section stage's part of it (empty if not computed).
    pub(crate) element: Vec<f64>,
    /// The section stage's part of `element` (`ErrorEstimate::section`).
    pub(crate) section: Vec<f64>,
    /// The parts of `element` varying along x, z and the axis
    /// (`ErrorEstimate::direction`; empty if not computed).
    pub(crate) direction: Vec<[f64; 3]>,
    /// Modal and buckling: the followed modes and their estimated
    /// errors; `None` otherwise.
    pub(crate) modes: Option<FollowedModes>,
    /// Transient: the kept state measured, its worst (`frame_0004`, or
    /// `end`: the last state, the only one seen without frames); `None`
    /// otherwise.
    pub(crate) state: Option<String>,
}

impl Measure {
    /// The measure of `solution` under `settings` (module docs).
    pub(crate) fn of(solution: &Solution, settings: &AdaptSettings) -> Self {
        match (&solution.modal, &solution.buckling) {
            (Some(modal), _) => {
                Self::of_modes(&modal.errors, &modal.frequencies, ModeQuantity::Frequency, |e| e.frequency(), settings)
            }
            (None, Some(buckling)) => Self::of_modes(
                &buckling.errors,
                &buckling.factors,
                ModeQuantity::LoadFactor,
                |e| e.eigenvalue,
                settings,
            ),
            (None, None) => {
                let transient = solution.energy.is_some();
                let worst = Self::worst_kept(solution).or(solution.error_estimate.as_ref().map(|e| ("end".into(), e)));
                match worst {
                    Some((state, e)) => Self {
                        estimate: e.relative(),
                        element: e.element.clone(),
                        section: e.section.clone(),
                        direction: e.direction.clone(),
                        state: transient.then_some(state),
                        ..Default::default()
                    },
                    None => Self::default(),
                }
            }
        }
    }

    /// A transient run's worst kept time: of its frames and its end, the
    /// state whose estimated error `η` is largest (the largest relative
    /// error belongs to a state of little energy, before the load arrives);
    /// `None` for a run without frames.
    fn worst_kept(solution: &Solution) -> Option<(String, &crate::post::ErrorEstimate)> {
        if solution.frames.is_empty() {
            return None;
        }
        let kept = solution.error_history.rows.iter().map(|r| (r.state.name(&solution.steps), &r.estimate));
        let kept = kept.chain(solution.error_estimate.as_ref().map(|e| ("end".to_string(), e)));
        kept.max_by(|a, b| a.1.error.total_cmp(&b.1.error))
    }

    /// The measure of the lowest `settings.modes` of an eigen-analysis's
    /// modes (all by default; `values` their frequencies or load factors,
    /// `errors` their estimates) by their eigenvalue's estimated relative
    /// `error` (module docs).
    fn of_modes(
        errors: &[ModeError],
        values: &[f64],
        quantity: ModeQuantity,
        error: impl Fn(&ModeError) -> f64,
        settings: &AdaptSettings,
    ) -> Self {
        let n = settings.modes.unwrap_or(errors.len()).min(errors.len());
        let relative: Vec<f64> = errors[..n].iter().map(&error).collect();
        let estimate = relative.iter().copied().fold(0.0, f64::max);
        let above = errors[..n].iter().filter(|e| error(e) >= settings.tolerance).map(|e| &e.estimate);
        let Combined { element, section, direction } = combined(above);
        let modes = FollowedModes { quantity, values: values[..n].to_vec(), errors: relative };
        Self { estimate, element, section, direction, modes: Some(modes), state: None }
    }

    /// The words of the stop at the tolerance.
    pub(crate) fn below(&self, tolerance: f64) -> String {
        match &self.modes {
            None => {
                let of = self.state.as_ref().map_or_else(String::new, |s| format!(" of the worst kept time ({s})"));
                format!(
                    "the estimate {:.2} %{of} is below the tolerance {:.2} %",
                    100.0 * self.estimate,
                    100.0 * tolerance
                )
            }
            Some(m) => format!(
                "the largest estimated {} error of the {} modes followed, {:.2} %, is below the tolerance {:.2} %",
                m.quantity.name(),
                m.errors.len(),
                100.0 * self.estimate,
                100.0 * tolerance
            ),
        }
    }
}

/// The followed modes' indicators, each normalised by its own total
/// ([`combined`]).
#[derive(Debug, Default)]
struct Combined {
    element: Vec<f64>,
    section: Vec<f64>,
    direction: Vec<[f64; 3]>,
}

/// `Σ_i η_{e,i}² / Σ_e η_{e,i}²` over the estimates (and their section and
/// direction parts alike), as `√` per element; the section (direction)
/// parts are dropped unless every estimate has them.
fn combined<'a>(estimates: impl Iterator<Item = &'a crate::post::estimate::ErrorEstimate>) -> Combined {
    let mut out = Combined::default();
    let (mut with_sections, mut with_directions) = (true, true);
    for est in estimates {
        let total = est.error * est.error;
        if !(total > 0.0) {
            continue;
        }
        let n = est.element.len();
        out.element.resize(n, 0.0);
        for (w, eta) in out.element.iter_mut().zip(&est.element) {
            *w += eta * eta / total;
        }
        with_sections &= est.section.len() == n;
        out.section.resize(n, 0.0);
        for (w, s) in out.section.iter_mut().zip(&est.section) {
            *w += s * s / total;
        }
        with_directions &= est.direction.len() == n;
        out.direction.resize(n, [0.0; 3]);
        for (w, s) in out.direction.iter_mut().zip(&est.direction) {
            (0..3).for_each(|d| w[d] += s[d] * s[d] / total);
        }
    }
    if !with_sections {
        out.section.clear();
    }
    if !with_directions {
        out.direction.clear();
    }
    out.element.iter_mut().chain(out.section.iter_mut()).for_each(|w| *w = w.sqrt());
    out.direction.iter_mut().flatten().for_each(|w| *w = w.sqrt());
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::post::estimate::ErrorEstimate;

    /// Two modes whose errors sit in different elements and differ 100-fold
    /// in scale weigh equally: each contributes its own shares.
    #[test]
    fn each_mode_counts_by_its_own_shares() {
        let a = ErrorEstimate {
            element: vec![3.0, 4.0, 0.0],
            error: 5.0,
            energy: 1.0,
            section: vec![3.0, 0.0, 0.0],
            direction: vec![[0.0, 4.0, 0.0]; 3],
        };
        let b = ErrorEstimate {
            element: vec![0.0, 0.0, 500.0],
            error: 500.0,
            energy: 1.0,
            section: vec![0.0; 3],
            direction: vec![[0.0, 0.0, 300.0]; 3],
        };
        let Combined { element, section, direction } = combined([&a, &b].into_iter());
        let expect = [0.36f64.sqrt(), 0.64f64.sqrt(), 1.0];
        for (e, x) in element.iter().zip(expect) {
            assert!((e - x).abs() < 1e-15, "{element:?}");
        }
        assert!((section[0] - 0.6).abs() < 1e-15 && section[1] == 0.0 && section[2] == 0.0, "{section:?}");
        // 4²/5² and 300²/500² in their own directions
        assert!(direction[0][0] == 0.0 && (direction[0][1] - 0.8).abs() < 1e-15, "{direction:?}");
        assert!((direction[0][2] - 0.6).abs() < 1e-15, "{direction:?}");
        // without section (direction) parts in one of them, none are given
        let c = ErrorEstimate { section: Vec::new(), ..b.clone() };
        assert!(combined([&a, &c].into_iter()).section.is_empty());
        let d = ErrorEstimate { direction: Vec::new(), ..b };
        let without = combined([&a, &d].into_iter());
        assert!(without.direction.is_empty() && without.section.len() == 3);
    }
}
