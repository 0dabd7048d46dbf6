//! The cells of the field VTUs over each CUF element's own Lagrange nodes
//! (`output.vtu_cells`).
//!
//! The points of an element are its nodes in cufem's order: section node
//! `ix + iz (p_s + 1)` (ξ along x fastest, then η along z) of beam node `k`
//! (ζ along y) at `k (p_s + 1)² + iz (p_s + 1) + ix`, all equispaced in
//! `[-1, 1]` as VTK's Lagrange cells assume (src/shape/lagrange.rs).
//!
//! * `"lagrange"`: one `VTK_LAGRANGE_HEXAHEDRON` per element with VTK's
//!   parametric `(r, s, t) = (ξ, ζ, η)`, right-handed in `(x, y, z)`, of
//!   orders `(p_s, p_b, p_s)` given per cell by the cell-data array
//!   `HigherOrderDegrees`; the points in VTK's order (corners, edges, faces,
//!   interior: [`vtk_index`]) of VTK 8, in a file of version `1.0`, which
//!   every reader of Lagrange cells reads alike: VTK ≥ 9.1 renumbers the
//!   Lagrange hexahedra of files older than `2.1` to its own order
//!   ([`vtk8_index`]), VTK 8.2–9.0 keep that order, and meshio reads
//!   versions `0.1` and `1.0` only. VTK interpolates them with the
//!   element's own Lagrange polynomials, so its geometry and displacement
//!   are cufem's.
//! * `"linear"`: the element split into `p_s² p_b` linear hexahedra between
//!   neighbouring nodes.

use crate::input::VtuCells;

/// One CUF element's points in a [`super::FieldGrid`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GridElement {
    /// Body index.
    pub body: usize,
    /// Global element index.
    pub element: usize,
    /// Index of the element's first point; its `(p_s + 1)² (p_b + 1)`
    /// points follow in cufem's node order.
    pub first: usize,
    /// Order `p_s` of the section element (L4 1, L9 2, L16 3).
    pub section_order: usize,
    /// Order `p_b` of the beam element (B2 1, B3 2, B4 3).
    pub axis_order: usize,
}

/// The cells of a [`super::FieldGrid`] as a VTU writes them.
#[derive(Debug, Clone, PartialEq)]
pub struct Cells {
    /// VTK cell type of every cell (12 linear hexahedron, 72 Lagrange
    /// hexahedron).
    pub(crate) cell_type: u8,
    /// The points of every cell, in VTK's order.
    pub connectivity: Vec<u64>,
    /// The end of every cell in `connectivity`.
    pub offsets: Vec<u64>,
    /// The body of every cell.
    pub body: Vec<i32>,
    /// The global element of every cell.
    pub element: Vec<i32>,
    /// Lagrange cells: VTK's `HigherOrderDegrees`, the orders along
    /// `(r, s, t)`, 3 per cell; empty for linear cells.
    pub degrees: Vec<i32>,
}

impl super::FieldGrid {
    /// The cells over the elements' points: one Lagrange hexahedron per
    /// element, or the linear sub-cells (`output.vtu_cells`).
    pub fn cells(&self, kind: VtuCells) -> Cells {
        cells(&self.elements, kind)
    }
}

/// VTK cell type of a linear hexahedron.
pub(super) const VTK_HEXAHEDRON: u8 = 12;
/// VTK cell type of an arbitrary-order Lagrange hexahedron.
pub(super) const VTK_LAGRANGE_HEXAHEDRON: u8 = 72;

