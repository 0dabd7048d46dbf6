//! Sections built from mapped blocks: each block is a map of the unit
//! square `(u, v) ∈ [0, 1]²` onto the x–z plane, cut into `n_u × n_v`
//! elements. Every Lagrange node of an element is placed by the map itself
//! (not on the straight chord between corners), so the nodes of a curved
//! wall lie on the curve and the isoparametric map interpolates it.
//!
//! Blocks that share an edge must place the same nodes on it (same count
//! and the same parametrization); nodes closer than 1e-9 of the section's
//! size are merged, which makes the mesh conforming and closes periodic
//! blocks (a ring whose `v = 1` edge is its `v = 0` edge).

use std::collections::HashMap;

use super::MeshError;
use super::section::{CrossSection, Region};
use crate::shape::SectionElementKind;

/// A map of the unit square onto the x–z plane (must keep the orientation:
/// `u` × `v` counter-clockwise).
pub(crate) type BlockMap = Box<dyn Fn(f64, f64) -> [f64; 2] + Send + Sync>;

/// One structured block of a section.
pub struct Block {
    /// Elements along `u` and along `v`.
    pub counts: [usize; 2],
    /// The map of the unit square.
    pub map: BlockMap,
    /// Region the block's elements belong to.
    pub region: String,
    /// The wall normal `(x, z)` of a ply block ([`super::section::Region::normal`]).
    pub normal: Option<[f64; 2]>,
}

impl std::fmt::Debug for Block {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Block").field("counts", &self.counts).field("region", &self.region).finish()
    }
}

impl Block {
    /// The axis-aligned rectangle `[x0, x1] × [z0, z1]` with `nx × nz` elements.
    pub fn rectangle(x: [f64; 2], z: [f64; 2], nx: usize, nz: usize, region: &str) -> Self {
        Self {
            counts: [nx, nz],
            map: Box::new(move |u, v| [x[0] + u * (x[1] - x[0]), z[0] + v * (z[1] - z[0])]),
            region: region.to_string(),
            normal: None,
        }
    }

    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.counts[0] * self.counts[1]
    }
}

/// Builds a section of `kind` elements from `blocks` (see the module docs).
pub(crate) fn from_blocks(kind: SectionElementKind, blocks: &[Block]) -> Result<CrossSection, MeshError> {
    if blocks.is_empty() || blocks.iter().any(|b| b.n_elements() == 0) {
        return Err(MeshError::invalid("section", "a profile without elements", "at least one element per wall"));
    }
    let p = kind.order();
    let m = p + 1;
    // the merge tolerance: 1e-9 of the extent of the block corners and mid-points
    let mut extent = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
    for b in blocks {
        for u in [0.0, 0.5, 1.0] {
            for v in [0.0, 0.5, 1.0] {
                let [x, z] = (b.map)(u, v);
                extent = [extent[0].min(x), extent[1].max(x), extent[2].min(z), extent[3].max(z)];
            }
        }
    }
    let size = (extent[1] - extent[0]).max(extent[3] - extent[2]);
    if !(size.is_finite() && size > 0.0) {
        return Err(MeshError::invalid("section", format!("extent {size:e} m"), "a section of positive finite size"));
    }
    let tol = 1e-9 * size;
    let mut merger = Merger { tol, cells: HashMap::new(), nodes: Vec::new() };
    let mut connectivity = Vec::new();
    let mut regions: Vec<Region> = Vec::new();
    let mut element = 0;
    for b in blocks {
        let [nu, nv] = b.counts;
        // node grid of the block: (p nu + 1) × (p nv + 1)
        let (gu, gv) = (p * nu + 1, p * nv + 1);
        let mut ids = Vec::with_capacity(gu * gv);
        for j in 0..gv {
            for i in 0..gu {
                let xz = (b.map)(i as f64 / (gu - 1) as f64, j as f64 / (gv - 1) as f64);
                if !xz.iter().all(|c| c.is_finite()) {
                    return Err(MeshError::invalid("section", format!("{xz:?}"), "finite node coordinates"));
                }
                ids.push(merger.insert(xz));
            }
        }
        let region = match regions.iter().position(|r| r.name == b.region) {
            Some(r) => r,
            None => {
                regions.push(Region { name: b.region.clone(), elements: Vec::new(), normal: b.normal });
                regions.len() - 1
            }
        };
        for ev in 0..nv {
            for eu in 0..nu {
                for j in 0..m {
                    for i in 0..m {
                        connectivity.push(ids[(ev * p + j) * gu + eu * p + i]);
                    }
                }
                regions[region].elements.push(element);
                element += 1;
            }
        }
    }
    Ok(CrossSection { kind, nodes: merger.nodes, connectivity, regions, twins: Vec::new() })
}

/// Merges coincident nodes through a grid of cells of the tolerance's size.
struct Merger {
    tol: f64,
    cells: HashMap<(i64, i64), Vec<usize>>,
    nodes: Vec<[f64; 2]>,
}

impl Merger {
    fn insert(&mut self, p: [f64; 2]) -> usize {
        let cell = |c: f64| (c / self.tol).floor() as i64;
        let (ci, cj) = (cell(p[0]), cell(p[1]));
        for di in -1..=1 {
            for dj in -1..=1 {
                if let Some(list) = self.cells.get(&(ci + di, cj + dj)) {
                    for &n in list {
                        let q = self.nodes[n];
                        if (q[0] - p[0]).abs() <= self.tol && (q[1] - p[1]).abs() <= self.tol {
                            return n;
                        }
                    }
                }
            }
        }
        self.nodes.push(p);
        let id = self.nodes.len() - 1;
        self.cells.entry((ci, cj)).or_default().push(id);
        id
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_rectangles_share_their_edge_nodes() {
        // [0,1]×[0,1] and [1,2]×[0,1], 2×2 L9 each: a 4×2 grid of L9, 9×5 nodes
        let blocks =
            [Block::rectangle([0.0, 1.0], [0.0, 1.0], 2, 2, "a"), Block::rectangle([1.0, 2.0], [0.0, 1.0], 2, 2, "b")];
        let s = from_blocks(SectionElementKind::L9, &blocks).unwrap();
        assert_eq!(s.n_elements(), 8);
        assert_eq!(s.n_nodes(), 9 * 5);
        assert_eq!(s.regions.len(), 2);
        assert_eq!(s.regions[1].elements, vec![4, 5, 6, 7]);
    }

    #[test]
    fn periodic_ring_closes() {
        // a ring of 8 × 1 L16: the v = 1 edge is merged with v = 0
        let ring = Block {
            counts: [1, 8],
            map: Box::new(|u, v| {
                let (r, t) = (1.0 + u, std::f64::consts::TAU * v);
                [r * t.cos(), r * t.sin()]
            }),
            region: "ring".into(),
            normal: None,
        };
        let s = from_blocks(SectionElementKind::L16, &[ring]).unwrap();
        assert_eq!(s.n_nodes(), 4 * 24);
        for n in &s.nodes {
            let r = n[0].hypot(n[1]);
            let on_a_circle = [1.0, 4.0 / 3.0, 5.0 / 3.0, 2.0].iter().any(|c| (r - c).abs() < 1e-14);
            assert!(on_a_circle, "node {n:?} at r = {r}");
        }
    }
}
