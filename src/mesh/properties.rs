//! Geometric properties of a section, integrated over its mesh through the
//! isoparametric map (the same map the elements use, so a curved wall
//! counts with the geometry the analysis sees).

use super::section::CrossSection;
use crate::quadrature::SquareRule;
use crate::shape::Lagrange2d;

/// Area, centroid and second moments of a section about its centroid.
///
/// With `x̄ = x − x_c`, `z̄ = z − z_c`: `ixx = ∫ z̄² dA` (about the x axis:
/// bending with deflection along z), `izz = ∫ x̄² dA` (about the z axis:
/// deflection along x), `ixz = ∫ x̄ z̄ dA` (product of area).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionProperties {
    /// Area (m²).
    pub area: f64,
    /// Centroid `(x_c, z_c)` (m).
    pub centroid: [f64; 2],
    /// Second moment about the centroidal x axis (m⁴).
    pub ixx: f64,
    /// Second moment about the centroidal z axis (m⁴).
    pub izz: f64,
    /// Product of area about the centroid (m⁴).
    pub ixz: f64,
    /// Smallest Jacobian determinant met at a quadrature point (m²); ≤ 0
    /// means an inverted or distorted element.
    pub min_det: f64,
}

impl CrossSection {
    /// The point `(x, z)` of element `e` at natural coordinates `(ξ, η)`
    /// (the isoparametric map).
    pub(crate) fn map_point(&self, e: usize, xi: f64, eta: f64) -> [f64; 2] {
        let basis = Lagrange2d::new(self.kind.order());
        let m = basis.len();
        let (mut f, mut dxi, mut deta) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        basis.eval(xi, eta, &mut f, &mut dxi, &mut deta);
        let mut x = [0.0; 2];
        for (k, &n) in self.element(e).iter().enumerate() {
            x[0] += f[k] * self.nodes[n][0];
            x[1] += f[k] * self.nodes[n][1];
        }
        x
    }

    /// True if the point `p = (x, z)` lies in one of `elements` or within
    /// `tol` (m) of them. The point is mapped back to each candidate
    /// element's natural coordinates (Newton on the isoparametric map, so
    /// curved edges count as they are integrated), clamped to the element,
    /// and accepted if the clamped point is within `tol` of `p`.
    pub fn covers(&self, elements: &[usize], p: [f64; 2], tol: f64) -> bool {
        let basis = Lagrange2d::new(self.kind.order());
        let m = basis.len();
        let (mut f, mut dxi, mut deta) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        let mut map = |e: usize, xi: f64, eta: f64| {
            basis.eval(xi, eta, &mut f, &mut dxi, &mut deta);
            let (mut x, mut j) = ([0.0; 2], [[0.0; 2]; 2]);
            for (k, &n) in self.element(e).iter().enumerate() {
                let c = self.nodes[n];
                for d in 0..2 {
                    x[d] += f[k] * c[d];
                    j[d][0] += dxi[k] * c[d];
                    j[d][1] += deta[k] * c[d];
                }
            }
            (x, j)
        };
        elements.iter().any(|&e| {
            // bounding box of the nodes, widened by a tenth (curved edges) and tol
            let mut b = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
            for &n in self.element(e) {
                let c = self.nodes[n];
                b = [b[0].min(c[0]), b[1].max(c[0]), b[2].min(c[1]), b[3].max(c[1])];
            }
            let pad = 0.1 * (b[1] - b[0]).max(b[3] - b[2]) + tol;
            if p[0] < b[0] - pad || p[0] > b[1] + pad || p[1] < b[2] - pad || p[1] > b[3] + pad {
                return false;
            }
            let mut xi = [0.0, 0.0];
            for _ in 0..25 {
                let (x, j) = map(e, xi[0], xi[1]);
                let r = [p[0] - x[0], p[1] - x[1]];
                let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                if !(det.abs() > 0.0) {
                    break;
                }
                let d = [(j[1][1] * r[0] - j[0][1] * r[1]) / det, (-j[1][0] * r[0] + j[0][0] * r[1]) / det];
                xi = [(xi[0] + d[0]).clamp(-1.5, 1.5), (xi[1] + d[1]).clamp(-1.5, 1.5)];
                if d[0].abs().max(d[1].abs()) < 1e-12 {
                    break;
                }
            }
            let (x, _) = map(e, xi[0].clamp(-1.0, 1.0), xi[1].clamp(-1.0, 1.0));
            (x[0] - p[0]).hypot(x[1] - p[1]) <= tol
        })
    }

