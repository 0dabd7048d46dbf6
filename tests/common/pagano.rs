//! Pagano's exact elasticity solution for the cylindrical bending of a
//! simply supported cross-ply laminate under a sinusoidal pressure.
//!
//! Reference: N. J. Pagano, "Exact solutions for composite laminates in
//! cylindrical bending", J. Composite Materials 3 (1969) 398–411.
//!
//! # Problem (cufem axes)
//!
//! - span along **y**, `0 ≤ y ≤ L`; thickness along **z**, `−h/2 ≤ z ≤ h/2`
//!   (plies listed bottom to top); **x** is the infinite direction: plane
//!   strain, `u_x = 0`, `ε_xx = 0` (σ_xx ≠ 0, see [`Pagano::sigma_xx`]);
//! - ends `y = 0, L`: diaphragm (`u_z = 0`, `σ_yy = 0` through the whole
//!   thickness; `u_y` free);
//! - top face `z = +h/2`: `σ_zz = −q0 sin(πy/L)` (pressure pushing toward
//!   −z), `τ_yz = 0`; bottom face traction-free;
//! - plies orthotropic, material axes 1 = fibre, 2 = in-plane transverse,
//!   3 = ply normal = z; a 0° ply has its fibre along y (the span), a 90° ply
//!   along x. Only 0° and 90° plies: the problem stays in the y–z plane.
//!
//! Signs: stresses positive in tension, `τ_yz = σ_yz`, engineering strains
//! (`γ_yz = ∂u_y/∂z + ∂u_z/∂y`), stresses returned in cufem's Voigt order for
//! the y–z plane: `[σ_yy, σ_zz, τ_yz]`.
//!
//! # Method: state space (transfer matrix), exact
//!
//! With `p = π/L`, every field separates:
//! `u_y = U(z) cos py`, `u_z = W(z) sin py`, `τ_yz = T(z) cos py`,
//! `σ_zz = N(z) sin py`, `σ_yy = Σ(z) sin py`, which meets the end conditions
//! exactly. Eliminating σ_xx with `ε_xx = 0` (plane-strain reduced compliance
//! `R_ij = S_ij − S_ix S_jx / S_xx`, i, j ∈ {y, z}) and inverting gives the
//! 2×2 stiffness `[σ_yy, σ_zz] = C [ε_yy, ε_zz]`; with `τ_yz = G γ_yz`
//! (G = G13 in a 0° ply, G23 in a 90° ply), strain–displacement and the two
//! equilibrium equations become, in each ply, the constant-coefficient system
//!
//! ```text
//! U' = −p W + T/G
//! W' = p (C_yz/C_zz) U + N/C_zz
//! T' = p² (C_yy − C_yz²/C_zz) U − p (C_yz/C_zz) N      (from ∂σ_yy/∂y + ∂τ_yz/∂z = 0)
//! N' = p T                                           (from ∂τ_yz/∂y + ∂σ_zz/∂z = 0)
//! Σ  = −p (C_yy − C_yz²/C_zz) U + (C_yz/C_zz) N
//! ```
//!
//! Written for the dimensionless state `s = [pU, pW, T/E, N/E]` against
//! `ξ = p z` (E a reference modulus), `ds/dξ = A s`, the state is carried
//! through each ply by the exact transfer matrix `exp(A p t)` (matrix
//! exponential by scaling and squaring with a 30-term Taylor series: the
//! scaled norm is below 1/4, so the series is exact to rounding). Continuity
//! of `u_y, u_z, τ_yz, σ_zz` at the interfaces is built in (the state is
//! continuous); the two unknowns `U, W` at the bottom face (where `T = N = 0`)
//! follow from `T = 0`, `N = −q0` at the top face (2×2 system, Gaussian
//! elimination with partial pivoting). This is the same solution as Pagano's
//! (his exponentials `exp(m z)` from the characteristic quartic are the
//! eigen-modes of `A`), computed without the eigen-decomposition.
#![allow(dead_code)]

use std::f64::consts::PI;

