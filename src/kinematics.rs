//! Kinematics: how a displacement gradient becomes a strain, and what the
//! material's stress does to the nodes.
//!
//! * **Small strain** ([`Kinematics::Linear`], the default and the paper's):
//!   `ε = sym ∇u`, Cauchy stress `σ`, internal force `f_a = ∫ B_aᵀ σ dV`.
//! * **Total Lagrangian** ([`Kinematics::TotalLagrangian`], model key
//!   `analysis.geometry = "nonlinear"`; Pagani & Carrera 2018 for CUF, and
//!   Bathe, *Finite Element Procedures*, §6.2): everything is integrated
//!   over the reference configuration `X`. With `H = ∂u/∂X` and the
//!   deformation gradient `F = I + H`,
//!
//!   ```text
//!   E = ½ (H + Hᵀ + Hᵀ H)                      Green–Lagrange strain
//!   S = S(E, history)                          second Piola–Kirchhoff stress (the material point)
//!   f_(a,k) = ∫ (F S)_(k·) · ∇N_a dV₀           internal force, P = F S the first Piola stress
//!   δE_(a,k) = sym(Fᵀ (e_k ⊗ ∇N_a))            the strain of a unit displacement u_(a,k)
//!   K_(ak,bl) = ∫ δE_(a,k) · C δE_(b,l) dV₀ + δ_kl ∫ ∇N_a · S ∇N_b dV₀
//!   ```
//!
//!   the second term being the geometric (initial-stress) stiffness. The
//!   CUF nucleus keeps its form: only `B_a` now depends on `F`, and the
//!   geometric term is a scalar per node pair times the 3×3 identity.
//!   Cauchy stress for output: `σ = J⁻¹ F S Fᵀ`, `J = det F`.
//! * **Total Lagrangian, logarithmic strain**
//!   ([`Kinematics::TotalLagrangianLog`], `analysis.strain = "logarithmic"`):
//!   the material sees `E_log = ½ ln C` instead of `E` and returns the
//!   stress `T` conjugate to it; [`hencky`] turns `(T, ∂T/∂E_log)` into
//!   `(S, ∂S/∂E)`, after which everything above is unchanged — finite-strain
//!   plasticity with the small-strain return map (Miehe, Apel & Lambrecht
//!   2002).
//!
//! Voigt order and the engineering shear convention are [`crate::voigt`]'s.

pub mod hencky;

pub use hencky::LogStrain;

use crate::voigt::{self, Voigt};

/// A 3×3 tensor `t[i][j]`.
pub(crate) type Tensor = [[f64; 3]; 3];

/// The identity tensor (`F` of the undeformed state).
pub(crate) const IDENTITY: Tensor = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The strain measure and configuration of the analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Kinematics {
    /// Small strain and small displacement (the default; the paper's).
    #[default]
    Linear,
    /// Total Lagrangian: Green–Lagrange strain, second Piola–Kirchhoff
    /// stress, the geometric stiffness (large rotations and displacements).
    TotalLagrangian,
    /// Total Lagrangian with the logarithmic (Hencky) strain `½ ln C` as the
    /// material's strain (`hencky`): finite-strain elastoplasticity.
    TotalLagrangianLog,
}

impl Kinematics {
    /// True for the total-Lagrangian formulation (either strain measure).
    pub fn is_nonlinear(self) -> bool {
        self != Kinematics::Linear
    }

    /// True for the logarithmic strain measure.
    pub(crate) fn is_logarithmic(self) -> bool {
        self == Kinematics::TotalLagrangianLog
    }

    /// The strain of the displacement gradient `h[k][d] = ∂u_k/∂X_d`.
    #[inline]
    pub fn strain(self, h: &Tensor) -> Voigt {
        match self {
            Kinematics::Linear => voigt::strain_from_gradient(h),
            Kinematics::TotalLagrangian => green_lagrange(h),
            Kinematics::TotalLagrangianLog => hencky::log_strain(h),
        }
    }
}

/// `F = I + H`.
#[inline]
pub(crate) fn deformation_gradient(h: &Tensor) -> Tensor {
    let mut f = *h;
    for (i, row) in f.iter_mut().enumerate() {
        row[i] += 1.0;
    }
    f
}

/// Green–Lagrange strain `E = ½ (H + Hᵀ + Hᵀ H)` in Voigt form (engineering
/// shear `2 E_ij`).
#[inline]
pub fn green_lagrange(h: &Tensor) -> Voigt {
    let q = quadratic_strain(h);
    [
        h[0][0] + q[0],
        h[1][1] + q[1],
        h[2][2] + q[2],
        h[0][1] + h[1][0] + q[3],
        h[0][2] + h[2][0] + q[4],
        h[1][2] + h[2][1] + q[5],
    ]
}

