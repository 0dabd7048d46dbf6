//! Cross-section meshes over the x–z plane: Lagrange quadrilaterals L4, L9,
//! L16 with straight edges (the isoparametric map itself is general, so any
//! convex quadrilateral works).
//!
//! Every builder reduces to [`CrossSection::from_quads`]: a list of corner
//! points and counter-clockwise quadrilaterals. Higher-order nodes are then
//! generated on the straight edges and inside each quad; nodes on an edge
//! shared by two quads are shared.

use std::collections::HashMap;

use super::MeshError;
use super::twins::EdgeTwin;
use crate::shape::{Lagrange2d, SectionElementKind};

/// A cross-section mesh: nodes `(x, z)` and quadrilateral Lagrange elements.
#[derive(Debug, Clone)]
pub struct CrossSection {
    /// Element type (all elements of a section share it).
    pub kind: SectionElementKind,
    /// Node coordinates `(x, z)` in m.
    pub nodes: Vec<[f64; 2]>,
    /// Connectivity, `kind.nodes()` entries per element, in the lexicographic
    /// local order of [`crate::shape`].
    pub connectivity: Vec<usize>,
    /// Named groups of elements (the walls of a parametric profile, the
    /// physical groups of a gmsh file); empty for the other builders.
    pub regions: Vec<Region>,
    /// Pairs of edges at the same place that share no node: the two faces of
    /// a cohesive interface between plies ([`super::twins`]); empty unless
    /// a laminate's interfaces are cohesive.
    pub twins: Vec<EdgeTwin>,
}

/// A named group of section elements.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// Name (a profile's wall, or a gmsh physical group).
    pub name: String,
    /// Section element indices, increasing.
    pub elements: Vec<usize>,
    /// The wall's normal `(x, z)` of a ply through a profile's wall
    /// (`None` for other regions).
    pub normal: Option<[f64; 2]>,
}

/// Local edge `k` of a quadrilateral as seen from its natural coordinates:
/// 0: η = −1, 1: ξ = +1, 2: η = +1, 3: ξ = −1.
pub(crate) const EDGES: usize = 4;

