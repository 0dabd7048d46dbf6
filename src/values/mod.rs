//! Shape values: the one place where the functions `N_a = F_τ(x, z) N_i(y)`
//! of a CUF body element, their gradients and the integration weights are
//! evaluated — at the Gauss points (for the element kernel), on boundary
//! faces (for loads and contact areas) and at arbitrary points (for probes,
//! lines and the VTU). In the spirit of Ferrite.jl's `CellValues`,
//! `FacetValues` and `PointValues`.
//!
//! A body element is a section element (functions `F_τ` over x–z through
//! the isoparametric map of its Lagrange nodes) times a beam element
//! (functions `N_i` along y). Local node `a = i · n_sec + τ`. The 3D gradient
//! is `∇N_a = (F_τ,x N_i, F_τ N_i,y, F_τ,z N_i)` ([`gradients`]) and the
//! strain `ε = Σ_a B_a u_a` ([`strain`], Voigt order and engineering shear
//! of [`crate::voigt`]). Weights are `w_q |J|` products: `dA` of the section
//! point times `dy` of the axis point.

use crate::mesh::{BeamAxis, Body, CrossSection};
use crate::quadrature::{GaussRule, SquareRule};
use crate::shape::{Lagrange1d, Lagrange2d};
use crate::voigt::{self, Voigt};

mod assumed;
mod facet;
mod point;

pub use assumed::AssumedShear;
pub(crate) use assumed::Covariant;

pub use facet::{FaceSide, FacetValues};
pub use point::{Location, PointValues, locate, locate_in_model};

/// A section element whose map is not valid.
#[derive(Debug, thiserror::Error)]
pub enum ElementError {
    /// A section element whose Jacobian is not positive at a Gauss point.
    #[error(
        "bodies.{body}: section element {element} is distorted (Jacobian determinant {det:e} at a Gauss point); \
         quads must be convex and listed counter-clockwise in the x–z plane"
    )]
    Distorted {
        /// Body name.
        body: String,
        /// Section element index.
        element: usize,
        /// Offending determinant.
        det: f64,
    },
}

/// The isoparametric map of one section element evaluated at `(ξ, η)`.
#[derive(Debug, Clone, Copy)]
pub struct SectionPoint {
    /// Physical `(x, z)`.
    pub position: [f64; 2],
    /// Jacobian determinant `det ∂(x,z)/∂(ξ,η)`.
    pub det: f64,
    /// Inverse Jacobian `[[ξ_x, ξ_z], [η_x, η_z]]`.
    pub inverse: [[f64; 2]; 2],
    /// Tangent `∂(x,z)/∂ξ` and `∂(x,z)/∂η` (for edge lengths and normals).
    pub tangents: [[f64; 2]; 2],
}

/// Evaluates shape functions and the map of section element `e` at `(ξ, η)`.
/// `f`, `dxi`, `deta` receive values and natural derivatives.
#[allow(clippy::too_many_arguments)] // three caller-owned output buffers keep the hot path allocation-free
pub fn section_point(
    section: &CrossSection,
    basis: &Lagrange2d,
    e: usize,
    xi: f64,
    eta: f64,
    f: &mut [f64],
    dxi: &mut [f64],
    deta: &mut [f64],
) -> SectionPoint {
    basis.eval(xi, eta, f, dxi, deta);
    let (mut x, mut z, mut x_xi, mut x_eta, mut z_xi, mut z_eta) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (k, &node) in section.element(e).iter().enumerate() {
        let [nx, nz] = section.nodes[node];
        x += f[k] * nx;
        z += f[k] * nz;
        x_xi += dxi[k] * nx;
        x_eta += deta[k] * nx;
        z_xi += dxi[k] * nz;
        z_eta += deta[k] * nz;
    }
    let det = x_xi * z_eta - x_eta * z_xi;
    let inverse = [[z_eta / det, -x_eta / det], [-z_xi / det, x_xi / det]];
    SectionPoint { position: [x, z], det, inverse, tangents: [[x_xi, z_xi], [x_eta, z_eta]] }
}