/// The cells of `kind` over `elements`.
fn cells(elements: &[GridElement], kind: VtuCells) -> Cells {
    let cell_type = match kind {
        VtuCells::Lagrange => VTK_LAGRANGE_HEXAHEDRON,
        VtuCells::Linear => VTK_HEXAHEDRON,
    };
    let mut c = Cells {
        cell_type,
        connectivity: Vec::new(),
        offsets: Vec::new(),
        body: Vec::new(),
        element: Vec::new(),
        degrees: Vec::new(),
    };
    for e in elements {
        let (ps, pb) = (e.section_order, e.axis_order);
        let m = ps + 1;
        // the point of section node (ix, iz) on beam node k
        let id = |k: usize, iz: usize, ix: usize| (e.first + k * m * m + iz * m + ix) as u64;
        let n_cells = match kind {
            VtuCells::Lagrange => {
                let order = [ps, pb, ps];
                let start = c.connectivity.len();
                c.connectivity.resize(start + m * m * (pb + 1), 0);
                for iz in 0..=ps {
                    for k in 0..=pb {
                        for ix in 0..=ps {
                            c.connectivity[start + vtk8_index([ix, k, iz], order)] = id(k, iz, ix);
                        }
                    }
                }
                c.degrees.extend(order.map(|p| p as i32));
                c.offsets.push(c.connectivity.len() as u64);
                1
            }
            VtuCells::Linear => {
                // (ξ, η, ζ) is left-handed in (x, y, z): list each bottom
                // face η-first so that VTK sees positive volumes
                for k in 0..pb {
                    for iz in 0..ps {
                        for ix in 0..ps {
                            c.connectivity.extend([
                                id(k, iz, ix),
                                id(k, iz + 1, ix),
                                id(k, iz + 1, ix + 1),
                                id(k, iz, ix + 1),
                                id(k + 1, iz, ix),
                                id(k + 1, iz + 1, ix),
                                id(k + 1, iz + 1, ix + 1),
                                id(k + 1, iz, ix + 1),
                            ]);
                            c.offsets.push(c.connectivity.len() as u64);
                        }
                    }
                }
                ps * ps * pb
            }
        };
        c.body.extend(std::iter::repeat_n(e.body as i32, n_cells));
        c.element.extend(std::iter::repeat_n(e.element as i32, n_cells));
    }
    c
}

/// [`vtk_index`] in the order of VTK 8, that of a file older than version
/// `2.1`: the points inside the edges along t from corners 2 and 3 of the
/// face t = 0 swap places (the inverse of
/// `vtkHigherOrderHexahedron::NodeNumberingMappingFromVTK8To9`, which VTK's
/// XML reader applies to such files in `vtkUpdateCellsV8toV9`).
fn vtk8_index(ijk: [usize; 3], order: [usize; 3]) -> usize {
    let [a, b, c] = order;
    let (ea, eb, ec) = (a - 1, b - 1, c - 1);
    let corner_2 = 8 + 4 * (ea + eb) + 2 * ec;
    match vtk_index(ijk, order) {
        n if (corner_2..corner_2 + ec).contains(&n) => n + ec,
        n if (corner_2 + ec..corner_2 + 2 * ec).contains(&n) => n - ec,
        n => n,
    }
}