/// The quadratic part `½ Hᵀ H` of the Green–Lagrange strain in Voigt form
/// (engineering shear `(HᵀH)_ij`).
#[inline]
pub(crate) fn quadratic_strain(h: &Tensor) -> Voigt {
    // (HᵀH)_ij = Σ_k H_ki H_kj
    let hh = |i: usize, j: usize| h[0][i] * h[0][j] + h[1][i] * h[1][j] + h[2][i] * h[2][j];
    [0.5 * hh(0, 0), 0.5 * hh(1, 1), 0.5 * hh(2, 2), hh(0, 1), hh(0, 2), hh(1, 2)]
}

/// The first Piola–Kirchhoff stress `P = F S` (not symmetric).
#[inline]
pub(crate) fn first_piola(f: &Tensor, s: &Voigt) -> Tensor {
    let st = voigt::stress_tensor(s);
    std::array::from_fn(|k| std::array::from_fn(|j| f[k][0] * st[0][j] + f[k][1] * st[1][j] + f[k][2] * st[2][j]))
}

/// `det F`.
#[inline]
pub fn determinant(f: &Tensor) -> f64 {
    f[0][0] * (f[1][1] * f[2][2] - f[1][2] * f[2][1]) - f[0][1] * (f[1][0] * f[2][2] - f[1][2] * f[2][0])
        + f[0][2] * (f[1][0] * f[2][1] - f[1][1] * f[2][0])
}

/// The Cauchy stress `σ = J⁻¹ F S Fᵀ` in Voigt form.
pub(crate) fn cauchy(f: &Tensor, s: &Voigt) -> Voigt {
    let p = first_piola(f, s);
    let j = determinant(f);
    // σ_ij = Σ_k P_ik F_jk / J
    let sij = |i: usize, jj: usize| (p[i][0] * f[jj][0] + p[i][1] * f[jj][1] + p[i][2] * f[jj][2]) / j;
    [sij(0, 0), sij(1, 1), sij(2, 2), sij(0, 1), sij(0, 2), sij(1, 2)]
}

/// The second Piola–Kirchhoff stress of a Cauchy stress,
/// `S = J F⁻¹ σ F⁻ᵀ` (the inverse of [`cauchy`]), in Voigt form.
pub(crate) fn second_piola(f: &Tensor, sigma: &Voigt) -> Voigt {
    let j = determinant(f);
    // the inverse by cofactors: F⁻¹ = cof(F)ᵀ / J
    let c = cofactor(f);
    let inv: Tensor = std::array::from_fn(|i| std::array::from_fn(|k| c[k][i] / j));
    let st = voigt::stress_tensor(sigma);
    // S_ab = J Σ_ij F⁻¹_ai σ_ij F⁻¹_bj
    let sab = |a: usize, b: usize| {
        j * (0..3).map(|i| (0..3).map(|jj| inv[a][i] * st[i][jj] * inv[b][jj]).sum::<f64>()).sum::<f64>()
    };
    [sab(0, 0), sab(1, 1), sab(2, 2), sab(0, 1), sab(0, 2), sab(1, 2)]
}

/// The cofactor matrix `cof F = J F⁻ᵀ` (signed minors, by cyclic indices).
pub(crate) fn cofactor(f: &Tensor) -> Tensor {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let (i1, i2, j1, j2) = ((i + 1) % 3, (i + 2) % 3, (j + 1) % 3, (j + 2) % 3);
            f[i1][j1] * f[i2][j2] - f[i1][j2] * f[i2][j1]
        })
    })
}

