//! Values on the faces of a body element, for face integrals (loads,
//! contact areas and normals).

use super::{AxisValues, SectionValues, degenerate, section_point, shape_values};
use crate::mesh::Body;
use crate::quadrature::{GaussRule, SquareRule};
use crate::shape::Lagrange2d;

/// Which face of a body element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceSide {
    /// Section edge `k` (0: η = −1, 1: ξ = +1, 2: η = +1, 3: ξ = −1) swept along the beam element.
    Lateral(usize),
    /// The section element at the start (`false`) or end (`true`) of the beam element.
    End(bool),
}

/// Values on one face of a body element: `N_a` at the face's quadrature
/// points, the area weights and the outward normal there.
#[derive(Debug, Clone)]
pub struct FacetValues {
    /// Global nodes of the element (local node order).
    pub nodes: Vec<usize>,
    /// `N_a` at `[point][a]`.
    pub shapes: Vec<f64>,
    /// Area weight of each point (m²).
    pub weights: Vec<f64>,
    /// Natural coordinates `(ξ, η, ζ)` of each point in the element.
    pub natural: Vec<[f64; 3]>,
    /// Outward unit normal at each point.
    pub normals: Vec<[f64; 3]>,
    /// Thickness of the element behind the face, measured along the normal (m).
    pub depth: f64,
}

impl FacetValues {
    /// Values on face `side` of the element (section element `es`, beam element `eb`).
    pub fn new(body: &Body, es: usize, eb: usize, side: FaceSide) -> Self {
        let (ps, pb) = (body.section.kind.order(), body.axis.kind.order());
        let (gs, gb) = (GaussRule::new(ps + 1), GaussRule::new(pb + 1));
        let n_sec = body.section.kind.nodes();
        let mut nodes = Vec::new();
        body.element_nodes(eb * body.section.n_elements() + es, &mut nodes);
        let basis = Lagrange2d::new(ps);
        let (mut f, mut dxi, mut deta) = (vec![0.0; n_sec], vec![0.0; n_sec], vec![0.0; n_sec]);
        // element area and centroid, for the depth and the outward direction
        let interior = SectionValues::at_points(
            &body.section,
            &[es],
            &SquareRule::new(ps + 1).points,
            &SquareRule::new(ps + 1).weights,
        )
        .unwrap_or_else(|_| degenerate(body));
        let area: f64 = interior.weight.iter().sum();
        let centroid = interior
            .position
            .iter()
            .zip(&interior.weight)
            .fold([0.0; 2], |c, (p, w)| [c[0] + w * p[0] / area, c[1] + w * p[1] / area]);
        let mut out = Self {
            nodes,
            shapes: Vec::new(),
            weights: Vec::new(),
            natural: Vec::new(),
            normals: Vec::new(),
            depth: 0.0,
        };
        let mut shapes = vec![0.0; n_sec * (pb + 1)];
        match side {
            FaceSide::Lateral(k) => {
                let axis = AxisValues::at_points(&body.axis, &[eb], &gb.points, &gb.weights);
                let mut length = 0.0;
                for (t, wt) in gs.points.iter().zip(&gs.weights) {
                    // the edge parameter t runs along ξ (edges 0, 2) or η (edges 1, 3)
                    let (xi, eta, along) = match k {
                        0 => (*t, -1.0, 0),
                        1 => (1.0, *t, 1),
                        2 => (*t, 1.0, 0),
                        _ => (-1.0, *t, 1),
                    };
                    let sp = section_point(&body.section, &basis, es, xi, eta, &mut f, &mut dxi, &mut deta);
                    let d = sp.tangents[along];
                    let ds = (d[0] * d[0] + d[1] * d[1]).sqrt();
                    let mut n2 = [d[1] / ds, -d[0] / ds];
                    let out_dir = [sp.position[0] - centroid[0], sp.position[1] - centroid[1]];
                    if n2[0] * out_dir[0] + n2[1] * out_dir[1] < 0.0 {
                        n2 = [-n2[0], -n2[1]];
                    }
                    length += wt * ds;
                    for q in 0..axis.n_gp {
                        let a = axis.point(0, q);
                        for (i, &n) in a.n.iter().enumerate() {
                            for tau in 0..n_sec {
                                shapes[i * n_sec + tau] = f[tau] * n;
                            }
                        }
                        out.shapes.extend_from_slice(&shapes);
                        out.weights.push(wt * ds * a.weight);
                        out.natural.push([xi, eta, gb.points[q]]);
                        out.normals.push([n2[0], 0.0, n2[1]]);
                    }
                }
                out.depth = area / length;
            }
            FaceSide::End(end) => {
                let zeta = if end { 1.0 } else { -1.0 };
                let axis = AxisValues::at_points(&body.axis, &[eb], &[zeta], &[1.0]);
                let a = axis.point(0, 0);
                for q in 0..interior.n_gp {
                    let s = interior.point(0, q);
                    shape_values(s, a, &mut shapes);
                    out.shapes.extend_from_slice(&shapes);
                    out.weights.push(s.weight);
                    out.natural.push([interior.natural[q][0], interior.natural[q][1], zeta]);
                    out.normals.push([0.0, zeta, 0.0]);
                }
                let (y0, y1) = body.axis.element_span(eb);
                out.depth = y1 - y0;
            }
        }
        out
    }

    /// Number of quadrature points.
    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// True if the face has no quadrature point.
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }

    /// `∫ N_a v(x) dA` per local node, for a value `v` per quadrature point.
    pub fn integrate(&self, v: impl Fn(usize) -> f64) -> Vec<f64> {
        let n = self.nodes.len();
        let mut out = vec![0.0; n];
        for q in 0..self.len() {
            let w = self.weights[q] * v(q);
            for (o, s) in out.iter_mut().zip(&self.shapes[q * n..(q + 1) * n]) {
                *o += w * s;
            }
        }
        out
    }
}
