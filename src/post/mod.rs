//! Field recovery at arbitrary points, probes and sampled lines.
//!
//! # Recovery rule
//!
//! A point `(x, y, z)` is located in a body element (beam element by `y`,
//! section element by inverting its isoparametric map) and every field is
//! computed from **that element** — never by averaging nodal values:
//!
//! * displacement `u = Σ F_τ N_i u_τi` and total strain `ε = D u` from the
//!   element's CUF expansion, exactly;
//! * in an element none of whose Gauss points has yielded, the stress is
//!   `σ = C ε` from the expansion, exactly — except in B-bar bodies, where
//!   the stress uses the element's projected dilatation and is the
//!   (unlimited) interpolation of the Gauss-point stresses, exact on affine
//!   elements; likewise in a total-Lagrangian analysis, where the strain
//!   is Green–Lagrange and the stress the Cauchy stress of the kernel;
//! * in an element with plastic Gauss points, stress and `peeq` are the
//!   Lagrange interpolation of their Gauss-point values through the
//!   element's Gauss points (the tensor grid of `p + 1` points per direction
//!   used for integration) — element-wise extrapolation — **limited** to the
//!   range of the element's own Gauss-point values, component by component.
//!   At a Gauss point this is exactly the stress of the return map.
//!
//! The limiter matters at stress concentrations. Fully integrated elements
//! show stress oscillations between Gauss points in isochoric plastic flow
//! (near the edge of the block-indentation punch one element has σ_zz =
//! −60, +83, −322 MPa at three consecutive points), and full-order
//! extrapolation to the element boundary amplifies them about twofold
//! (σ_zz = −590 MPa at the punch edge, where perfect plasticity bounds it
//! near Prandtl's (2 + π)k ≈ 297 MPa; the Gauss points nearest the edge give
//! −299 and −322 MPa). With the limiter a recovered value never leaves the
//! range actually computed in the element; `peeq ≥ 0` is a special case.
//! In smooth fields the limiter is inactive inside the Gauss-point hull and
//! may cut the extrapolation to an element face by the gradient over the
//! last ~11 % (3 points) of the element.
//!
//! For an elastic element with an affine map the two rules coincide: each
//! stress component is a polynomial of degree ≤ p per natural direction,
//! which the interpolation through `p + 1` Gauss points reproduces.
//!
//! A point on the boundary between elements (an element face, a node line)
//! belongs to several elements; the value reported is the mean of their
//! values (fields such as stress are discontinuous there).

pub mod estimate;
pub mod failure;
mod free_faces;
mod least_squares;
pub mod mode_error;
mod patch_map;
pub mod recovery;
pub mod spr;
mod yielded;

pub use crate::quantity::{Quantity, Sample};
pub use estimate::ErrorEstimate;
pub use recovery::Recovered;

use crate::assembly::FeState;
use crate::values::PointValues;
use crate::voigt::{self, Voigt};

pub use crate::values::Location;

pub use crate::values::locate_in_model;

/// Lagrange basis through arbitrary abscissae, evaluated at `x`.
fn lagrange_through(points: &[f64], x: f64, out: &mut [f64]) {
    for (k, o) in out.iter_mut().enumerate() {
        *o = points.iter().enumerate().filter(|&(j, _)| j != k).map(|(_, &pj)| (x - pj) / (points[k] - pj)).product();
    }
}

/// Everything needed to evaluate fields of a solved (or partially solved)
/// model: its finite-element state (the one an assembly reads), the
/// Gauss-point stresses, and how to read them.
pub struct FieldView<'a> {
    /// Mesh, geometry, materials, displacements and Gauss-point states.
    pub state: FeState<'a>,
    /// Gauss-point stresses of all bodies (same layout as `states`).
    pub stresses: &'a [Voigt],
    /// Recovered nodal stress and peeq: when present, stress and peeq at
    /// points come from it (continuous); otherwise element by element.
    pub recovered: Option<&'a Recovered>,
    /// The model's planes of symmetry: a point in the part they leave out
    /// is evaluated at its image, its fields reflected back.
    pub symmetry: &'a [crate::bc::symmetry::Plane],
    /// The ply damage of the Gauss points (same layout as `stresses`),
    /// `None` where no material damages: an element with a softened point
    /// takes its stress from its Gauss points, as a plastic one.
    pub damage: Option<&'a crate::damage::Damage>,
}

impl<'a> std::ops::Deref for FieldView<'a> {
    type Target = FeState<'a>;

    fn deref(&self) -> &FeState<'a> {
        &self.state
    }
}

