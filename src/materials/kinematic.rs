//! Von Mises plasticity with nonlinear kinematic hardening (Armstrong–
//! Frederick, several back-stresses as in Chaboche) combined with any
//! isotropic law, integrated by a return map along the direction of the
//! relative trial stress, with its consistent tangent.
//!
//! # Equations
//!
//! Yield function `f = sqrt(3/2) |s − X| − σ_y(ε̄ᵖ)` with `X = Σ_i X_i`
//! (deviatoric back-stresses). Associative flow `ε̇ᵖ = ṗ n`,
//! `n = 3/2 (s − X)/σ_y`, and for each back-stress
//! `Ẋ_i = 2/3 C_i ε̇ᵖ − γ_i X_i ṗ` (Armstrong & Frederick 1966; Chaboche,
//! Int. J. Plasticity 5, 1989). `C_i` (Pa) is the initial kinematic modulus,
//! `γ_i` (−) its recall rate; `X_i` saturates at `C_i/γ_i` in uniaxial flow.
//!
//! # Integration
//!
//! Backward Euler for the flow, and the *exact* solution of the back-stress
//! equation for a direction held constant over the increment (exponential
//! integration): with `θ_i = e^{−γ_i Δp}`, `φ_i = (1 − θ_i)/γ_i` (`Δp` for
//! `γ_i = 0`), `X_i = θ_i X_i,n + 2/3 C_i φ_i n`. Then `s − X` is collinear
//! with `ξ*(Δp) = s_trial − Σ θ_i X_i,n`, and `Δp` is the root of the scalar
//! equation
//!
//! `F(Δp) = sqrt(3/2) |ξ*(Δp)| − σ_y(ε̄ᵖ_n + Δp) − 3G Δp − Σ C_i φ_i = 0`,
//!
//! solved by Newton's method safeguarded by bisection. `F` is strictly
//! decreasing, `−F' = H + 3G + Σ C_i θ_i − sqrt(3/2) n̂:a ≥ H + 3G` with
//! `a = Σ γ_i θ_i X_i,n` (the back-stresses stay inside their saturation
//! sphere), so the root is unique. In uniaxial flow the back-stress is the
//! closed form of the check branch by branch, whatever the step.
//!
//! # Tangent
//!
//! With `n̂ = ξ*/|ξ*|`, `σ = σ_trial − 2G sqrt(3/2) Δp n̂`, and linearising
//! `F = 0` and `n̂`:
//! `C^cep = C − 2G sqrt(3/2) [ n̂ ⊗ b + Δp/|ξ*| (2G P I_dev + (P a) ⊗ b) ]`,
//! `b = sqrt(3/2) 2G n̂ / D`, `D = −F'`, `P = I − n̂ ⊗ n̂`. The term
//! `(P a) ⊗ b` is not symmetric: it vanishes when the stored back-stresses are
//! parallel to the flow direction (proportional loading, e.g. uniaxial or
//! the fibres of a bent beam), and otherwise makes the exact tangent
//! unsymmetric. [`super::Material::update`] returns the exact tangent
//! (finite-difference checked); the element kernel uses its symmetric part,
//! which keeps Newton's convergence quadratic under proportional loading.

use super::{Hardening, PointState, Predictor, Response};
use crate::voigt::{self, Matrix6, Voigt};

/// Most back-stresses a material may have (Chaboche models use 2–3).
pub(crate) const MAX_BACKSTRESSES: usize = 3;

/// One Armstrong–Frederick back-stress.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BackStress {
    /// Initial kinematic hardening modulus C (Pa), > 0.
    pub modulus: f64,
    /// Recall rate γ (−), ≥ 0 (0: linear Prager–Ziegler hardening).
    pub recall: f64,
}

impl BackStress {
    /// `(θ, φ) = (e^{−γΔp}, (1 − e^{−γΔp})/γ)`, `φ = Δp` for `γ = 0`.
    fn decay(&self, dp: f64) -> (f64, f64) {
        if self.recall == 0.0 {
            (1.0, dp)
        } else {
            let x = -self.recall * dp;
            (x.exp(), -x.exp_m1() / self.recall)
        }
    }
}

/// Double contraction `a : b` of two stress-like Voigt tensors (shear entries
/// count twice).
fn dot(a: &Voigt, b: &Voigt) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5])
}

/// The relative trial stress `ξ*(Δp) = s_trial − Σ θ_i X_i,n` and
/// `a = dξ*/dΔp = Σ γ_i θ_i X_i,n`.
fn relative_trial(s_trial: &Voigt, kinematic: &[BackStress], old: &PointState, dp: f64) -> (Voigt, Voigt) {
    let mut xi = *s_trial;
    let mut a = [0.0; 6];
    for (k, bs) in kinematic.iter().enumerate() {
        let (theta, _) = bs.decay(dp);
        for c in 0..6 {
            xi[c] -= theta * old.back_stress[k][c];
            a[c] += bs.recall * theta * old.back_stress[k][c];
        }
    }
    (xi, a)
}

