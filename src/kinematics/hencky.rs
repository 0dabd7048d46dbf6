//! The logarithmic (Hencky) strain of the total-Lagrangian formulation
//! (`analysis.strain = "logarithmic"`), and the pull-back of the stress it
//! is conjugate to: finite-strain elastoplasticity with the unchanged
//! small-strain return map.
//!
//! Miehe, Apel & Lambrecht, *Anisotropic additive plasticity in the
//! logarithmic strain space*, CMAME 191 (2002) 5383–5425 (§2–§4; for an
//! isotropic material the additive split of `E_log` into elastic and
//! plastic parts reproduces multiplicative J2 plasticity with exponential
//! integration, Simo, CMAME 99 (1992) 61–112, and Eterovic & Bathe 1990):
//!
//! ```text
//! C = Fᵀ F = I + 2E                           E the Green–Lagrange strain
//! E_log = ½ ln C = Σ_i ½ ln c_i  N_i ⊗ N_i       c_i, N_i: eigenpairs of C
//! (T, D, state) = material(E_log, history)     the small-strain J2 point, unchanged:
//!                                              T conjugate to E_log, D = ∂T/∂E_log,
//!                                              plastic strain stored in log space
//! S = T : L,   L = ∂E_log/∂E                   second Piola–Kirchhoff stress
//! ∂S/∂E = Lᵀ D L + T : ∂²E_log/∂E²             its tangent
//! ```
//!
//! **The derivatives, by divided differences.** `E_log = f(C)` with the
//! scalar `f(c) = ½ ln c` applied to the eigenvalues. In the eigenframe of
//! `C` (components `Ã = Qᵀ A Q`) the first and second derivatives of such an
//! isotropic tensor function are (Daleckii–Krein; Bhatia, *Matrix
//! Analysis*, §V.3)
//!
//! ```text
//! (Df[H])~_ij      = f[c_i, c_j] H̃_ij
//! (D²f[H, K])~_ij  = Σ_k f[c_i, c_k, c_j] (H̃_ik K̃_kj + K̃_ik H̃_kj)
//! ```
//!
//! with the divided differences `f[a, b] = (f(a) − f(b))/(a − b)`,
//! `f[a, b, c] = (f[a, b] − f[b, c])/(a − c)` and their confluent limits
//! (`f[a, a] = f'(a)`, `f[a, a, a] = f''(a)/2`). Since `dC = 2 dE`:
//! `L̃ = 2 f[c_i, c_j]` on the component `ij` (so `S̃_ij = 2 f[c_i, c_j] T̃_ij`)
//! and `T : ∂²E_log/∂E²[H, K] = 4 T̃ : D²f[H̃, K̃]` — for any `T`, coaxial with
//! `C` or not (a non-proportional plastic history makes it non-coaxial).
//!
//! **Equal and nearly equal eigenvalues** (uniaxial tension has two equal
//! stretches; the undeformed state three) have no special case beyond the
//! divided differences themselves, computed without cancellation:
//! `f[a, b] = artanh(r)/(a − b)` with `r = (a − b)/(c_a + c_b)` (exact, since
//! `ln(c_a/c_b) = 2 artanh r`), by its series `(1 + r²/3 + r⁴/5 + r⁶/7)/(c_a + c_b)`
//! for `|r| < 10⁻³`; `f[a, b, c]` from the two first differences of the
//! outermost pairs (largest minus smallest eigenvalue in the denominator),
//! and, when all three lie within `2·10⁻³` of their mean `m`, by the Taylor
//! series of divided differences
//! `f[c_0, c_1, c_2] = −1/(2m²) Σ_n (−1)ⁿ h_n(δ)/(n + 2)`, `δ_i = (c_i − m)/m`,
//! `h_n` the complete homogeneous symmetric polynomials, to `n = 6`.
//! The formulas are invariant to the choice of eigenvectors within a
//! repeated eigenvalue, so the eigensolver (cyclic Jacobi on `2E = C − I`,
//! which keeps small strains accurate) needs no care there either.
//!
//! Tensors are handled in the orthonormal Mandel basis in the eigenframe and
//! rotated back; the inputs and outputs follow [`crate::voigt`] (engineering
//! shear strains, tensor shear stresses).