/// One orthotropic ply (engineering constants in material axes 1 = fibre,
/// 2 = in-plane transverse, 3 = normal), SI units or any consistent set.
/// `nu_ij` is the Poisson ratio for a stress along i (`ε_j = −ν_ij σ_i / E_i`).
#[derive(Clone, Copy, Debug)]
pub struct Ply {
    /// Ply thickness.
    pub thickness: f64,
    /// Modulus along the fibre.
    pub e1: f64,
    /// In-plane transverse modulus.
    pub e2: f64,
    /// Through-thickness modulus.
    pub e3: f64,
    /// In-plane shear modulus.
    pub g12: f64,
    /// Transverse shear modulus in the fibre–normal plane.
    pub g13: f64,
    /// Transverse shear modulus in the transverse–normal plane.
    pub g23: f64,
    /// Major in-plane Poisson ratio.
    pub nu12: f64,
    /// Poisson ratio 1–3.
    pub nu13: f64,
    /// Poisson ratio 2–3.
    pub nu23: f64,
    /// Fibre angle from the span y toward x: 0 (fibre along y) or 90 (along x).
    pub angle_deg: f64,
}

impl Ply {
    /// A ply of Pagano's (1969) material, in units of `e2`: E_L/E_T = 25,
    /// E_3 = E_T, G_LT = G_LN = 0.5 E_T, G_TN = 0.2 E_T, every ν = 0.25.
    pub fn pagano(thickness: f64, angle_deg: f64, e2: f64) -> Self {
        Ply {
            thickness,
            e1: 25.0 * e2,
            e2,
            e3: e2,
            g12: 0.5 * e2,
            g13: 0.5 * e2,
            g23: 0.2 * e2,
            nu12: 0.25,
            nu13: 0.25,
            nu23: 0.25,
            angle_deg,
        }
    }

    /// An isotropic layer (E, ν) written as a ply.
    pub fn isotropic(thickness: f64, e: f64, nu: f64) -> Self {
        let g = e / (2.0 * (1.0 + nu));
        Ply { thickness, e1: e, e2: e, e3: e, g12: g, g13: g, g23: g, nu12: nu, nu13: nu, nu23: nu, angle_deg: 0.0 }
    }
}

/// Per-ply constants in the y–z plane.
#[derive(Clone, Copy, Debug)]
struct Layer {
    z0: f64,
    z1: f64,
    /// Plane-strain (ε_xx = 0) stiffness: σ_yy = c_yy ε_yy + c_yz ε_zz, σ_zz = c_yz ε_yy + c_zz ε_zz.
    c_yy: f64,
    c_yz: f64,
    c_zz: f64,
    /// Transverse shear modulus τ_yz = g γ_yz.
    g: f64,
    /// Full 3D compliances needed for σ_xx = −(s_xy σ_yy + s_xz σ_zz)/s_xx.
    s_xx: f64,
    s_xy: f64,
    s_xz: f64,
    /// Dimensionless state matrix A (ds/dξ = A s, s = [pU, pW, T/E, N/E]).
    a: [[f64; 4]; 4],
    /// Dimensionless state at the bottom of the ply.
    s0: [f64; 4],
}

/// Pagano's exact cylindrical-bending solution of one laminate and load.
#[derive(Clone, Debug)]
pub struct Pagano {
    layers: Vec<Layer>,
    span: f64,
    q0: f64,
    p: f64,
    e_ref: f64,
    h: f64,
}

type M4 = [[f64; 4]; 4];

fn mat_mul(a: &M4, b: &M4) -> M4 {
    let mut c = [[0.0; 4]; 4];
    for i in 0..4 {
        for k in 0..4 {
            for j in 0..4 {
                c[i][j] += a[i][k] * b[k][j];
            }
        }
    }
    c
}

fn mat_vec(a: &M4, v: &[f64; 4]) -> [f64; 4] {
    let mut r = [0.0; 4];
    for i in 0..4 {
        for j in 0..4 {
            r[i] += a[i][j] * v[j];
        }
    }
    r
}

/// `exp(a t)` by scaling and squaring with a Taylor series.
fn expm(a: &M4, t: f64) -> M4 {
    let norm = (0..4).map(|j| (0..4).map(|i| (a[i][j] * t).abs()).sum::<f64>()).fold(0.0, f64::max);
    let mut squarings = 0;
    let mut scale = t;
    while norm * (scale / t).abs() > 0.25 {
        scale *= 0.5;
        squarings += 1;
    }
    let mut m = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            m[i][j] = a[i][j] * scale;
        }
    }
    let mut e = [[0.0; 4]; 4];
    let mut term = [[0.0; 4]; 4];
    for i in 0..4 {
        e[i][i] = 1.0;
        term[i][i] = 1.0;
    }
    for k in 1..=30 {
        term = mat_mul(&term, &m);
        for i in 0..4 {
            for j in 0..4 {
                term[i][j] /= k as f64;
                e[i][j] += term[i][j];
            }
        }
    }
    for _ in 0..squarings {
        e = mat_mul(&e, &e);
    }
    e
}

