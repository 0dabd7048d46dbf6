//! The total-Lagrangian kernel's own term: the geometric (initial-stress)
//! stiffness `K_(ak,bl) = δ_kl ∫ ∇N_a · S ∇N_b dV₀` (crate::kinematics),
//! a scalar per node pair times the 3×3 identity, added to the material
//! part that `gather_operators` and `tangent_product` formed.

use super::Workspace;
use crate::values::CellValues;

/// Adds the geometric stiffness of element `(es, eb)` (with `nodes` nodes)
/// to the upper triangle of `ws.tangent`, from the second Piola–Kirchhoff
/// stresses `ws.pk2` of the first pass.
pub(super) fn add_geometric_stiffness(geom: &CellValues, es: usize, eb: usize, nodes: usize, ws: &mut Workspace) {
    let (sg, ag) = (&geom.section, &geom.axis);
    let n = 3 * nodes;
    // kg[a][b] for a ≤ b, row-major nodes × nodes; S ∇N_b per node
    let mut kg = std::mem::take(&mut ws.geometric);
    let mut sg_b = std::mem::take(&mut ws.stressed_grads);
    kg.clear();
    kg.resize(nodes * nodes, 0.0);
    sg_b.resize(nodes, [0.0; 3]);
    for gb in 0..ag.n_gp {
        for gs in 0..sg.n_gp {
            let q = gb * sg.n_gp + gs;
            let w = geom.gradients(es, eb, gb, gs, &mut ws.grads[..nodes]);
            let s = crate::voigt::stress_tensor(&ws.pk2[q]);
            for (sgb, g) in sg_b.iter_mut().zip(&ws.grads[..nodes]) {
                *sgb = std::array::from_fn(|i| w * (s[i][0] * g[0] + s[i][1] * g[1] + s[i][2] * g[2]));
            }
            for a in 0..nodes {
                let ga = ws.grads[a];
                let row = &mut kg[a * nodes..(a + 1) * nodes];
                for (k, sgb) in row[a..].iter_mut().zip(&sg_b[a..]) {
                    *k += ga[0] * sgb[0] + ga[1] * sgb[1] + ga[2] * sgb[2];
                }
            }
        }
    }
    for a in 0..nodes {
        for b in a..nodes {
            let v = kg[a * nodes + b];
            for k in 0..3 {
                ws.tangent[(3 * a + k) * n + 3 * b + k] += v;
            }
        }
    }
    (ws.geometric, ws.stressed_grads) = (kg, sg_b);
}
