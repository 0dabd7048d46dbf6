//! Dissipation control of the path following
//! ([`super::ArcLengthSettings::dissipation`]). Where a crack grows, the displacements' change of an increment turns with the
//! crack front, and the cylinder's line `δu_R + δλ δu_F` misses it (complex
//! roots) or converges turned away from its predictor. An elastic structure
//! that damages and unloads on its secant stores `½ λ fᵀu`, so what the
//! loads did beyond it, its dissipation, grows over an increment by
//!
//! ```text
//! Δτ = ½ (λ₀ fᵀΔu − Δλ fᵀu₀)
//! ```
//!
//! (`λ₀`, `u₀` at its start; Gutiérrez, *Commun. Numer. Meth. Engng* 20
//! (2004) 19–29; Verhoosel, Remmers & Gutiérrez, *Int. J. Numer. Meth.
//! Engng* 77 (2009) 1290–1321), which never decreases along the path,
//! through a snap-back as elsewhere. Once the cylinder's predictor would
//! dissipate the given share of the elastic energy, each increment is held
//! to a dissipation `Δτ` instead: the constraint is linear, so the
//! predictor is `Δλ₁ = 2Δτ / (λ₀ fᵀδu_F − fᵀu₀)` — its sign is the path's,
//! negative past a peak — and each correction's `δλ` has one root.
//! `Δτ` follows the converged increments' corrections as `Δl` does (from
//! the dissipation of the last), at most `ArcLengthSettings::max_dissipation`
//! (a path whose points soften depends on its increments: fast convergence
//! alone would let them grow to a large share of a crack's energy). An increment along which the tangent does
//! not dissipate (`λ₀ fᵀδu_F = fᵀu₀` to round-off: an elastic state) takes
//! the cylinder. [`super::PathProblem::pseudo_time_step`] gives a rate-dependent
//! regularisation its time: the increment's arc length over the first's,
//! times the first `|Δλ|` (fixed through the increment's iterations).

use super::{Path, PathProblem};

impl<P: PathProblem> Path<'_, P> {
    /// `λ₀ fᵀδu_F − fᵀu₀` with `δu_F` in `df`: twice the dissipation per
    /// unit `Δλ` along the tangent — zero where the tangent is the secant
    /// (no point damages), positive where it is softer and the load rises,
    /// negative on a softening branch, where λ falls.
    pub(super) fn rate(&self) -> f64 {
        self.lambda * dot(&self.f, &self.df) - dot(&self.f, &self.total)
    }

    /// The rate is not round-off of its two terms (an elastic tangent's).
    pub(super) fn dissipates(&self, rate: f64) -> bool {
        let scale = (self.lambda * dot(&self.f, &self.df)).abs().max(dot(&self.f, &self.total).abs());
        rate.is_finite() && rate.abs() > 1e-8 * scale
    }

    /// The dissipation of the present increment, `½ (λ₀ fᵀΔu − Δλ fᵀu₀)`
    /// (exact for an elastic-damage structure whose unloading is secant).
    pub(super) fn dissipated(&self, dlambda: f64) -> f64 {
        0.5 * (self.lambda * dot(&self.f, &self.du) - dlambda * dot(&self.f, &self.total))
    }

    /// Holds the increments to their dissipation from now on if the
    /// cylinder's predictor `Δλ₁ = ±dlambda` would dissipate the switch's
    /// share of the elastic energy `½ λ₀ fᵀu₀` (`rate`: [`Self::rate`]).
    pub(super) fn switch_to_dissipation(&mut self, rate: f64, dlambda: f64) {
        if let (Some(share), None) = (self.switch, self.tau) {
            let along = 0.5 * (rate * dlambda).abs();
            if self.dissipates(rate) && along > share * 0.5 * (self.lambda * dot(&self.f, &self.total)).abs() {
                self.tau = Some(along.min(self.max_dissipation));
            }
        }
    }

    /// The correction's `δλ` that holds the increment to `Δτ`, with
    /// `δu_R` in `dr`, `δu_F` in `df` and `Δλ = dlambda` so far:
    /// `½ [λ₀ fᵀ(Δu + δu_R + δλ δu_F) − (Δλ + δλ) fᵀu₀] = Δτ`; `None` where
    /// the tangent does not dissipate.
    pub(super) fn dissipation_root(&self, dlambda: f64) -> Option<f64> {
        let tau = self.tau?;
        let (ff, fu0) = (dot(&self.f, &self.df), dot(&self.f, &self.total));
        let now = 0.5 * (self.lambda * (dot(&self.f, &self.du) + dot(&self.f, &self.dr)) - dlambda * fu0);
        let rate = 0.5 * (self.lambda * ff - fu0);
        self.dissipates(2.0 * rate).then(|| (tau - now) / rate)
    }
}

/// The Euclidean inner product (the dissipation's, whatever `PathProblem::dot` weighs).
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
