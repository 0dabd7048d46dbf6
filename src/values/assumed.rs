//! The assumed in-section shear strain (`formulation = "assumed_shear"`):
//! the covariant shear strain `ε_ξη` of each section element is sampled at
//! the `p × p` Gauss points of the element of order `p` (the tying points:
//! 2 × 2 for L9, 3 × 3 for L16) and interpolated from them through the
//! element, in the spirit of the MITC shells (Bucalem & Bathe, *Int. J.
//! Numer. Methods Eng.* 36, 1993; Bathe & Dvorkin 1985). A wall of the
//! section bending in the section plane (cross-wall bending: a flange under
//! a roller, a box wall in a local mode) otherwise locks: its parasitic
//! shear `ε_ξη ∝ ξ η` costs energy the exact solution does not have, and a
//! thin wall of L9 elements is tens of percent too stiff
//! (`tests/assumed_shear.rs`).
//!
//! In small strain, at a Gauss point of natural coordinates `(ξ, η)`,
//!
//! ```text
//! ε_ξη = ½ (∂u/∂ξ · t_η + ∂u/∂η · t_ξ)                  t_ξ = ∂x/∂ξ, t_η = ∂x/∂η (x–z)
//! ε̃_ξη(ξ, η) = Σ_k L_k(ξ, η) ε_ξη(ξ_k, η_k)             L_k: Lagrange through the tying points
//! ε̄ = ε + (ε̃_ξη − ε_ξη) m,   m = g₀^ξ ⊗ g₀^η + g₀^η ⊗ g₀^ξ  (in Voigt: engineering shear, crate::voigt)
//! ```
//!
//! with `g₀^ξ, g₀^η` the contravariant base vectors (rows of the inverse
//! Jacobian) at the element's centre: on a parallelogram only the
//! covariant shear changes. Taken at the centre rather than at each point,
//! `σ · m` is constant under a constant stress, so that the change does no
//! virtual work then (the interpolation error of a polynomial of degree
//! ≤ p per direction at the p Gauss points is orthogonal to the linear
//! `det J` of a straight-sided element): the patch test holds on any
//! straight-sided element, which the pointwise basis would miss by
//! O(distortion).
//! With `v_τ = Σ_i N_i u_(i,τ)` the change is linear in the section's
//! in-plane displacements, `ε̃_ξη − ε_ξη = Σ_τ d_τ · (v_τx, v_τz)`, so the
//! operator of node `(i, τ)` gains `N_i m d_τᵀ` on its x and z columns:
//! the kernel's strain, internal force and tangent stay consistent, the
//! material point is unchanged (plasticity included).
//!
//! On elements whose map is bilinear (straight sides, any distortion) a
//! linear displacement gives a bilinear `ε_ξη`, reproduced exactly by the
//! `p × p` interpolation (p ≥ 2): a constant strain is unchanged. L4 (p =
//! 1, one tying point) would not reproduce it on a distorted quad and is
//! refused. On curved elements (rings) both hold only approximately.

use super::section_point;
use crate::mesh::CrossSection;
use crate::quadrature::GaussRule;
use crate::shape::Lagrange2d;
use crate::voigt::Voigt;

/// The assumed covariant shear of every section element at its Gauss
/// points (section values' order: element, then point).
#[derive(Debug, Clone)]
pub struct AssumedShear {
    n_gp: usize,
    n_fun: usize,
    /// `m` at `[element]` (Voigt order of [`crate::voigt`]).
    direction: Vec<Voigt>,
    /// `d_τ = (x, z)` at `[element][point][τ]`.
    coefficients: Vec<[f64; 2]>,
}

