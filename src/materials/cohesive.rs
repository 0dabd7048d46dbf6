//! The bilinear cohesive law of an interface between two plies, with
//! Benzeggagh–Kenane mixed-mode propagation (Camanho & Dávila 2002,
//! NASA/TM-2002-211737; Benzeggagh & Kenane 1996, *Compos. Sci. Technol.*
//! 56:439).
//!
//! A point of the interface is a pure function, as every material point
//! ([`super`]): `(separation δ, committed state) → (traction t, tangent
//! ∂t/∂δ, new state)`; the caller commits the state only after an increment
//! has converged.
//!
//! The separation is written in the interface's frame, `δ = (δ1, δ2, δ3)`:
//! two sliding components and the opening `δ3` along the normal from the
//! lower to the upper face (m). With one penalty stiffness `K` (Pa/m) for
//! every mode, `⟨x⟩ = max(x, 0)`:
//!
//! * mixed-mode separation `δ_m = √(⟨δ3⟩² + δ_s²)`, `δ_s = √(δ1² + δ2²)`,
//!   mode mixity `β = δ_s/δ3` (opening) and `G_II/G_T = β²/(1 + β²)`;
//! * onset on the quadratic criterion `(⟨t3⟩/N)² + (t_s/S)² = 1`:
//!   `δ_m⁰ = δ3⁰ δs⁰ √((1 + β²)/((δs⁰)² + (β δ3⁰)²))`, `δ3⁰ = N/K`,
//!   `δs⁰ = S/K`; in closure (`δ3 ≤ 0`) `δ_m⁰ = δs⁰`;
//! * final separation from the Benzeggagh–Kenane toughness
//!   `G_c = G_Ic + (G_IIc − G_Ic) (G_II/G_T)^η`: `δ_m^f = 2 G_c/(K δ_m⁰)`;
//!   in closure `δ_m^f = 2 G_IIc/S`;
//! * damage `d = δ_m^f (δ_m − δ_m⁰)/(δ_m (δ_m^f − δ_m⁰))`, never below the
//!   committed one (irreversible), at most 1;
//! * traction `t_i = (1 − d) K δ_i`, except a closing normal separation
//!   (`δ3 < −10⁻⁹ N/K`, `Cohesive::is_closed`: round-off of a zero opening
//!   stays open), which carries the full penalty `t3 = K δ3` at any damage:
//!   the faces of a delamination do not pass through each other.
//!
//! The tangent is `(1 − d) K I − K (∂d/∂δ_m) δ̂ δ̂ᵀ/δ_m` while the damage
//! grows (`δ̂ = (δ1, δ2, ⟨δ3⟩)`), the secant otherwise, with the mixity held
//! as Camanho & Dávila do: it is the exact derivative in a pure mode and
//! symmetric in every case.
//!
//! **Dissipation.** Along the bilinear curve of one mixity the energy
//! dissipated per unit area up to damage `d` is
//! `D(d) = ½ K (δ_m⁰)² δ_m^f d / (δ_m^f − d (δ_m^f − δ_m⁰))` (the work done
//! less the elastic energy left, `½ (1 − d) K κ²`): `D(1) = ½ K δ_m⁰ δ_m^f =
//! G_c`. Each update adds `D(d_{n+1}) − D(d_n)` at the present mixity, which
//! is exact at a fixed mixity and never negative.

use thiserror::Error;

/// The constants of a bilinear cohesive law (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cohesive {
    /// Penalty stiffness `K` of the intact interface (Pa/m).
    pub penalty: f64,
    /// Normal (mode I) strength `N` (Pa).
    pub normal_strength: f64,
    /// Shear (mode II) strength `S` (Pa).
    pub(crate) shear_strength: f64,
    /// Mode I fracture toughness `G_Ic` (J/m²).
    pub(crate) g_ic: f64,
    /// Mode II fracture toughness `G_IIc` (J/m²).
    pub(crate) g_iic: f64,
    /// Benzeggagh–Kenane exponent `η` (dimensionless).
    pub bk_exponent: f64,
    /// Duvaut–Lions viscosity in load-factor units (0: none): the damage
    /// that carries the traction relaxes towards the law's,
    /// `d_v,n+1 = (η d_v,n + Δλ d_n+1)/(η + Δλ)` (applied by
    /// the interface assembly, `interfaces::Interfaces`).
    pub viscosity: f64,
}