/// The natural coordinates `(ξ, η)` of the physical point `target` under
/// section element `e`'s isoparametric map, continued beyond the element:
/// Newton from the centre, stopped at a step below `1e-10` (quadratic
/// convergence: exact to round-off after it; a tighter bound is missed by
/// the round-off of a small element's map far from the origin). `None`
/// where Newton meets a fold of the map (`det J ≤ 0`) or does not
/// converge. `f`, `dxi`, `deta`: [`section_point`]'s buffers.
pub(crate) fn natural_of(
    section: &CrossSection,
    basis: &Lagrange2d,
    e: usize,
    target: [f64; 2],
    (f, dxi, deta): (&mut [f64], &mut [f64], &mut [f64]),
) -> Option<[f64; 2]> {
    let (mut xi, mut eta) = (0.0, 0.0);
    for _ in 0..50 {
        let sp = section_point(section, basis, e, xi, eta, f, dxi, deta);
        if !(sp.det > 0.0) {
            return None;
        }
        let r = [target[0] - sp.position[0], target[1] - sp.position[1]];
        let [[xi_x, xi_z], [eta_x, eta_z]] = sp.inverse;
        let (dx, de) = (xi_x * r[0] + xi_z * r[1], eta_x * r[0] + eta_z * r[1]);
        xi += dx;
        eta += de;
        if dx.abs() + de.abs() < 1e-10 {
            return Some([xi, eta]);
        }
    }
    None
}

/// Section functions at a set of points of every section element:
/// `F_τ`, `∂F_τ/∂x`, `∂F_τ/∂z`, the area weight `w |J|` and the position.
#[derive(Debug, Clone)]
pub struct SectionValues {
    /// Points per element.
    pub n_gp: usize,
    /// Functions per element.
    pub n_fun: usize,
    /// Natural coordinates of the points (the same in every element).
    pub natural: Vec<[f64; 2]>,
    /// `F_τ` at `[element][point][τ]`.
    pub f: Vec<f64>,
    /// `∂F_τ/∂x` at `[element][point][τ]`.
    pub fx: Vec<f64>,
    /// `∂F_τ/∂z` at `[element][point][τ]`.
    pub fz: Vec<f64>,
    /// Weight × Jacobian determinant at `[element][point]` (an area, m²).
    pub weight: Vec<f64>,
    /// Physical `(x, z)` at `[element][point]`.
    pub position: Vec<[f64; 2]>,
}

impl SectionValues {
    /// Values at the `(p + 1) × (p + 1)` Gauss points of every element
    /// (rejecting a distorted element: `det J ≤ 0` at a Gauss point).
    pub fn new(section: &CrossSection, body: &str) -> Result<Self, ElementError> {
        let rule = SquareRule::new(section.kind.order() + 1);
        let elements: Vec<usize> = (0..section.n_elements()).collect();
        Self::at_points(section, &elements, &rule.points, &rule.weights)
            .map_err(|(element, det)| ElementError::Distorted { body: body.to_string(), element, det })
    }

    /// Values at the natural points `natural` (weights `w`) of the listed
    /// elements; the error names the first element with `det J ≤ 0`.
    pub fn at_points(
        section: &CrossSection,
        elements: &[usize],
        natural: &[[f64; 2]],
        w: &[f64],
    ) -> Result<Self, (usize, f64)> {
        let basis = Lagrange2d::new(section.kind.order());
        let (n_gp, n_fun, n_el) = (natural.len(), basis.len(), elements.len());
        let mut g = Self {
            n_gp,
            n_fun,
            natural: natural.to_vec(),
            f: Vec::with_capacity(n_el * n_gp * n_fun),
            fx: Vec::with_capacity(n_el * n_gp * n_fun),
            fz: Vec::with_capacity(n_el * n_gp * n_fun),
            weight: Vec::with_capacity(n_el * n_gp),
            position: Vec::with_capacity(n_el * n_gp),
        };
        let (mut f, mut dxi, mut deta) = (vec![0.0; n_fun], vec![0.0; n_fun], vec![0.0; n_fun]);
        for &e in elements {
            for (q, &[xi, eta]) in natural.iter().enumerate() {
                let sp = section_point(section, &basis, e, xi, eta, &mut f, &mut dxi, &mut deta);
                if !(sp.det > 0.0) {
                    return Err((e, sp.det));
                }
                let [[xi_x, xi_z], [eta_x, eta_z]] = sp.inverse;
                for k in 0..n_fun {
                    g.f.push(f[k]);
                    g.fx.push(dxi[k] * xi_x + deta[k] * eta_x);
                    g.fz.push(dxi[k] * xi_z + deta[k] * eta_z);
                }
                g.weight.push(w[q] * sp.det);
                g.position.push(sp.position);
            }
        }
        Ok(g)
    }

