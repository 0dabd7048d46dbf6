//! Classical laminate theory (CLT): ply stiffness, ABD matrices, ply
//! stresses of a laminate in bending, and first-ply failure by the maximum
//! stress, Tsai–Wu and Hashin criteria.
//!
//! References: R. M. Jones, "Mechanics of Composite Materials", 2nd ed.
//! (Taylor & Francis, 1999), ch. 2 and 4 (Q, Q̄, ABD); S. W. Tsai and
//! E. M. Wu, "A general theory of strength for anisotropic materials",
//! J. Composite Materials 5 (1971) 58–80, with F12 = −½√(F11 F22) after
//! S. W. Tsai and H. T. Hahn, "Introduction to Composite Materials" (1980);
//! Z. Hashin, "Failure criteria for unidirectional fiber composites",
//! J. Applied Mechanics 47 (1980) 329–334 (plane-stress forms, below).
//!
//! # Conventions (cufem axes)
//!
//! - The laminate lies in the x–y plane: **y** is the span (the beam axis),
//!   **x** the width, **z** the thickness; plies are listed **bottom to top**,
//!   the laminate is centred on z = 0 (`z_0 = −h/2 … z_n = +h/2`).
//! - Ply angle θ: the rotation about +z from the **y axis toward the x axis**.
//!   The material axes are `e1 = (sin θ, cos θ, 0)` (fibre),
//!   `e2 = (−cos θ, sin θ, 0)`, `e3 = z`. A 0° ply has its fibre along the
//!   span y (then e2 = −x), a 90° ply along x (then e2 = +y). τ12 is taken
//!   on the (e1, e2) pair above; all criteria use τ12² only.
//! - In-plane laminate Voigt order is cufem's: `[xx, yy, xy]` for stresses
//!   `[σ_xx, σ_yy, τ_xy]` and engineering strains `[ε_xx, ε_yy, γ_xy]`;
//!   material order `[11, 22, 12]`. So the span bending stiffness is
//!   `D[1][1]` (= D_yy), not `D[0][0]`.
//! - `ε(z) = ε⁰ + z κ`, `N = ∫σ dz`, `M = ∫σ z dz` (per unit width). A
//!   positive `M_yy` gives a positive `κ_yy`: tension on top (z > 0).
//! - Stresses positive in tension; strengths are positive numbers.
#![allow(dead_code)]

/// A 3×3 matrix (row-major).
pub type M3 = [[f64; 3]; 3];

/// Orthotropic in-plane elastic constants of a ply (material axes).
#[derive(Clone, Copy, Debug)]
pub struct Lamina {
    /// Fibre modulus E1.
    pub e1: f64,
    /// Transverse modulus E2.
    pub e2: f64,
    /// Major Poisson ratio ν12 (ε2 = −ν12 σ1 / E1).
    pub nu12: f64,
    /// In-plane shear modulus G12.
    pub g12: f64,
}

/// One ply of a laminate.
#[derive(Clone, Copy, Debug)]
pub struct Ply {
    /// Thickness.
    pub thickness: f64,
    /// Angle θ from y toward x, degrees.
    pub angle_deg: f64,
    /// Elastic constants.
    pub material: Lamina,
}

/// Ply strengths (all positive): tension/compression along the fibre and
/// across it, in-plane shear, and transverse (2–3) shear for Hashin's
/// matrix-compression mode (S23 = Yc/2 is a common choice when unknown).
#[derive(Clone, Copy, Debug)]
pub struct Strengths {
    /// Fibre tensile strength Xt.
    pub xt: f64,
    /// Fibre compressive strength Xc.
    pub xc: f64,
    /// Transverse tensile strength Yt.
    pub yt: f64,
    /// Transverse compressive strength Yc.
    pub yc: f64,
    /// In-plane shear strength S12.
    pub s12: f64,
    /// Transverse shear strength S23 (Hashin matrix compression only).
    pub s23: f64,
}

/// Failure criterion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Criterion {
    /// Maximum stress.
    MaxStress,
    /// Tsai–Wu (F12 = −½√(F11 F22)).
    TsaiWu,
    /// Hashin 1980, plane stress, the smallest of the active modes.
    Hashin,
}

/// Laminate stiffness matrices in laminate axes (order xx, yy, xy).
#[derive(Clone, Copy, Debug)]
pub struct Abd {
    /// Extensional stiffness A = Σ Q̄ (z_k − z_{k−1}).
    pub a: M3,
    /// Coupling stiffness B = Σ Q̄ (z_k² − z_{k−1}²)/2.
    pub b: M3,
    /// Bending stiffness D = Σ Q̄ (z_k³ − z_{k−1}³)/3.
    pub d: M3,
}

