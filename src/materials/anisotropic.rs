//! Anisotropic linear elasticity: orthotropic engineering constants, a full
//! 6×6 stiffness, material frames and the rotation of stiffness and stress
//! between the material axes (1, 2, 3) and the global axes (x, y, z).
//!
//! Both frames use the crate's Voigt order and shear convention
//! ([`crate::voigt`]): material components are stored as
//! `(11, 22, 33, 12, 13, 23)` with engineering shear strains.
//!
//! # Orthotropic compliance
//!
//! With the engineering constants of the material axes (Jones, *Mechanics
//! of Composite Materials*, 2nd ed., eq. 2.54; `ν_ij/E_i = ν_ji/E_j`):
//!
//! ```text
//! ε11 = σ11/E1 − ν21 σ22/E2 − ν31 σ33/E3      γ12 = τ12/G12
//! ε22 = −ν12 σ11/E1 + σ22/E2 − ν32 σ33/E3     γ13 = τ13/G13
//! ε33 = −ν13 σ11/E1 − ν23 σ22/E2 + σ33/E3     γ23 = τ23/G23
//! ```
//!
//! The stiffness is the inverse of this symmetric compliance; the constants
//! are admissible exactly when the compliance is positive definite (Jones
//! §2.4.1: `1 − ν12ν21 − ν23ν32 − ν31ν13 − 2ν21ν32ν13 > 0` among others),
//! which `positive_definite` tests by a Cholesky factorization.
//!
//! # Rotation
//!
//! A [`Frame`] holds the material axes `e1, e2, e3` as unit vectors in global
//! coordinates (rows of the rotation `R`). A strain tensor rotates as
//! `ε_m = R ε Rᵀ`; in Voigt form with engineering shears `ε_m = T ε` (the
//! matrix `Frame::strain_rotation`). Equal work `σ·ε = σ_m·ε_m` gives
//! `σ = Tᵀ σ_m`, hence the global stiffness `C = Tᵀ C_m T` (symmetric and
//! positive definite with `C_m`), and `σ_m = R σ Rᵀ`.

use crate::voigt::{Matrix6, Voigt};

/// Orthotropic engineering constants in the material axes (Pa and −).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orthotropic {
    /// Young's moduli `E1, E2, E3`.
    pub young: [f64; 3],
    /// Shear moduli `G12, G13, G23`.
    pub shear: [f64; 3],
    /// Poisson's ratios `ν12, ν13, ν23` (`ν_ij`: contraction along j under stress along i).
    pub poisson: [f64; 3],
}

impl Orthotropic {
    /// The compliance `S = C⁻¹` in the material axes (engineering shear).
    pub fn compliance(&self) -> Matrix6 {
        let [e1, e2, e3] = self.young;
        let [g12, g13, g23] = self.shear;
        let [n12, n13, n23] = self.poisson;
        let mut s = [[0.0; 6]; 6];
        s[0][0] = 1.0 / e1;
        s[1][1] = 1.0 / e2;
        s[2][2] = 1.0 / e3;
        s[0][1] = -n12 / e1;
        s[0][2] = -n13 / e1;
        s[1][2] = -n23 / e2;
        s[1][0] = s[0][1];
        s[2][0] = s[0][2];
        s[2][1] = s[1][2];
        s[3][3] = 1.0 / g12;
        s[4][4] = 1.0 / g13;
        s[5][5] = 1.0 / g23;
        s
    }

    /// The stiffness in the material axes, `None` if the constants are not
    /// admissible (compliance not positive definite).
    pub fn stiffness(&self) -> Option<Matrix6> {
        let s = self.compliance();
        if !positive_definite(&s) {
            return None;
        }
        invert(&s)
    }
}

