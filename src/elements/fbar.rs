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
//! K   = ∫ [B; d]ᵀ [[∂S/∂E, v/3], [vᵀ/3, mᵀDm/9]] [B; d] dV₀        (B = δE, the 7th row d)
//!     + ∫ ∇N_a · S ∇N_b δ_kl dV₀                                   (geometric, unchanged)
//!     − ∫ (p̄ − p) g̃_(a,l) g̃_(b,k) dV₀                              (Δδθ = −g̃_(a,l) g̃_(b,k))
//! ```
//!
//! with `D = ∂T/∂Ē`, `m = (1, 1, 1, 0, 0, 0)` and `v = Lᵀ D m` the pull-back
//! of `D m` (`L = ∂E_log/∂E`). The last term uses that `Π` is self-adjoint:
//! `∫ p Π(Δδθ) = ∫ Π(p) Δδθ`. The Cauchy stress is `σ = F S Fᵀ / J̄`
//! (`F̄ S̄ F̄ᵀ = F S Fᵀ` since `S̄ = (J/J̄)^{2/3} S`).

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

/// The curvature of the dilatation, `−∫ (p̄ − p) g̃_(a,l) g̃_(b,k) dV₀` for
/// the DOF pair `((a, k), (b, l))`, into the upper triangle of
/// `ws.tangent`; `p` per point in `ws.pressure`, `p̄ = Π p`; `modulus` the
/// material's largest elastic stiffness (`C₁₁`), the scale below which
/// `p̄ − p` is round-off.
pub(super) fn add_dilatation_curvature(
    ps: &PressureSpace,
    nodes: usize,
    points: usize,
    modulus: f64,
    ws: &mut Workspace,
) {
    let n = ps.n;
    let mut p_l = [0.0; 4];
    for q in 0..points {
        let psi = &ps.psi[q * n..(q + 1) * n];
        for l in 0..n {
            p_l[l] += ws.weights[q] * psi[l] * ws.pressure[q];
        }
    }
    let ndof = 3 * nodes;
    // p̄ − p per point, in the force-free buffer of the projection's weights
    let mut excess = std::mem::take(&mut ws.proj_w);
    excess.clear();
    excess.extend((0..points).map(|q| {
        let c = &ws.proj_c[q * 4..q * 4 + 4];
        (0..n).map(|l| c[l] * p_l[l]).sum::<f64>() - ws.pressure[q]
    }));
    // With isotropic elasticity and isochoric plastic flow (every material
    // of crate::materials) p = K θ̄ lies in the pressure space and p̄ = p up
    // to round-off (θ and tr E_log are summed differently): the term is
    // then below 1e-10 of the material part, and the loop (half of an
    // evaluation's time) is skipped.
    if excess.iter().all(|e| e.abs() <= 1e-10 * modulus) {
        ws.proj_w = excess;
        return;
    }
    for q in 0..points {
        let s = -ws.weights[q] * excess[q];
        let gt = &ws.spatial[q * nodes..(q + 1) * nodes];
        for a in 0..nodes {
            for k in 0..3 {
                let row = (3 * a + k) * ndof;
                for b in a..nodes {
                    let first = if b == a { k } else { 0 };
                    for l in first..3 {
                        ws.tangent[row + 3 * b + l] += s * gt[a][l] * gt[b][k];
                    }
                }
            }
        }
    }
    ws.proj_w = excess;
}
