//! Continuous stress and plastic-strain fields: the L2 projection of the
//! Gauss-point values onto the CUF displacement basis.
//!
//! For a Gauss-point field `f` (a stress component, peeq) the nodal values
//! `f_b` solve `M f = r` with the scalar "mass" matrix
//! `M_ab = ∫ N_a N_b dV` and `r_a = ∫ N_a f dV`, both integrated with the
//! element kernel's own Gauss rule (Hinton & Campbell, *Int. J. Numer.
//! Methods Eng.* 8, 1974; Zienkiewicz, Taylor & Zhu, *The Finite Element
//! Method* vol. 1, §14.3). `M` is factorized once (sparse Cholesky, nested
//! dissection ordering of the node graph) and solved for the seven fields.
//! The recovered field `Σ N_a f_a` is continuous across elements, smooth
//! where the solution is, and reproduces exactly any field the basis can
//! represent (the Gauss rule integrates `N_a N_b` exactly on affine
//! elements). Bodies are projected independently (no coupling across a
//! contact).

use crate::assembly::node_adjacency;
use crate::materials::PointState;
use crate::mesh::Mesh;
use crate::solver::linear::{Cholesky, LinearError, LowerCsc, nested_dissection};
use crate::values::{CellValues, shape_values};
use crate::voigt::Voigt;

/// Recovered nodal values, one per global node.
#[derive(Debug, Clone, Default)]
pub struct Recovered {
    /// Stress (Voigt order), Pa.
    pub stress: Vec<Voigt>,
    /// Equivalent plastic strain.
    pub peeq: Vec<f64>,
}

/// Projects the Gauss-point stresses and peeq of every body onto its basis.
pub(crate) fn project(
    mesh: &Mesh,
    cells: &[CellValues],
    stresses: &[Voigt],
    states: &[PointState],
    gp_offsets: &[usize],
) -> Result<Recovered, LinearError> {
    let n = mesh.n_nodes();
    // node order by nested dissection; equation k holds node order[k]
    let adjacency = node_adjacency(mesh, &[]);
    let graph: Vec<Vec<usize>> =
        adjacency.iter().enumerate().map(|(a, l)| l.iter().copied().filter(|&b| b != a).collect()).collect();
    let order = nested_dissection(&graph)?;
    let mut eq = vec![0; n];
    for (k, &node) in order.iter().enumerate() {
        eq[node] = k;
    }
    let mut columns: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (a, adj) in adjacency.iter().enumerate() {
        let c = eq[a];
        columns[c].extend(adj.iter().map(|&b| eq[b]).filter(|&r| r >= c));
    }
    for c in &mut columns {
        c.sort_unstable();
    }
    let pattern = LowerCsc::from_columns(n, &columns);
    let mut m = vec![0.0; pattern.nnz()];
    let mut rhs = vec![[0.0; 7]; n];
    let mut nodes = Vec::new();
    for (b, body) in mesh.bodies.iter().enumerate() {
        let cell = &cells[b];
        let mut shapes = vec![0.0; body.nodes_per_element()];
        let ngp = cell.gp_per_element();
        for e in 0..body.n_elements() {
            let (es, eb) = body.split_element(e);
            body.element_nodes(e, &mut nodes);
            for gb in 0..cell.axis.n_gp {
                for gs in 0..cell.section.n_gp {
                    let (s, a) = (cell.section.point(es, gs), cell.axis.point(eb, gb));
                    shape_values(s, a, &mut shapes);
                    let w = s.weight * a.weight;
                    let g = gp_offsets[b] + e * ngp + gb * cell.section.n_gp + gs;
                    let f = stresses[g];
                    let values = [f[0], f[1], f[2], f[3], f[4], f[5], states[g].peeq];
                    for (i, &na) in shapes.iter().enumerate() {
                        let r = &mut rhs[eq[nodes[i]]];
                        for k in 0..7 {
                            r[k] += w * na * values[k];
                        }
                        for (j, &nb) in shapes.iter().enumerate() {
                            let (p, q) = (eq[nodes[i]], eq[nodes[j]]);
                            if p >= q
                                && let Some(pos) = pattern.find(p, q)
                            {
                                m[pos] += w * na * nb;
                            }
                        }
                    }
                }
            }
        }
    }
    let mut chol = Cholesky::analyze(&pattern)?;
    chol.factorize(&m)?;
    let mut out = Recovered { stress: vec![[0.0; 6]; n], peeq: vec![0.0; n] };
    let mut column = vec![0.0; n];
    for k in 0..7 {
        for (c, r) in column.iter_mut().zip(&rhs) {
            *c = r[k];
        }
        chol.solve_in_place(&mut column)?;
        for (node, &e) in eq.iter().enumerate() {
            if k < 6 {
                out.stress[node][k] = column[e];
            } else {
                out.peeq[node] = column[e];
            }
        }
    }
    Ok(out)
}
