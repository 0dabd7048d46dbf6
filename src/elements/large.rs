//! The total-Lagrangian kernel's own term: the geometric (initial-stress)
//! stiffness `K_(ak,bl) = δ_kl ∫ ∇N_a · S ∇N_b dV₀` (crate::kinematics),
//! a scalar per node pair times the 3×3 identity, added to the material
//! part that `gather_operators` and `tangent_product` formed.
//!
//! The scalars are one product, as the material part: with the gradients
//! of all nodes at all Gauss points stacked, `G` (nodes × 3Q) and
//! `G_S` (`w S ∇N_a` in the same layout), `k = G G_Sᵀ` (faer GEMM, upper
//! triangle). The node-pair loop it replaced took 15 % of a
//! total-Lagrangian run's time.

use super::Workspace;
use crate::values::CellValues;

/// Adds the geometric stiffness of element `(es, eb)` (with `nodes` nodes)
/// to the upper triangle of `ws.tangent`, from the second Piola–Kirchhoff
/// stresses `ws.pk2` of the first pass.
pub(super) fn add_geometric_stiffness(geom: &CellValues, es: usize, eb: usize, nodes: usize, ws: &mut Workspace) {
    let (sg, ag) = (&geom.section, &geom.axis);
    let n = 3 * nodes;
    let stride = 3 * sg.n_gp * ag.n_gp;
    let mut g = std::mem::take(&mut ws.gradients);
    let mut gs = std::mem::take(&mut ws.stressed_grads);
    g.resize(nodes * stride, 0.0);
    gs.resize(nodes * stride, 0.0);
    for gb in 0..ag.n_gp {
        for gp in 0..sg.n_gp {
            let q = gb * sg.n_gp + gp;
            let w = geom.gradients(es, eb, gb, gp, &mut ws.grads[..nodes]);
            let s = crate::voigt::stress_tensor(&ws.pk2[q]);
            for (a, ga) in ws.grads[..nodes].iter().enumerate() {
                let p = a * stride + 3 * q;
                g[p..p + 3].copy_from_slice(ga);
                for i in 0..3 {
                    gs[p + i] = w * (s[i][0] * ga[0] + s[i][1] * ga[1] + s[i][2] * ga[2]);
                }
            }
        }
    }
    let mut kg = std::mem::take(&mut ws.geometric);
    kg.resize(nodes * nodes, 0.0);
    super::upper_product(
        faer::MatMut::from_row_major_slice_mut(&mut kg, nodes, nodes),
        faer::MatRef::from_row_major_slice(&g, nodes, stride),
        faer::MatRef::from_row_major_slice(&gs, nodes, stride),
    );
    for a in 0..nodes {
        for b in a..nodes {
            let v = kg[a * nodes + b];
            for k in 0..3 {
                ws.tangent[(3 * a + k) * n + 3 * b + k] += v;
            }
        }
    }
    (ws.geometric, ws.gradients, ws.stressed_grads) = (kg, g, gs);
}
