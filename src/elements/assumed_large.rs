//! The assumed in-section shear's share of the total-Lagrangian tangent
//! ([`crate::values::AssumedShear`], nonlinear geometry).
//!
//! The strain the material sees is `Ē = E + Δ m` with `Δ = Ẽ_ξη − E_ξη`.
//! A unit displacement `u_(a,c)` of node `a = (i, τ)` varies it by
//! `δĒ = H_c ∇N_a + m A_(a,c)`, `A_(a,c) = N_i D_τc` (the first pass's
//! `D`, `ws.assumed`), and the second variation of `Δ` is
//! `N_i N_j δ_cd G_τσ`. Over the points `q` of weight `w`, with `C` the
//! material tangent and `S` the stress of the geometric term,
//!
//! ```text
//! K = K_std + Σ_q w [P Aᵀ + A Pᵀ + (m·C m) A Aᵀ] + Σ_q w (S·m) G ⊗ N Nᵀ ⊗ I
//! P_(a,c) = ∇N_a · H_cᵀ C m      (the standard operator against C m)
//! ```
//!
//! `K_std` is [`super::nucleus`]'s. The middle sum is `Z Aᵀ + A Zᵀ` with
//! `Z = w (P + ½ (m·C m) A)` stacked over the points — one product of the
//! element DOF by the points; the last is a scalar per node pair, summed
//! over the section points first.

use super::{Element, Workspace};
use crate::values::{AssumedShear, CellValues, Covariant};
use crate::voigt::Voigt;

/// The first pass's share at point `gs` of section element `es`: `D_τ`
/// into `d` (kept for the tangent) and `h_τ += w (S·m) D_τ` from the
/// contracted displacements `v` and their tying derivatives `tying`.
pub(super) fn add_force(
    sh: &AssumedShear,
    (es, gs): (usize, usize),
    w: f64,
    stress: &Voigt,
    (v, tying): (&[[f64; 3]], &[Covariant]),
    (d, h): (&mut [[f64; 3]], &mut [[f64; 3]]),
) {
    sh.large_variation(es, gs, v, tying, d);
    let sm = w * stress.iter().zip(sh.direction(es)).map(|(s, m)| s * m).sum::<f64>();
    for (ht, dt) in h.iter_mut().zip(d.iter()) {
        for k in 0..3 {
            ht[k] += sm * dt[k];
        }
    }
}

/// Adds the assumed shear's terms (module docs) to the upper triangle of
/// `ws.tangent` of element `el`, from the first pass's `F`, `C`, `S` and
/// `D` (`ws.frames`, `ws.tangents`, `ws.pk2`, `ws.assumed`).
pub(super) fn add_terms(geom: &CellValues, el: &Element, ws: &mut Workspace) {
    let Some(sh) = geom.shear.as_ref() else { return };
    let (sg, ag) = (&geom.section, &geom.axis);
    let (ns, nodes, points) = (sg.n_fun, el.nodes, el.n_points);
    let n = 3 * nodes;
    let m = sh.direction(el.es);
    ws.assumed_z.clear();
    ws.assumed_z.resize(points * n, 0.0);
    ws.assumed_a.clear();
    ws.assumed_a.resize(points * n, 0.0);
    let mut sums = std::mem::take(&mut ws.assumed_g);
    sums.resize(ns * ns, 0.0);
    for gb in 0..ag.n_gp {
        let at = ag.point(el.eb, gb);
        sums.fill(0.0);
        for gs in 0..sg.n_gp {
            let q = gb * sg.n_gp + gs;
            let sp = sg.point(el.es, gs);
            let w = sp.weight * at.weight;
            let c = &ws.tangents[q];
            let cm: [f64; 6] = std::array::from_fn(|r| w * (0..6).map(|k| c[r][k] * m[k]).sum::<f64>());
            let mcm: f64 = m.iter().zip(&cm).map(|(a, b)| a * b).sum();
            // r_c[l] = (H_c e_l) · w C m
            let r: [[f64; 3]; 3] = std::array::from_fn(|cc| {
                std::array::from_fn(|l| {
                    let mut e = [0.0; 3];
                    e[l] = 1.0;
                    let v = crate::kinematics::strain_variation(&ws.frames[q], e, cc);
                    v.iter().zip(&cm).map(|(a, b)| a * b).sum()
                })
            });
            let d = &ws.assumed[q * ns..(q + 1) * ns];
            let (zq, aq) = (&mut ws.assumed_z[q * n..(q + 1) * n], &mut ws.assumed_a[q * n..(q + 1) * n]);
            for (i, (&ni, &nyi)) in at.n.iter().zip(at.ny).enumerate() {
                for (t, dt) in d.iter().enumerate() {
                    let g = [ni * sp.fx[t], nyi * sp.f[t], ni * sp.fz[t]];
                    let a = 3 * (i * ns + t);
                    for cc in 0..3 {
                        let p = g[0] * r[cc][0] + g[1] * r[cc][1] + g[2] * r[cc][2];
                        aq[a + cc] = ni * dt[cc];
                        zq[a + cc] = p + 0.5 * mcm * aq[a + cc];
                    }
                }
            }
            let sm = w * ws.pk2[q].iter().zip(m).map(|(s, m)| s * m).sum::<f64>();
            for (o, g) in sums.iter_mut().zip(sh.curvature(gs)) {
                *o += sm * g;
            }
        }
        // the geometric share: N_i N_j Σ_gs w (S·m) G_τσ on the diagonal components
        for (i, &ni) in at.n.iter().enumerate() {
            for (j, &nj) in at.n.iter().enumerate().skip(i) {
                for t in 0..ns {
                    let a = i * ns + t;
                    for s in 0..ns {
                        let b = j * ns + s;
                        if b < a {
                            continue;
                        }
                        let v = ni * nj * sums[t * ns + s];
                        for cc in 0..3 {
                            ws.tangent[(3 * a + cc) * n + 3 * b + cc] += v;
                        }
                    }
                }
            }
        }
    }
    ws.assumed_g = sums;
    // Z Aᵀ (n × n), then its symmetric sum into the upper triangle
    ws.assumed_k.clear();
    ws.assumed_k.resize(n * n, 0.0);
    faer::linalg::matmul::matmul(
        faer::MatMut::from_row_major_slice_mut(&mut ws.assumed_k, n, n),
        faer::Accum::Replace,
        faer::MatRef::from_row_major_slice(&ws.assumed_z, points, n).transpose(),
        faer::MatRef::from_row_major_slice(&ws.assumed_a, points, n),
        1.0,
        faer::Par::Seq,
    );
    for p in 0..n {
        for q in p..n {
            ws.tangent[p * n + q] += ws.assumed_k[p * n + q] + ws.assumed_k[q * n + p];
        }
    }
}
