//! Twin edges: the two faces of a cohesive interface between the plies of
//! a laminate section. Where an interface is cohesive each ply has its own
//! row of corner points at the interface's z, so the two plies' elements
//! meet along edges at the same place that share no node; the pairs are
//! kept in [`CrossSection::twins`]. Swept along the beam axis a twin is the
//! interface's surface, and the twin nodes `(τ_lower, τ_upper)` at each beam
//! node are the two sides of one interface point (`crate::interfaces`).
//!
//! A twin edge is no boundary (`CrossSection::boundary_edges` leaves it
//! out: a face selection at the interface's z finds no face there, as
//! without twins) and joins its two elements into one part
//! ([`CrossSection::parts`]).

use std::collections::HashSet;

use super::{CrossSection, MeshError};
use crate::shape::SectionElementKind;

/// Two element edges at one place, facing each other across an interface:
/// `(element, local edge)` of the element below and of the one above. Both
/// edges list their nodes in the same order along the edge, so the `t`-th
/// nodes of the two are twins.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EdgeTwin {
    /// The lower element and its edge.
    pub lower: (usize, usize),
    /// The upper element and its edge.
    pub upper: (usize, usize),
    /// The interface: the 0-based index of the ply below it.
    pub interface: usize,
}

impl CrossSection {
    /// Every `(element, local edge)` of a twin.
    pub(crate) fn twin_edges(&self) -> HashSet<(usize, usize)> {
        self.twins.iter().flat_map(|t| [t.lower, t.upper]).collect()
    }

    /// The twin node pairs `(τ_lower, τ_upper)` of interface `interface`,
    /// each with its share of the interface's width `∫F_τ ds` (m; the
    /// integral of the node's shape function along the edges it lies on,
    /// the closed Newton–Cotes weight of equispaced nodes), in the order of
    /// first appearance.
    pub(crate) fn twin_nodes(&self, interface: usize) -> Vec<(usize, usize, f64)> {
        let weights = edge_weights(self.kind.order());
        let mut out: Vec<(usize, usize, f64)> = Vec::new();
        let mut index = std::collections::HashMap::new();
        for t in self.twins.iter().filter(|t| t.interface == interface) {
            let lower: Vec<usize> =
                self.edge_local_nodes(t.lower.1).iter().map(|&a| self.element(t.lower.0)[a]).collect();
            let upper: Vec<usize> =
                self.edge_local_nodes(t.upper.1).iter().map(|&a| self.element(t.upper.0)[a]).collect();
            let (a, b) = (self.nodes[lower[0]], self.nodes[*lower.last().unwrap()]);
            let length = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            for (k, (&l, &u)) in lower.iter().zip(&upper).enumerate() {
                let slot = *index.entry((l, u)).or_insert_with(|| {
                    out.push((l, u, 0.0));
                    out.len() - 1
                });
                out[slot].2 += weights[k] * length;
            }
        }
        out
    }

    /// A stack of plies over `x_lines`, ply `k` divided by its element
    /// boundaries `plies[k]` (increasing z; each ply's first line is the
    /// previous ply's last). Where `split[k]` (the interface above ply `k`)
    /// the two plies get their own corner rows, and the edges between them
    /// become twins; elsewhere they share their nodes. Elements are numbered
    /// row by row from the bottom, x fastest, as [`CrossSection::rectangle`]
    /// does, which this is without splits.
    pub fn stack(
        kind: SectionElementKind,
        x_lines: &[f64],
        plies: &[Vec<f64>],
        split: &[bool],
    ) -> Result<Self, MeshError> {
        let nx = x_lines.len();
        let mut corners: Vec<[f64; 2]> = Vec::new();
        // the corner row of each ply's lines
        let mut rows: Vec<Vec<usize>> = Vec::new();
        let mut n_rows = 0;
        for (k, lines) in plies.iter().enumerate() {
            let shared = k > 0 && !split[k - 1];
            let mut ply_rows = Vec::with_capacity(lines.len());
            for (j, &z) in lines.iter().enumerate() {
                if j == 0 && shared {
                    ply_rows.push(n_rows - 1);
                    continue;
                }
                corners.extend(x_lines.iter().map(|&x| [x, z]));
                ply_rows.push(n_rows);
                n_rows += 1;
            }
            rows.push(ply_rows);
        }
        let mut quads = Vec::new();
        let mut first_row = Vec::with_capacity(plies.len());
        for ply_rows in &rows {
            first_row.push(quads.len() / (nx - 1));
            for w in ply_rows.windows(2) {
                for i in 0..nx - 1 {
                    let (c, d) = (w[0] * nx + i, w[1] * nx + i);
                    quads.push([c, c + 1, d + 1, d]);
                }
            }
        }
        let mut section = Self::from_quads(kind, &corners, &quads, "section")?;
        let ne = nx - 1;
        for k in (0..plies.len().saturating_sub(1)).filter(|&k| split[k]) {
            let top_row = first_row[k] + plies[k].len() - 2;
            for i in 0..ne {
                section.twins.push(EdgeTwin {
                    lower: (top_row * ne + i, 2),
                    upper: (first_row[k + 1] * ne + i, 0),
                    interface: k,
                });
            }
        }
        Ok(section)
    }
}

