//! Voigt notation: the one place where the order of components and the
//! shear convention are fixed for the whole crate.
//!
//! # Convention
//!
//! Symmetric second-order tensors are stored as 6-vectors in the order of the
//! paper (Nagaraj et al., eq. 3):
//!
//! | index | 0  | 1  | 2  | 3  | 4  | 5  |
//! |-------|----|----|----|----|----|----|
//! | comp. | xx | yy | zz | xy | xz | yz |
//!
//! * **Stresses** store the tensor components: `σ = [σxx, σyy, σzz, σxy, σxz, σyz]`.
//! * **Strains** (total and plastic) store *engineering* shear strains:
//!   `ε = [εxx, εyy, εzz, γxy, γxz, γyz]` with `γij = 2 εij`.
//!
//! With this pairing the work density is the plain dot product `σ·ε`, the
//! strain–displacement operator is the paper's `D` (eq. 4) and a material
//! tangent `C[I][J] = ∂σ_I/∂ε_J` is the usual symmetric 6×6 matrix.
//!
//! All quantities are in SI units (Pa for stresses and moduli, m for lengths).

/// A symmetric tensor in Voigt form (see the module docs for the order).
pub type Voigt = [f64; 6];

/// A 6×6 material matrix acting on engineering-strain Voigt vectors.
pub type Matrix6 = [[f64; 6]; 6];

/// Adds the strain `B_a u_a` of one node (shape-function gradient `g`,
/// nodal displacement `u`) to `eps`: the operator `D` of the paper's eq. (4)
/// in this module's order and shear convention.
#[inline]
pub(crate) fn add_nodal_strain(eps: &mut Voigt, g: [f64; 3], u: [f64; 3]) {
    eps[0] += g[0] * u[0];
    eps[1] += g[1] * u[1];
    eps[2] += g[2] * u[2];
    eps[3] += g[1] * u[0] + g[0] * u[1];
    eps[4] += g[2] * u[0] + g[0] * u[2];
    eps[5] += g[2] * u[1] + g[1] * u[2];
}

/// The strain of a displacement gradient `h[k][d] = ∂u_k/∂x_d` (its
/// symmetric part, engineering shear): the sum of [`add_nodal_strain`] over
/// nodes, when the gradient is assembled first.
#[inline]
pub(crate) fn strain_from_gradient(h: &[[f64; 3]; 3]) -> Voigt {
    [h[0][0], h[1][1], h[2][2], h[0][1] + h[1][0], h[0][2] + h[2][0], h[1][2] + h[2][1]]
}

/// A stress in Voigt form as the symmetric 3×3 tensor `σ[i][j]`.
#[inline]
pub(crate) fn stress_tensor(s: &Voigt) -> [[f64; 3]; 3] {
    [[s[0], s[3], s[4]], [s[3], s[1], s[5]], [s[4], s[5], s[2]]]
}

/// Trace of a stress or strain tensor (shear convention does not matter).
#[inline]
pub fn trace(v: &Voigt) -> f64 {
    v[0] + v[1] + v[2]
}

/// Deviatoric part of a *stress-like* tensor.
#[inline]
pub(crate) fn deviator(s: &Voigt) -> Voigt {
    let p = trace(s) / 3.0;
    [s[0] - p, s[1] - p, s[2] - p, s[3], s[4], s[5]]
}

/// Frobenius norm `sqrt(s:s)` of a *stress-like* tensor (shear entries count twice).
#[inline]
pub(crate) fn norm_stress(s: &Voigt) -> f64 {
    (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])).sqrt()
}

/// Von Mises equivalent stress `sqrt(3/2 s:s)` of a stress vector.
#[inline]
pub fn von_mises(stress: &Voigt) -> f64 {
    (1.5f64).sqrt() * norm_stress(&deviator(stress))
}

/// Converts a stress-like tensor to the strain-like (engineering shear) form:
/// shear entries are doubled.
#[inline]
pub(crate) fn stress_like_to_strain_like(s: &Voigt) -> Voigt {
    [s[0], s[1], s[2], 2.0 * s[3], 2.0 * s[4], 2.0 * s[5]]
}

/// The symmetric part `½ (C + Cᵀ)` of a 6×6 matrix (a tangent the
/// structure factorizes).
pub(crate) fn symmetric_part(c: &Matrix6) -> Matrix6 {
    std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (c[i][j] + c[j][i])))
}

/// Matrix–vector product `C ε`.
#[inline]
pub fn mat_vec(c: &Matrix6, e: &Voigt) -> Voigt {
    let mut out = [0.0; 6];
    for (o, row) in out.iter_mut().zip(c) {
        *o = row.iter().zip(e).map(|(a, b)| a * b).sum();
    }
    out
}