/// A cohesive law that cannot be used, by the key of its constant.
#[derive(Debug, Error, PartialEq)]
pub enum CohesiveError {
    /// A constant that must be positive and finite is not.
    #[error("cohesive `{key}` = {value}: must be a positive finite number")]
    NotPositive {
        /// The constant's key.
        key: &'static str,
        /// Its value.
        value: f64,
    },
    /// The elastic energy at onset reaches the toughness: the softening
    /// branch would have a negative length (a snap-back inside the point).
    #[error(
        "cohesive strengths too high for the penalty and toughness: `{strength}`²/(2 `penalty`) = {onset_energy:.4e} J/m² must be below `{toughness}` = {value:.4e} J/m² (lower the strength or raise the penalty)"
    )]
    OnsetAboveToughness {
        /// The strength's key.
        strength: &'static str,
        /// The toughness's key.
        toughness: &'static str,
        /// `strength² / (2 penalty)` (J/m²).
        onset_energy: f64,
        /// The smaller toughness (J/m²).
        value: f64,
    },
}

/// The history of one interface point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CohesiveState {
    /// Damage `d ∈ [0, 1]`; 1 is a delaminated point.
    pub damage: f64,
    /// Energy dissipated per unit area so far (J/m²).
    pub dissipated: f64,
}

/// The answer of [`Cohesive::update`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CohesiveResponse {
    /// Traction `(t1, t2, t3)` on the upper face's separation (Pa).
    pub traction: [f64; 3],
    /// `∂t/∂δ` (Pa/m), symmetric.
    pub tangent: [[f64; 3]; 3],
    /// The trial state.
    pub state: CohesiveState,
}

/// Onset and final mixed-mode separations of one mixity (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Envelope {
    /// `δ_m⁰`.
    pub onset: f64,
    /// `δ_m^f`.
    pub last: f64,
}