impl AssumedShear {
    /// The tying interpolation of every element of `section` at the natural
    /// points `natural` (the section Gauss points of the kernel). `None` for
    /// L4 sections (module docs).
    pub(crate) fn new(section: &CrossSection, natural: &[[f64; 2]]) -> Option<Self> {
        let p = section.kind.order();
        if p < 2 {
            return None;
        }
        let basis = Lagrange2d::new(p);
        let n_fun = basis.len();
        let tying = GaussRule::new(p).points;
        let (mut f, mut dxi, mut deta) = (vec![0.0; n_fun], vec![0.0; n_fun], vec![0.0; n_fun]);
        let n_gp = natural.len();
        let mut direction = Vec::with_capacity(section.n_elements());
        let mut coefficients = Vec::with_capacity(section.n_elements() * n_gp * n_fun);
        // c_τ(ξ, η) = ½ (∂F_τ/∂ξ t_η + ∂F_τ/∂η t_ξ): ε_ξη = Σ_τ c_τ · v_τ
        let mut covariant = |e: usize, xi: f64, eta: f64, out: &mut [[f64; 2]]| {
            let sp = section_point(section, &basis, e, xi, eta, &mut f, &mut dxi, &mut deta);
            let [t_xi, t_eta] = sp.tangents;
            for (c, (a, b)) in out.iter_mut().zip(dxi.iter().zip(&deta)) {
                *c = [0.5 * (a * t_eta[0] + b * t_xi[0]), 0.5 * (a * t_eta[1] + b * t_xi[1])];
            }
            sp.inverse
        };
        let mut at_tying = vec![[0.0; 2]; tying.len() * tying.len() * n_fun];
        let mut here = vec![[0.0; 2]; n_fun];
        for e in 0..section.n_elements() {
            for (j, &eta) in tying.iter().enumerate() {
                for (i, &xi) in tying.iter().enumerate() {
                    let k = j * tying.len() + i;
                    covariant(e, xi, eta, &mut at_tying[k * n_fun..(k + 1) * n_fun]);
                }
            }
            // m from the contravariant basis at the element's centre (module docs)
            let [g_xi, g_eta] = covariant(e, 0.0, 0.0, &mut here);
            direction.push([
                2.0 * g_xi[0] * g_eta[0],
                0.0,
                2.0 * g_xi[1] * g_eta[1],
                0.0,
                2.0 * (g_xi[0] * g_eta[1] + g_eta[0] * g_xi[1]),
                0.0,
            ]);
            for &[xi, eta] in natural {
                covariant(e, xi, eta, &mut here);
                let (lx, lz) = (lagrange(&tying, xi), lagrange(&tying, eta));
                for (t, c) in here.iter().enumerate() {
                    let mut d = [-c[0], -c[1]];
                    for (j, wz) in lz.iter().enumerate() {
                        for (i, wx) in lx.iter().enumerate() {
                            let ct = at_tying[(j * tying.len() + i) * n_fun + t];
                            d[0] += wx * wz * ct[0];
                            d[1] += wx * wz * ct[1];
                        }
                    }
                    coefficients.push(d);
                }
            }
        }
        Some(Self { n_gp, n_fun, direction, coefficients })
    }

    /// `m` and the `d_τ` of point `q` of section element `e`.
    pub(crate) fn at(&self, e: usize, q: usize) -> (&Voigt, &[[f64; 2]]) {
        let p = e * self.n_gp + q;
        (&self.direction[e], &self.coefficients[p * self.n_fun..(p + 1) * self.n_fun])
    }

    /// Adds the strain change `(ε̃_ξη − ε_ξη) m` at point `q` of section
    /// element `e` to `eps`, from the axis-contracted displacements
    /// `v_τ = Σ_i N_i u_(i,τ)` (3 per node).
    pub(crate) fn add_strain(&self, e: usize, q: usize, v: &[[f64; 3]], eps: &mut Voigt) {
        let (m, d) = self.at(e, q);
        let s: f64 = d.iter().zip(v).map(|(d, v)| d[0] * v[0] + d[1] * v[2]).sum();
        for (e, mi) in eps.iter_mut().zip(m) {
            *e += s * mi;
        }
    }

    /// Adds the point's share of the internal force to the kernel's `h_τ`
    /// (which the caller multiplies by `N_i`): `w (σ · m) d_τ` on x and z.
    pub(crate) fn add_force(&self, e: usize, q: usize, w: f64, stress: &Voigt, h: &mut [[f64; 3]]) {
        let (m, d) = self.at(e, q);
        let sm: f64 = stress.iter().zip(m).map(|(s, m)| s * m).sum();
        for (ht, dt) in h.iter_mut().zip(d) {
            ht[0] += w * sm * dt[0];
            ht[2] += w * sm * dt[1];
        }
    }
}

/// The Lagrange polynomials through `points` at `x`.
fn lagrange(points: &[f64], x: f64) -> Vec<f64> {
    (0..points.len())
        .map(|i| {
            points.iter().enumerate().filter(|&(j, _)| j != i).map(|(_, &pj)| (x - pj) / (points[i] - pj)).product()
        })
        .collect()
}