/// The lower Cholesky factor of a symmetric 6×6 matrix, `None` unless it is
/// positive definite (pivots above 1e-12 of the largest diagonal entry, so
/// a matrix singular to round-off is refused too).
fn cholesky(a: &Matrix6) -> Option<Matrix6> {
    let scale = (0..6).map(|i| a[i][i].abs()).fold(0.0, f64::max);
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    let mut l = [[0.0; 6]; 6];
    for j in 0..6 {
        let d = a[j][j] - (0..j).map(|k| l[j][k] * l[j][k]).sum::<f64>();
        if !(d > 1e-12 * scale) {
            return None;
        }
        l[j][j] = d.sqrt();
        for i in j + 1..6 {
            l[i][j] = (a[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>()) / l[j][j];
        }
    }
    Some(l)
}

/// True if the symmetric part of `a` equals `a` (to 1e-9 of its largest
/// entry) and `a` is positive definite.
pub(crate) fn positive_definite(a: &Matrix6) -> bool {
    let big = a.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let symmetric = (0..6).all(|i| (0..i).all(|j| (a[i][j] - a[j][i]).abs() <= 1e-9 * big));
    symmetric && cholesky(a).is_some()
}

/// The inverse of a symmetric positive definite 6×6 matrix (by Cholesky),
/// `None` otherwise.
pub fn invert(a: &Matrix6) -> Option<Matrix6> {
    let l = cholesky(a)?;
    let mut inv = [[0.0; 6]; 6];
    for c in 0..6 {
        // L y = e_c, then Lᵀ x = y
        let mut y = [0.0; 6];
        for i in 0..6 {
            let rhs = if i == c { 1.0 } else { 0.0 };
            y[i] = (rhs - (0..i).map(|k| l[i][k] * y[k]).sum::<f64>()) / l[i][i];
        }
        for i in (0..6).rev() {
            let x = (y[i] - (i + 1..6).map(|k| l[k][i] * inv[k][c]).sum::<f64>()) / l[i][i];
            inv[i][c] = x;
        }
    }
    Some(inv)
}

/// Material axes as unit vectors in global coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// `axes[i]` is `e_{i+1}` (rows of the rotation `R`, `x_m = R x`).
    pub axes: [[f64; 3]; 3],
}

impl Default for Frame {
    /// The global axes: `e1 = x, e2 = y, e3 = z`.
    fn default() -> Self {
        Self { axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] }
    }
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

impl Frame {
    /// The frame of a ply: `e3` along `normal`, `e1` the direction `fibre`
    /// (made orthogonal to the normal) turned by `angle` (radians) about
    /// `e3` (right-handed), `e2 = e3 × e1`. `None` if a vector is zero or
    /// the fibre is parallel to the normal.
    pub fn ply(fibre: [f64; 3], normal: [f64; 3], angle: f64) -> Option<Self> {
        let nn = norm(normal);
        if !(nn > 0.0 && nn.is_finite()) {
            return None;
        }
        let e3 = normal.map(|v| v / nn);
        let d: f64 = (0..3).map(|k| fibre[k] * e3[k]).sum();
        let f = [fibre[0] - d * e3[0], fibre[1] - d * e3[1], fibre[2] - d * e3[2]];
        let nf = norm(f);
        if !(nf > 1e-9 * norm(fibre) && nf.is_finite()) {
            return None;
        }
        let a = f.map(|v| v / nf);
        let b = cross(e3, a);
        let (s, c) = angle.sin_cos();
        let e1 = [c * a[0] + s * b[0], c * a[1] + s * b[1], c * a[2] + s * b[2]];
        Some(Self { axes: [e1, cross(e3, e1), e3] })
    }

    /// `T` with `ε_m = T ε` for strains in Voigt form with engineering shears.
    pub(crate) fn strain_rotation(&self) -> Matrix6 {
        // (i, j) of each Voigt index in this crate's order
        const IJ: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
        let r = &self.axes;
        let mut t = [[0.0; 6]; 6];
        for (a, &(i, j)) in IJ.iter().enumerate() {
            for (b, &(k, l)) in IJ.iter().enumerate() {
                // ε_m,ij = R_ik R_jl ε_kl; a Voigt shear column b (k ≠ l)
                // carries γ_kl = 2 ε_kl, once for (k, l) and once for (l, k)
                let m = if k == l { r[i][k] * r[j][l] } else { 0.5 * (r[i][k] * r[j][l] + r[i][l] * r[j][k]) };
                // a shear row a stores γ_ij = 2 ε_ij
                t[a][b] = if i == j { m } else { 2.0 * m };
            }
        }
        t
    }

    /// The global stiffness `C = Tᵀ C_m T` of a stiffness given in this frame.
    pub fn stiffness_to_global(&self, material: &Matrix6) -> Matrix6 {
        let t = self.strain_rotation();
        let mut ct = [[0.0; 6]; 6];
        for i in 0..6 {
            for j in 0..6 {
                ct[i][j] = (0..6).map(|k| material[i][k] * t[k][j]).sum();
            }
        }
        let mut c = [[0.0; 6]; 6];
        for i in 0..6 {
            for j in 0..6 {
                c[i][j] = (0..6).map(|k| t[k][i] * ct[k][j]).sum();
            }
        }
        // exactly symmetric (the factorization relies on it)
        for i in 0..6 {
            for j in 0..i {
                let m = 0.5 * (c[i][j] + c[j][i]);
                c[i][j] = m;
                c[j][i] = m;
            }
        }
        c
    }

