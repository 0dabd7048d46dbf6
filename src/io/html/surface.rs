//! The outer surface of a [`FieldGrid`] for the report's 3D view: the
//! faces of its hexahedra that no other hexahedron of the same body shares,
//! as triangles, decimated by vertex clustering beyond [`MAX_VERTICES`].

use std::collections::HashMap;

use crate::io::FieldGrid;

/// The most surface vertices the 3D view carries; a larger surface is
/// decimated by vertex clustering (Rossignac and Borrel, 1993): the points
/// in each cube of a grid over the body are merged into one, at their mean
/// position with their mean values, the cube's edge doubled until at most
/// this many remain.
pub(crate) const MAX_VERTICES: usize = 40_000;

/// The faces of a VTK hexahedron, outward for its right-handed corner order.
const HEX_FACES: [[usize; 4]; 6] = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];

/// The surface shown: its vertices and, for each, the grid points whose
/// values it takes the mean of (one point each unless decimated).
#[derive(Debug, Clone)]
pub(crate) struct Surface {
    /// Vertex positions in the reference configuration, 3 per vertex (m).
    pub(crate) positions: Vec<f32>,
    /// Triangles, 3 vertex indices each.
    pub(crate) triangles: Vec<u32>,
    /// Where the grid points of vertex `v` start in [`Self::sources`].
    offsets: Vec<usize>,
    /// The grid points behind each vertex.
    sources: Vec<u32>,
    /// The grid's bounding box, `[min x, min y, min z, max x, max y, max z]` (m).
    pub(crate) bbox: [f64; 6],
    /// The grid's surface vertices before any decimation.
    pub(crate) full_vertices: usize,
}

impl Surface {
    /// The outer surface of `grid`, decimated to at most `cap` vertices.
    pub(crate) fn of(grid: &FieldGrid, cap: usize) -> Surface {
        let bbox = bounding_box(&grid.points);
        let quads = outer_faces(grid, &bbox);
        // the grid points on the surface, each a vertex
        let mut vertex_of = HashMap::new();
        let mut points: Vec<u32> = Vec::new();
        for &p in quads.iter().flatten() {
            vertex_of.entry(p).or_insert_with(|| {
                points.push(p);
                points.len() - 1
            });
        }
        let full_vertices = points.len();
        let cluster =
            if points.len() > cap { clusters(grid, &points, &bbox, cap) } else { (0..points.len()).collect() };
        let n = cluster.iter().max().map_or(0, |m| m + 1);
        let mut counts = vec![0usize; n + 1];
        for &c in &cluster {
            counts[c + 1] += 1;
        }
        for k in 0..n {
            counts[k + 1] += counts[k];
        }
        let offsets = counts.clone();
        let mut sources = vec![0u32; points.len()];
        for (&p, &c) in points.iter().zip(&cluster) {
            sources[counts[c]] = p;
            counts[c] += 1;
        }
        let mut surface =
            Surface { positions: Vec::new(), triangles: Vec::new(), offsets, sources, bbox, full_vertices };
        surface.positions = surface.gather(&grid.points, 3);
        for q in &quads {
            let v = q.map(|p| cluster[vertex_of[&p]] as u32);
            for t in [[v[0], v[1], v[2]], [v[0], v[2], v[3]]] {
                if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                    surface.triangles.extend(t);
                }
            }
        }
        surface
    }

    /// The number of vertices.
    pub(crate) fn vertices(&self) -> usize {
        self.offsets.len() - 1
    }

    /// A point array of the grid (`components` per point) at the vertices:
    /// the mean over each vertex's points, NaN where one of them is NaN.
    pub(crate) fn gather(&self, values: &[f64], components: usize) -> Vec<f32> {
        let mut out = Vec::with_capacity(self.vertices() * components);
        for v in 0..self.vertices() {
            let points = &self.sources[self.offsets[v]..self.offsets[v + 1]];
            for c in 0..components {
                let sum: f64 = points.iter().map(|&p| values[p as usize * components + c]).sum();
                out.push((sum / points.len() as f64) as f32);
            }
        }
        out
    }
}

