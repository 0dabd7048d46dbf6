//! Geometry caches: shape functions, their physical derivatives and
//! integration weights at the Gauss points of every section element and
//! every beam element of a body. Computed once; the element kernel combines
//! them into 3D gradients `∇(F_τ N_i) = (F_τ,x N_i, F_τ N_i,y, F_τ,z N_i)`.

use super::ElementError;
use crate::mesh::{BeamAxis, Body, CrossSection};
use crate::quadrature::{GaussRule, SquareRule};
use crate::shape::{Lagrange1d, Lagrange2d};

/// The isoparametric map of one section element evaluated at `(ξ, η)`.
#[derive(Debug, Clone, Copy)]
pub struct SectionPoint {
    /// Physical `(x, z)`.
    pub position: [f64; 2],
    /// Jacobian determinant `det ∂(x,z)/∂(ξ,η)`.
    pub det: f64,
    /// Inverse Jacobian `[[ξ_x, ξ_z], [η_x, η_z]]`.
    pub inverse: [[f64; 2]; 2],
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
    SectionPoint { position: [x, z], det, inverse }
}

/// Cross-section functions at the Gauss points of every section element.
#[derive(Debug, Clone)]
pub struct SectionGeometry {
    /// Gauss points per element.
    pub n_gp: usize,
    /// Functions per element.
    pub n_fun: usize,
    /// Natural coordinates of the Gauss points.
    pub natural: Vec<[f64; 2]>,
    /// `F_τ` at `[element][gp][τ]`.
    pub f: Vec<f64>,
    /// `∂F_τ/∂x` at `[element][gp][τ]`.
    pub fx: Vec<f64>,
    /// `∂F_τ/∂z` at `[element][gp][τ]`.
    pub fz: Vec<f64>,
    /// Weight × Jacobian determinant at `[element][gp]` (an area, m²).
    pub weight: Vec<f64>,
    /// Physical `(x, z)` at `[element][gp]`.
    pub position: Vec<[f64; 2]>,
}

impl SectionGeometry {
    /// Builds the cache with `order + 1` Gauss points per direction.
    pub fn new(section: &CrossSection, body: &str) -> Result<Self, ElementError> {
        let p = section.kind.order();
        let basis = Lagrange2d::new(p);
        let rule = SquareRule::new(p + 1);
        let (n_gp, n_fun, n_el) = (rule.len(), basis.len(), section.n_elements());
        let mut g = Self {
            n_gp,
            n_fun,
            natural: rule.points.clone(),
            f: Vec::with_capacity(n_el * n_gp * n_fun),
            fx: Vec::with_capacity(n_el * n_gp * n_fun),
            fz: Vec::with_capacity(n_el * n_gp * n_fun),
            weight: Vec::with_capacity(n_el * n_gp),
            position: Vec::with_capacity(n_el * n_gp),
        };
        let (mut f, mut dxi, mut deta) = (vec![0.0; n_fun], vec![0.0; n_fun], vec![0.0; n_fun]);
        for e in 0..n_el {
            for (q, &[xi, eta]) in rule.points.iter().enumerate() {
                let sp = section_point(section, &basis, e, xi, eta, &mut f, &mut dxi, &mut deta);
                if !(sp.det > 0.0) {
                    return Err(ElementError::Distorted { body: body.to_string(), element: e, det: sp.det });
                }
                let [[xi_x, xi_z], [eta_x, eta_z]] = sp.inverse;
                for k in 0..n_fun {
                    g.f.push(f[k]);
                    g.fx.push(dxi[k] * xi_x + deta[k] * eta_x);
                    g.fz.push(dxi[k] * xi_z + deta[k] * eta_z);
                }
                g.weight.push(rule.weights[q] * sp.det);
                g.position.push(sp.position);
            }
        }
        Ok(g)
    }
}

/// Beam functions at the Gauss points of every beam element.
#[derive(Debug, Clone)]
pub struct AxisGeometry {
    /// Gauss points per element.
    pub n_gp: usize,
    /// Functions per element.
    pub n_fun: usize,
    /// Natural coordinates of the Gauss points.
    pub natural: Vec<f64>,
    /// `N_i` at `[element][gp][i]`.
    pub n: Vec<f64>,
    /// `∂N_i/∂y` at `[element][gp][i]`.
    pub ny: Vec<f64>,
    /// Weight × Jacobian at `[element][gp]` (a length, m).
    pub weight: Vec<f64>,
    /// Physical y at `[element][gp]`.
    pub position: Vec<f64>,
}

impl AxisGeometry {
    /// Builds the cache with `order + 1` Gauss points.
    pub fn new(axis: &BeamAxis) -> Self {
        let p = axis.kind.order();
        let basis = Lagrange1d::new(p);
        let rule = GaussRule::new(p + 1);
        let (n_gp, n_fun, n_el) = (rule.len(), basis.len(), axis.n_elements());
        let mut g = Self {
            n_gp,
            n_fun,
            natural: rule.points.clone(),
            n: Vec::with_capacity(n_el * n_gp * n_fun),
            ny: Vec::with_capacity(n_el * n_gp * n_fun),
            weight: Vec::with_capacity(n_el * n_gp),
            position: Vec::with_capacity(n_el * n_gp),
        };
        let (mut n, mut dn) = (vec![0.0; n_fun], vec![0.0; n_fun]);
        for e in 0..n_el {
            let (y0, y1) = axis.element_span(e);
            let jac = 0.5 * (y1 - y0);
            for (q, &zeta) in rule.points.iter().enumerate() {
                basis.eval(zeta, &mut n, &mut dn);
                g.n.extend_from_slice(&n);
                g.ny.extend(dn.iter().map(|d| d / jac));
                g.weight.push(rule.weights[q] * jac);
                g.position.push(0.5 * (y0 + y1) + jac * zeta);
            }
        }
        g
    }
}

/// Geometry caches of one body.
#[derive(Debug, Clone)]
pub struct BodyGeometry {
    /// Section part.
    pub section: SectionGeometry,
    /// Axis part.
    pub axis: AxisGeometry,
}

impl BodyGeometry {
    /// Builds both caches for `body`.
    pub fn new(body: &Body) -> Result<Self, ElementError> {
        Ok(Self { section: SectionGeometry::new(&body.section, &body.name)?, axis: AxisGeometry::new(&body.axis) })
    }

    /// Gauss points per 3D element (`section × axis`); point `g = g_axis · n_section + g_section`.
    pub fn gp_per_element(&self) -> usize {
        self.section.n_gp * self.axis.n_gp
    }
}