/// Plane-stress (σ33 = 0) reduced stiffness in material axes, order
/// `[11, 22, 12]`: Q11 = E1/(1−ν12ν21), Q22 = E2/(1−ν12ν21),
/// Q12 = ν12 E2/(1−ν12ν21), Q66 = G12 (ν21 = ν12 E2/E1).
pub fn q_material(m: &Lamina) -> M3 {
    let nu21 = m.nu12 * m.e2 / m.e1;
    let den = 1.0 - m.nu12 * nu21;
    [[m.e1 / den, m.nu12 * m.e2 / den, 0.0], [m.nu12 * m.e2 / den, m.e2 / den, 0.0], [0.0, 0.0, m.g12]]
}

/// Strain transformation: `ε_mat = T ε_lam`, engineering strains,
/// laminate order `[xx, yy, xy]` → material order `[11, 22, 12]`.
pub fn strain_to_material(angle_deg: f64) -> M3 {
    let (s, c) = angle_deg.to_radians().sin_cos();
    let e1 = [s, c];
    let e2 = [-c, s];
    [
        [e1[0] * e1[0], e1[1] * e1[1], e1[0] * e1[1]],
        [e2[0] * e2[0], e2[1] * e2[1], e2[0] * e2[1]],
        [2.0 * e1[0] * e2[0], 2.0 * e1[1] * e2[1], e1[0] * e2[1] + e1[1] * e2[0]],
    ]
}

fn mul3(a: &M3, b: &M3) -> M3 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            for k in 0..3 {
                c[i][j] += a[i][k] * b[k][j];
            }
        }
    }
    c
}

fn mul3v(a: &M3, v: &[f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| a[i][0] * v[0] + a[i][1] * v[1] + a[i][2] * v[2])
}

fn transpose3(a: &M3) -> M3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[j][i]))
}

/// Transformed reduced stiffness in laminate axes (order xx, yy, xy):
/// `Q̄ = Tᵀ Q T` with T = [`strain_to_material`] (energy invariance).
pub fn q_bar(m: &Lamina, angle_deg: f64) -> M3 {
    let t = strain_to_material(angle_deg);
    mul3(&transpose3(&t), &mul3(&q_material(m), &t))
}

/// Ply interface heights `z_0 = −h/2 < … < z_n = h/2`.
pub fn interfaces(plies: &[Ply]) -> Vec<f64> {
    let h: f64 = plies.iter().map(|p| p.thickness).sum();
    let mut z = vec![-0.5 * h];
    for p in plies {
        z.push(z.last().unwrap() + p.thickness);
    }
    z
}

/// A, B, D of the laminate.
pub fn abd(plies: &[Ply]) -> Abd {
    let z = interfaces(plies);
    let mut r = Abd { a: [[0.0; 3]; 3], b: [[0.0; 3]; 3], d: [[0.0; 3]; 3] };
    for (k, p) in plies.iter().enumerate() {
        let q = q_bar(&p.material, p.angle_deg);
        let (z0, z1) = (z[k], z[k + 1]);
        for i in 0..3 {
            for j in 0..3 {
                r.a[i][j] += q[i][j] * (z1 - z0);
                r.b[i][j] += q[i][j] * (z1 * z1 - z0 * z0) / 2.0;
                r.d[i][j] += q[i][j] * (z1.powi(3) - z0.powi(3)) / 3.0;
            }
        }
    }
    r
}

/// The 6×6 `[[A, B], [B, D]]`: `[N; M] = ABD [ε⁰; κ]`.
pub fn abd_matrix(plies: &[Ply]) -> [[f64; 6]; 6] {
    let s = abd(plies);
    let mut m = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = s.a[i][j];
            m[i][j + 3] = s.b[i][j];
            m[i + 3][j] = s.b[i][j];
            m[i + 3][j + 3] = s.d[i][j];
        }
    }
    m
}

/// Dense `a x = b` (Gaussian elimination with partial pivoting), shared
/// with the Pagano oracle: a test binary including this file includes it too.
pub use super::pagano::gauss_solve;

/// Mid-plane strains and curvatures `(ε⁰, κ)` under the resultants
/// `n = [N_xx, N_yy, N_xy]`, `m = [M_xx, M_yy, M_xy]` (per unit width):
/// the inverse of the full ABD.
pub fn midplane_response(plies: &[Ply], n: [f64; 3], m: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let k = abd_matrix(plies);
    let x = gauss_solve(k.iter().map(|r| r.to_vec()).collect(), vec![n[0], n[1], n[2], m[0], m[1], m[2]]);
    ([x[0], x[1], x[2]], [x[3], x[4], x[5]])
}