    /// Values of point `q` of element slot `e`.
    pub fn point(&self, e: usize, q: usize) -> SectionAt<'_> {
        let b = (e * self.n_gp + q) * self.n_fun;
        let r = b..b + self.n_fun;
        SectionAt {
            f: &self.f[r.clone()],
            fx: &self.fx[r.clone()],
            fz: &self.fz[r],
            weight: self.weight[e * self.n_gp + q],
        }
    }
}

/// Section functions at one point.
#[derive(Debug, Clone, Copy)]
pub struct SectionAt<'a> {
    /// `F_τ`.
    pub f: &'a [f64],
    /// `∂F_τ/∂x`.
    pub fx: &'a [f64],
    /// `∂F_τ/∂z`.
    pub fz: &'a [f64],
    /// Area weight (m²).
    pub weight: f64,
}

/// Beam functions at a set of points of every beam element: `N_i`,
/// `∂N_i/∂y`, the length weight `w J` and the position y.
#[derive(Debug, Clone)]
pub struct AxisValues {
    /// Points per element.
    pub n_gp: usize,
    /// Functions per element.
    pub n_fun: usize,
    /// Natural coordinates of the points.
    pub natural: Vec<f64>,
    /// `N_i` at `[element][point][i]`.
    pub n: Vec<f64>,
    /// `∂N_i/∂y` at `[element][point][i]`.
    pub ny: Vec<f64>,
    /// Weight × Jacobian at `[element][point]` (a length, m).
    pub weight: Vec<f64>,
    /// Physical y at `[element][point]`.
    pub position: Vec<f64>,
}

impl AxisValues {
    /// Values at the `p + 1` Gauss points of every beam element.
    pub fn new(axis: &BeamAxis) -> Self {
        let rule = GaussRule::new(axis.kind.order() + 1);
        let elements: Vec<usize> = (0..axis.n_elements()).collect();
        Self::at_points(axis, &elements, &rule.points, &rule.weights)
    }

    /// Values at the natural points `natural` (weights `w`) of the listed elements.
    pub fn at_points(axis: &BeamAxis, elements: &[usize], natural: &[f64], w: &[f64]) -> Self {
        let basis = Lagrange1d::new(axis.kind.order());
        let (n_gp, n_fun, n_el) = (natural.len(), basis.len(), elements.len());
        let mut g = Self {
            n_gp,
            n_fun,
            natural: natural.to_vec(),
            n: Vec::with_capacity(n_el * n_gp * n_fun),
            ny: Vec::with_capacity(n_el * n_gp * n_fun),
            weight: Vec::with_capacity(n_el * n_gp),
            position: Vec::with_capacity(n_el * n_gp),
        };
        let (mut n, mut dn) = (vec![0.0; n_fun], vec![0.0; n_fun]);
        for &e in elements {
            let (y0, y1) = axis.element_span(e);
            let jac = 0.5 * (y1 - y0);
            for (q, &zeta) in natural.iter().enumerate() {
                basis.eval(zeta, &mut n, &mut dn);
                g.n.extend_from_slice(&n);
                g.ny.extend(dn.iter().map(|d| d / jac));
                g.weight.push(w[q] * jac);
                g.position.push(0.5 * (y0 + y1) + jac * zeta);
            }
        }
        g
    }

    /// Values of point `q` of element slot `e`.
    pub fn point(&self, e: usize, q: usize) -> AxisAt<'_> {
        let b = (e * self.n_gp + q) * self.n_fun;
        AxisAt {
            n: &self.n[b..b + self.n_fun],
            ny: &self.ny[b..b + self.n_fun],
            weight: self.weight[e * self.n_gp + q],
        }
    }
}

