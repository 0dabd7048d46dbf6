//! Values at arbitrary points: locating a point in a body (inverting the
//! isoparametric map) and the shape values and gradients there, for probes,
//! lines and the VTU.

use super::{AxisValues, SectionValues, degenerate, gradients, natural_of, shape_values};
use crate::mesh::{Body, Mesh};
use crate::shape::Lagrange2d;
use crate::voigt::{self, Voigt};

/// A point located in a body element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Location {
    /// Body index.
    pub body: usize,
    /// Body-local element index.
    pub element: usize,
    /// Natural coordinates `(ξ, η, ζ)`.
    pub natural: [f64; 3],
}

/// Values at one arbitrary point of a body element.
#[derive(Debug, Clone)]
pub struct PointValues {
    /// Local node → global node.
    pub nodes: Vec<usize>,
    /// `N_a` per local node.
    pub shapes: Vec<f64>,
    /// `∇N_a` per local node.
    pub grads: Vec<[f64; 3]>,
}

impl PointValues {
    /// Evaluates the functions of the element holding `loc`.
    pub fn new(body: &Body, loc: &Location) -> Self {
        let (es, eb) = body.split_element(loc.element);
        let [xi, eta, zeta] = loc.natural;
        let section =
            SectionValues::at_points(&body.section, &[es], &[[xi, eta]], &[1.0]).unwrap_or_else(|_| degenerate(body));
        let axis = AxisValues::at_points(&body.axis, &[eb], &[zeta], &[1.0]);
        let n = body.nodes_per_element();
        let mut nodes = Vec::with_capacity(n);
        body.element_nodes(loc.element, &mut nodes);
        let (s, a) = (section.point(0, 0), axis.point(0, 0));
        let mut shapes = vec![0.0; n];
        let mut grads = vec![[0.0; 3]; n];
        shape_values(s, a, &mut shapes);
        gradients(s, a, &mut grads);
        Self { nodes, shapes, grads }
    }

    /// The point's reference position `x = Σ N_a X_a` (m) in `body`.
    pub fn position(&self, body: &Body) -> [f64; 3] {
        let mut out = [0.0; 3];
        for (&n, &node) in self.shapes.iter().zip(&self.nodes) {
            let x = body.local_coords(node - body.node_offset);
            for k in 0..3 {
                out[k] += n * x[k];
            }
        }
        out
    }

    /// Displacement `u = Σ N_a u_a` from the global displacement vector.
    pub fn displacement(&self, u: &[f64]) -> [f64; 3] {
        let mut out = [0.0; 3];
        for (&n, &node) in self.shapes.iter().zip(&self.nodes) {
            for k in 0..3 {
                out[k] += n * u[3 * node + k];
            }
        }
        out
    }

    /// Displacement gradient `∂u_k/∂x_d` from the global displacement vector.
    pub fn gradient(&self, u: &[f64]) -> crate::kinematics::Tensor {
        let mut h = [[0.0; 3]; 3];
        for (g, &node) in self.grads.iter().zip(&self.nodes) {
            for (k, row) in h.iter_mut().enumerate() {
                for d in 0..3 {
                    row[d] += u[3 * node + k] * g[d];
                }
            }
        }
        h
    }

    /// Small strain from the global displacement vector.
    pub fn strain(&self, u: &[f64]) -> Voigt {
        let mut eps = [0.0; 6];
        for (g, &node) in self.grads.iter().zip(&self.nodes) {
            voigt::add_nodal_strain(&mut eps, *g, [u[3 * node], u[3 * node + 1], u[3 * node + 2]]);
        }
        eps
    }
}

/// Every element of `body` (index `b`) containing `point`, with its natural
/// coordinates (a point on an element boundary is in several elements).
pub fn locate(b: usize, body: &Body, point: [f64; 3]) -> Vec<Location> {
    let tol = 1e-9 * body.size();
    let beams = body.axis.locate(point[1], tol);
    if beams.is_empty() {
        return Vec::new();
    }
    let section = &body.section;
    let basis = Lagrange2d::new(section.kind.order());
    let m = basis.len();
    let (mut f, mut dxi, mut deta) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
    let mut found = Vec::new();
    for es in 0..section.n_elements() {
        let el = section.element(es);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &n in el {
            for d in 0..2 {
                lo[d] = lo[d].min(section.nodes[n][d]);
                hi[d] = hi[d].max(section.nodes[n][d]);
            }
        }
        // a curved element bulges past the box of its nodes (an arc between
        // two nodes of a circle's rim): widen the box by half its size, the
        // Newton solve below decides
        let margin = 0.5 * (hi[0] - lo[0]).max(hi[1] - lo[1]) + tol;
        let target = [point[0], point[2]];
        if (0..2).any(|d| target[d] < lo[d] - margin || target[d] > hi[d] + margin) {
            continue;
        }
        let natural = natural_of(section, &basis, es, target, (&mut f, &mut dxi, &mut deta));
        let slack = 1e-7;
        if let Some([xi, eta]) = natural.filter(|n| n[0].abs() <= 1.0 + slack && n[1].abs() <= 1.0 + slack) {
            for &(eb, zeta) in &beams {
                found.push(Location {
                    body: b,
                    element: eb * section.n_elements() + es,
                    natural: [xi.clamp(-1.0, 1.0), eta.clamp(-1.0, 1.0), zeta],
                });
            }
        }
    }
    found
}

/// Locations of `point` in the named body, or in the first body containing it.
pub fn locate_in_model(mesh: &Mesh, body: Option<usize>, point: [f64; 3]) -> Vec<Location> {
    match body {
        Some(b) => locate(b, &mesh.bodies[b], point),
        None => mesh
            .bodies
            .iter()
            .enumerate()
            .map(|(b, body)| locate(b, body, point))
            .find(|l| !l.is_empty())
            .unwrap_or_default(),
    }
}