use super::{Tensor, green_lagrange};
use crate::voigt::{Matrix6, Voigt};
use std::f64::consts::FRAC_1_SQRT_2;

/// The Mandel components: index pairs of the six basis tensors.
const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];

/// The non-zero terms `(a, b, i, k, j, c)` of `Σ_ijk T̃_ij f[c_i, c_k, c_j]
/// (H_ik K_kj + K_ik H_kj)` for the Mandel basis tensors `H = B_a`,
/// `K = B_b`, `a ≤ b`: `c` the product of their entries `H_ik K_kj` (36
/// terms of the 6 · 7/2 pairs' 4 · 4 index products).
const SECOND_TERMS: [(usize, usize, usize, usize, usize, f64); 36] = second_terms();

/// Builds [`SECOND_TERMS`].
const fn second_terms() -> [(usize, usize, usize, usize, usize, f64); 36] {
    // entries (row, column, value) of the basis tensor of pair `a`
    const fn entries(a: usize) -> [(usize, usize, f64); 2] {
        let (i, j) = PAIRS[a];
        if i == j { [(i, i, 1.0), (i, i, 0.0)] } else { [(i, j, FRAC_1_SQRT_2), (j, i, FRAC_1_SQRT_2)] }
    }
    let mut out = [(0, 0, 0, 0, 0, 0.0); 36];
    let mut n = 0;
    let mut a = 0;
    while a < 6 {
        let mut b = a;
        while b < 6 {
            let mut order = 0;
            while order < 2 {
                let (h, k) = if order == 0 { (entries(a), entries(b)) } else { (entries(b), entries(a)) };
                let mut p = 0;
                while p < 2 {
                    let mut q = 0;
                    while q < 2 {
                        let ((i, m, hv), (m2, j, kv)) = (h[p], k[q]);
                        if m == m2 && hv * kv != 0.0 {
                            out[n] = (a, b, i, m, j, hv * kv);
                            n += 1;
                        }
                        q += 1;
                    }
                    p += 1;
                }
                order += 1;
            }
            b += 1;
        }
        a += 1;
    }
    assert!(n == 36);
    out
}

/// The logarithmic strain at a point, with the spectral data of `C` that
/// its derivatives need.
#[derive(Debug, Clone, Copy)]
pub struct LogStrain {
    /// Eigenvalues of `C − I = 2E` (`c_i − 1`).
    x: [f64; 3],
    /// Eigenvectors of `C`, as columns.
    q: Tensor,
    /// `E_log` in Voigt form (engineering shear).
    strain: Voigt,
    /// The first divided differences `f[c_i, c_j]` (symmetric; both the
    /// stress and the tangent pull-back need them, the second differences
    /// are made of them).
    f1: Tensor,
}

impl LogStrain {
    /// The logarithmic strain of the displacement gradient `h[k][d] = ∂u_k/∂X_d`.
    pub fn new(h: &Tensor) -> Self {
        Self::from_green_lagrange(&green_lagrange(h))
    }