/// Solves the dense system `a x = b` by Gaussian elimination with partial
/// pivoting (n = a.len()); panics on a singular matrix.
pub fn gauss_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let piv = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs())).unwrap();
        assert!(a[piv][k] != 0.0, "singular system");
        a.swap(k, piv);
        b.swap(k, piv);
        for i in k + 1..n {
            let f = a[i][k] / a[k][k];
            for j in k..n {
                a[i][j] -= f * a[k][j];
            }
            b[i] -= f * b[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| a[k][j] * x[j]).sum();
        x[k] = (b[k] - s) / a[k][k];
    }
    x
}

/// 3D normal compliances in the (x, y, z) laminate axes and the transverse
/// shear modulus G_yz of a 0° or 90° ply.
fn compliances(ply: &Ply) -> ([[f64; 3]; 3], f64) {
    // Material-axis compliance (1, 2, 3).
    let m = [
        [1.0 / ply.e1, -ply.nu12 / ply.e1, -ply.nu13 / ply.e1],
        [-ply.nu12 / ply.e1, 1.0 / ply.e2, -ply.nu23 / ply.e2],
        [-ply.nu13 / ply.e1, -ply.nu23 / ply.e2, 1.0 / ply.e3],
    ];
    // Laminate axis (x, y, z) -> material axis index.
    let (map, g) = if ply.angle_deg.abs() < 1e-9 {
        ([1, 0, 2], ply.g13) // x = 2, y = 1 (fibre), z = 3
    } else if (ply.angle_deg.abs() - 90.0).abs() < 1e-9 {
        ([0, 1, 2], ply.g23) // x = 1 (fibre), y = 2, z = 3
    } else {
        panic!("Pagano cylindrical bending: only 0° and 90° plies (got {}°)", ply.angle_deg)
    };
    let mut s = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            s[i][j] = m[map[i]][map[j]];
        }
    }
    (s, g)
}