/// `F(Δp)` of the module docs and `D = −F'(Δp)`.
fn residual(
    s_trial: &Voigt,
    hardening: &Hardening,
    kinematic: &[BackStress],
    old: &PointState,
    three_g: f64,
    dp: f64,
) -> (f64, f64) {
    let (xi, a) = relative_trial(s_trial, kinematic, old, dp);
    let norm = voigt::norm_stress(&xi);
    let (sy, h) = hardening.eval(old.peeq + dp);
    let mut f = 1.5f64.sqrt() * norm - sy - three_g * dp;
    let mut d = h + three_g;
    for bs in kinematic {
        let (theta, phi) = bs.decay(dp);
        f -= bs.modulus * phi;
        d += bs.modulus * theta;
    }
    if norm > 0.0 {
        d -= 1.5f64.sqrt() * dot(&xi, &a) / norm;
    }
    (f, d)
}

/// The plastic update with kinematic (and any isotropic) hardening; `trial`
/// is the elastic trial stress. Returns `None` if the trial state is elastic
/// (then the caller keeps the elastic response).
pub(super) fn update(
    g: f64,
    elastic: &Matrix6,
    hardening: &Hardening,
    kinematic: &[BackStress],
    trial: &Voigt,
    old: &PointState,
    predictor: Predictor,
) -> Option<Response> {
    let three_g = 3.0 * g;
    let s_trial = voigt::deviator(trial);
    let (f0, d0) = residual(&s_trial, hardening, kinematic, old, three_g, 0.0);
    let sy0 = hardening.eval(old.peeq).0;
    // same round-off guards as the isotropic return (see `Material::update`)
    if f0 <= 1e-12 * sy0 {
        if predictor == Predictor::Loading && f0 >= -1e-10 * sy0 {
            // on the surface: the loading branch of the tangent (Δp → 0)
            let tangent = tangent(g, elastic, &s_trial, kinematic, old, 0.0, d0)?;
            return Some(Response { stress: *trial, tangent, state: *old, plastic: false, elastic_tangent: false });
        }
        return None;
    }
    // Safeguarded Newton on the strictly decreasing F: F(lo) > 0 > F(hi).
    // F(Δp) ≤ F(0) − 3G Δp, so Δp = F(0)/(3G) brackets the root.
    let (mut lo, mut hi) = (0.0, f0 / three_g);
    let mut dp = f0 / d0;
    for _ in 0..200 {
        if !(dp > lo && dp < hi) {
            dp = 0.5 * (lo + hi);
        }
        let (f, d) = residual(&s_trial, hardening, kinematic, old, three_g, dp);
        if f > 0.0 {
            lo = dp;
        } else {
            hi = dp;
        }
        let step = f / d;
        dp += step;
        if step.abs() <= 1e-15 * dp.abs() || hi - lo <= 1e-16 * hi {
            break;
        }
    }
    let d = residual(&s_trial, hardening, kinematic, old, three_g, dp).1;

    let (xi, _) = relative_trial(&s_trial, kinematic, old, dp);
    let norm = voigt::norm_stress(&xi);
    let n_hat: Voigt = xi.map(|v| v / norm);
    let r = 1.5f64.sqrt();
    let mut stress = *trial;
    let mut state = *old;
    let flow = voigt::stress_like_to_strain_like(&n_hat);
    for c in 0..6 {
        stress[c] -= 2.0 * g * r * dp * n_hat[c];
        state.plastic_strain[c] += r * dp * flow[c];
    }
    state.peeq += dp;
    for (k, bs) in kinematic.iter().enumerate() {
        let (theta, phi) = bs.decay(dp);
        for c in 0..6 {
            state.back_stress[k][c] = theta * old.back_stress[k][c] + 2.0 / 3.0 * bs.modulus * phi * r * n_hat[c];
        }
    }
    let tangent = tangent(g, elastic, &s_trial, kinematic, old, dp, d)?;
    Some(Response { stress, tangent, state, plastic: true, elastic_tangent: false })
}

/// `C^cep = C − 2G r [n̂ ⊗ b + Δp/|ξ*| (2G P I_dev + (P a) ⊗ b)]`,
/// `r = sqrt(3/2)`, at the solution `Δp` with `D = −F'(Δp)`.
fn tangent(
    g: f64,
    elastic: &Matrix6,
    s_trial: &Voigt,
    kinematic: &[BackStress],
    old: &PointState,
    dp: f64,
    d: f64,
) -> Option<Matrix6> {
    let (xi, a) = relative_trial(s_trial, kinematic, old, dp);
    let norm = voigt::norm_stress(&xi);
    if !(norm > 0.0) {
        return None;
    }
    let n_hat: Voigt = xi.map(|v| v / norm);
    let r = 1.5f64.sqrt();
    let b: Voigt = n_hat.map(|v| r * 2.0 * g * v / d);
    let na = dot(&n_hat, &a);
    let pa: Voigt = std::array::from_fn(|c| a[c] - n_hat[c] * na);
    let idev = voigt::deviatoric_projector();
    let ratio = dp / norm;
    let mut tangent = *elastic;
    for j in 0..6 {
        let col: Voigt = std::array::from_fn(|i| idev[i][j]);
        let nc = dot(&n_hat, &col);
        for i in 0..6 {
            let p_idev = col[i] - n_hat[i] * nc;
            tangent[i][j] -= 2.0 * g * r * (n_hat[i] * b[j] + ratio * (2.0 * g * p_idev + pa[i] * b[j]));
        }
    }
    Some(tangent)
}

#[cfg(test)]
#[path = "kinematic_tests.rs"]
mod tests;