/// `[min x, min y, min z, max x, max y, max z]` of points (3 per point).
fn bounding_box(points: &[f64]) -> [f64; 6] {
    let mut b = [f64::INFINITY, f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
    for p in points.chunks_exact(3) {
        for i in 0..3 {
            b[i] = b[i].min(p[i]);
            b[i + 3] = b[i + 3].max(p[i]);
        }
    }
    b
}

/// A face: its body and its corners' positions in steps of the tolerance, sorted.
type FaceKey = (i32, [[i64; 3]; 4]);

/// The faces of the grid's hexahedra that no other hexahedron of the same
/// body has (compared by their corners' positions, which are duplicated
/// per element), as 4 grid points each.
fn outer_faces(grid: &FieldGrid, bbox: &[f64; 6]) -> Vec<[u32; 4]> {
    let size = (0..3).map(|i| bbox[i + 3] - bbox[i]).fold(0.0, f64::max);
    let tolerance = if size > 0.0 { 1e-9 * size } else { 1.0 };
    let key = |p: u64| -> [i64; 3] {
        let p = p as usize;
        std::array::from_fn(|i| ((grid.points[3 * p + i] - bbox[i]) / tolerance).round() as i64)
    };
    let mut seen: HashMap<FaceKey, (usize, [u32; 4])> = HashMap::new();
    let mut order = Vec::new();
    let cells = grid.cells(crate::input::VtuCells::Linear);
    for (hex, &body) in cells.connectivity.chunks_exact(8).zip(&cells.body) {
        for face in HEX_FACES {
            let corners = face.map(|i| hex[i]);
            let mut k = corners.map(key);
            k.sort_unstable();
            let entry = seen.entry((body, k)).or_insert_with(|| {
                order.push((body, k));
                (0, corners.map(|c| c as u32))
            });
            entry.0 += 1;
        }
    }
    order.into_iter().filter_map(|k| seen.get(&k).filter(|(n, _)| *n == 1).map(|(_, f)| *f)).collect()
}

/// The cluster of each of `points`: the cube of edge `h` it falls in (a
/// cube may merge points of bodies that touch), `h` doubled from an
/// estimate until at most `cap` clusters remain.
fn clusters(grid: &FieldGrid, points: &[u32], bbox: &[f64; 6], cap: usize) -> Vec<usize> {
    let extent: Vec<f64> = (0..3).map(|i| (bbox[i + 3] - bbox[i]).max(0.0)).collect();
    let largest = extent.iter().cloned().fold(0.0, f64::max).max(f64::MIN_POSITIVE);
    // from fine to coarse: the finest cubes (within a factor 2) that keep the cap
    let mut h = largest / cap as f64;
    loop {
        let mut ids: HashMap<[i64; 3], usize> = HashMap::new();
        let cluster: Vec<usize> = points
            .iter()
            .map(|&p| {
                let p = p as usize;
                let cell = std::array::from_fn(|i| ((grid.points[3 * p + i] - bbox[i]) / h).floor() as i64);
                let n = ids.len();
                *ids.entry(cell).or_insert(n)
            })
            .collect();
        if ids.len() <= cap {
            return cluster;
        }
        h *= 2.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::FieldArray;
    use crate::io::GridElement;

    /// A slab of `nx` × `ny` unit hexahedra, each an L4 × B2 element with
    /// its own 8 points in cufem's node order (beam node, then ζ, then ξ),
    /// as `field_grid` writes them.
    fn slab(nx: usize, ny: usize) -> FieldGrid {
        let mut points = Vec::new();
        let mut elements = Vec::new();
        for e in 0..nx * ny {
            elements.push(GridElement { body: 0, element: e, first: 8 * e, section_order: 1, axis_order: 1 });
            for k in 0..2 {
                for iz in 0..2 {
                    for ix in 0..2 {
                        points.extend([(ix + e % nx) as f64, (k + e / nx) as f64, iz as f64]);
                    }
                }
            }
        }
        let x: Vec<f64> = points.chunks(3).map(|p| p[0]).collect();
        FieldGrid { elements, point_data: vec![FieldArray { name: "x".into(), components: 1, values: x }], points }
    }

    /// A row of n cubes has 4 n + 2 outer faces (the 2 (n − 1) faces
    /// between cubes are shared), 2 triangles each, and keeps 8 n vertices
    /// (one per grid point: none is interior); the box is [0, n] × [0, 1]².
    #[test]
    fn a_row_of_cubes_shows_its_outer_faces() {
        let s = Surface::of(&slab(3, 1), MAX_VERTICES);
        assert_eq!(s.triangles.len() / 3, 2 * (4 * 3 + 2));
        assert_eq!(s.vertices(), 24);
        assert_eq!(s.bbox, [0., 0., 0., 3., 1., 1.]);
        // every triangle's normal points away from the row's axis (outward)
        let p = |v: u32| -> [f64; 3] { std::array::from_fn(|i| s.positions[3 * v as usize + i] as f64) };
        for t in s.triangles.chunks(3) {
            let [a, b, c] = [p(t[0]), p(t[1]), p(t[2])];
            let (u, w) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
            let n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
            let centre = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0, (a[2] + b[2] + c[2]) / 3.0];
            let out = [centre[0] - 1.5, centre[1] - 0.5, centre[2] - 0.5];
            assert!(n[0] * out[0] + n[1] * out[1] + n[2] * out[2] > 0.0, "inward triangle {t:?}");
        }
    }

    /// Beyond the cap, vertices merge: at most `cap` remain, each at the
    /// mean of its points (a field linear in x keeps its range inside
    /// [0, 20]), the top still drawn, and the box is the undecimated grid's.
    #[test]
    fn a_large_surface_is_decimated_to_the_cap() {
        let g = slab(20, 20);
        let s = Surface::of(&g, 500);
        assert!(s.vertices() <= 500 && s.vertices() > 100, "{} vertices", s.vertices());
        assert_eq!(s.full_vertices, 3200);
        assert_eq!(s.bbox, [0., 0., 0., 20., 20., 1.]);
        let x = s.gather(&g.point_data[0].values, 1);
        assert!(x.iter().all(|v| (0.0..=20.0).contains(v)));
        assert!(x.iter().cloned().fold(0.0, f32::max) > 18.0);
        assert!(s.triangles.len() / 3 > 100, "{} triangles", s.triangles.len() / 3);
    }
}
