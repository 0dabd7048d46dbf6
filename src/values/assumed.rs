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
//! **Nonlinear geometry** (total Lagrangian, Green–Lagrange strain): the
//! covariant component of `E` is
//!
//! ```text
//! E_ξη = ½ (f_ξ · f_η − t_ξ · t_η),   f_ξ = t_ξ + g_ξ, g_ξ = ∂u/∂ξ = Σ_τ a_τ v_τ  (a_τ = ∂F_τ/∂ξ, b_τ = ∂F_τ/∂η)
//!      = Σ_τ c_τ · v_τ + ½ g_ξ · g_η
//! ```
//!
//! (`g` with all three components: the section's points move out of its
//! plane), tied and changed as above: `Ē = E + (Ẽ_ξη − E_ξη) m`. Its
//! variation for a unit displacement `u_(i,τ,k)` is `N_i D_τk`,
//! `D_τ = Σ_k L_k ½ (a_τ f_η + b_τ f_ξ)(ξ_k, η_k) − ½ (a_τ f_η + b_τ f_ξ)(ξ, η)`,
//! whose in-plane reference part is the small strain's `d_τ`; its second
//! variation is `N_i N_j δ_kl G_τσ` with the reference numbers
//! `G_τσ = Σ_k L_k sym(a_τ b_σ)(ξ_k, η_k) − sym(a_τ b_σ)(ξ, η)`, the
//! geometric stiffness's share (`crate::elements`' `assumed_large`). The
//! derivatives `a, b`, the interpolation `L_k` and `G` are those of the
//! reference square, the same for every element. A homogeneous
//! deformation gives a bilinear `g_ξ · g_η` on a straight-sided element,
//! so the patch test holds at finite strain as well.
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
    /// Nonlinear geometry, on the reference square (module docs):
    /// `(a_τ, b_τ)` at the tying points `[k][τ]` and at the section's
    /// points `[point][τ]`, `L_k` at `[point][k]`, `G_τσ` at `[point][τ][σ]`.
    tying_derivatives: Vec<[f64; 2]>,
    point_derivatives: Vec<[f64; 2]>,
    interpolation: Vec<f64>,
    curvature: Vec<f64>,
}