/// The position in a VTK Lagrange hexahedron of orders `order` of its
/// point `(i, j, k)` (along r, s, t): the 8 corners, then the points inside
/// the 12 edges, the 6 faces and the interior, as VTK ≥ 9.1 numbers them
/// (`vtkHigherOrderHexahedron::PointIndexFromIJK`).
fn vtk_index([i, j, k]: [usize; 3], order: [usize; 3]) -> usize {
    let [a, b, c] = order;
    let (ib, jb, kb) = (i == 0 || i == a, j == 0 || j == b, k == 0 || k == c);
    // the corner (i, j) of a face k = const: 0 (0, 0), 1 (a, 0), 2 (a, b), 3 (0, b)
    let corner = match (i > 0, j > 0) {
        (false, false) => 0,
        (true, false) => 1,
        (true, true) => 2,
        (false, true) => 3,
    };
    let (ea, eb, ec) = (a - 1, b - 1, c - 1);
    match (ib, jb, kb) {
        (true, true, true) => corner + if k > 0 { 4 } else { 0 },
        // edges: along r at j = 0 and j = b, along s at i = a and i = 0, on
        // the bottom face then the top one; then the 4 edges along t
        (false, true, true) => 8 + (i - 1) + if j > 0 { ea + eb } else { 0 } + if k > 0 { 2 * (ea + eb) } else { 0 },
        (true, false, true) => {
            8 + (j - 1) + if i > 0 { ea } else { 2 * ea + eb } + if k > 0 { 2 * (ea + eb) } else { 0 }
        }
        (true, true, false) => 8 + 4 * (ea + eb) + (k - 1) + ec * corner,
        // faces: i = 0, a; j = 0, b; k = 0, c
        (true, false, false) => 8 + 4 * (ea + eb + ec) + (j - 1) + eb * (k - 1) + if i > 0 { eb * ec } else { 0 },
        (false, true, false) => {
            8 + 4 * (ea + eb + ec) + 2 * eb * ec + (i - 1) + ea * (k - 1) + if j > 0 { ec * ea } else { 0 }
        }
        (false, false, true) => {
            8 + 4 * (ea + eb + ec) + 2 * (eb * ec + ec * ea) + (i - 1) + ea * (j - 1) + if k > 0 { ea * eb } else { 0 }
        }
        (false, false, false) => {
            8 + 4 * (ea + eb + ec) + 2 * (eb * ec + ec * ea + ea * eb) + (i - 1) + ea * ((j - 1) + eb * (k - 1))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The numbering VTK 9.7.2 gives (`vtkLagrangeHexahedron.PointIndexFromIJK`
    /// from the `vtk` wheel, i fastest, then j, then k), uniform and
    /// anisotropic orders.
    #[test]
    fn points_are_numbered_as_vtk_does() {
        let vtk: [([usize; 3], &[usize]); 4] = [
            (
                [2, 2, 2],
                &[0, 8, 1, 11, 24, 9, 3, 10, 2, 16, 22, 17, 20, 26, 21, 19, 23, 18, 4, 12, 5, 15, 25, 13, 7, 14, 6],
            ),
            ([1, 3, 1], &[0, 1, 10, 8, 11, 9, 3, 2, 4, 5, 14, 12, 15, 13, 7, 6]),
            ([2, 1, 2], &[0, 8, 1, 3, 9, 2, 12, 16, 13, 15, 17, 14, 4, 10, 5, 7, 11, 6]),
            (
                [3, 2, 3],
                &[
                    0, 8, 9, 1, 13, 40, 41, 10, 3, 11, 12, 2, 20, 32, 33, 22, 28, 44, 45, 30, 26, 36, 37, 24, 21, 34,
                    35, 23, 29, 46, 47, 31, 27, 38, 39, 25, 4, 14, 15, 5, 19, 42, 43, 16, 7, 17, 18, 6,
                ],
            ),
        ];
        check_numbering(&vtk, vtk_index);
    }

    /// The numbering of a file older than version 2.1 as VTK 9.7.2 reads
    /// it: the position `n8` whose `NodeNumberingMappingFromVTK8To9(order, n8)`
    /// is `PointIndexFromIJK(i, j, k, order)` (from the `vtk` wheel, i
    /// fastest, then j, then k).
    #[test]
    fn points_are_numbered_as_vtk_8_did() {
        let vtk8: [([usize; 3], &[usize]); 3] = [
            (
                [2, 2, 2],
                &[0, 8, 1, 11, 24, 9, 3, 10, 2, 16, 22, 17, 20, 26, 21, 18, 23, 19, 4, 12, 5, 15, 25, 13, 7, 14, 6],
            ),
            (
                [2, 3, 2],
                &[
                    0, 8, 1, 12, 30, 9, 13, 31, 10, 3, 11, 2, 20, 28, 21, 24, 34, 26, 25, 35, 27, 22, 29, 23, 4, 14, 5,
                    18, 32, 15, 19, 33, 16, 7, 17, 6,
                ],
            ),
            (
                [3, 2, 3],
                &[
                    0, 8, 9, 1, 13, 40, 41, 10, 3, 11, 12, 2, 20, 32, 33, 22, 28, 44, 45, 30, 24, 36, 37, 26, 21, 34,
                    35, 23, 29, 46, 47, 31, 25, 38, 39, 27, 4, 14, 15, 5, 19, 42, 43, 16, 7, 17, 18, 6,
                ],
            ),
        ];
        check_numbering(&vtk8, vtk8_index);
    }

    /// `index` of every point (i fastest, then j, then k) against VTK's
    /// numbering, per order triple.
    fn check_numbering(expected: &[([usize; 3], &[usize])], index: fn([usize; 3], [usize; 3]) -> usize) {
        for &(order, expected) in expected {
            let [a, b, c] = order;
            let ours: Vec<usize> = (0..=c)
                .flat_map(|k| (0..=b).flat_map(move |j| (0..=a).map(move |i| index([i, j, k], order))))
                .collect();
            assert_eq!(ours, expected, "order {order:?}");
        }
    }

    /// Every point of an L9 × B4 element is in its Lagrange cell once; the
    /// linear split has 2 × 2 × 3 hexahedra.
    #[test]
    fn both_layouts_use_every_point_of_the_element() {
        let e = GridElement { body: 1, element: 7, first: 10, section_order: 2, axis_order: 3 };
        let lagrange = cells(&[e], VtuCells::Lagrange);
        let mut seen = lagrange.connectivity.clone();
        seen.sort_unstable();
        assert_eq!(seen, (10..46).collect::<Vec<u64>>());
        assert_eq!((lagrange.offsets, lagrange.degrees, lagrange.body), (vec![36], vec![2, 3, 2], vec![1]));
        let linear = cells(&[e], VtuCells::Linear);
        assert_eq!((linear.offsets.len(), linear.connectivity.len()), (12, 96));
        assert!(linear.degrees.is_empty() && linear.element == vec![7; 12]);
    }
}
