//! Equation numbering and the sparsity pattern.
//!
//! Nodes are ordered by METIS nested dissection of the node graph (two
//! nodes are adjacent when they share an element or a contact pair); the
//! free degrees of freedom are then numbered node by node in that order, so
//! the matrix handed to the Cholesky factorization is already fill-reduced.
//! Constrained DOFs get no equation. The pattern is the lower triangle of
//! the tangent in compressed-column form, built from the tensor-product
//! structure of CUF bodies: nodes `(i, τ)` and `(j, s)` are coupled iff beam
//! nodes `i, j` share a beam element and section nodes `τ, s` share a
//! section element.

use std::collections::BTreeSet;

use crate::mesh::Mesh;
use crate::solver::linear::{LinearError, LowerCsc, nested_dissection};

/// Marker for a DOF without an equation (constrained).
pub const NO_EQ: usize = usize::MAX;

/// Map from global DOFs (`3 · node + component`) to equations.
#[derive(Debug, Clone)]
pub struct DofMap {
    /// Equation of each DOF, or [`NO_EQ`].
    pub eq: Vec<usize>,
    /// Number of equations (free DOFs).
    pub n_eq: usize,
}

/// Equation numbering and sparsity pattern: everything the symbolic
/// factorization needs, built before the (larger) scatter maps so that the
/// memory of the whole analysis can be estimated first.
#[derive(Debug, Clone)]
pub struct Numbering {
    /// DOF → equation map.
    pub dofs: DofMap,
    /// Lower-triangular pattern in equation numbering.
    pub pattern: LowerCsc,
    /// Node adjacency entries (node pairs sharing an element or a contact pair, with self).
    pub node_pairs: usize,
    /// Time spent building the node graph and the METIS ordering.
    pub ordering_time: std::time::Duration,
    /// Time spent building the pattern.
    pub pattern_time: std::time::Duration,
}

impl Numbering {
    /// Orders the nodes (METIS nested dissection), numbers the free DOFs and
    /// builds the pattern. `constrained[d]` marks DOFs without an equation;
    /// `couplings` lists extra node pairs (contact between bodies).
    pub fn new(mesh: &Mesh, constrained: &[bool], couplings: &[(usize, usize)]) -> Result<Self, LinearError> {
        let t0 = std::time::Instant::now();
        let adjacency = node_adjacency(mesh, couplings);
        let node_pairs = adjacency.iter().map(Vec::len).sum();
        let graph: Vec<Vec<usize>> =
            adjacency.iter().enumerate().map(|(n, l)| l.iter().copied().filter(|&m| m != n).collect()).collect();
        let order = nested_dissection(&graph)?;
        drop(graph);
        let mut eq = vec![NO_EQ; 3 * mesh.n_nodes()];
        let mut n_eq = 0;
        for &node in &order {
            for c in 0..3 {
                if !constrained[3 * node + c] {
                    eq[3 * node + c] = n_eq;
                    n_eq += 1;
                }
            }
        }
        let dofs = DofMap { eq, n_eq };
        let ordering_time = t0.elapsed();
        let t0 = std::time::Instant::now();
        let pattern = lower_pattern(&dofs, &adjacency);
        if pattern.nnz() >= u32::MAX as usize {
            return Err(LinearError::Symbolic(format!(
                "{} stored matrix entries exceed the scatter-map index range (u32)",
                pattern.nnz()
            )));
        }
        Ok(Self { dofs, pattern, node_pairs, ordering_time, pattern_time: t0.elapsed() })
    }
}

/// Sorted node adjacency (including the node itself) of the whole mesh.
pub(crate) fn node_adjacency(mesh: &Mesh, couplings: &[(usize, usize)]) -> Vec<Vec<usize>> {
    let mut adjacency = Vec::with_capacity(mesh.n_nodes());
    for body in &mesh.bodies {
        let sec = &body.section;
        let mut sec_adj = vec![BTreeSet::new(); sec.n_nodes()];
        for e in 0..sec.n_elements() {
            let el = sec.element(e);
            for &a in el {
                sec_adj[a].extend(el.iter().copied());
            }
        }
        let p = body.axis.kind.order();
        let mut ax_adj = vec![BTreeSet::new(); body.axis.n_nodes()];
        for e in 0..body.axis.n_elements() {
            let first = body.axis.first_node(e);
            for i in first..=first + p {
                ax_adj[i].extend(first..=first + p);
            }
        }
        for ax in &ax_adj {
            for sa in &sec_adj {
                adjacency.push(ax.iter().flat_map(|&j| sa.iter().map(move |&s| body.node(j, s))).collect::<Vec<_>>());
            }
        }
    }
    for &(a, b) in couplings {
        adjacency[a].push(b);
        adjacency[b].push(a);
    }
    for l in &mut adjacency {
        l.sort_unstable();
        l.dedup();
    }
    adjacency
}