/// `∫N_a` over `[0, 1]` of the equispaced Lagrange basis of order `p`: the
/// closed Newton–Cotes weights (p = 3: 1/8, 3/8, 3/8, 1/8; p = 4: 7, 32,
/// 12, 32, 7 over 90), by Gauss quadrature of the basis itself.
pub(crate) fn edge_weights(p: usize) -> Vec<f64> {
    let basis = crate::shape::Lagrange1d::new(p);
    let rule = crate::quadrature::GaussRule::new(p + 1);
    let mut w = vec![0.0; basis.len()];
    let (mut n, mut dn) = (vec![0.0; basis.len()], vec![0.0; basis.len()]);
    for (&x, &wq) in rule.points.iter().zip(&rule.weights) {
        basis.eval(x, &mut n, &mut dn);
        for (wa, na) in w.iter_mut().zip(&n) {
            *wa += 0.5 * wq * na;
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Newton–Cotes weights of the closed rules (Abramowitz & Stegun
    /// 25.4.13–25.4.14: trapezoid, Simpson, 3/8, Boole).
    #[test]
    fn edge_weights_are_the_closed_newton_cotes_weights() {
        let expect: [&[f64]; 4] = [
            &[0.5, 0.5],
            &[1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0],
            &[0.125, 0.375, 0.375, 0.125],
            &[7.0 / 90.0, 32.0 / 90.0, 12.0 / 90.0, 32.0 / 90.0, 7.0 / 90.0],
        ];
        for (p, e) in (1..=4).zip(expect) {
            let w = edge_weights(p);
            assert_eq!(w.len(), e.len());
            for (a, b) in w.iter().zip(e) {
                assert!((a - b).abs() < 1e-14, "p = {p}: {w:?}");
            }
        }
    }

    /// Without splits the stack is the rectangle, node for node; a split
    /// doubles the interface's nodes, keeps one part and no boundary there.
    #[test]
    fn a_split_doubles_the_interface_nodes_only() {
        let xl = [0.0, 0.5, 1.0];
        let plies = vec![vec![0.0, 0.1, 0.2], vec![0.2, 0.3]];
        let whole = CrossSection::stack(SectionElementKind::L9, &xl, &plies, &[false]).unwrap();
        let rect = CrossSection::rectangle(SectionElementKind::L9, &xl, &[0.0, 0.1, 0.2, 0.3]).unwrap();
        assert_eq!(whole.nodes, rect.nodes);
        assert_eq!(whole.connectivity, rect.connectivity);
        assert!(whole.twins.is_empty());
        let split = CrossSection::stack(SectionElementKind::L9, &xl, &plies, &[true]).unwrap();
        // one more row of 2·2 + 1 = 5 nodes at z = 0.2
        assert_eq!(split.n_nodes(), rect.n_nodes() + 5);
        assert_eq!(split.n_elements(), rect.n_elements());
        assert_eq!(split.twins.len(), 2);
        assert_eq!(split.parts().len(), 1);
        assert_eq!(split.boundary_edges().len(), rect.boundary_edges().len());
        let pairs = split.twin_nodes(0);
        assert_eq!(pairs.len(), 5);
        for &(l, u, w) in &pairs {
            assert_ne!(l, u);
            assert_eq!(split.nodes[l], split.nodes[u]);
            assert!(split.nodes[l][1] == 0.2 && w > 0.0);
        }
        // the widths add up to the interface's width
        assert!((pairs.iter().map(|p| p.2).sum::<f64>() - 1.0).abs() < 1e-14);
    }

    /// A symmetry cut keeps the twins whose two elements it keeps,
    /// renumbered with them.
    #[test]
    fn a_cut_keeps_the_twins_of_the_kept_elements() {
        let xl = [0.0, 0.5, 1.0];
        let plies = vec![vec![0.0, 0.1], vec![0.1, 0.2]];
        let split = CrossSection::stack(SectionElementKind::L9, &xl, &plies, &[true]).unwrap();
        assert_eq!(split.twins.len(), 2);
        let centre = |e: usize| split.element(e).iter().map(|&n| split.nodes[n][0]).sum::<f64>() / 9.0;
        let right = split.retain_elements(|e| centre(e) > 0.5);
        assert_eq!(right.twins, vec![EdgeTwin { lower: (0, 2), upper: (1, 0), interface: 0 }]);
        assert_eq!(right.twin_nodes(0).len(), 3);
        let bottom = split.retain_elements(|e| e < 2);
        assert!(bottom.twins.is_empty());
    }
}