/// Ply stresses in material axes `[σ11, σ22, τ12]` at the bottom and the top
/// of every ply for the mid-plane state (ε⁰, κ): entry `2k` is the bottom of
/// ply k, `2k + 1` its top, each as `(z, σ)`.
pub fn ply_stresses(plies: &[Ply], eps0: [f64; 3], kappa: [f64; 3]) -> Vec<(f64, [f64; 3])> {
    let z = interfaces(plies);
    let mut out = Vec::with_capacity(2 * plies.len());
    for (k, p) in plies.iter().enumerate() {
        let t = strain_to_material(p.angle_deg);
        let q = q_material(&p.material);
        for zz in [z[k], z[k + 1]] {
            let e = [0, 1, 2].map(|i| eps0[i] + zz * kappa[i]);
            out.push((zz, mul3v(&q, &mul3v(&t, &e))));
        }
    }
    out
}

/// Narrow beam (span y, width `width` along x) under a bending moment
/// `moment` (N·m) bending the span in the y–z plane: `M_yy = moment/width`,
/// every other resultant zero (N = 0, M_xx = M_xy = 0: anticlastic and twist
/// curvatures free), solved with the inverse of the full ABD. Returns the
/// ply stresses in material axes as [`ply_stresses`] does.
pub fn beam_bending_stresses(plies: &[Ply], width: f64, moment: f64) -> Vec<(f64, [f64; 3])> {
    let (e0, k) = midplane_response(plies, [0.0; 3], [0.0, moment / width, 0.0]);
    ply_stresses(plies, e0, k)
}

/// Effective bending stiffness EI of the narrow beam: `moment / κ_yy` =
/// `width / (ABD⁻¹)[4][4]`.
pub fn beam_bending_stiffness(plies: &[Ply], width: f64) -> f64 {
    let (_, k) = midplane_response(plies, [0.0; 3], [0.0, 1.0, 0.0]);
    width / k[1]
}

/// Cylindrical bending of a plate infinitely wide in x (plate version):
/// nothing depends on x, so `ε⁰_xx = κ_xx = κ_xy = 0`; the unknowns
/// `ε⁰_yy, γ⁰_xy, κ_yy` follow from `N_yy = N_xy = 0`,
/// `M_yy = moment_per_width`. Returns ply stresses as [`ply_stresses`].
pub fn plate_cylindrical_bending_stresses(plies: &[Ply], moment_per_width: f64) -> Vec<(f64, [f64; 3])> {
    let k = abd_matrix(plies);
    let (rows, cols) = ([1usize, 2, 4], [1usize, 2, 4]);
    let a = rows.iter().map(|&r| cols.iter().map(|&c| k[r][c]).collect()).collect();
    let x = gauss_solve(a, vec![0.0, 0.0, moment_per_width]);
    ply_stresses(plies, [0.0, x[0], x[1]], [0.0, x[2], 0.0])
}

/// Maximum stress index: the largest of σ11/Xt (or −σ11/Xc),
/// σ22/Yt (or −σ22/Yc), |τ12|/S12. Failure at 1.
pub fn max_stress_index(s: &[f64; 3], st: &Strengths) -> f64 {
    let f1 = if s[0] >= 0.0 { s[0] / st.xt } else { -s[0] / st.xc };
    let f2 = if s[1] >= 0.0 { s[1] / st.yt } else { -s[1] / st.yc };
    f1.max(f2).max(s[2].abs() / st.s12)
}

/// Tsai–Wu quadratic and linear parts `(a, b)` at σ:
/// `a = F11σ1² + F22σ2² + F66τ12² + 2F12σ1σ2`, `b = F1σ1 + F2σ2`, with
/// F1 = 1/Xt − 1/Xc, F11 = 1/(Xt Xc), F2 = 1/Yt − 1/Yc, F22 = 1/(Yt Yc),
/// F66 = 1/S12², F12 = −½√(F11 F22).
pub fn tsai_wu_parts(s: &[f64; 3], st: &Strengths) -> (f64, f64) {
    let f1 = 1.0 / st.xt - 1.0 / st.xc;
    let f2 = 1.0 / st.yt - 1.0 / st.yc;
    let f11 = 1.0 / (st.xt * st.xc);
    let f22 = 1.0 / (st.yt * st.yc);
    let f66 = 1.0 / (st.s12 * st.s12);
    let f12 = -0.5 * (f11 * f22).sqrt();
    let a = f11 * s[0] * s[0] + f22 * s[1] * s[1] + f66 * s[2] * s[2] + 2.0 * f12 * s[0] * s[1];
    (a, f1 * s[0] + f2 * s[1])
}