    /// The logarithmic strain of a Green–Lagrange strain `e` (Voigt,
    /// engineering shear).
    pub(crate) fn from_green_lagrange(e: &Voigt) -> Self {
        // 2E: the engineering shear is already 2 E_ij
        let two_e = [[2.0 * e[0], e[3], e[4]], [e[3], 2.0 * e[1], e[5]], [e[4], e[5], 2.0 * e[2]]];
        let (x, q) = symmetric_eigen(two_e);
        let log = x.map(|xi| 0.5 * xi.ln_1p());
        let t: Tensor =
            std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| q[i][k] * log[k] * q[j][k]).sum()));
        // symmetric: one evaluation per pair
        let mut f1 = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in i..3 {
                f1[i][j] = first_divided(x[i], x[j]);
                f1[j][i] = f1[i][j];
            }
        }
        let strain = [t[0][0], t[1][1], t[2][2], 2.0 * t[0][1], 2.0 * t[0][2], 2.0 * t[1][2]];
        Self { x, q, strain, f1 }
    }

    /// `E_log` (Voigt, engineering shear): the strain the material sees.
    pub fn strain(&self) -> Voigt {
        self.strain
    }

    /// The second Piola–Kirchhoff stress `S = T : L` and its tangent
    /// `∂S/∂E = Lᵀ D L + T : ∂²E_log/∂E²` (engineering-strain columns) from
    /// the material's stress `t` conjugate to `E_log` and its tangent
    /// `d = ∂T/∂E_log` (module docs).
    pub(crate) fn pull_back(&self, t: &Voigt, d: &Matrix6) -> (Voigt, Matrix6) {
        let q = &self.q;
        let x = self.x;
        let f1 = self.f1;
        let f2 = second_differences(x, &f1);
        let (stress, tt) = self.pull_back_in_frame(t, &f1);
        // L̃ is diagonal in the eigenframe's Mandel basis
        let l: [f64; 6] = PAIRS.map(|(i, j)| 2.0 * f1[i][j]);
        let r6 = mandel_rotation(q);
        // D in Mandel components (engineering columns → orthonormal basis), then into the frame
        let dm: Matrix6 = std::array::from_fn(|a| std::array::from_fn(|b| d[a][b] * mandel_scale(a) * mandel_scale(b)));
        let dt = congruence(&r6, &dm, true);
        // T̃ : 4 D²f[B_a, B_b] = 4 Σ_ijk T̃_ij f[c_i, c_k, c_j] (H_ik K_kj + K_ik H_kj), term by term
        let mut g = [[0.0; 6]; 6];
        for &(a, b, i, k, j, c) in &SECOND_TERMS {
            g[a][b] += tt[i][j] * f2[i][k][j] * c;
        }
        let mut kt = [[0.0; 6]; 6];
        for a in 0..6 {
            for b in a..6 {
                kt[a][b] = l[a] * dt[a][b] * l[b] + 4.0 * g[a][b];
                kt[b][a] = kt[a][b];
            }
        }
        let km = congruence(&r6, &kt, false);
        // back to stress rows and engineering-strain columns
        let tangent =
            std::array::from_fn(|a| std::array::from_fn(|b| km[a][b] * MANDEL_UNSCALE[a] * MANDEL_UNSCALE[b]));
        (stress, tangent)
    }
}

impl LogStrain {
    /// `Lᵀ t` for a stress-like `t` (Voigt, tensor shear): the second
    /// Piola–Kirchhoff stress of a stress `t` conjugate to `E_log`, with
    /// `(Lᵀ t) · δE = t · δE_log`.
    pub(crate) fn pull_back_stress(&self, t: &Voigt) -> Voigt {
        self.pull_back_in_frame(t, &self.f1).0
    }

    /// `S = Lᵀ t` (Voigt) and `T̃ = Qᵀ t Q`: in the eigenframe `S̃_ij = 2 f[c_i, c_j] T̃_ij`.
    fn pull_back_in_frame(&self, t: &Voigt, f1: &Tensor) -> (Voigt, Tensor) {
        let tt = to_frame(&self.q, &crate::voigt::stress_tensor(t));
        let st: Tensor = std::array::from_fn(|i| std::array::from_fn(|j| 2.0 * f1[i][j] * tt[i][j]));
        let s = from_frame(&self.q, &st);
        ([s[0][0], s[1][1], s[2][2], s[0][1], s[0][2], s[1][2]], tt)
    }
}

/// The logarithmic strain `½ ln(Fᵀ F)` of a displacement gradient (Voigt,
/// engineering shear).
pub(crate) fn log_strain(h: &Tensor) -> Voigt {
    LogStrain::new(h).strain()
}

/// `√2` on the shear components: Mandel component = Voigt stress × scale
/// = engineering strain / scale.
#[inline]
fn mandel_scale(a: usize) -> f64 {
    if a < 3 { 1.0 } else { std::f64::consts::SQRT_2 }
}

