//! B-bar at finite strain: the projected logarithmic dilatation (an F-bar
//! method in mixed, variational form), for `formulation = "bbar"` with
//! `analysis.geometry = "nonlinear"` and `analysis.strain = "logarithmic"`.
//!
//! The volumetric part of the logarithmic strain is `tr E_log = ln J =: θ`,
//! and `E_log(α F) = E_log(F) + ln α · 1`. The element replaces `θ` by its
//! L2 projection `θ̄ = Π θ` on the pressure space of the small-strain B-bar
//! ([`crate::values::PressureSpace`], `{1, ξ, η, ζ}` over the reference
//! element):
//!
//! ```text
//! Ē = E_log(F) + (θ̄ − θ)/3 · 1  = E_log(F̄),   F̄ = (J̄/J)^{1/3} F,   J̄ = e^θ̄
//! ```
//!
//! the F-bar deformation gradient of de Souza Neto et al. (IJSS 33, 1996)
//! with the projected logarithmic dilatation — for a constant pressure space
//! a logarithmic variant of the mean dilatation of Simo, Taylor & Pister
//! (CMAME 51, 1985), which averages J where this averages ln J. The
//! element's energy is `∫ W(Ē(u)) dV₀`, so its force and tangent are exact
//! variations and the tangent is symmetric (the material's is: J2 with the
//! associative flow rule). With `T` the material's stress (conjugate to
//! `Ē`), `p = tr T / 3`, `S` its pull-back ([`crate::kinematics::hencky`]),
//! `g̃_a = F⁻ᵀ ∇N_a` (so `δθ = g̃_a · δu_a`), `d_a = Π g̃_a − g̃_a`
//! (so `δθ̄ − δθ = d_a · δu_a`) and `p̄ = Π p`:
//!
//! ```text
//! f_a = ∫ (F S) ∇N_a + p d_a dV₀
//! K   = ∫ [B; d]ᵀ [[∂S/∂E, v/3], [vᵀ/3, mᵀDm/9]] [B; d] dV₀        (B = δE, d the dilatation row)
//!     + ∫ ∇N_a · S ∇N_b δ_kl dV₀                                   (geometric, as without B-bar)
//!     − ∫ (p̄ − p) g̃_(a,l) g̃_(b,k) dV₀                              (Δδθ = −g̃_(a,l) g̃_(b,k))
//! ```
//!
//! with `D = ∂T/∂Ē`, `m = (1, 1, 1, 0, 0, 0)` and `v = Lᵀ D m` the pull-back
//! of `D m` (`L = ∂E_log/∂E`). The last term uses that `Π` is self-adjoint:
//! `∫ p Π(Δδθ) = ∫ Π(p) Δδθ`. The Cauchy stress is `σ = F S Fᵀ / J̄`
//! (`F̄ S̄ F̄ᵀ = F S Fᵀ` since `S̄ = (J/J̄)^{2/3} S`).
//!
//! The tangent is formed in the kernel's nucleus form (`nucleus`): the
//! terms of `d`'s local half `−g̃` (and the curvature) are 3 × 3 matrices
//! per point and component pair ([`add_point_terms`]), those of its
//! projected half `Π g̃` a rank-2n update per element ([`add_projected`]).

use super::Workspace;
use super::bbar::invert_spd;
use crate::values::{CellValues, PressureSpace};