/// Tsai–Wu index `a + b` (failure at 1; not a load factor: see
/// [`strength_ratio`]).
pub fn tsai_wu_index(s: &[f64; 3], st: &Strengths) -> f64 {
    let (a, b) = tsai_wu_parts(s, st);
    a + b
}

/// Hashin (1980) plane-stress modes, as `(quadratic, linear)` parts of each
/// index, `[fibre tension, fibre compression, matrix tension, matrix
/// compression]`; a mode whose sign condition fails is `(0, 0)` (inactive):
/// - fibre tension (σ11 ≥ 0): `(σ11/Xt)² + (τ12/S12)²`;
/// - fibre compression (σ11 < 0): `(σ11/Xc)²` (Hashin's `|σ11| = Xc`);
/// - matrix tension (σ22 ≥ 0): `(σ22/Yt)² + (τ12/S12)²`;
/// - matrix compression (σ22 < 0): `(σ22/(2S23))² + (τ12/S12)²` quadratic,
///   `((Yc/(2S23))² − 1) σ22/Yc` linear.
pub fn hashin_parts(s: &[f64; 3], st: &Strengths) -> [(f64, f64); 4] {
    let t = (s[2] / st.s12).powi(2);
    let mut r = [(0.0, 0.0); 4];
    if s[0] >= 0.0 {
        r[0] = ((s[0] / st.xt).powi(2) + t, 0.0);
    } else {
        r[1] = ((s[0] / st.xc).powi(2), 0.0);
    }
    if s[1] >= 0.0 {
        r[2] = ((s[1] / st.yt).powi(2) + t, 0.0);
    } else {
        r[3] = ((s[1] / (2.0 * st.s23)).powi(2) + t, ((st.yc / (2.0 * st.s23)).powi(2) - 1.0) * s[1] / st.yc);
    }
    r
}

/// Hashin indices (quadratic + linear part) of the four modes, in the order
/// of [`hashin_parts`]; failure when one reaches 1.
pub fn hashin_indices(s: &[f64; 3], st: &Strengths) -> [f64; 4] {
    hashin_parts(s, st).map(|(a, b)| a + b)
}

/// The smallest positive R with `a R² + b R = 1` (∞ if none).
pub fn positive_root(a: f64, b: f64) -> f64 {
    if a == 0.0 {
        return if b > 0.0 { 1.0 / b } else { f64::INFINITY };
    }
    let disc = b * b + 4.0 * a;
    if disc < 0.0 {
        return f64::INFINITY;
    }
    // Roots (−b ± √disc)/(2a); the stable form 2/(b ± √disc) of the same roots.
    let roots = [2.0 / (b + disc.sqrt()), 2.0 / (b - disc.sqrt())];
    roots.into_iter().filter(|r| r.is_finite() && *r > 0.0).fold(f64::INFINITY, f64::min)
}

/// Strength ratio R at one point: the load multiplier at which the
/// criterion reaches 1 under proportional loading σ → Rσ (max stress:
/// 1/index; Tsai–Wu: positive root of a R² + b R − 1 = 0; Hashin: the
/// smallest such root over the active modes).
pub fn strength_ratio(s: &[f64; 3], st: &Strengths, c: Criterion) -> f64 {
    match c {
        Criterion::MaxStress => 1.0 / max_stress_index(s, st),
        Criterion::TsaiWu => {
            let (a, b) = tsai_wu_parts(s, st);
            positive_root(a, b)
        }
        Criterion::Hashin => {
            hashin_parts(s, st).iter().map(|&(a, b)| positive_root(a, b)).fold(f64::INFINITY, f64::min)
        }
    }
}

/// The criterion's index at σ: max-stress index, Tsai–Wu `a + b`, or the
/// largest Hashin mode index; each equals 1 at R·σ with R = [`strength_ratio`].
pub fn failure_index(s: &[f64; 3], st: &Strengths, c: Criterion) -> f64 {
    match c {
        Criterion::MaxStress => max_stress_index(s, st),
        Criterion::TsaiWu => tsai_wu_index(s, st),
        Criterion::Hashin => hashin_indices(s, st).into_iter().fold(f64::NEG_INFINITY, f64::max),
    }
}

/// First-ply failure factor over the evaluation points (e.g. the output of
/// [`beam_bending_stresses`]): the smallest strength ratio and the index of
/// the point where it occurs.
pub fn first_ply_failure_factor(points: &[(f64, [f64; 3])], st: &Strengths, c: Criterion) -> (f64, usize) {
    points
        .iter()
        .enumerate()
        .map(|(i, (_, s))| (strength_ratio(s, st, c), i))
        .fold((f64::INFINITY, usize::MAX), |best, x| if x.0 < best.0 { x } else { best })
}
