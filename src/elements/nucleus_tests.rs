//! The nucleus form of the total-Lagrangian tangent (`nucleus`, with
//! B-bar's terms from `fbar`) against the operator form written out
//! entry by entry from the formulas of the module docs,
//!
//! ```text
//! K = Σ_q w [B; d]ᵀ [[∂S/∂E, v/3], [vᵀ/3, κ]] [B; d] + δ_cd Σ_q w ∇N_aᵀ S ∇N_b
//!     − Σ_q w (p̄ − p) g̃_(a,d) g̃_(b,c)
//! ```
//!
//! (`B` the Green–Lagrange operator from `kinematics::strain_variation`; `d`,
//! `v`, `κ`, `p` only with B-bar): the same matrix to round-off on every
//! element size, elastic and plastic, with both strain measures and with
//! B-bar. The finite-difference tests (`tests`, `log_tests`, `fbar_tests`)
//! check the tangent against the force to 1e-6; this one checks every entry
//! of the upper triangle to 1e-12, so a transposed pair block, a missing
//! entry of the pairs `c > d`, a wrong projected term or a wrong curvature
//! (checked with a pressure set outside the pressure space) fails it.

use super::tests::single_element_body;
use super::*;
use crate::materials::{Hardening, PointState};
use crate::shape::{BeamElementKind, SectionElementKind};

/// A large rotation about x with stretch and shear: plastic at every point
/// with the hardening material.
fn deformed(body: &crate::mesh::Body) -> Vec<f64> {
    let mut el = Vec::new();
    body.element_nodes(0, &mut el);
    let (s, c) = 0.7f64.sin_cos();
    let mut u = vec![0.0; 3 * el.len()];
    for (a, &g) in el.iter().enumerate() {
        let [x, y, z] = body.local_coords(g);
        let (yr, zr) = (0.1 + c * (y - 0.1) - s * z, s * (y - 0.1) + c * z);
        u[3 * a] = 4e-3 * y * z / 0.01 + 2e-3 * x + 1e-2 * x * x;
        u[3 * a + 1] = yr - y + 6e-3 * (y - 0.1) + 2e-3 * x * z / 0.01;
        u[3 * a + 2] = zr - z - 2e-3 * (y - 0.1) * (y - 0.1) / 0.03 + 3e-3 * z;
    }
    u
}

#[test]
fn nucleus_tangent_equals_the_operator_form() {
    let kinds = [
        (SectionElementKind::L4, BeamElementKind::B2),
        (SectionElementKind::L9, BeamElementKind::B3),
        (SectionElementKind::L16, BeamElementKind::B4),
    ];
    let materials = [
        Material::new("m", 70e9, 0.3, None),
        Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 })),
    ];
    // (kinematics, B-bar, a pressure outside the pressure space): with
    // cufem's materials p̄ = p and the dilatation's curvature vanishes, so
    // the last variant sets p by hand (as fbar_tests' curvature test) and
    // forms the tangent again to check that term too
    let variants = [
        (Kinematics::TotalLagrangian, false, false),
        (Kinematics::TotalLagrangianLog, false, false),
        (Kinematics::TotalLagrangianLog, true, false),
        (Kinematics::TotalLagrangianLog, true, true),
    ];
    for (sk, bk) in kinds {
        let body = single_element_body(sk, bk);
        let u = deformed(&body);
        for mat in &materials {
            for (kin, bbar, off_space) in variants {
                let geom = if bbar {
                    CellValues::new(&body).unwrap().with_bbar(&body)
                } else {
                    CellValues::new(&body).unwrap()
                };
                let committed = vec![PointState::default(); geom.gp_per_element()];
                let (k, reference, plastic) = both(&geom, mat, &u, &committed, kin, off_space);
                assert_eq!(plastic > 0, mat.is_plastic(), "the state is plastic with the hardening material");
                let n = 3 * body.nodes_per_element();
                let kmax = reference.iter().fold(0.0f64, |a, b| a.max(b.abs()));
                let mut worst: f64 = 0.0;
                for p in 0..n {
                    for q in p..n {
                        worst = worst.max((k[p * n + q] - reference[p * n + q]).abs() / kmax);
                    }
                }
                assert!(
                    worst < 1e-12,
                    "{sk:?} x {bk:?}, {kin:?}, B-bar {bbar} (p and v set by hand {off_space}), plastic {}: {worst:e}",
                    mat.is_plastic()
                );
            }
        }
    }
}