/// First pass: at every Gauss point `F` from the element displacement `u`,
/// `g̃_a = F⁻ᵀ ∇N_a` (into `ws.spatial`), the dilatation correction
/// `θ̄ − θ` (into `ws.dilatation`), `d_a = Π g̃_a − g̃_a` (into `ws.bbar`)
/// and the projection's coefficients `c_l(q) = Σ_k ψ_k(q) (M⁻¹)_kl` (into
/// `ws.proj_c`), `M_kl = ∫ ψ_k ψ_l dV₀`. A point with `J ≤ 0` gets NaN (the
/// increment is then cut back).
pub(super) fn dilatation_projection(
    geom: &CellValues,
    ps: &PressureSpace,
    (es, eb, nodes): (usize, usize, usize),
    u: &[f64],
    ws: &mut Workspace,
) {
    let (sg, ag) = (&geom.section, &geom.axis);
    let (n, points) = (ps.n, sg.n_gp * ag.n_gp);
    ws.spatial.resize(points * nodes, [0.0; 3]);
    ws.dilatation.resize(points, 0.0);
    ws.weights.resize(points, 0.0);
    ws.proj_c.resize(points * 4, 0.0);
    // w ψ_k per point (row-major n × points), for ∫ ψ_k (·) as one product
    let mut w_psi = std::mem::take(&mut ws.proj_w);
    w_psi.resize(n * points, 0.0);
    let mut m = [[0.0; 4]; 4];
    let mut theta_l = [0.0; 4];
    for gb in 0..ag.n_gp {
        for gs in 0..sg.n_gp {
            let q = gb * sg.n_gp + gs;
            let w = geom.gradients(es, eb, gb, gs, &mut ws.grads[..nodes]);
            ws.weights[q] = w;
            let mut f = [[0.0; 3]; 3];
            for (a, g) in ws.grads[..nodes].iter().enumerate() {
                for (k, row) in f.iter_mut().enumerate() {
                    for d in 0..3 {
                        row[d] += u[3 * a + k] * g[d];
                    }
                }
            }
            for (k, row) in f.iter_mut().enumerate() {
                row[k] += 1.0;
            }
            let j = crate::kinematics::determinant(&f);
            let theta = if j > 0.0 { j.ln() } else { f64::NAN };
            // F⁻ᵀ = cof(F) / J
            let inv_t = crate::kinematics::cofactor(&f).map(|row| row.map(|c| c / j));
            ws.dilatation[q] = theta;
            for (gt, g) in ws.spatial[q * nodes..(q + 1) * nodes].iter_mut().zip(&ws.grads[..nodes]) {
                *gt = std::array::from_fn(|i| inv_t[i][0] * g[0] + inv_t[i][1] * g[1] + inv_t[i][2] * g[2]);
            }
            let psi = &ps.psi[q * n..(q + 1) * n];
            for k in 0..n {
                w_psi[k * points + q] = w * psi[k];
                theta_l[k] += w * psi[k] * theta;
                for l in 0..n {
                    m[k][l] += w * psi[k] * psi[l];
                }
            }
        }
    }
    let inv = invert_spd(&m, n);
    for q in 0..points {
        let psi = &ps.psi[q * n..(q + 1) * n];
        let c = &mut ws.proj_c[q * 4..q * 4 + 4];
        for l in 0..n {
            c[l] = (0..n).map(|k| psi[k] * inv[k][l]).sum();
        }
        ws.dilatation[q] = (0..n).map(|l| c[l] * theta_l[l]).sum::<f64>() - ws.dilatation[q];
    }
    // G = (w ψ) · g̃ (n × 3 nodes: ∫ ψ_l g̃_(a,c)), then d = c · G − g̃
    // (points × 3 nodes): two small GEMMs
    let width = 3 * nodes;
    let spatial = faer::MatRef::from_row_major_slice(ws.spatial.as_flattened(), points, width);
    let g = faer::MatMut::from_row_major_slice_mut(&mut ws.proj_g[..n * width], n, width);
    let lhs = faer::MatRef::from_row_major_slice(&w_psi, n, points);
    faer::linalg::matmul::matmul(g, faer::Accum::Replace, lhs, spatial, 1.0, faer::Par::Seq);
    ws.bbar.resize(points * nodes, [0.0; 3]);
    // d = c G − g̃: c G accumulated onto −g̃
    let d = ws.bbar[..points * nodes].as_flattened_mut();
    for (x, s) in d.iter_mut().zip(ws.spatial.as_flattened()) {
        *x = -s;
    }
    let d = faer::MatMut::from_row_major_slice_mut(d, points, width);
    let c = faer::MatRef::from_row_major_slice_with_stride(&ws.proj_c, points, n, 4);
    let g = faer::MatRef::from_row_major_slice(&ws.proj_g[..n * width], n, width);
    faer::linalg::matmul::matmul(d, faer::Accum::Add, c, g, 1.0, faer::Par::Seq);
    ws.proj_w = w_psi;
}

/// Per element, before the points' nuclei: `p̄ − p` per point (into
/// `ws.proj_w`, the projection's weights are no longer needed) and
/// `A_lm = Σ_q w κ c_l c_m` (`κ = mᵀDm/9`), the weight of the projected
/// dilatation's own term.
pub(super) fn prepare(ps: &PressureSpace, points: usize, ws: &mut Workspace) -> [[f64; 4]; 4] {
    let n = ps.n;
    let mut p_l = [0.0; 4];
    let mut a = [[0.0; 4]; 4];
    for q in 0..points {
        let psi = &ps.psi[q * n..(q + 1) * n];
        let c = &ws.proj_c[q * 4..q * 4 + 4];
        let wk = ws.weights[q] * ws.coupling[q].1;
        for l in 0..n {
            p_l[l] += ws.weights[q] * psi[l] * ws.pressure[q];
            for m in 0..n {
                a[l][m] += wk * c[l] * c[m];
            }
        }
    }
    let mut excess = std::mem::take(&mut ws.proj_w);
    excess.clear();
    excess.extend((0..points).map(|q| {
        let c = &ws.proj_c[q * 4..q * 4 + 4];
        (0..n).map(|l| c[l] * p_l[l]).sum::<f64>() - ws.pressure[q]
    }));
    ws.proj_w = excess;
    a
}