    /// A global stress in the material axes, `σ_m = R σ Rᵀ` (Voigt, tensor shears).
    pub(crate) fn stress_to_material(&self, s: &Voigt) -> Voigt {
        let sig = crate::voigt::stress_tensor(s);
        let r = &self.axes;
        let mut m = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] = (0..3).map(|k| (0..3).map(|l| r[i][k] * sig[k][l] * r[j][l]).sum::<f64>()).sum();
            }
        }
        [m[0][0], m[1][1], m[2][2], m[0][1], m[0][2], m[1][2]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voigt::{isotropic_stiffness, mat_vec};

    /// A carbon/epoxy ply (Pagano's ratios: E1/E2 = 25, G12 = G13 = 0.5 E2, G23 = 0.2 E2, ν = 0.25).
    fn pagano() -> Orthotropic {
        let e2 = 1e9;
        Orthotropic { young: [25.0 * e2, e2, e2], shear: [0.5 * e2, 0.5 * e2, 0.2 * e2], poisson: [0.25; 3] }
    }

    #[test]
    fn isotropic_constants_give_the_isotropic_stiffness() {
        // the orthotropic path with E, G = E/(2(1+ν)), ν in every direction
        // against voigt::isotropic_stiffness (Lamé form): to round-off
        let (e, nu) = (70e9, 0.3);
        let g = e / (2.0 * (1.0 + nu));
        let c = Orthotropic { young: [e; 3], shear: [g; 3], poisson: [nu; 3] }.stiffness().unwrap();
        let iso = isotropic_stiffness(e, nu);
        for i in 0..6 {
            for j in 0..6 {
                assert!((c[i][j] - iso[i][j]).abs() <= 1e-12 * e, "{i},{j}: {} vs {}", c[i][j], iso[i][j]);
            }
        }
    }

    #[test]
    fn inadmissible_constants_are_refused() {
        // ν12 ν21 ≥ 1 (here ν12 = 6 with E1/E2 = 25 gives ν21 = 0.24, product 1.44)
        let mut m = pagano();
        m.poisson[0] = 6.0;
        assert!(m.stiffness().is_none());
        // a negative shear modulus
        let mut m = pagano();
        m.shear[2] = -1.0;
        assert!(m.stiffness().is_none());
        assert!(pagano().stiffness().is_some());
    }

    #[test]
    fn compliance_inverts_stiffness() {
        let m = pagano();
        let c = m.stiffness().unwrap();
        let s = m.compliance();
        for i in 0..6 {
            for j in 0..6 {
                let p: f64 = (0..6).map(|k| c[i][k] * s[k][j]).sum();
                assert!((p - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn rotation_of_stiffness_is_work_conjugate_and_positive_definite() {
        // for any angle the global stiffness is positive definite, and a
        // global strain's stress in material axes equals C_m (T ε)
        let cm = pagano().stiffness().unwrap();
        for k in 0..24 {
            let angle = k as f64 * std::f64::consts::PI / 12.0 + 0.1;
            let f = Frame::ply([0.3, 1.0, 0.2], [0.1, -0.2, 1.0], angle).unwrap();
            let c = f.stiffness_to_global(&cm);
            assert!(positive_definite(&c), "angle {angle}");
            let eps = [1e-3, -2e-4, 5e-4, 3e-4, -1e-4, 2e-4];
            let sg = mat_vec(&c, &eps);
            let sm = mat_vec(&cm, &mat_vec(&f.strain_rotation(), &eps));
            let back = f.stress_to_material(&sg);
            for i in 0..6 {
                assert!((back[i] - sm[i]).abs() < 1e-9 * cm[0][0] * 1e-3, "angle {angle}, {i}");
            }
        }
    }

    #[test]
    fn a_ply_at_90_degrees_swaps_the_in_plane_axes() {
        // fibre along y at 0°; turned by 90° about z it lies along −x
        let f = Frame::ply([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_2).unwrap();
        let e1 = f.axes[0];
        assert!((e1[0] + 1.0).abs() < 1e-15 && e1[1].abs() < 1e-15);
        let c = f.stiffness_to_global(&pagano().stiffness().unwrap());
        let c0 = Frame::ply([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], 0.0)
            .unwrap()
            .stiffness_to_global(&pagano().stiffness().unwrap());
        // the fibre stiffness moved from C_yy to C_xx
        assert!((c[0][0] - c0[1][1]).abs() < 1e-6 * c0[1][1]);
        assert!((c[1][1] - c0[0][0]).abs() < 1e-6 * c0[1][1]);
        assert!(Frame::ply([0.0, 0.0, 1.0], [0.0, 0.0, 2.0], 0.0).is_none());
    }
}
