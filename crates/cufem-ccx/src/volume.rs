//! The volume of a rigid tool's hexahedra: an impactor's mass is its
//! tool's, through the density `m / V` ([`super::deck`]).

use super::mesh::{HEX_NODES, HexMesh, Tool};

/// Volume (m³) of a tool's 8-node hexahedra (2 × 2 × 2 Gauss points of
/// the trilinear map: exact for the tools' straight-edged cells).
pub fn tool_volume(mesh: &HexMesh, tool: &Tool) -> f64 {
    let g = 1.0 / 3f64.sqrt();
    let mut volume = 0.0;
    for e in &mesh.elements[tool.elements.clone()] {
        for gp in 0..8 {
            let xi = [0, 1, 2].map(|k| if gp >> k & 1 == 1 { g } else { -g });
            let mut jac = [[0.0; 3]; 3];
            // the corners: the first eight nodes in CalculiX order
            for (a, c) in HEX_NODES[..8].iter().enumerate() {
                let x = mesh.nodes[e[a]];
                for d in 0..3 {
                    // ∂N_a/∂ξ_d of N_a = Π (1 + c_k ξ_k)/8
                    let dn = c[d] * (0..3).filter(|&k| k != d).map(|k| 1.0 + c[k] * xi[k]).product::<f64>() / 8.0;
                    for (i, row) in jac.iter_mut().enumerate() {
                        row[d] += x[i] * dn;
                    }
                }
            }
            let det = jac[0][0] * (jac[1][1] * jac[2][2] - jac[1][2] * jac[2][1])
                - jac[0][1] * (jac[1][0] * jac[2][2] - jac[1][2] * jac[2][0])
                + jac[0][2] * (jac[1][0] * jac[2][1] - jac[1][1] * jac[2][0]);
            volume += det.abs();
        }
    }
    volume
}