/// The point-local part of the dilatation's terms in the nuclei `m` of
/// point `q` (`crate::elements::nucleus`, pairs `(c, d)` in `pairs`), with
/// `d = Π g̃ − g̃`, `y = w Bᵀ v / 3` (`y_(a,c) = α_ck ∂_k N_a`, `α = w F V / 3`
/// with `V` the tensor of `v`) and `g̃_(a,c) = β_ck ∂_k N_a`, `β = F⁻ᵀ`:
///
/// ```text
/// M^(cd)_kl += −α_ck β_dl − β_ck α_dl + w κ β_ck β_dl − w (p̄ − p) β_dk β_cl
/// ```
///
/// (the `−g̃` halves of `y dᵀ + d yᵀ + w κ d dᵀ`, and the curvature).
/// Returns `γ = α − w κ β`, whose projection `Z_l = Σ_q c_l γ ∇N` carries
/// the rest ([`add_projected`]).
#[inline(always)]
pub(super) fn add_point_terms(
    m: &mut [[[f64; 3]; 3]; 6],
    pairs: &[(usize, usize); 6],
    f: &crate::kinematics::Tensor,
    (v, kappa): (crate::voigt::Voigt, f64),
    w: f64,
    excess: f64,
) -> [[f64; 3]; 3] {
    let j = crate::kinematics::determinant(f);
    let beta = crate::kinematics::cofactor(f).map(|row| row.map(|c| c / j));
    let vt = crate::voigt::stress_tensor(&v);
    let alpha: [[f64; 3]; 3] =
        std::array::from_fn(|c| std::array::from_fn(|k| w / 3.0 * (0..3).map(|i| f[c][i] * vt[i][k]).sum::<f64>()));
    let (wk, we) = (w * kappa, w * excess);
    for (mp, &(c, d)) in m.iter_mut().zip(pairs) {
        for (k, row) in mp.iter_mut().enumerate() {
            for (l, x) in row.iter_mut().enumerate() {
                *x += -alpha[c][k] * beta[d][l] - beta[c][k] * alpha[d][l] + wk * beta[c][k] * beta[d][l]
                    - we * beta[d][k] * beta[c][l];
            }
        }
    }
    std::array::from_fn(|c| std::array::from_fn(|k| alpha[c][k] - wk * beta[c][k]))
}

/// The projected part of the dilatation's terms, added to the upper
/// triangle of `ws.tangent`: with `G_l = ∫ ψ_l g̃` (`ws.proj_g`), `Z_l`
/// (`ws.proj_z`, rows `(l, c)` × nodes) and `A` from [`prepare`],
///
/// ```text
/// K += Σ_l (U_l G_lᵀ + G_l U_lᵀ),   U_l = Z_l + ½ Σ_m A_lm G_m
/// ```
///
/// (`Σ_q z_q Pᵀ + P z_qᵀ + w κ P Pᵀ` with `P = Σ_l c_l G_l`, `z = y − w κ g̃`):
/// a rank-2n update.
pub(super) fn add_projected(n: usize, nodes: usize, a: &[[f64; 4]; 4], ws: &mut Workspace) {
    use faer::linalg::matmul::triangular::{BlockStructure, matmul};
    let (ndof, k) = (3 * nodes, 2 * n);
    let (g, z) = (&ws.proj_g[..n * ndof], &ws.proj_z);
    // [U | G] and [G | U], DOF × 2n each, row-major: K += [U | G] [G | U]ᵀ
    let mut w = std::mem::take(&mut ws.proj_u);
    w.resize(2 * ndof * k, 0.0);
    let (w1, w2) = w.split_at_mut(ndof * k);
    for p in 0..ndof {
        let (node, c) = (p / 3, p % 3);
        for l in 0..n {
            let u = z[(3 * l + c) * nodes + node] + 0.5 * (0..n).map(|m| a[l][m] * g[m * ndof + p]).sum::<f64>();
            let gl = g[l * ndof + p];
            (w1[p * k + l], w1[p * k + n + l]) = (u, gl);
            (w2[p * k + l], w2[p * k + n + l]) = (gl, u);
        }
    }
    matmul(
        faer::MatMut::from_row_major_slice_mut(&mut ws.tangent[..ndof * ndof], ndof, ndof),
        BlockStructure::TriangularUpper,
        faer::Accum::Add,
        faer::MatRef::from_row_major_slice(w1, ndof, k),
        BlockStructure::Rectangular,
        faer::MatRef::from_row_major_slice(w2, ndof, k).transpose(),
        BlockStructure::Rectangular,
        1.0,
        faer::Par::Seq,
    );
    ws.proj_u = w;
}