/// Isotropic linear-elastic stiffness `C = λ 1⊗1 + 2μ I` in this module's
/// convention (engineering shear strains, so the shear diagonal is `μ`).
pub(crate) fn isotropic_stiffness(young: f64, poisson: f64) -> Matrix6 {
    let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    let mu = young / (2.0 * (1.0 + poisson));
    let mut c = [[0.0; 6]; 6];
    for (i, row) in c.iter_mut().enumerate().take(3) {
        for (j, v) in row.iter_mut().enumerate().take(3) {
            *v = lambda + if i == j { 2.0 * mu } else { 0.0 };
        }
    }
    for (i, row) in c.iter_mut().enumerate().skip(3) {
        row[i] = mu;
    }
    c
}

/// Fourth-order deviatoric projector `I_dev` mapping engineering strains to
/// the (stress-like) deviatoric strain tensor: `(I_dev ε)` equals the
/// tensor-component deviator of `ε`.
pub(crate) fn deviatoric_projector() -> Matrix6 {
    let mut p = [[0.0; 6]; 6];
    for (i, row) in p.iter_mut().enumerate().take(3) {
        for (j, v) in row.iter_mut().enumerate().take(3) {
            *v = if i == j { 2.0 / 3.0 } else { -1.0 / 3.0 };
        }
    }
    for (i, row) in p.iter_mut().enumerate().skip(3) {
        row[i] = 0.5;
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The gradient form agrees with the nodal form it sums (one node with
    /// gradient g and displacement u has ∂u_k/∂x_d = u_k g_d), and the
    /// tensor of a stress puts each shear in both of its places.
    #[test]
    fn gradient_and_tensor_forms_follow_the_convention() {
        let (g, u) = ([0.3, -1.1, 2.0], [0.7, 0.2, -0.5]);
        let mut nodal = [0.0; 6];
        add_nodal_strain(&mut nodal, g, u);
        let h: [[f64; 3]; 3] = std::array::from_fn(|k| std::array::from_fn(|d| u[k] * g[d]));
        let from_gradient = strain_from_gradient(&h);
        for i in 0..6 {
            assert!((nodal[i] - from_gradient[i]).abs() < 1e-15, "{nodal:?} {from_gradient:?}");
        }
        let t = stress_tensor(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        assert_eq!(t, [[1.0, 4.0, 5.0], [4.0, 2.0, 6.0], [5.0, 6.0, 3.0]]);
    }

    #[test]
    fn uniaxial_stress_von_mises_is_the_stress() {
        let s = [120e6, 0.0, 0.0, 0.0, 0.0, 0.0];
        assert!((von_mises(&s) - 120e6).abs() < 1e-6);
    }

    #[test]
    fn pure_shear_von_mises_is_sqrt3_tau() {
        // sigma_vm = sqrt(3) tau for pure shear (textbook identity).
        let s = [0.0, 0.0, 0.0, 50e6, 0.0, 0.0];
        assert!((von_mises(&s) - 3f64.sqrt() * 50e6).abs() < 1e-6);
    }

    #[test]
    fn isotropic_stiffness_gives_hooke_in_uniaxial_stress() {
        // Uniaxial stress sigma: eps_xx = sigma/E, eps_yy = eps_zz = -nu sigma/E.
        let (e, nu, s) = (70e9, 0.3, 1e8);
        let c = isotropic_stiffness(e, nu);
        let eps = [s / e, -nu * s / e, -nu * s / e, 0.0, 0.0, 0.0];
        let sig = mat_vec(&c, &eps);
        assert!((sig[0] - s).abs() < 1e-3);
        assert!(sig[1].abs() < 1e-3 && sig[2].abs() < 1e-3);
        // Engineering shear: sigma_xy = G gamma_xy.
        let g = e / (2.0 * (1.0 + nu));
        let sig = mat_vec(&c, &[0.0, 0.0, 0.0, 1e-3, 0.0, 0.0]);
        assert!((sig[3] - g * 1e-3).abs() < 1e-3);
    }

    #[test]
    fn deviatoric_projector_matches_tensor_deviator() {
        let eps = [1.0, 2.0, -0.5, 0.4, -0.2, 0.6];
        let dev = mat_vec(&deviatoric_projector(), &eps);
        // tensor shear components are half the engineering ones
        let t = [1.0, 2.0, -0.5, 0.2, -0.1, 0.3];
        let expect = deviator(&t);
        for k in 0..6 {
            assert!((dev[k] - expect[k]).abs() < 1e-14);
        }
    }
}