impl FieldView<'_> {
    /// Fields at a located point.
    pub fn sample(&self, loc: &Location) -> Sample {
        let mut s = self.sample_stress(loc);
        let body = &self.mesh.bodies[loc.body];
        let material = &self.materials[body.material_of(body.split_element(loc.element).0)];
        if let Some(ix) = material.failure_indices(&s.stress) {
            s.failure = failure::as_array(&ix);
        }
        s
    }

    /// [`FieldView::sample`] without the failure indices.
    fn sample_stress(&self, loc: &Location) -> Sample {
        let body = &self.mesh.bodies[loc.body];
        let geom = &self.geometry[loc.body];
        let [xi, eta, zeta] = loc.natural;
        // the same shape values and strain as the element kernel
        let pv = PointValues::new(body, loc);
        let strain = self.kinematics.strain(&pv.gradient(self.u));
        let mut s = Sample { u: pv.displacement(self.u), strain, ..Default::default() };
        if let Some(r) = self.recovered {
            for (&n, &node) in pv.shapes.iter().zip(&pv.nodes) {
                for k in 0..6 {
                    s.stress[k] += n * r.stress[node][k];
                }
                s.peeq += n * r.peeq[node];
            }
            // a projection may undershoot zero next to a plastic zone
            s.peeq = s.peeq.max(0.0);
            s.von_mises = voigt::von_mises(&s.stress);
            return s;
        }

        // Gauss-point history, interpolated through the Gauss points
        let sgp = geom.section.n_gp;
        let m = (sgp as f64).sqrt().round() as usize;
        let gauss_line: Vec<f64> = (0..m).map(|i| geom.section.natural[i][0]).collect();
        let (mut lx, mut lz) = (vec![0.0; m], vec![0.0; m]);
        lagrange_through(&gauss_line, xi, &mut lx);
        lagrange_through(&gauss_line, eta, &mut lz);
        let mut ly = vec![0.0; geom.axis.n_gp];
        lagrange_through(&geom.axis.natural, zeta, &mut ly);
        let base = self.gp_offsets[loc.body] + loc.element * geom.gp_per_element();
        let mut sigma = [0.0; 6];
        let mut peeq = 0.0;
        // range of the element's Gauss-point values, for the limiter
        let mut lo = [f64::INFINITY; 7];
        let mut hi = [f64::NEG_INFINITY; 7];
        let mut softened = false;
        for (gb, wy) in ly.iter().enumerate() {
            for j in 0..m {
                for i in 0..m {
                    let w = wy * lz[j] * lx[i];
                    let g = base + gb * sgp + j * m + i;
                    let values = self.stresses[g];
                    for k in 0..6 {
                        sigma[k] += w * values[k];
                        lo[k] = lo[k].min(values[k]);
                        hi[k] = hi[k].max(values[k]);
                    }
                    softened |= self.damage.is_some_and(|d| d.softened(g));
                    let p = self.states[g].peeq;
                    peeq += w * p;
                    lo[6] = lo[6].min(p);
                    hi[6] = hi[6].max(p);
                }
            }
        }
        if hi[6] > 0.0 || softened {
            // a yielded or damaged element: the stress at a point is not
            // the elastic stiffness's times the strain there but the Gauss
            // points' through them, limited to their range. With damage,
            // the intact stiffness times the strain of a softened band (or
            // the law's secant at the damage interpolated to the point,
            // tried) gave failure indices of tens to hundreds at a crack
            // that carries nothing
            for k in 0..6 {
                s.stress[k] = sigma[k].clamp(lo[k], hi[k]);
            }
            s.peeq = peeq.clamp(lo[6], hi[6]);
        } else if geom.modified_strain() || self.kinematics.is_nonlinear() {
            // B-bar: the stress depends on the projected dilatation, not on
            // `div u` at the point (with ν → 0.5 the latter times λ is noise);
            // the Gauss-point stresses are the kernel's, and the interpolation
            // through them is exact on affine elements (the projected
            // dilatation is linear, the deviatoric strain of degree ≤ p;
            // likewise the assumed shear's strain is not `ε(u)` at the point)
            // (total Lagrangian: the Cauchy stress is not `C E`, and the
            // kernel's Gauss-point values are the ones to interpolate)
            s.stress = sigma;
        } else {
            s.stress = voigt::mat_vec(
                self.materials[body.material_of(body.split_element(loc.element).0)].elastic_stiffness(),
                &s.strain,
            );
        }
        s.von_mises = voigt::von_mises(&s.stress);
        s
    }

    /// Fields at a point (mean over the elements holding it), or `None` outside;
    /// in the part a symmetry plane leaves out, its image's reflected back.
    pub fn sample_point(&self, body: Option<usize>, point: [f64; 3]) -> Option<Sample> {
        crate::bc::symmetry::sample(self.symmetry, point, |image| {
            self.sample_at(&locate_in_model(self.mesh, body, image))
        })
    }

    /// Fields at a point already located (mean over its elements), `None` without a location.
    pub fn sample_at(&self, locations: &[Location]) -> Option<Sample> {
        if locations.is_empty() {
            return None;
        }
        let samples: Vec<Sample> = locations.iter().map(|l| self.sample(l)).collect();
        Some(Sample::mean(&samples))
    }

    /// Fields at a probe (located during preprocessing).
    pub fn sample_probe(&self, probe: &crate::setup::Probe) -> Option<Sample> {
        crate::bc::symmetry::sample(self.symmetry, probe.point, |_| self.sample_at(&probe.locations))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lagrange_through_gauss_points_reproduces_quadratics() {
        let g = crate::quadrature::GaussRule::new(3);
        let mut l = vec![0.0; 3];
        // extrapolation to the element end is exact for quadratics
        lagrange_through(&g.points, 1.0, &mut l);
        let f = |x: f64| 2.0 - x + 3.0 * x * x;
        let v: f64 = l.iter().zip(&g.points).map(|(a, &x)| a * f(x)).sum();
        assert!((v - f(1.0)).abs() < 1e-13);
    }
}

/// One sample of a line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineSample {
    /// Distance from the start of the line (m).
    pub s: f64,
    /// Point (m).
    pub point: [f64; 3],
    /// Fields, `None` where the point is outside every body.
    pub sample: Option<Sample>,
}

/// Samples a line at its equally spaced points.
pub fn sample_line(view: &FieldView<'_>, line: &crate::setup::Line) -> Vec<LineSample> {
    let len = (0..3).map(|k| (line.to[k] - line.from[k]).powi(2)).sum::<f64>().sqrt();
    (0..line.points)
        .map(|i| {
            let t = i as f64 / (line.points - 1) as f64;
            let point = [0, 1, 2].map(|k| line.from[k] + t * (line.to[k] - line.from[k]));
            LineSample { s: t * len, point, sample: view.sample_point(line.body, point) }
        })
        .collect()
}