impl CrossSection {
    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.connectivity.len() / self.kind.nodes()
    }

    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Global node indices of element `e`.
    pub fn element(&self, e: usize) -> &[usize] {
        let m = self.kind.nodes();
        &self.connectivity[e * m..(e + 1) * m]
    }

    /// Local node indices (in the element's lexicographic order) on local edge `k`,
    /// ordered along the edge parameter (increasing ξ or η).
    pub(crate) fn edge_local_nodes(&self, k: usize) -> Vec<usize> {
        let m = self.kind.order() + 1;
        (0..m)
            .map(|t| match k {
                0 => t,
                1 => t * m + (m - 1),
                2 => (m - 1) * m + t,
                _ => t * m,
            })
            .collect()
    }

    /// Builds a section from corner points and counter-clockwise quads
    /// (corner order: (−1,−1), (1,−1), (1,1), (−1,1) in natural coordinates).
    /// `key` names the model-file key in errors.
    pub(crate) fn from_quads(
        kind: SectionElementKind,
        corners: &[[f64; 2]],
        quads: &[[usize; 4]],
        key: &str,
    ) -> Result<Self, MeshError> {
        check_quads(corners, quads, key)?;
        let (nodes, connectivity) = lagrange_nodes(kind.order(), corners, quads);
        Ok(Self { kind, nodes, connectivity, regions: Vec::new(), twins: Vec::new() })
    }

    /// A rectangle cut by the given element boundaries along x and along z.
    pub fn rectangle(kind: SectionElementKind, x_lines: &[f64], z_lines: &[f64]) -> Result<Self, MeshError> {
        let nx = x_lines.len();
        let mut corners = Vec::with_capacity(nx * z_lines.len());
        for &z in z_lines {
            for &x in x_lines {
                corners.push([x, z]);
            }
        }
        let mut quads = Vec::new();
        for j in 0..z_lines.len() - 1 {
            for i in 0..nx - 1 {
                let c = j * nx + i;
                quads.push([c, c + 1, c + 1 + nx, c + nx]);
            }
        }
        Self::from_quads(kind, &corners, &quads, "section")
    }

    /// A thin-walled rectangular tube with outer corner `(x0, z0)`, outer
    /// `width` × `height` and wall `thickness`. Each corner is a square block
    /// of `through × through` elements; the straight parts between corner
    /// blocks carry `along_x` (top and bottom walls) and `along_z` (side walls)
    /// elements, `through` elements thick. Elements around the wall (for
    /// `through = 1`): `4 + 2 along_x + 2 along_z`.
    #[allow(clippy::too_many_arguments)]
    pub fn tube(
        kind: SectionElementKind,
        x0: f64,
        z0: f64,
        width: f64,
        height: f64,
        thickness: f64,
        along_x: usize,
        along_z: usize,
        through: usize,
    ) -> Result<Self, MeshError> {
        let xl = tube_lines(x0, width, thickness, along_x, through);
        let zl = tube_lines(z0, height, thickness, along_z, through);
        let (nx, nz) = (xl.len() - 1, zl.len() - 1);
        Self::hollow_rectangle(kind, &xl, &zl, [[through, nx - through], [through, nz - through]])
    }

    /// A grid of element boundaries `x_lines` × `z_lines` whose cells with
    /// x interval in `hole[0][0]..hole[0][1]` and z interval in
    /// `hole[1][0]..hole[1][1]` are left out (an empty range leaves none
    /// out). Elements are numbered z interval by z interval, x fastest,
    /// skipping the hole's cells (as `grid::grid_cell` numbers them); a `tube`
    /// is this grid with its inside as the hole.
    pub(crate) fn hollow_rectangle(
        kind: SectionElementKind,
        x_lines: &[f64],
        z_lines: &[f64],
        hole: [[usize; 2]; 2],
    ) -> Result<Self, MeshError> {
        let nx = x_lines.len() - 1;
        // corner ids for used grid points only
        let mut id = vec![usize::MAX; (nx + 1) * z_lines.len()];
        let mut corners = Vec::new();
        let mut quads = Vec::new();
        for (i, j) in super::grid::grid_cells(nx, z_lines.len() - 1, Some(hole)) {
            let grid = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            let q = grid.map(|(a, b)| {
                let g = b * (nx + 1) + a;
                if id[g] == usize::MAX {
                    id[g] = corners.len();
                    corners.push([x_lines[a], z_lines[b]]);
                }
                id[g]
            });
            quads.push(q);
        }
        Self::from_quads(kind, &corners, &quads, "section")
    }

    /// Edges on the section boundary, as `(element, local edge)`; the
    /// edges of a cohesive interface ([`Self::twins`]) are inner surfaces,
    /// left out.
    pub(crate) fn boundary_edges(&self) -> Vec<(usize, usize)> {
        let inner = self.twin_edges();
        let mut count: HashMap<(usize, usize), usize> = HashMap::new();
        let ends = |e: usize, k: usize| {
            let loc = self.edge_local_nodes(k);
            let el = self.element(e);
            let (a, b) = (el[loc[0]], el[*loc.last().unwrap()]);
            (a.min(b), a.max(b))
        };
        for e in 0..self.n_elements() {
            for k in 0..EDGES {
                *count.entry(ends(e, k)).or_default() += 1;
            }
        }
        let mut out = Vec::new();
        for e in 0..self.n_elements() {
            for k in 0..EDGES {
                if count[&ends(e, k)] == 1 && !inner.contains(&(e, k)) {
                    out.push((e, k));
                }
            }
        }
        out
    }

    /// The section's parts: groups of elements connected through shared
    /// edges or the two faces of a cohesive interface (two elements sharing
    /// only a corner node are not connected: swept along the axis, that
    /// node is a hinge line). Each part lists its
    /// elements in increasing order; parts are ordered by their first element.
    pub fn parts(&self) -> Vec<Vec<usize>> {
        let n = self.n_elements();
        let mut parent: Vec<usize> = (0..n).collect();
        fn root(parent: &mut [usize], mut e: usize) -> usize {
            while parent[e] != e {
                parent[e] = parent[parent[e]];
                e = parent[e];
            }
            e
        }
        let mut first_user: HashMap<(usize, usize), usize> = HashMap::new();
        for e in 0..n {
            for k in 0..EDGES {
                let loc = self.edge_local_nodes(k);
                let el = self.element(e);
                let (a, b) = (el[loc[0]], el[*loc.last().unwrap()]);
                let other = *first_user.entry((a.min(b), a.max(b))).or_insert(e);
                let (ra, rb) = (root(&mut parent, e), root(&mut parent, other));
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
        for t in &self.twins {
            let (ra, rb) = (root(&mut parent, t.lower.0), root(&mut parent, t.upper.0));
            parent[ra.max(rb)] = ra.min(rb);
        }
        let mut parts: Vec<Vec<usize>> = Vec::new();
        let mut index: HashMap<usize, usize> = HashMap::new();
        for e in 0..n {
            let r = root(&mut parent, e);
            let k = *index.entry(r).or_insert_with(|| {
                parts.push(Vec::new());
                parts.len() - 1
            });
            parts[k].push(e);
        }
        parts
    }

    /// Bounding box `[xmin, xmax, zmin, zmax]`.
    pub fn bounds(&self) -> [f64; 4] {
        let mut b = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
        for n in &self.nodes {
            b[0] = b[0].min(n[0]);
            b[1] = b[1].max(n[0]);
            b[2] = b[2].min(n[1]);
            b[3] = b[3].max(n[1]);
        }
        b
    }
}

/// Rejects a quad list that is no conforming mesh of convex
/// counter-clockwise quads: no quad, an index out of range, a repeated
/// corner, a clockwise or non-convex quad, an edge shared by more than two
/// quads, overlapping quads, or a point no quad uses.
fn check_quads(corners: &[[f64; 2]], quads: &[[usize; 4]], key: &str) -> Result<(), MeshError> {
    if quads.is_empty() {
        return Err(MeshError::invalid(format!("{key}.quads"), "[]", "at least one quadrilateral"));
    }
    for (q, quad) in quads.iter().enumerate() {
        check_quad(corners, q, quad, key)?;
    }
    check_edge_use(quads, key)?;
    super::overlaps::check_overlaps(corners, quads, key)?;
    let mut used = vec![false; corners.len()];
    for &c in quads.iter().flatten() {
        used[c] = true;
    }
    if let Some(i) = used.iter().position(|u| !u) {
        return Err(MeshError::invalid(
            format!("{key}.points[{i}]"),
            format!("{:?}", corners[i]),
            "a point used by at least one quad (unused points would be unconstrained)",
        ));
    }
    Ok(())
}

/// Quad `q` alone: four distinct corner indices in range, convex and
/// counter-clockwise.
fn check_quad(corners: &[[f64; 2]], q: usize, quad: &[usize; 4], key: &str) -> Result<(), MeshError> {
    if quad.iter().any(|&c| c >= corners.len()) {
        return Err(MeshError::invalid(
            format!("{key}.quads[{q}]"),
            format!("{quad:?}"),
            format!("indices of points from 0 to {} (the points listed)", corners.len().saturating_sub(1)),
        ));
    }
    let mut sorted = *quad;
    sorted.sort_unstable();
    if sorted.windows(2).any(|w| w[0] == w[1]) {
        return Err(MeshError::invalid(
            format!("{key}.quads[{q}]"),
            format!("{quad:?}"),
            "four distinct corner points",
        ));
    }
    let [a, b, c, d] = quad.map(|i| corners[i]);
    // Jacobian sign at the four corners: all positive for a convex CCW quad.
    let cross = |o: [f64; 2], p: [f64; 2], r: [f64; 2]| (p[0] - o[0]) * (r[1] - o[1]) - (p[1] - o[1]) * (r[0] - o[0]);
    let dets = [cross(a, b, d), cross(b, c, a), cross(c, d, b), cross(d, a, c)];
    if dets.iter().any(|&v| !(v > 0.0)) {
        return Err(MeshError::invalid(
            format!("{key}.quads[{q}]"),
            format!("{quad:?}"),
            "a convex quadrilateral with corners listed counter-clockwise in the x–z plane",
        ));
    }
    Ok(())
}

/// A conforming mesh uses each edge at most twice: more means overlapping
/// or duplicated quads.
fn check_edge_use(quads: &[[usize; 4]], key: &str) -> Result<(), MeshError> {
    let mut edge_use: HashMap<(usize, usize), usize> = HashMap::new();
    for (q, quad) in quads.iter().enumerate() {
        for k in 0..4 {
            let (a, b) = (quad[k], quad[(k + 1) % 4]);
            let uses = edge_use.entry((a.min(b), a.max(b))).or_default();
            *uses += 1;
            if *uses > 2 {
                return Err(MeshError::invalid(
                    format!("{key}.quads[{q}]"),
                    format!("{quad:?}"),
                    format!("quads that do not overlap (the edge {a}–{b} is already shared by two quads)"),
                ));
            }
        }
    }
    Ok(())
}

/// The nodes and connectivity of Lagrange elements of order `p` over
/// checked quads: the corners first (same indices), then, quad by quad in
/// lexicographic local order, the nodes on an edge (shared with the quad
/// across it) and inside.
fn lagrange_nodes(p: usize, corners: &[[f64; 2]], quads: &[[usize; 4]]) -> (Vec<[f64; 2]>, Vec<usize>) {
    let m = p + 1;
    let basis = Lagrange2d::new(p);
    let mut nodes: Vec<[f64; 2]> = corners.to_vec();
    let mut edge_nodes: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    let mut connectivity = Vec::with_capacity(quads.len() * m * m);
    for quad in quads {
        for j in 0..m {
            for i in 0..m {
                let id = if let Some(c) = corner_at(quad, p, i, j) {
                    c
                } else if let Some((u, v, s)) = edge_at(quad, p, i, j) {
                    let key = (u.min(v), u.max(v));
                    let list = edge_nodes.entry(key).or_insert_with(|| {
                        // nodes ordered from the lower corner index to the higher
                        let (a, b) = (corners[key.0], corners[key.1]);
                        (1..p)
                            .map(|t| {
                                let f = t as f64 / p as f64;
                                nodes.push([a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]);
                                nodes.len() - 1
                            })
                            .collect()
                    });
                    if u < v { list[s - 1] } else { list[p - 1 - s] }
                } else {
                    let [xi, eta] = basis.node(j * m + i);
                    nodes.push(bilinear(quad.map(|c| corners[c]), xi, eta));
                    nodes.len() - 1
                };
                connectivity.push(id);
            }
        }
    }
    (nodes, connectivity)
}

/// The corner of `quad` at local node `(i, j)` of an order-`p` element.
fn corner_at(quad: &[usize; 4], p: usize, i: usize, j: usize) -> Option<usize> {
    match (i, j) {
        (0, 0) => Some(quad[0]),
        (i, 0) if i == p => Some(quad[1]),
        (i, j) if i == p && j == p => Some(quad[2]),
        (0, j) if j == p => Some(quad[3]),
        _ => None,
    }
}

/// The edge of `quad` through local node `(i, j)` (not a corner): `(u, v,
/// s)`, the edge from corner `u` to corner `v` and the node's position `s`
/// along it; `None` inside.
fn edge_at(quad: &[usize; 4], p: usize, i: usize, j: usize) -> Option<(usize, usize, usize)> {
    if j == 0 {
        Some((quad[0], quad[1], i))
    } else if j == p {
        Some((quad[3], quad[2], i))
    } else if i == 0 {
        Some((quad[0], quad[3], j))
    } else if i == p {
        Some((quad[1], quad[2], j))
    } else {
        None
    }
}

/// The bilinear map of a quad with corners `c` at natural point `(ξ, η)`.
fn bilinear(c: [[f64; 2]; 4], xi: f64, eta: f64) -> [f64; 2] {
    let w = [
        0.25 * (1.0 - xi) * (1.0 - eta),
        0.25 * (1.0 + xi) * (1.0 - eta),
        0.25 * (1.0 + xi) * (1.0 + eta),
        0.25 * (1.0 - xi) * (1.0 + eta),
    ];
    let mut x = [0.0; 2];
    for (k, wk) in w.iter().enumerate() {
        x[0] += wk * c[k][0];
        x[1] += wk * c[k][1];
    }
    x
}

/// The element boundaries of a `tube`'s walls across one direction: from
/// `start`, `through` elements through the first wall, `along` over the
/// `length − 2 thickness` between the walls, `through` through the second.
fn tube_lines(start: f64, length: f64, thickness: f64, along: usize, through: usize) -> Vec<f64> {
    let mut l = Vec::new();
    for k in 0..=through {
        l.push(start + thickness * k as f64 / through as f64);
    }
    let inner = length - 2.0 * thickness;
    for k in 1..=along {
        l.push(start + thickness + inner * k as f64 / along as f64);
    }
    for k in 1..=through {
        l.push(start + length - thickness + thickness * k as f64 / through as f64);
    }
    l
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_node_counts() {
        let xl: Vec<f64> = (0..=18).map(|i| i as f64 / 36.0).collect();
        let zl: Vec<f64> = (0..=6).map(|i| i as f64 / 20.0).collect();
        let s = CrossSection::rectangle(SectionElementKind::L9, &xl, &zl).unwrap();
        assert_eq!(s.n_elements(), 108);
        assert_eq!(s.n_nodes(), 37 * 13);
        let s = CrossSection::rectangle(SectionElementKind::L16, &xl[..3], &zl[..3]).unwrap();
        assert_eq!(s.n_nodes(), 7 * 7);
        let s = CrossSection::rectangle(SectionElementKind::L4, &xl[..3], &zl[..3]).unwrap();
        assert_eq!(s.n_nodes(), 9);
    }

    #[test]
    fn tube_ring_node_counts() {
        // A ring of n L9 elements, one through the wall, has 2n nodes per layer, 3 layers.
        for (along, n) in [(4, 20), (6, 28)] {
            let s = CrossSection::tube(SectionElementKind::L9, 0.0, 0.0, 0.03, 0.03, 0.0015, along, along, 1).unwrap();
            assert_eq!(s.n_elements(), n);
            assert_eq!(s.n_nodes(), 6 * n);
        }
    }

    #[test]
    fn element_nodes_sit_where_the_basis_says() {
        // Every element's nodes must map to the bilinear image of its natural nodes.
        let s = CrossSection::tube(SectionElementKind::L16, 0.0, 0.0, 0.04, 0.03, 0.004, 3, 2, 2).unwrap();
        let basis = Lagrange2d::new(3);
        for e in 0..s.n_elements() {
            let el = s.element(e);
            let (c0, c1, c2, c3) = (s.nodes[el[0]], s.nodes[el[3]], s.nodes[el[15]], s.nodes[el[12]]);
            for (k, &g) in el.iter().enumerate() {
                let [xi, eta] = basis.node(k);
                let w = [
                    0.25 * (1.0 - xi) * (1.0 - eta),
                    0.25 * (1.0 + xi) * (1.0 - eta),
                    0.25 * (1.0 + xi) * (1.0 + eta),
                    0.25 * (1.0 - xi) * (1.0 + eta),
                ];
                for d in 0..2 {
                    let x = w[0] * c0[d] + w[1] * c1[d] + w[2] * c2[d] + w[3] * c3[d];
                    assert!((x - s.nodes[g][d]).abs() < 1e-14);
                }
            }
        }
        // element count: four 2×2 corner blocks, 3 and 2 elements along the sides, 2 through
        assert_eq!(s.n_elements(), 4 * 4 + 2 * 3 * 2 + 2 * 2 * 2);
        // boundary edges: outer perimeter 2·(2+3+2) + 2·(2+2+2), inner 2·3 + 2·2
        assert_eq!(s.boundary_edges().len(), 2 * (7 + 6) + 2 * (3 + 2));
    }

    #[test]
    fn rejects_overlapping_quads() {
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let err = CrossSection::from_quads(SectionElementKind::L9, &corners, &[[0, 1, 2, 3]; 3], "s")
            .unwrap_err()
            .to_string();
        assert!(err.contains("s.quads[2]") && err.contains("do not overlap"), "{err}");
    }

    #[test]
    fn rejects_duplicated_and_partly_overlapping_quads() {
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.0], [0.5, 1.0], [2.0, 0.0], [2.0, 1.0]];
        // the same quad twice (its edges are used exactly twice, so the edge count alone misses it)
        let err = CrossSection::from_quads(SectionElementKind::L9, &corners, &[[0, 1, 2, 3], [0, 1, 2, 3]], "s")
            .unwrap_err()
            .to_string();
        assert!(err.contains("s.quads[1]") && err.contains("100.000 % of quads[0]"), "{err}");
        // a square plus its own left half
        let err = CrossSection::from_quads(SectionElementKind::L9, &corners, &[[0, 1, 2, 3], [0, 4, 5, 3]], "s")
            .unwrap_err()
            .to_string();
        assert!(err.contains("s.quads[1]") && err.contains("50.000 % of quads[0]"), "{err}");
        // neighbours sharing an edge are fine
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 0.0], [2.0, 1.0]];
        CrossSection::from_quads(SectionElementKind::L9, &corners, &[[0, 1, 2, 3], [1, 4, 5, 2]], "s").unwrap();
    }

    /// Elements touching only at a corner, or not at all, are separate
    /// parts; a shared edge joins them.
    #[test]
    fn parts_are_joined_by_edges_only() {
        let pts = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0], [2.0, 0.0]];
        let corner = CrossSection::from_quads(SectionElementKind::L9, &pts[..7], &[[0, 1, 2, 3], [2, 4, 5, 6]], "s");
        assert_eq!(corner.unwrap().parts(), vec![vec![0], vec![1]]);
        let edge =
            CrossSection::from_quads(SectionElementKind::L4, &pts, &[[0, 1, 2, 3], [2, 4, 5, 6], [1, 7, 4, 2]], "s");
        assert_eq!(edge.unwrap().parts(), vec![vec![0, 1, 2]]);
    }

    #[test]
    fn rejects_clockwise_quads() {
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let err = CrossSection::from_quads(SectionElementKind::L9, &corners, &[[0, 3, 2, 1]], "bodies[0].section")
            .unwrap_err()
            .to_string();
        assert!(err.contains("bodies[0].section.quads[0]") && err.contains("counter-clockwise"), "{err}");
    }
}
