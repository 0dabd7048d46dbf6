//! The local error estimate of a Newmark time step, for adaptive time steps
//! (`solver.step_control.time_error`, `solver::step_control`).
//!
//! Zienkiewicz & Xie (1991, *Earthquake Eng. Struct. Dyn.* 20, 871–887):
//! Newmark's displacement `u_(n+1) = u_n + Δt v_n + Δt² ((½ − β) a_n +
//! β a_(n+1))` against the Taylor series of the exact motion from the same
//! state differs by `(β − 1/6) Δt³ ȧ + O(Δt⁴)`; with `ȧ Δt ≈ a_(n+1) − a_n`
//! the step's local error is estimated per DOF as
//!
//! ```text
//! e = (β − 1/6) Δt² (a_(n+1) − a_n)        (1/12 Δt² Δa for β = ¼)
//! ```
//!
//! `a_(n+1)` from Newmark's relation at the converged `u_(n+1)`
//! (`dynamics::inertia`), on the free DOFs (those with an equation and not
//! prescribed: a prescribed history's motion is given, not integrated)
//! that carry mass: a contact node whose mass `dynamics::redistribution`
//! moved away is held by the contact spring, not by inertia, and Newmark's
//! acceleration there alternates from step to step whatever Δt (measured on
//! a hammer striking a rod: with those nodes the step fell to its smallest
//! at the touch and stayed there).
//!
//! **The measure** is the largest nodal `|e|` over the displacement scale
//! `U`, the largest `|u|` at a free DOF of any state so far (the step's end
//! included): `η = max |e| / U`. It is dimensionless, so one `time_error`
//! fits any model's units, and `U` does not vanish when the motion passes
//! through zero (a vibration's `u_(n+1)` does, twice a period), so `η`
//! stays `O(Δt³)` through the whole cycle and the control's exponent 1/3
//! applies (`solver::step_control`). The alternative scale, the step's
//! displacement increment, makes `η = O(Δt²)` where the motion is smooth
//! and `O(Δt³)` where it turns, so no one exponent would fit. A rigid
//! translation raises `U` (a flying body's error is then measured against
//! how far it flew), and a structure starting at rest has `U` of its first
//! moving step only: there `η` is about `(β − 1/6)/β` (a third for β = ¼)
//! whatever the step, so the first step of a motion is cut back to the
//! smallest factors the control allows, once, and the next ones regrow.
//!
//! With `γ > ½` the method is first order in the velocity; the estimate
//! keeps to the displacement's β term (the control then bounds that term
//! only). The impactors' own Newmark unknowns (`analysis::structure::force`)
//! are not measured.

/// The displacement scale of the estimate: the largest `|u|` at a free DOF
/// of the committed states (module docs).
#[derive(Debug, Default)]
pub(crate) struct TimeError {
    scale: f64,
    /// Per equation: whether it carries mass (`Inertia::massive`).
    pub(crate) massive: Vec<bool>,
}

/// The committed state of a Newmark step, per DOF, and its parameters:
/// what the estimate reads of `dynamics::Inertia`.
pub(crate) struct Committed<'a> {
    /// Velocity and acceleration at `t_n`.
    pub v: &'a [f64],
    pub a: &'a [f64],
    /// Newmark's β.
    pub beta: f64,
}

impl TimeError {
    /// No displacement yet; `massive` per equation (`Inertia::massive`).
    pub(crate) fn new(massive: Vec<bool>) -> Self {
        Self { scale: 0.0, massive }
    }