/// The kernel's tangent, the reference (full matrix) and the number of
/// plastic points; with `off_space` the tangent formed again after the
/// points' pressures are set to a field outside the pressure space and
/// their couplings `v` away from the materials' own.
fn both(
    geom: &CellValues,
    mat: &Material,
    u: &[f64],
    committed: &[PointState],
    kin: Kinematics,
    off_space: bool,
) -> (Vec<f64>, Vec<f64>, usize) {
    let ngp = geom.gp_per_element();
    let super::tests::KernelRun { mut ws, stats, .. } = super::tests::kernel(geom, mat, u, committed, kin, None);
    let nodes = geom.section.n_fun * geom.axis.n_fun;
    if off_space {
        for (q, p) in ws.pressure[..ngp].iter_mut().enumerate() {
            *p = 1e8 * (1.0 + ((q * q) % 7) as f64);
        }
        // and a coupling v that is not 3κ Lᵀm: with cufem's materials
        // (D m = 3K m, J2 deviatoric) γ = α − wκβ vanishes at every point
        // and the projections Z_l with it, which would leave them unchecked
        for (q, (v, _)) in ws.coupling[..ngp].iter_mut().enumerate() {
            v[0] += 2e10 * (1.0 + (q % 3) as f64);
            v[1] -= 1e10;
            v[3] += 1e10 * ((q % 5) as f64 - 2.0);
            v[5] += 5e9;
        }
        nucleus::large_tangent(geom, (0, 0, nodes), geom.volumetric.as_ref(), &mut ws);
    }
    let n = 3 * nodes;
    let mut k = vec![0.0; n * n];
    let mut grads = vec![[0.0; 3]; nodes];
    // p̄ = Π p (B-bar)
    let pbar: Vec<f64> = match geom.volumetric.as_ref() {
        Some(ps) => {
            let mut p_l = [0.0; 4];
            for q in 0..ngp {
                for l in 0..ps.n {
                    p_l[l] += ws.weights[q] * ps.psi[q * ps.n + l] * ws.pressure[q];
                }
            }
            (0..ngp).map(|q| (0..ps.n).map(|l| ws.proj_c[4 * q + l] * p_l[l]).sum()).collect()
        }
        None => vec![0.0; ngp],
    };
    for gb in 0..geom.axis.n_gp {
        for gs in 0..geom.section.n_gp {
            let q = gb * geom.section.n_gp + gs;
            let w = geom.gradients(0, 0, gb, gs, &mut grads);
            let (f, c, s) = (&ws.frames[q], &ws.tangents[q], crate::voigt::stress_tensor(&ws.pk2[q]));
            let b: Vec<Voigt> = (0..n).map(|p| crate::kinematics::strain_variation(f, grads[p / 3], p % 3)).collect();
            let bbar = geom.volumetric.is_some();
            let (v, kappa) = ws.coupling[q];
            let d = |p: usize| if bbar { ws.bbar[q * nodes + p / 3][p % 3] } else { 0.0 };
            let gt = |p: usize, i: usize| ws.spatial[q * nodes + p / 3][i];
            for p in 0..n {
                for r in 0..n {
                    let mut x: f64 = (0..6).map(|i| (0..6).map(|j| b[p][i] * c[i][j] * b[r][j]).sum::<f64>()).sum();
                    if p % 3 == r % 3 {
                        let (ga, gb) = (grads[p / 3], grads[r / 3]);
                        x += (0..3).map(|i| (0..3).map(|j| ga[i] * s[i][j] * gb[j]).sum::<f64>()).sum::<f64>();
                    }
                    if bbar {
                        let bv = |t: usize| (0..6).map(|i| b[t][i] * v[i]).sum::<f64>() / 3.0;
                        x += bv(p) * d(r) + d(p) * bv(r) + kappa * d(p) * d(r);
                        x -= (pbar[q] - ws.pressure[q]) * gt(p, r % 3) * gt(r, p % 3);
                    }
                    k[p * n + r] += w * x;
                }
            }
        }
    }
    (ws.tangent.clone(), k, stats.plastic_points)
}