    /// The outline of element `e` through the isoparametric map,
    /// counter-clockwise, `per_edge` segments per edge (curved edges drawn
    /// as they are integrated).
    pub(crate) fn outline(&self, e: usize, per_edge: usize) -> Vec<[f64; 2]> {
        let mut pts = Vec::with_capacity(4 * per_edge);
        for k in 0..4 {
            for s in 0..per_edge {
                let t = -1.0 + 2.0 * s as f64 / per_edge as f64;
                let (xi, eta) = match k {
                    0 => (t, -1.0),
                    1 => (1.0, t),
                    2 => (-t, 1.0),
                    _ => (-1.0, -t),
                };
                pts.push(self.map_point(e, xi, eta));
            }
        }
        pts
    }

    /// The elements holding each node (by node index).
    pub(crate) fn elements_at_nodes(&self) -> Vec<Vec<usize>> {
        let mut holding = vec![Vec::new(); self.n_nodes()];
        for e in 0..self.n_elements() {
            self.element(e).iter().for_each(|&t| holding[t].push(e));
        }
        holding
    }

    /// The element other than `e` that holds every one of `nodes` (the
    /// element across the edge of `e` they lie on), `None` on the
    /// section's boundary; `holding` from [`Self::elements_at_nodes`].
    pub(crate) fn across(&self, holding: &[Vec<usize>], e: usize, nodes: &[usize]) -> Option<usize> {
        holding[nodes[0]].iter().copied().find(|&f| f != e && nodes.iter().all(|t| holding[*t].contains(&f)))
    }

    /// Whether each node is a re-entrant corner of the section: a corner of
    /// every element holding it, on the boundary, where the interior angles
    /// of those elements (between the chords to their neighbouring corners)
    /// sum to more than `5π/4` — the boundary turns into the body by more
    /// than `45°`, as at the inner corner where two walls of a profile meet
    /// or at a rectangular hole's corner (a circular hole's vertices turn by
    /// `2π/n`). Every other node is not.
    pub(crate) fn reentrant_corners(&self) -> Vec<bool> {
        let p = self.kind.order();
        let m = p + 1;
        // the corners' local nodes, counter-clockwise
        let corners = [0, p, m * m - 1, p * m];
        let n = self.n_nodes();
        let (mut angle, mut held, mut as_corner) = (vec![0.0; n], vec![0usize; n], vec![0usize; n]);
        for e in 0..self.n_elements() {
            let nodes = self.element(e);
            nodes.iter().for_each(|&t| held[t] += 1);
            for k in 0..4 {
                let v = nodes[corners[k]];
                let at = self.nodes[v];
                let [a, b] = [corners[(k + 1) % 4], corners[(k + 3) % 4]]
                    .map(|c| [self.nodes[nodes[c]][0] - at[0], self.nodes[nodes[c]][1] - at[1]]);
                angle[v] += (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1]).abs();
                as_corner[v] += 1;
            }
        }
        let pi = std::f64::consts::PI;
        (0..n)
            .map(|t| {
                held[t] > 0 && as_corner[t] == held[t] && angle[t] > 1.25 * pi + 1e-6 && angle[t] < 2.0 * pi - 1e-6
            })
            .collect()
    }

    /// Integrates the section's properties with a `(p + 3)²` Gauss rule per
    /// element (exact for straight-edged elements; a polygon-free
    /// integration of the isoparametric geometry for curved ones).
    pub fn properties(&self) -> SectionProperties {
        let p = self.kind.order();
        let basis = Lagrange2d::new(p);
        let rule = SquareRule::new(p + 3);
        let m = basis.len();
        let (mut f, mut dxi, mut deta) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        // (x, z, weight · det J) at every quadrature point
        let mut points = Vec::with_capacity(self.n_elements() * rule.len());
        let mut min_det = f64::INFINITY;
        for e in 0..self.n_elements() {
            let el = self.element(e);
            for (q, &[xi, eta]) in rule.points.iter().enumerate() {
                basis.eval(xi, eta, &mut f, &mut dxi, &mut deta);
                let (mut x, mut j) = ([0.0; 2], [[0.0; 2]; 2]);
                for (k, &n) in el.iter().enumerate() {
                    let c = self.nodes[n];
                    for d in 0..2 {
                        x[d] += f[k] * c[d];
                        j[0][d] += dxi[k] * c[d];
                        j[1][d] += deta[k] * c[d];
                    }
                }
                let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                min_det = min_det.min(det);
                points.push((x, rule.weights[q] * det));
            }
        }
        let area: f64 = points.iter().map(|p| p.1).sum();
        let centroid = [0, 1].map(|d| points.iter().map(|p| p.0[d] * p.1).sum::<f64>() / area);
        let (mut ixx, mut izz, mut ixz) = (0.0, 0.0, 0.0);
        for (x, w) in &points {
            let (dx, dz) = (x[0] - centroid[0], x[1] - centroid[1]);
            ixx += dz * dz * w;
            izz += dx * dx * w;
            ixz += dx * dz * w;
        }
        SectionProperties { area, centroid, ixx, izz, ixz, min_det }
    }
}

