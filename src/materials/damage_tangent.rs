//! The consistent tangent of a loading ply point ([`super::PlyDamage`]):
//! `C_T = C_d + Σ_I s_I ⊗ g_I`, the secant `C_d` and one rank-one term per
//! active mode that loads in the update (κ grew, d below the cap; or the
//! strain on the damage surface, `δ = κ_n`, where the caller asks for the
//! loading branch, as the cohesive law and plasticity do at an
//! increment's first iteration), with
//! `s_I = ∂σ/∂d_I` and `g_I = ∂d_I/∂ε`:
//!
//! * `g_I = share · δf δ0/(κ² (δf − δ0)) · L_I ∂e_I/∂ε` (the viscosity's
//!   share of the law's damage in the regularised one), `δ0` and `δf`
//!   held; at a point's first onset, where they move with the strain, by
//!   central differences of the law's softening;
//! * `s_I` through the normal compliance the mode holds (central
//!   differences of `C_d ε`) and `d_s` (`∂d_s/∂d_I = Π_{J≠I} (1 − d_J)`,
//!   the shear stresses `−G γ`).
//!
//! `C_T` is unsymmetric. The element takes its symmetric part into the
//! factorized tangent and the terms apart ([`Softening`]): the rest
//! `½ Σ_I (s_I g_Iᵀ − g_I s_Iᵀ)` becomes, per Gauss point of weight `w`,
//! the two outer products `½ w [(Bᵀs)(Bᵀg)ᵀ − (Bᵀg)(Bᵀs)ᵀ]` of the
//! structure's unsymmetric rest (`crate::elements::softening`), which the
//! solver takes by GMRES preconditioned by the symmetric part's factor, as
//! friction's.

use super::{DamageState, FC, FT, MT, PlyDamage, equivalent, equivalent_gradient};
use crate::voigt::{Matrix6, Voigt, mat_vec};

/// The rank-one terms `s_I ⊗ g_I` of a point's consistent tangent beyond
/// its secant (at most one per active mode: the fibre's and the matrix's).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Softening {
    terms: [(Voigt, Voigt); 2],
    len: usize,
}

impl Softening {
    /// The terms `(s, g)`.
    pub(crate) fn terms(&self) -> &[(Voigt, Voigt)] {
        &self.terms[..self.len]
    }

    /// `c += Σ s gᵀ`.
    fn add_to(&self, c: &mut Matrix6) {
        for (s, g) in self.terms() {
            for (row, si) in c.iter_mut().zip(s) {
                for (v, gj) in row.iter_mut().zip(g) {
                    *v += si * gj;
                }
            }
        }
    }

    /// The terms in the global axes, times `factor`: `σ = Tᵀ σ_m` and
    /// `ε_m = T ε`, so `s ⊗ g` of the material axes is `(Tᵀ s) ⊗ (Tᵀ g)`
    /// of the global ones (`t` the strain rotation `T`).
    pub(crate) fn in_global_axes(&self, t: &Matrix6, factor: f64) -> Self {
        let turn = |v: &Voigt| -> Voigt { std::array::from_fn(|i| (0..6).map(|k| t[k][i] * v[k]).sum()) };
        let mut out = *self;
        for (s, g) in out.terms[..self.len].iter_mut() {
            *s = turn(s).map(|x| factor * x);
            *g = turn(g);
        }
        out
    }
}

impl PlyDamage {
    /// The consistent tangent (module docs) from the secant `secant`, and
    /// its rank-one terms.
    #[allow(clippy::too_many_arguments)] // the update's own intermediate values, not recomputed
    pub(super) fn consistent_tangent(
        &self,
        strain: &Voigt,
        effective: &Voigt,
        band: [f64; 2],
        ([fibre, matrix], normal): ([usize; 2], [usize; 3]),
        (old, share, loading): (&DamageState, f64, bool),
        state: &DamageState,
        secant: &Matrix6,
    ) -> (Matrix6, Softening) {
        let mut terms = Softening::default();
        let (d, law) = (state.viscous, state.damage);
        for (mode, length) in [(fibre, band[0]), (matrix, band[1])] {
            let (onset, last, kappa) = (state.onset[mode], state.last[mode], state.kappa[mode]);
            if onset == 0.0 || kappa <= onset || law[mode] >= self.max_damage {
                continue;
            }
            // unloading (inside the surface), or on it with the secant asked for
            let (e, _) = equivalent(mode, strain, effective, self.fibre_shear);
            if length * e < old.kappa[mode] || (length * e == old.kappa[mode] && !loading) {
                continue;
            }
            let grad = if old.onset[mode] == 0.0 {
                self.onset_gradient(mode, [fibre == FT, matrix == MT], length, strain, old).map(|g| share * g)
            } else {
                let slope = share * length * last * onset / (kappa * kappa * (last - onset));
                equivalent_gradient(mode, strain, self.fibre_shear).map(|g| slope * g / e)
            };
            terms.terms[terms.len] = (self.stress_sensitivity(mode, normal, &d, strain), grad);
            terms.len += 1;
        }
        let mut c = *secant;
        terms.add_to(&mut c);
        (c, terms)
    }

    /// `∂d_I/∂ε` of a point whose mode `mode` starts to damage in this
    /// update (none at the committed state `old`): its onset `δ0` and
    /// `δf = 2 G_I/σ0` are set where this strain's path crossed the onset
    /// surface, so they move with the strain too; central differences of
    /// the law's own softening (`PlyDamage::soften`, the branches
    /// `tension` held) take them all. Once per point and mode: later
    /// updates hold `δ0`, `δf` and take the closed form.
    fn onset_gradient(&self, mode: usize, tension: [bool; 2], length: f64, strain: &Voigt, old: &DamageState) -> Voigt {
        let damage = |e: &Voigt| {
            let effective = mat_vec(&self.stiffness, e);
            let ratios = self.strengths.hashin_ratios(&effective, tension, self.fibre_shear);
            let ratio = if mode == FT || mode == FC { ratios[0] } else { ratios[1] };
            let mut state = *old;
            self.soften(mode, 1.0 / ratio, length, e, &effective, &mut state);
            state.damage[mode]
        };
        let h = 1e-7 * strain.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        std::array::from_fn(|k| {
            let (mut plus, mut minus) = (*strain, *strain);
            plus[k] += h;
            minus[k] -= h;
            (damage(&plus) - damage(&minus)) / (2.0 * h)
        })
    }

    /// `∂σ/∂d_I` at the damage `d` and strain `strain` (material axes),
    /// the normal stresses' modes `normal` held.
    fn stress_sensitivity(&self, mode: usize, normal: [usize; 3], d: &[f64; 4], strain: &Voigt) -> Voigt {
        let ds = 1.0 - d.iter().map(|x| 1.0 - x).product::<f64>();
        let mut out = [0.0; 6];
        if normal.contains(&mode) {
            let h = 1e-6 * (1.0 - d[mode]);
            let stress = |dm: f64| {
                let diagonal = normal.map(|m| if m == mode { dm } else { d[m] });
                mat_vec(&self.damaged_stiffness(diagonal, ds), strain)
            };
            let (plus, minus) = (stress(d[mode] + h), stress(d[mode] - h));
            for k in 0..6 {
                out[k] = (plus[k] - minus[k]) / (2.0 * h);
            }
        }
        // d_s scales the shear moduli: ∂τ_k/∂d_s = −G_k γ_k
        let others: f64 = (0..4).filter(|&j| j != mode).map(|j| 1.0 - d[j]).product();
        for k in 0..3 {
            out[3 + k] -= others * self.elastic.shear[k] * strain[3 + k];
        }
        out
    }
}