/// `1 / mandel_scale(a)`, as a table (a product in the pull-back's last
/// step instead of 36 divisions).
const MANDEL_UNSCALE: [f64; 6] = [1.0, 1.0, 1.0, FRAC_1_SQRT_2, FRAC_1_SQRT_2, FRAC_1_SQRT_2];

/// `A B` of 3×3 matrices.
fn product(a: &Tensor, b: &Tensor) -> Tensor {
    std::array::from_fn(|i| std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j]))
}

/// `Aᵀ`.
fn transposed(a: &Tensor) -> Tensor {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// `Qᵀ A Q`: components in the eigenframe.
fn to_frame(q: &Tensor, a: &Tensor) -> Tensor {
    product(&transposed(q), &product(a, q))
}

/// `Q Ã Qᵀ`: back from the eigenframe.
fn from_frame(q: &Tensor, a: &Tensor) -> Tensor {
    product(&product(q, a), &transposed(q))
}

/// The orthogonal 6×6 matrix whose column `b` holds the global Mandel
/// components of the eigenframe's basis tensor `b`: `Q B_kl Qᵀ` is
/// `q_k q_kᵀ` for `k = l` and `(q_k q_lᵀ + q_l q_kᵀ)/√2` otherwise (`q_k`
/// the columns of `Q`).
fn mandel_rotation(q: &Tensor) -> Matrix6 {
    let mut r = [[0.0; 6]; 6];
    for (b, &(k, l)) in PAIRS.iter().enumerate() {
        let g = |i: usize, j: usize| {
            if k == l {
                q[i][k] * q[j][k]
            } else {
                std::f64::consts::FRAC_1_SQRT_2 * (q[i][k] * q[j][l] + q[i][l] * q[j][k])
            }
        };
        for (a, &(i, j)) in PAIRS.iter().enumerate() {
            r[a][b] = if i == j { g(i, i) } else { std::f64::consts::SQRT_2 * g(i, j) };
        }
    }
    r
}

/// `Rᵀ M R` (`transpose_first`) or `R M Rᵀ`, for a symmetric `M`: the
/// upper triangle computed, the lower mirrored (the result is symmetric to
/// the last bit). Row-times-matrix loops with the contiguous index
/// innermost.
fn congruence(r: &Matrix6, m: &Matrix6, transpose_first: bool) -> Matrix6 {
    // A = Rᵀ or R; the result is A M Aᵀ
    let a: Matrix6 = if transpose_first { std::array::from_fn(|i| std::array::from_fn(|j| r[j][i])) } else { *r };
    let mut tmp = [[0.0; 6]; 6];
    for (ti, ai) in tmp.iter_mut().zip(&a) {
        for (aik, mk) in ai.iter().zip(m) {
            for (t, mkj) in ti.iter_mut().zip(mk) {
                *t += aik * mkj;
            }
        }
    }
    let mut out = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in i..6 {
            let v = (0..6).map(|k| tmp[i][k] * a[j][k]).sum();
            out[i][j] = v;
            out[j][i] = v;
        }
    }
    out
}

/// `f[c_a, c_b]` for `f(c) = ½ ln c`, `c = 1 + x`, without cancellation
/// (module docs).
fn first_divided(a: f64, b: f64) -> f64 {
    // symmetric in (a, b) to the last bit
    let m = 2.0 + (a + b);
    let r = (a - b) / m;
    if r.abs() < 1e-3 {
        let r2 = r * r;
        (1.0 + r2 * (1.0 / 3.0 + r2 * (1.0 / 5.0 + r2 / 7.0))) / m
    } else {
        r.atanh() / (a - b)
    }
}

