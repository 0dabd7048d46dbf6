//! The B-bar projection of the volumetric strain (Hughes, *Int. J. Numer.
//! Methods Eng.* 15, 1980): the element kernel's `ε̄ = ε + (θ̄ − θ)/3 · 1`
//! needs, per Gauss point and node, `d_a = b̄_a − ∇N_a` (see
//! [`crate::values::PressureSpace`] for the projection space).

use super::Workspace;
use crate::values::CellValues;

/// B-bar: fills `ws.bbar` with `d_a(q) = b̄_a(q) − g_a(q)`, where
/// `b̄_a(q) = Σ_kl ψ_k(q) (M⁻¹)_kl ∫ ψ_l ∇N_a dV` is the gradient whose dot
/// product with `u_a` gives the projected volumetric strain
/// `θ̄ = Π div u` on the element's pressure space, `M_kl = ∫ ψ_k ψ_l dV`.
pub(super) fn volumetric_projection(
    geom: &CellValues,
    ps: &crate::values::PressureSpace,
    es: usize,
    eb: usize,
    nodes: usize,
    ws: &mut Workspace,
) {
    let (sg, ag) = (&geom.section, &geom.axis);
    let n = ps.n;
    let mut m = [[0.0; 4]; 4];
    // G_{k,(a,c)} = ∫ ψ_k ∂N_a/∂x_c
    let g_mat = &mut ws.proj_g[..n * 3 * nodes];
    g_mat.fill(0.0);
    for gb in 0..ag.n_gp {
        for gs in 0..sg.n_gp {
            let q = gb * sg.n_gp + gs;
            let w = geom.gradients(es, eb, gb, gs, &mut ws.grads[..nodes]);
            let psi = &ps.psi[q * n..(q + 1) * n];
            for k in 0..n {
                for l in 0..n {
                    m[k][l] += w * psi[k] * psi[l];
                }
                for (a, g) in ws.grads[..nodes].iter().enumerate() {
                    for c in 0..3 {
                        g_mat[k * 3 * nodes + 3 * a + c] += w * psi[k] * g[c];
                    }
                }
            }
        }
    }
    let inv = invert_spd(&m, n);
    for gb in 0..ag.n_gp {
        for gs in 0..sg.n_gp {
            let q = gb * sg.n_gp + gs;
            geom.gradients(es, eb, gb, gs, &mut ws.grads[..nodes]);
            let psi = &ps.psi[q * n..(q + 1) * n];
            // coefficients of θ̄ at q: c_l = Σ_k ψ_k (M⁻¹)_kl
            let mut cq = [0.0; 4];
            for l in 0..n {
                cq[l] = (0..n).map(|k| psi[k] * inv[k][l]).sum();
            }
            for a in 0..nodes {
                let g = ws.grads[a];
                let mut d = [0.0; 3];
                for c in 0..3 {
                    let bbar: f64 = (0..n).map(|l| cq[l] * ws.proj_g[l * 3 * nodes + 3 * a + c]).sum();
                    d[c] = bbar - g[c];
                }
                ws.bbar[q * nodes + a] = d;
            }
        }
    }
}

/// Inverse of a small symmetric positive definite matrix (the `n × n`
/// leading block of `m`, n ≤ 4) by Gauss–Jordan elimination.
pub(super) fn invert_spd(m: &[[f64; 4]; 4], n: usize) -> [[f64; 4]; 4] {
    let mut a = *m;
    let mut inv = [[0.0; 4]; 4];
    for (i, row) in inv.iter_mut().enumerate().take(n) {
        row[i] = 1.0;
    }
    for i in 0..n {
        let p = a[i][i];
        for j in 0..n {
            a[i][j] /= p;
            inv[i][j] /= p;
        }
        for r in 0..n {
            if r != i {
                let f = a[r][i];
                for j in 0..n {
                    a[r][j] -= f * a[i][j];
                    inv[r][j] -= f * inv[i][j];
                }
            }
        }
    }
    inv
}