impl Cohesive {
    /// A law from its constants, refused by the key of the first one that
    /// cannot be used.
    pub fn new(
        penalty: f64,
        normal_strength: f64,
        shear_strength: f64,
        g_ic: f64,
        g_iic: f64,
        bk_exponent: f64,
    ) -> Result<Self, CohesiveError> {
        for (key, value) in [
            ("penalty", penalty),
            ("normal_strength", normal_strength),
            ("shear_strength", shear_strength),
            ("g_ic", g_ic),
            ("g_iic", g_iic),
            ("bk_exponent", bk_exponent),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(CohesiveError::NotPositive { key, value });
            }
        }
        // ½ K δ_m⁰² = (t3² + t_s²)/(2K) ≤ max(N, S)²/(2K) on the onset
        // ellipse, and G_c ≥ min(G_Ic, G_IIc) for η > 0: this keeps
        // δ_m^f > δ_m⁰ at every mixity.
        let (strength, high) = if normal_strength >= shear_strength {
            ("normal_strength", normal_strength)
        } else {
            ("shear_strength", shear_strength)
        };
        let (toughness, low) = if g_ic <= g_iic { ("g_ic", g_ic) } else { ("g_iic", g_iic) };
        let onset_energy = high * high / (2.0 * penalty);
        if onset_energy >= low {
            return Err(CohesiveError::OnsetAboveToughness { strength, toughness, onset_energy, value: low });
        }
        Ok(Self { penalty, normal_strength, shear_strength, g_ic, g_iic, bk_exponent, viscosity: 0.0 })
    }

    /// The mixed-mode toughness `G_c` (J/m²) at the mode-II share
    /// `G_II/G_T` (Benzeggagh–Kenane).
    pub fn toughness(&self, mode_ii_share: f64) -> f64 {
        self.g_ic + (self.g_iic - self.g_ic) * mode_ii_share.powf(self.bk_exponent)
    }

    /// Onset and final separations of the separation `δ`'s mixity.
    pub(crate) fn envelope(&self, separation: [f64; 3]) -> Envelope {
        let k = self.penalty;
        let shear_onset = self.shear_strength / k;
        let [d1, d2, d3] = separation;
        if d3 <= 0.0 {
            return Envelope { onset: shear_onset, last: 2.0 * self.g_iic / self.shear_strength };
        }
        let normal_onset = self.normal_strength / k;
        let beta2 = (d1 * d1 + d2 * d2) / (d3 * d3);
        let onset = normal_onset
            * shear_onset
            * ((1.0 + beta2) / (shear_onset * shear_onset + beta2 * normal_onset * normal_onset)).sqrt();
        let last = 2.0 * self.toughness(beta2 / (1.0 + beta2)) / (k * onset);
        Envelope { onset, last }
    }

    /// The onset index of the separation `δ`: the quadratic criterion
    /// `(⟨t3⟩/N)² + (t_s/S)²` of the intact traction `t = K δ` (1 on the
    /// onset envelope of every mixity, [`Self::envelope`]; past it once the
    /// point has damaged). In closure the shear term alone.
    pub(crate) fn onset_index(&self, separation: [f64; 3]) -> f64 {
        let k = self.penalty;
        let [d1, d2, d3] = separation;
        (k * d3.max(0.0) / self.normal_strength).powi(2) + k * k * (d1 * d1 + d2 * d2) / self.shear_strength.powi(2)
    }

    /// Energy dissipated per unit area from intact to damage `d` along the
    /// curve of the envelope `e` (J/m²).
    pub fn dissipation(&self, e: Envelope, d: f64) -> f64 {
        0.5 * self.penalty * e.onset * e.onset * e.last * d / (e.last - d * (e.last - e.onset))
    }

    /// True if the opening `δ3` closes the faces (the full penalty carries
    /// it): below `−10⁻⁹ N/K`, a billionth of the normal onset separation,
    /// not merely below zero. A face pair brought back to zero opening (a
    /// specimen unloaded) sits at `δ3 ≈ ±10⁻¹⁷⁰` m, round-off of zero; its
    /// sign would pick the stiffness point by point, the next correction
    /// would glue some of a delamination's faces and free others, and a
    /// reopening would unzip the faces about one node row per correction.
    /// A closure of physical size, `δ3 = −p/K` under a pressure `p` above
    /// `10⁻⁹ N` (`N` the normal strength: 0.08 Pa for AS4/PEEK), is closed;
    /// the traction's jump at the threshold, `d K · 10⁻⁹ N/K ≤ 10⁻⁹ N`, is far
    /// below any residual tolerance. Tested in `cohesive_tests.rs`
    /// (`round_off_of_zero_opening_does_not_close_the_faces`).
    pub(crate) fn is_closed(&self, opening: f64) -> bool {
        opening < -1e-9 * self.normal_strength / self.penalty
    }

    /// Traction, tangent and trial state at the separation `δ` from the
    /// committed state `old`.
    pub fn update(&self, separation: [f64; 3], old: &CohesiveState) -> CohesiveResponse {
        let k = self.penalty;
        let [d1, d2, d3] = separation;
        let opening = d3.max(0.0);
        let mixed = (d1 * d1 + d2 * d2 + opening * opening).sqrt();
        let e = self.envelope(separation);
        let reached =
            if mixed > e.onset { (e.last * (mixed - e.onset) / (mixed * (e.last - e.onset))).min(1.0) } else { 0.0 };
        // on the damage surface (reached = d_n: a point that softened in the
        // last increment, at its converged state) the tangent is the
        // softening one, the branch the next increment continues
        let growing = reached >= old.damage && reached > 0.0 && reached < 1.0;
        let damage = reached.max(old.damage);
        let soft = (1.0 - damage) * k;
        let closing = if self.is_closed(d3) { k } else { soft };
        let traction = [soft * d1, soft * d2, closing * d3];
        let mut tangent = [[0.0; 3]; 3];
        tangent[0][0] = soft;
        tangent[1][1] = soft;
        tangent[2][2] = closing;
        if growing {
            let slope = e.last * e.onset / (mixed * mixed * (e.last - e.onset));
            let hat = [d1, d2, opening];
            for (i, row) in tangent.iter_mut().enumerate() {
                for (j, entry) in row.iter_mut().enumerate() {
                    *entry -= k * slope * hat[i] * hat[j] / mixed;
                }
            }
        }
        let dissipated = old.dissipated + self.dissipation(e, damage) - self.dissipation(e, old.damage);
        CohesiveResponse { traction, tangent, state: CohesiveState { damage, dissipated } }
    }
}

#[cfg(test)]
#[path = "cohesive_tests.rs"]
mod tests;