/// `f[c_a, c_b, c_c]` for `f(c) = ½ ln c`, `c = 1 + x`, of the eigenvalues
/// `x[a], x[b], x[c]` (module docs), from their first divided differences
/// `f1`.
fn second_divided(x: [f64; 3], f1: &Tensor, abc: [usize; 3]) -> f64 {
    // the indices by decreasing eigenvalue (a sorting network; ties in
    // either order give the same values)
    let [mut hi, mut mid, mut lo] = abc;
    if x[mid] > x[hi] {
        std::mem::swap(&mut hi, &mut mid);
    }
    if x[lo] > x[mid] {
        std::mem::swap(&mut mid, &mut lo);
    }
    if x[mid] > x[hi] {
        std::mem::swap(&mut hi, &mut mid);
    }
    let (a, b, c) = (x[abc[0]], x[abc[1]], x[abc[2]]);
    let mean = 1.0 + (a + b + c) / 3.0;
    if x[hi] - x[lo] > 2e-3 * mean {
        return (f1[hi][mid] - f1[mid][lo]) / (x[hi] - x[lo]);
    }
    // Taylor series of the divided difference about the mean
    let xbar = (a + b + c) / 3.0;
    let d = [hi, mid, lo].map(|i| (x[i] - xbar) / mean);
    // Σ_n (−1)ⁿ h_n / (n + 2), the coefficients as products (the seven
    // divisions per triple were a fifth of the pull-back's time)
    const COEFFICIENTS: [f64; 7] = [1.0 / 2.0, -1.0 / 3.0, 1.0 / 4.0, -1.0 / 5.0, 1.0 / 6.0, -1.0 / 7.0, 1.0 / 8.0];
    let h = complete_homogeneous(d);
    let sum: f64 = h.iter().zip(COEFFICIENTS).map(|(hn, c)| c * hn).sum();
    -sum / (2.0 * mean * mean)
}

/// The complete homogeneous symmetric polynomials `h_0 … h_6` of
/// `(d_0, d_1, d_2)`, by adding one variable at a time:
/// `h_n(x_1 … x_k) = h_n(x_1 … x_(k−1)) + x_k h_(n−1)(x_1 … x_k)`.
fn complete_homogeneous(d: [f64; 3]) -> [f64; 7] {
    let mut h = [1.0; 7];
    for n in 1..7 {
        h[n] = h[n - 1] * d[0];
    }
    for &x in &d[1..] {
        for n in 1..7 {
            h[n] += x * h[n - 1];
        }
    }
    h
}

/// `f[c_i, c_k, c_j]` for every index triple (symmetric in its arguments),
/// from the first differences `f1`.
fn second_differences(x: [f64; 3], f1: &Tensor) -> [[[f64; 3]; 3]; 3] {
    let mut f2 = [[[0.0; 3]; 3]; 3];
    for i in 0..3 {
        for k in i..3 {
            for j in k..3 {
                let v = second_divided(x, f1, [i, k, j]);
                for (p, q, r) in [(i, k, j), (i, j, k), (k, i, j), (k, j, i), (j, i, k), (j, k, i)] {
                    f2[p][q][r] = v;
                }
            }
        }
    }
    f2
}

/// Eigenvalues and eigenvectors (columns) of a symmetric 3×3 matrix by the
/// cyclic Jacobi method (orthonormal eigenvectors also for repeated
/// eigenvalues; Golub & Van Loan §8.5). An off-diagonal entry below 10⁻¹⁸
/// of its two diagonal entries is left: the results are those of a matrix
/// that close to the given one.
pub(crate) fn symmetric_eigen(mut a: Tensor) -> ([f64; 3], Tensor) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..50 {
        let mut rotated = false;
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            let apq = a[p][q];
            if apq == 0.0 || apq.abs() <= 1e-18 * (a[p][p].abs() + a[q][q].abs()) {
                continue;
            }
            rotated = true;
            let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            let t = if theta.abs() > 1e100 {
                0.5 / theta
            } else {
                theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt())
            };
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            a[p][p] -= t * apq;
            a[q][q] += t * apq;
            a[p][q] = 0.0;
            a[q][p] = 0.0;
            let r = 3 - p - q;
            let (arp, arq) = (a[r][p], a[r][q]);
            a[r][p] = c * arp - s * arq;
            a[p][r] = a[r][p];
            a[r][q] = s * arp + c * arq;
            a[q][r] = a[r][q];
            for row in v.iter_mut() {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
        if !rotated {
            break;
        }
    }
    ([a[0][0], a[1][1], a[2][2]], v)
}

#[cfg(test)]
mod tests;