/// Beam functions at one point.
#[derive(Debug, Clone, Copy)]
pub struct AxisAt<'a> {
    /// `N_i`.
    pub n: &'a [f64],
    /// `∂N_i/∂y`.
    pub ny: &'a [f64],
    /// Length weight (m).
    pub weight: f64,
}

/// `∇N_a = (F_τ,x N_i, F_τ N_i,y, F_τ,z N_i)` for every local node
/// `a = i · n_sec + τ`; returns the volume weight `dA · dy`.
pub fn gradients(s: SectionAt<'_>, a: AxisAt<'_>, out: &mut [[f64; 3]]) -> f64 {
    let ns = s.f.len();
    for (i, (&n, &ny)) in a.n.iter().zip(a.ny).enumerate() {
        for t in 0..ns {
            out[i * ns + t] = [s.fx[t] * n, s.f[t] * ny, s.fz[t] * n];
        }
    }
    s.weight * a.weight
}

/// `N_a = F_τ N_i` for every local node.
pub fn shape_values(s: SectionAt<'_>, a: AxisAt<'_>, out: &mut [f64]) {
    let ns = s.f.len();
    for (i, &n) in a.n.iter().enumerate() {
        for t in 0..ns {
            out[i * ns + t] = s.f[t] * n;
        }
    }
}

/// Strain `ε = Σ_a B_a u_a` from the gradients and the element's nodal
/// displacements (3 per node, node-major).
pub fn strain(grads: &[[f64; 3]], u: &[f64]) -> Voigt {
    let mut eps = [0.0; 6];
    for (a, g) in grads.iter().enumerate() {
        voigt::add_nodal_strain(&mut eps, *g, [u[3 * a], u[3 * a + 1], u[3 * a + 2]]);
    }
    eps
}

/// Gauss-point values of every element of one body: what the element kernel
/// reads (computed once).
#[derive(Debug, Clone)]
pub struct CellValues {
    /// Section part.
    pub section: SectionValues,
    /// Axis part.
    pub axis: AxisValues,
    /// The space the volumetric strain is projected on (B-bar), if any.
    pub volumetric: Option<PressureSpace>,
    /// The assumed in-section shear strain (`formulation = "assumed_shear"`), if any.
    pub shear: Option<AssumedShear>,
}

/// An element-wise discontinuous polynomial space for the volumetric strain
/// of the B-bar formulation (Hughes, *Int. J. Numer. Methods Eng.* 15,
/// 1980; Simo, Taylor & Pister, 1985), in the element's natural coordinates:
/// `{1}`, plus `ξ, η` when the section element is quadratic or cubic, plus
/// `ζ` when the beam element is. For the L9 × B4 element (Q2 per section
/// direction) this is the linear discontinuous pressure of the stable
/// Q2–P1 pair; for L4 × B2 the constant of the mean-dilatation element.
#[derive(Debug, Clone)]
pub struct PressureSpace {
    /// Number of functions (1 to 4).
    pub n: usize,
    /// `ψ_k` at `[gauss point][k]`, Gauss points in the kernel's order
    /// `g = g_axis · n_section + g_section`.
    pub psi: Vec<f64>,
}

impl PressureSpace {
    /// The space for a body's element kinds, at the Gauss points of `section` × `axis`.
    pub fn new(section: &SectionValues, axis: &AxisValues, section_order: usize, axis_order: usize) -> Self {
        let n = 1 + 2 * usize::from(section_order >= 2) + usize::from(axis_order >= 2);
        let mut psi = Vec::with_capacity(section.n_gp * axis.n_gp * n);
        for &zeta in &axis.natural {
            for &[xi, eta] in &section.natural {
                psi.push(1.0);
                if section_order >= 2 {
                    psi.extend([xi, eta]);
                }
                if axis_order >= 2 {
                    psi.push(zeta);
                }
            }
        }
        Self { n, psi }
    }
}

impl CellValues {
    /// Builds both caches for `body`.
    pub fn new(body: &Body) -> Result<Self, ElementError> {
        Ok(Self {
            section: SectionValues::new(&body.section, &body.name)?,
            axis: AxisValues::new(&body.axis),
            volumetric: None,
            shear: None,
        })
    }