/// The Green–Lagrange strain variation of a unit displacement in direction
/// `k` of a node with reference gradient `g`: `δE = sym(Fᵀ (e_k ⊗ g))`,
/// i.e. `δE_ij = ½ (F_ki g_j + F_kj g_i)` (engineering shear). With `F = I`
/// it is the small-strain column of [`voigt::add_nodal_strain`].
#[inline]
pub(crate) fn strain_variation(f: &Tensor, g: [f64; 3], k: usize) -> Voigt {
    let r = f[k];
    [
        r[0] * g[0],
        r[1] * g[1],
        r[2] * g[2],
        r[0] * g[1] + r[1] * g[0],
        r[0] * g[2] + r[2] * g[0],
        r[1] * g[2] + r[2] * g[1],
    ]
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The rotation by `angle` (rad) about `axis` (Rodrigues' formula);
    /// shared with the tests of `hencky`.
    pub(crate) fn rotation(axis: [f64; 3], angle: f64) -> Tensor {
        let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        let [x, y, z] = axis.map(|a| a / n);
        let (s, c) = angle.sin_cos();
        let t = 1.0 - c;
        [
            [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
        ]
    }

    /// The product `a b`.
    pub(crate) fn mul(a: &Tensor, b: &Tensor) -> Tensor {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
    }

    fn minus_identity(f: &Tensor) -> Tensor {
        let mut h = *f;
        for (i, row) in h.iter_mut().enumerate() {
            row[i] -= 1.0;
        }
        h
    }

    /// A rigid rotation has no Green–Lagrange strain (while its small
    /// strain is of the order of the angle squared and more).
    #[test]
    fn rigid_rotation_is_strain_free() {
        let r = rotation([1.0, -2.0, 0.5], 1.3);
        let e = green_lagrange(&minus_identity(&r));
        assert!(e.iter().all(|v| v.abs() < 1e-15), "{e:?}");
        let small = voigt::strain_from_gradient(&minus_identity(&r));
        assert!(small.iter().any(|v| v.abs() > 0.1));
    }

    /// Uniaxial stretch λ: E_xx = (λ² − 1)/2; Cauchy σ_xx = λ² S_xx / J.
    #[test]
    fn stretch_and_cauchy() {
        let lam: f64 = 1.5;
        let f = [[lam, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let e = green_lagrange(&minus_identity(&f));
        assert!((e[0] - (lam * lam - 1.0) / 2.0).abs() < 1e-15);
        let s = [2.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        let sig = cauchy(&f, &s);
        assert!((sig[0] - lam * lam * 2.0 / lam).abs() < 1e-14);
        assert!((sig[1] - 1.0 / lam).abs() < 1e-15);
    }

    /// Objectivity: rotating the deformation (F → R F) rotates the Cauchy
    /// stress (σ → R σ Rᵀ) and leaves E unchanged.
    #[test]
    fn cauchy_rotates_with_the_body() {
        let f = [[1.1, 0.2, -0.05], [0.03, 0.95, 0.1], [-0.02, 0.07, 1.2]];
        let s = [3.0, -1.0, 2.0, 0.5, -0.7, 0.25];
        let r = rotation([0.3, 1.0, -0.4], 0.9);
        let rf = mul(&r, &f);
        let (e0, e1) = (green_lagrange(&minus_identity(&f)), green_lagrange(&minus_identity(&rf)));
        for k in 0..6 {
            assert!((e0[k] - e1[k]).abs() < 1e-14);
        }
        let sig = voigt::stress_tensor(&cauchy(&f, &s));
        let rot = voigt::stress_tensor(&cauchy(&rf, &s));
        let rt: Tensor = std::array::from_fn(|i| std::array::from_fn(|j| r[j][i]));
        let expected = mul(&mul(&r, &sig), &rt);
        for i in 0..3 {
            for j in 0..3 {
                assert!((rot[i][j] - expected[i][j]).abs() < 1e-13, "{i}{j}");
            }
        }
    }

    /// `second_piola` inverts `cauchy` for a general (unsymmetric,
    /// stretched, rotated) F, to round-off.
    #[test]
    fn second_piola_inverts_cauchy() {
        let f = mul(&rotation([0.3, 1.0, -0.4], 0.9), &[[1.1, 0.2, -0.05], [0.03, 0.95, 0.1], [-0.02, 0.07, 1.2]]);
        let s = [3.0, -1.0, 2.0, 0.5, -0.7, 0.25];
        let back = second_piola(&f, &cauchy(&f, &s));
        for k in 0..6 {
            assert!((back[k] - s[k]).abs() < 1e-13, "{k}: {back:?}");
        }
    }

    /// δE is the derivative of E: E(H + t e_k ⊗ g) − E(H − t e_k ⊗ g) over 2t.
    #[test]
    fn strain_variation_is_the_derivative() {
        let h = [[0.1, 0.2, -0.05], [0.03, -0.05, 0.1], [-0.02, 0.07, 0.2]];
        let f = deformation_gradient(&h);
        let g = [0.7, -1.3, 0.4];
        for k in 0..3 {
            let t = 1e-6;
            let (mut hp, mut hm) = (h, h);
            for d in 0..3 {
                hp[k][d] += t * g[d];
                hm[k][d] -= t * g[d];
            }
            let (ep, em) = (green_lagrange(&hp), green_lagrange(&hm));
            let de = strain_variation(&f, g, k);
            for c in 0..6 {
                assert!(((ep[c] - em[c]) / (2.0 * t) - de[c]).abs() < 1e-9, "k {k} c {c}");
            }
        }
    }
}