#[cfg(test)]
mod tests {
    use crate::shape::SectionElementKind;

    use super::*;

    #[test]
    fn covers_points_of_curved_elements() {
        use crate::mesh::{blocks, profiles};
        let ring = profiles::circular_tube([0.0, 0.0], 1.0, 0.1, 8, 1).unwrap();
        let s = blocks::from_blocks(SectionElementKind::L9, &ring).unwrap();
        let all: Vec<usize> = (0..s.n_elements()).collect();
        // on the curved outer edge between nodes (outside the chord), inside the wall, in the hole, outside
        let a = 0.3f64;
        let on_edge = s.map_point(0, 1.0, 0.5);
        assert!(on_edge[0].hypot(on_edge[1]) > 0.99);
        assert!(!s.covers(&[3], on_edge, 1e-3) && s.covers(&all, on_edge, 1e-12));
        assert!(s.covers(&all, [0.95 * a.cos(), 0.95 * a.sin()], 1e-9));
        assert!(!s.covers(&all, [0.5, 0.0], 1e-6));
        assert!(!s.covers(&all, [1.01, 0.0], 1e-6));
        // only the first element (angles 0 to 45°)
        assert!(s.covers(&[0], [0.95 * a.cos(), 0.95 * a.sin()], 1e-9));
        assert!(!s.covers(&[0], [0.0, 0.95], 1e-9));
    }

    #[test]
    fn the_inner_corner_of_an_l_and_no_other_node_is_re_entrant() {
        // an L of three unit squares: its inner corner (1, 1)
        let corners = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 1.0], [0.0, 2.0], [1.0, 2.0]];
        let quads = [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6]];
        for kind in [SectionElementKind::L4, SectionElementKind::L9] {
            let s = CrossSection::from_quads(kind, &corners, &quads, "quads").unwrap();
            let flagged: Vec<[f64; 2]> =
                s.reentrant_corners().iter().enumerate().filter(|(_, r)| **r).map(|(t, _)| s.nodes[t]).collect();
            assert_eq!(flagged, [[1.0, 1.0]], "{kind:?}");
        }
        // a grid's interior and boundary vertices, a hollow square's hole
        // corners (re-entrant) and a circular tube's hole (turning by 22.5°)
        let grid = CrossSection::rectangle(SectionElementKind::L9, &[0.0, 1.0, 2.0], &[0.0, 1.0, 2.0]).unwrap();
        assert!(grid.reentrant_corners().iter().all(|r| !r));
        let lines = [0.0, 1.0, 2.0, 3.0];
        let hollow = CrossSection::hollow_rectangle(SectionElementKind::L9, &lines, &lines, [[1, 2], [1, 2]]).unwrap();
        assert_eq!(hollow.reentrant_corners().iter().filter(|r| **r).count(), 4);
        use crate::mesh::{blocks, profiles};
        let ring = profiles::circular_tube([0.0, 0.0], 1.0, 0.1, 16, 1).unwrap();
        let tube = blocks::from_blocks(SectionElementKind::L9, &ring).unwrap();
        assert!(tube.reentrant_corners().iter().all(|r| !r));
    }

    #[test]
    fn rectangle_properties_are_exact() {
        // b × h = 0.3 × 0.2 with its corner at (1, 2): A = b h, I = b h³/12
        let xl = [1.0, 1.1, 1.3];
        let zl = [2.0, 2.05, 2.2];
        for kind in [SectionElementKind::L4, SectionElementKind::L9, SectionElementKind::L16] {
            let s = CrossSection::rectangle(kind, &xl, &zl).unwrap().properties();
            let (b, h) = (0.3f64, 0.2f64);
            assert!((s.area - b * h).abs() < 1e-14);
            assert!((s.centroid[0] - 1.15).abs() < 1e-13 && (s.centroid[1] - 2.1).abs() < 1e-13);
            assert!((s.ixx / (b * h.powi(3) / 12.0) - 1.0).abs() < 1e-11);
            assert!((s.izz / (h * b.powi(3) / 12.0) - 1.0).abs() < 1e-11);
            assert!(s.ixz.abs() < 1e-13 * s.ixx, "{}", s.ixz);
        }
    }
}