    /// The estimate `η` of the step of length `dt` from the committed
    /// state (`u_committed`, `committed`) to `u`, over the DOFs `free`
    /// (module docs); 0 for a step of no length or no motion.
    pub(crate) fn measure(
        &self,
        (u, u_committed): (&[f64], &[f64]),
        committed: &Committed<'_>,
        dt: f64,
        free: impl Fn(usize) -> bool,
    ) -> f64 {
        if dt <= 0.0 {
            return 0.0;
        }
        let beta = committed.beta;
        let c0 = 1.0 / (beta * dt * dt);
        let c2 = 1.0 / (2.0 * beta) - 1.0;
        let coefficient = local_error_coefficient(beta) * dt * dt;
        let (mut error, mut scale) = (0.0f64, self.scale);
        for d in (0..u.len()).filter(|&d| free(d)) {
            let a = c0 * (u[d] - u_committed[d] - dt * committed.v[d]) - c2 * committed.a[d];
            error = error.max((coefficient * (a - committed.a[d])).abs());
            scale = scale.max(u[d].abs());
        }
        if error == 0.0 { 0.0 } else { error / scale.max(f64::MIN_POSITIVE) }
    }

    /// Takes the committed displacements `u` into the scale.
    pub(crate) fn commit(&mut self, u: &[f64], free: impl Fn(usize) -> bool) {
        for (d, v) in u.iter().enumerate() {
            if free(d) {
                self.scale = self.scale.max(v.abs());
            }
        }
    }
}

/// `β − 1/6`: the leading coefficient of the local displacement error of
/// Newmark's step, in units of `Δt² (a_(n+1) − a_n)`.
pub(crate) fn local_error_coefficient(beta: f64) -> f64 {
    beta - 1.0 / 6.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One average-acceleration step of an undamped oscillator `ü = −ω² u`
    /// from the exact state of `u = sin t` (ω = 1): the estimate against
    /// the step's true error (Newmark's `u_(n+1)` − `sin(t + Δt)`). Both
    /// are `Δt³/12 cos t + O(Δt⁴)` (module docs), so their ratio tends to
    /// 1 as Δt → 0, the next term `O(Δt tan t)` of it: within 1.5 Δt of 1
    /// where `|cos t|` ≥ ½ (where `ȧ` vanishes the ratio is one of
    /// higher-order terms: 2.4 at Δt = 0.2, t = 1.3).
    #[test]
    fn the_estimate_matches_the_true_local_error_of_a_step() {
        let beta = 0.25;
        for dt in [0.2, 0.1, 0.05] {
            for t in [0.1, 0.7, 2.5, 3.5, 6.0] {
                let (u, v, a) = (f64::sin(t), f64::cos(t), -f64::sin(t));
                // Newmark with the oscillator: (1 + β Δt²) u1 = u + Δt v + Δt² (½ − β) a
                let u1 = (u + dt * v + dt * dt * (0.5 - beta) * a) / (1.0 + beta * dt * dt);
                let truth = u1 - f64::sin(t + dt);
                let committed = Committed { v: &[v], a: &[a], beta };
                let scaled =
                    TimeError { scale: 1.0, ..Default::default() }.measure((&[u1], &[u]), &committed, dt, |_| true);
                // the scale is 1 (|sin| ≤ 1 reached): η is |e| itself
                let ratio = scaled / truth.abs();
                assert!((ratio - 1.0).abs() < 1.5 * dt, "Δt = {dt}, t = {t}: {scaled} against {truth}");
            }
        }
    }

    #[test]
    fn the_scale_is_the_largest_free_displacement_so_far() {
        let mut e = TimeError::default();
        e.commit(&[0.5, -2.0, 9.0], |d| d < 2);
        assert_eq!(e.scale, 2.0);
        let committed = Committed { v: &[0.0; 3], a: &[0.0; 3], beta: 0.25 };
        // at rest: no error; a step of no length: none
        assert_eq!(e.measure((&[0.5, -2.0, 9.0], &[0.5, -2.0, 9.0]), &committed, 0.1, |d| d < 2), 0.0);
        assert_eq!(e.measure((&[1.0, -2.0, 9.0], &[0.5, -2.0, 9.0]), &committed, 0.0, |d| d < 2), 0.0);
        // Δu = 0.5 from rest: a = Δu/(β Δt²), e = a Δt²/12 = Δu/3, over U = 2
        let eta = e.measure((&[1.0, -2.0, 9.0], &[0.5, -2.0, 9.0]), &committed, 0.1, |d| d < 2);
        assert!((eta - 0.5 / 3.0 / 2.0).abs() < 1e-12, "{eta}");
    }
}