/// `(g_ξ, g_η)`: the in-section covariant derivatives of the displacement
/// at one point (nonlinear geometry; module docs).
pub(crate) type Covariant = [[f64; 3]; 2];

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
        let reference = |xi: f64, eta: f64| -> Vec<[f64; 2]> {
            let (mut f, mut a, mut b) = (vec![0.0; n_fun], vec![0.0; n_fun], vec![0.0; n_fun]);
            basis.eval(xi, eta, &mut f, &mut a, &mut b);
            a.into_iter().zip(b).map(|(a, b)| [a, b]).collect()
        };
        let tying_points: Vec<[f64; 2]> =
            tying.iter().flat_map(|&eta| tying.iter().map(move |&xi| [xi, eta])).collect();
        let tying_derivatives: Vec<[f64; 2]> = tying_points.iter().flat_map(|&[xi, eta]| reference(xi, eta)).collect();
        let point_derivatives: Vec<[f64; 2]> = natural.iter().flat_map(|&[xi, eta]| reference(xi, eta)).collect();
        let mut interpolation = Vec::with_capacity(n_gp * tying_points.len());
        for &[xi, eta] in natural {
            let (lx, lz) = (lagrange(&tying, xi), lagrange(&tying, eta));
            interpolation.extend(lz.iter().flat_map(|wz| lx.iter().map(move |wx| wx * wz)));
        }
        // sym(a_τ b_σ) = ½ (a_τ b_σ + b_τ a_σ) at the listed derivatives
        let sym = |ab: &[[f64; 2]], t: usize, s: usize| 0.5 * (ab[t][0] * ab[s][1] + ab[t][1] * ab[s][0]);
        let mut curvature = Vec::with_capacity(n_gp * n_fun * n_fun);
        for q in 0..n_gp {
            let here = &point_derivatives[q * n_fun..(q + 1) * n_fun];
            let weights = &interpolation[q * tying_points.len()..(q + 1) * tying_points.len()];
            for t in 0..n_fun {
                for s in 0..n_fun {
                    let tied: f64 = weights
                        .iter()
                        .zip(tying_derivatives.chunks_exact(n_fun))
                        .map(|(l, ab)| l * sym(ab, t, s))
                        .sum();
                    curvature.push(tied - sym(here, t, s));
                }
            }
        }
        Some(Self {
            n_gp,
            n_fun,
            direction,
            coefficients,
            tying_derivatives,
            point_derivatives,
            interpolation,
            curvature,
        })
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

    /// `m` of section element `e`.
    pub(crate) fn direction(&self, e: usize) -> &Voigt {
        &self.direction[e]
    }

    /// Nonlinear geometry: `(g_ξ, g_η)` at every tying point from the
    /// axis-contracted displacements `v_τ` (3 per node), into `out`.
    pub(crate) fn tying_covariants(&self, v: &[[f64; 3]], out: &mut Vec<Covariant>) {
        out.clear();
        out.extend(self.tying_derivatives.chunks_exact(self.n_fun).map(|ab| covariant(ab, v)));
    }

    /// Nonlinear geometry: the quadratic part of `Ẽ_ξη − E_ξη` at point `q`,
    /// `½ Σ_k L_k g_ξ·g_η(ξ_k, η_k) − ½ g_ξ·g_η(ξ, η)`, from `v_τ` and the
    /// tying points' derivatives `tying` ([`Self::tying_covariants`] of the same `v`).
    pub(crate) fn quadratic_change(&self, q: usize, v: &[[f64; 3]], tying: &[Covariant]) -> f64 {
        let dot = |[gx, ge]: &Covariant| gx[0] * ge[0] + gx[1] * ge[1] + gx[2] * ge[2];
        let here = covariant(&self.point_derivatives[q * self.n_fun..(q + 1) * self.n_fun], v);
        let tied: f64 = self.weights(q).iter().zip(tying).map(|(l, g)| l * dot(g)).sum();
        0.5 * (tied - dot(&here))
    }

    /// Nonlinear geometry: adds `(Ẽ_ξη − E_ξη) m` at point `q` of section
    /// element `e` to the Green–Lagrange strain `eps` (module docs).
    pub(crate) fn add_large_strain(&self, e: usize, q: usize, v: &[[f64; 3]], tying: &[Covariant], eps: &mut Voigt) {
        let (m, d) = self.at(e, q);
        let linear: f64 = d.iter().zip(v).map(|(d, v)| d[0] * v[0] + d[1] * v[2]).sum();
        let s = linear + self.quadratic_change(q, v, tying);
        for (e, mi) in eps.iter_mut().zip(m) {
            *e += s * mi;
        }
    }

    /// Nonlinear geometry: the variation `D_τ` (3 per node `τ`, into `out`)
    /// of `Ẽ_ξη − E_ξη` at point `q` of section element `e` (module docs).
    pub(crate) fn large_variation(
        &self,
        e: usize,
        q: usize,
        v: &[[f64; 3]],
        tying: &[Covariant],
        out: &mut [[f64; 3]],
    ) {
        let (_, d) = self.at(e, q);
        let here_ab = &self.point_derivatives[q * self.n_fun..(q + 1) * self.n_fun];
        let [gx, ge] = covariant(here_ab, v);
        for (o, (d, ab)) in out.iter_mut().zip(d.iter().zip(here_ab)) {
            // the reference part d_τ, less ½ (a_τ g_η + b_τ g_ξ) here
            *o = std::array::from_fn(|k| -0.5 * (ab[0] * ge[k] + ab[1] * gx[k]));
            o[0] += d[0];
            o[2] += d[1];
        }
        for (l, (ab, [gx, ge])) in
            self.weights(q).iter().zip(self.tying_derivatives.chunks_exact(self.n_fun).zip(tying))
        {
            for (o, ab) in out.iter_mut().zip(ab) {
                for k in 0..3 {
                    o[k] += 0.5 * l * (ab[0] * ge[k] + ab[1] * gx[k]);
                }
            }
        }
    }

    /// Nonlinear geometry: `G_τσ` at point `q` (`n × n`, row-major; module docs).
    pub(crate) fn curvature(&self, q: usize) -> &[f64] {
        let n = self.n_fun * self.n_fun;
        &self.curvature[q * n..(q + 1) * n]
    }

    /// `L_k` at point `q`.
    fn weights(&self, q: usize) -> &[f64] {
        let k = self.interpolation.len() / self.n_gp;
        &self.interpolation[q * k..(q + 1) * k]
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

/// `(g_ξ, g_η) = Σ_τ (a_τ, b_τ) v_τ` from the derivatives `ab` of one point.
fn covariant(ab: &[[f64; 2]], v: &[[f64; 3]]) -> Covariant {
    let mut g = [[0.0; 3]; 2];
    for ([a, b], v) in ab.iter().zip(v) {
        for k in 0..3 {
            g[0][k] += a * v[k];
            g[1][k] += b * v[k];
        }
    }
    g
}

/// The Lagrange polynomials through `points` at `x`.
fn lagrange(points: &[f64], x: f64) -> Vec<f64> {
    (0..points.len())
        .map(|i| {
            points.iter().enumerate().filter(|&(j, _)| j != i).map(|(_, &pj)| (x - pj) / (points[i] - pj)).product()
        })
        .collect()
}