/// Lower-triangular pattern in equation numbering.
fn lower_pattern(dofs: &DofMap, adjacency: &[Vec<usize>]) -> LowerCsc {
    let mut columns: Vec<Vec<usize>> = vec![Vec::new(); dofs.n_eq];
    for (node, adj) in adjacency.iter().enumerate() {
        for c in 0..3 {
            let col = dofs.eq[3 * node + c];
            if col == NO_EQ {
                continue;
            }
            let rows = &mut columns[col];
            for &m in adj {
                for d in 0..3 {
                    let r = dofs.eq[3 * m + d];
                    if r != NO_EQ && r >= col {
                        rows.push(r);
                    }
                }
            }
            rows.sort_unstable();
        }
    }
    LowerCsc::from_columns(dofs.n_eq, &columns)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::mesh::{BeamAxis, Body, CrossSection, Division};
    use crate::shape::{BeamElementKind, SectionElementKind};

    /// Two bodies of different element kinds (L4 × B2 and L16 × B3, the
    /// second with a skewed two-quad section).
    pub(crate) fn two_body_mesh() -> Mesh {
        let xl = Division::uniform(0.0, 0.02, 2).lines("x").unwrap();
        let zl = Division::uniform(0.0, 0.01, 3).lines("z").unwrap();
        let yl = Division::uniform(0.0, 0.05, 3).lines("y").unwrap();
        let a = Body {
            name: "a".into(),
            section: CrossSection::rectangle(SectionElementKind::L4, &xl, &zl).unwrap(),
            axis: BeamAxis::from_lines(BeamElementKind::B2, &yl),
            material: 0,
            element_materials: Vec::new(),
            element_layers: Vec::new(),
            node_offset: 0,
            element_offset: 0,
            whole_size: None,
        };
        let corners = [[0.0, 0.01], [0.011, 0.011], [0.02, 0.01], [0.0, 0.02], [0.01, 0.021], [0.02, 0.02]];
        let b = Body {
            name: "b".into(),
            section: CrossSection::from_quads(SectionElementKind::L16, &corners, &[[0, 1, 4, 3], [1, 2, 5, 4]], "s")
                .unwrap(),
            axis: BeamAxis::from_lines(BeamElementKind::B3, &Division::uniform(0.0, 0.05, 2).lines("y").unwrap()),
            material: 0,
            element_materials: Vec::new(),
            element_layers: Vec::new(),
            node_offset: 0,
            element_offset: 0,
            whole_size: None,
        };
        Mesh::new(vec![a, b])
    }

    /// Every pair of free DOFs of every element (and of every coupled node
    /// pair) has its entry in the pattern, and the pattern has no other
    /// entry; free DOFs are numbered once each, constrained ones not at all.
    #[test]
    fn the_pattern_holds_exactly_the_element_and_coupling_entries() {
        let mesh = two_body_mesh();
        let n = mesh.n_dofs();
        // constrain u_z on the first 20 nodes and u_x of every 7th DOF's node
        let constrained: Vec<bool> = (0..n).map(|d| (d / 3 < 20 && d % 3 == 2) || d % 21 == 0).collect();
        let last_a = mesh.bodies[0].n_nodes() - 1;
        let couplings = [(last_a, mesh.bodies[1].node_offset + 3)];
        let num = Numbering::new(&mesh, &constrained, &couplings).unwrap();
        let mut seen = vec![false; num.dofs.n_eq];
        for (d, &e) in num.dofs.eq.iter().enumerate() {
            assert_eq!(e == NO_EQ, constrained[d]);
            if e != NO_EQ {
                assert!(!seen[e], "equation {e} numbered twice");
                seen[e] = true;
            }
        }
        assert!(seen.iter().all(|&s| s));
        let mut expected = std::collections::BTreeSet::new();
        let mut add_nodes = |nodes: &[usize]| {
            for &a in nodes {
                for &b in nodes {
                    for (i, j) in (0..3).flat_map(|i| (0..3).map(move |j| (i, j))) {
                        let (r, c) = (num.dofs.eq[3 * a + i], num.dofs.eq[3 * b + j]);
                        if r != NO_EQ && c != NO_EQ && r >= c {
                            expected.insert((r, c));
                        }
                    }
                }
            }
        };
        let mut nodes = Vec::new();
        for body in &mesh.bodies {
            for e in 0..body.n_elements() {
                body.element_nodes(e, &mut nodes);
                add_nodes(&nodes);
            }
        }
        for &(a, b) in &couplings {
            add_nodes(&[a, b]);
        }
        for &(r, c) in &expected {
            assert!(num.pattern.find(r, c).is_some(), "entry ({r}, {c}) missing");
        }
        assert_eq!(num.pattern.nnz(), expected.len(), "the pattern holds entries no element couples");
    }
}