impl Pagano {
    /// Builds the solution for `plies` listed bottom to top (the laminate is
    /// centred on z = 0), span `span`, load amplitude `q0` (> 0 pushes down).
    pub fn new(plies: &[Ply], span: f64, q0: f64) -> Self {
        assert!(!plies.is_empty() && span > 0.0);
        let p = PI / span;
        let h: f64 = plies.iter().map(|k| k.thickness).sum();
        let e_ref = plies.iter().map(|k| k.e2).fold(0.0, f64::max);
        let mut layers = Vec::with_capacity(plies.len());
        let mut z = -0.5 * h;
        for ply in plies {
            let (s, g) = compliances(ply);
            // Plane-strain reduced compliance over (y, z).
            let r = |i: usize, j: usize| s[i][j] - s[i][0] * s[j][0] / s[0][0];
            let (ryy, ryz, rzz) = (r(1, 1), r(1, 2), r(2, 2));
            let det = ryy * rzz - ryz * ryz;
            let (c_yy, c_yz, c_zz) = (rzz / det, -ryz / det, ryy / det);
            let cb = c_yy - c_yz * c_yz / c_zz;
            let a = [
                [0.0, -1.0, e_ref / g, 0.0],
                [c_yz / c_zz, 0.0, 0.0, e_ref / c_zz],
                [cb / e_ref, 0.0, 0.0, -c_yz / c_zz],
                [0.0, 0.0, 1.0, 0.0],
            ];
            layers.push(Layer {
                z0: z,
                z1: z + ply.thickness,
                c_yy,
                c_yz,
                c_zz,
                g,
                s_xx: s[0][0],
                s_xy: s[0][1],
                s_xz: s[0][2],
                a,
                s0: [0.0; 4],
            });
            z += ply.thickness;
        }
        // Transfer of the two bottom unknowns (pU, pW) to the top.
        let mut cols = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]];
        let transfers: Vec<M4> = layers.iter().map(|l| expm(&l.a, p * (l.z1 - l.z0))).collect();
        for t in &transfers {
            for c in cols.iter_mut() {
                *c = mat_vec(t, c);
            }
        }
        let x = gauss_solve(vec![vec![cols[0][2], cols[1][2]], vec![cols[0][3], cols[1][3]]], vec![0.0, -q0 / e_ref]);
        let mut s = [x[0], x[1], 0.0, 0.0];
        for (l, t) in layers.iter_mut().zip(&transfers) {
            l.s0 = s;
            s = mat_vec(t, &s);
        }
        Pagano { layers, span, q0, p, e_ref, h }
    }

    /// Total thickness h.
    pub fn thickness(&self) -> f64 {
        self.h
    }

    /// Span L.
    pub fn span(&self) -> f64 {
        self.span
    }

    /// Load amplitude q0.
    pub fn load(&self) -> f64 {
        self.q0
    }

    /// Interface heights z_0 = −h/2 < z_1 < … < z_n = h/2.
    pub fn interfaces(&self) -> Vec<f64> {
        let mut z = vec![self.layers[0].z0];
        z.extend(self.layers.iter().map(|l| l.z1));
        z
    }

    /// The ply containing z (an interface belongs to the ply above it, the
    /// top face to the top ply; z is clamped to the laminate).
    pub fn ply_at(&self, z: f64) -> usize {
        self.layers.iter().position(|l| z < l.z1).unwrap_or(self.layers.len() - 1)
    }

    /// Amplitudes `[U, W, T, N, Σ]` at z in ply `k` (z may be on its faces):
    /// `u_y = U cos py`, `u_z = W sin py`, `τ_yz = T cos py`,
    /// `σ_zz = N sin py`, `σ_yy = Σ sin py`.
    pub fn amplitudes_in_ply(&self, k: usize, z: f64) -> [f64; 5] {
        let l = &self.layers[k];
        let s = mat_vec(&expm(&l.a, self.p * (z - l.z0)), &l.s0);
        let (u, w, t, n) = (s[0] / self.p, s[1] / self.p, s[2] * self.e_ref, s[3] * self.e_ref);
        let sig = -self.p * (l.c_yy - l.c_yz * l.c_yz / l.c_zz) * u + l.c_yz / l.c_zz * n;
        [u, w, t, n, sig]
    }

    /// Displacements `[u_y, u_z]` at (y, z).
    pub fn displacement(&self, y: f64, z: f64) -> [f64; 2] {
        self.displacement_in_ply(self.ply_at(z), y, z)
    }

    /// Displacements `[u_y, u_z]` at (y, z), z taken in ply `k`.
    pub fn displacement_in_ply(&self, k: usize, y: f64, z: f64) -> [f64; 2] {
        let a = self.amplitudes_in_ply(k, z);
        [a[0] * (self.p * y).cos(), a[1] * (self.p * y).sin()]
    }

    /// Stresses `[σ_yy, σ_zz, τ_yz]` at (y, z) (σ_yy jumps at the
    /// interfaces: see [`Pagano::stress_in_ply`] to pick the side).
    pub fn stress(&self, y: f64, z: f64) -> [f64; 3] {
        self.stress_in_ply(self.ply_at(z), y, z)
    }

    /// Stresses `[σ_yy, σ_zz, τ_yz]` at (y, z), z taken in ply `k`.
    pub fn stress_in_ply(&self, k: usize, y: f64, z: f64) -> [f64; 3] {
        let a = self.amplitudes_in_ply(k, z);
        let (s, c) = (self.p * y).sin_cos();
        [a[4] * s, a[3] * s, a[2] * c]
    }

    /// Out-of-plane normal stress σ_xx (plane strain ε_xx = 0) at (y, z).
    pub fn sigma_xx(&self, y: f64, z: f64) -> f64 {
        self.sigma_xx_in_ply(self.ply_at(z), y, z)
    }

    /// σ_xx at (y, z), z taken in ply `k`.
    pub fn sigma_xx_in_ply(&self, k: usize, y: f64, z: f64) -> f64 {
        let l = &self.layers[k];
        let s = self.stress_in_ply(k, y, z);
        -(l.s_xy * s[0] + l.s_xz * s[1]) / l.s_xx
    }

    /// Engineering strains `[ε_yy, ε_zz, γ_yz]` at (y, z) in ply `k`, from the
    /// stresses through the ply's plane-strain compliance.
    pub fn strain_in_ply(&self, k: usize, y: f64, z: f64) -> [f64; 3] {
        let l = &self.layers[k];
        let s = self.stress_in_ply(k, y, z);
        let det = l.c_yy * l.c_zz - l.c_yz * l.c_yz;
        [(l.c_zz * s[0] - l.c_yz * s[1]) / det, (l.c_yy * s[1] - l.c_yz * s[0]) / det, s[2] / l.g]
    }
}