    /// The same values with the B-bar projection of the volumetric strain.
    pub(crate) fn with_bbar(mut self, body: &Body) -> Self {
        self.volumetric =
            Some(PressureSpace::new(&self.section, &self.axis, body.section.kind.order(), body.axis.kind.order()));
        self
    }

    /// The same values with the assumed in-section shear strain
    /// ([`AssumedShear`]; no change for L4 sections, which the model
    /// reader refuses).
    pub(crate) fn with_assumed_shear(mut self, body: &Body) -> Self {
        self.shear = AssumedShear::new(&body.section, &self.section.natural);
        self
    }

    /// True if the kernel's strain is not the symmetric gradient of the
    /// displacement at a Gauss point (B-bar, the assumed shear): then the
    /// Gauss-point stresses, not `C ε(u)` at a point, are the element's.
    pub(crate) fn modified_strain(&self) -> bool {
        self.volumetric.is_some() || self.shear.is_some()
    }

    /// Gauss points per 3D element (`section × axis`); point `g = g_axis · n_section + g_section`.
    pub fn gp_per_element(&self) -> usize {
        self.section.n_gp * self.axis.n_gp
    }

    /// Gradients at Gauss point `(gb, gs)` of element `(es, eb)` into `out`;
    /// returns the volume weight.
    pub fn gradients(&self, es: usize, eb: usize, gb: usize, gs: usize, out: &mut [[f64; 3]]) -> f64 {
        gradients(self.section.point(es, gs), self.axis.point(eb, gb), out)
    }
}

/// Values of an element whose map is singular at the point (only reachable
/// on elements validation has accepted at their Gauss points, at a corner
/// of a degenerate element): zero gradients rather than NaN.
pub(crate) fn degenerate(body: &Body) -> SectionValues {
    let n = body.section.kind.nodes();
    SectionValues {
        n_gp: 1,
        n_fun: n,
        natural: vec![[0.0, 0.0]],
        f: vec![1.0 / n as f64; n],
        fx: vec![0.0; n],
        fz: vec![0.0; n],
        weight: vec![0.0],
        position: vec![[0.0, 0.0]],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Division;
    use crate::shape::{BeamElementKind, SectionElementKind};

    fn skewed_body() -> Body {
        let corners = [[0.0, 0.0], [0.012, 0.001], [0.010, 0.011], [-0.001, 0.009]];
        let section = CrossSection::from_quads(SectionElementKind::L9, &corners, &[[0, 1, 2, 3]], "s").unwrap();
        let lines = Division::uniform(0.1, 0.13, 1).lines("y").unwrap();
        Body::new("b", section, BeamAxis::from_lines(BeamElementKind::B3, &lines), 0)
    }

    /// The three evaluations agree: at a Gauss point, `PointValues` gives the
    /// kernel's gradients; the face weights sum to the face area and the
    /// shapes to one.
    #[test]
    fn point_cell_and_facet_values_agree() {
        let body = skewed_body();
        let cell = CellValues::new(&body).unwrap();
        let n = body.nodes_per_element();
        let mut g_cell = vec![[0.0; 3]; n];
        let (gs, gb) = (4, 1);
        cell.gradients(0, 0, gb, gs, &mut g_cell);
        let [xi, eta] = cell.section.natural[gs];
        let loc = Location { body: 0, element: 0, natural: [xi, eta, cell.axis.natural[gb]] };
        let pv = PointValues::new(&body, &loc);
        for a in 0..n {
            for d in 0..3 {
                assert!((pv.grads[a][d] - g_cell[a][d]).abs() < 1e-9 * (1.0 + g_cell[a][d].abs()), "{a} {d}");
            }
        }
        assert!((pv.shapes.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        // lateral face 0 runs from corner 0 to corner 1: length √(0.012² + 0.001²) × 0.03
        let face = FacetValues::new(&body, 0, 0, FaceSide::Lateral(0));
        let area: f64 = face.weights.iter().sum();
        assert!((area - (0.012f64.powi(2) + 0.001f64.powi(2)).sqrt() * 0.03).abs() < 1e-15);
        let per_node = face.integrate(|_| 1.0);
        assert!((per_node.iter().sum::<f64>() - area).abs() < 1e-15);
        // outward normal of the bottom edge points down
        assert!(face.normals[0][2] < -0.99);
    }
}
