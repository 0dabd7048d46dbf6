//! A node-level (scalar) element matrix written out for the three
//! displacement components, as the mass matrices are formed.

use super::MassKind;

/// Writes the node-level matrix `m` (`nodes` square, row-major, one
/// displacement component) into the zeroed `tangent` (`3 nodes` square,
/// row-major, DOF `3a + c`) for each of the three components: its upper
/// triangle, or for `kind = Lumped` its row sums on the diagonal.
pub(super) fn expand(m: &[f64], nodes: usize, kind: MassKind, tangent: &mut [f64]) {
    let n = 3 * nodes;
    for a in 0..nodes {
        let row = &m[a * nodes..(a + 1) * nodes];
        for c in 0..3 {
            let p = 3 * a + c;
            match kind {
                MassKind::Consistent => {
                    for (b, &v) in row.iter().enumerate().skip(a) {
                        tangent[p * n + 3 * b + c] = v;
                    }
                }
                MassKind::Lumped => tangent[p * n + p] = row.iter().sum(),
            }
        }
    }
}
