//! Boundary conditions: geometric node selections, boundary faces and their
//! integrals, constraints (fixed or prescribed displacements) and loads
//! (nodal forces, tractions, pressures).

mod faces;
pub mod symmetry;

pub use faces::{Face, FaceIntegral, FaceSide, boundary_faces, integrate_face};
pub(crate) use faces::{integrate_face_with, selected_faces};

use std::sync::Arc;

use crate::mesh::{Body, CrossSection};

/// One coordinate condition of a [`Selection`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Condition {
    /// Coordinate equal to a value (within the tolerance).
    Equal(f64),
    /// Coordinate inside a closed range (widened by the tolerance).
    Range(f64, f64),
}

impl Condition {
    fn accepts(&self, v: f64, tol: f64) -> bool {
        match *self {
            Self::Equal(a) => (v - a).abs() <= tol,
            Self::Range(a, b) => v >= a - tol && v <= b + tol,
        }
    }
}

/// A geometric selection of nodes: optional conditions on x, y and z, all of
/// which must hold (e.g. the face `z = 0`, the line `y = 0.025, z = 0`, a
/// point), and optionally a named section region (the point's `(x, z)` in
/// one of its elements).
#[derive(Debug, Clone, PartialEq)]
pub struct Selection {
    /// Conditions on `(x, y, z)`; `None` accepts any value.
    pub conditions: [Option<Condition>; 3],
    /// Absolute tolerance (m).
    pub tolerance: f64,
    /// A section region the point must lie in (`None`: anywhere).
    pub region: Option<RegionFilter>,
    /// A condition on the distance from the axis parallel to y through
    /// `[x, z]` (`None`: any distance).
    pub radial: Option<(Condition, [f64; 2])>,
}

/// The elements of a named section region, as a geometric condition on
/// `(x, z)` (so it applies to any mesh of the same body, e.g. the 3D export).
#[derive(Debug, Clone)]
pub struct RegionFilter {
    /// Region name.
    pub name: String,
    /// The section holding the region.
    pub section: Arc<CrossSection>,
    /// The region's elements.
    pub elements: Vec<usize>,
}

impl PartialEq for RegionFilter {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name && self.elements == other.elements && Arc::ptr_eq(&self.section, &other.section)
    }
}

impl Selection {
    /// True if the point satisfies every condition.
    pub fn contains(&self, p: [f64; 3]) -> bool {
        self.conditions.iter().zip(p).all(|(c, v)| c.is_none_or(|c| c.accepts(v, self.tolerance)))
            && self.radial.is_none_or(|(c, o)| c.accepts((p[0] - o[0]).hypot(p[2] - o[1]), self.tolerance))
            && self.region.as_ref().is_none_or(|r| r.section.covers(&r.elements, [p[0], p[2]], self.tolerance))
    }

    /// Body-local indices of the selected nodes of `body`.
    pub fn nodes(&self, body: &Body) -> Vec<usize> {
        (0..body.n_nodes()).filter(|&n| self.contains(body.local_coords(n))).collect()
    }
}

/// A constraint on the displacement of a node set: components fixed at zero
/// or prescribed (scaled by the load factor).
#[derive(Debug, Clone)]
pub struct Constraint {
    /// Name (used for reactions).
    pub name: String,
    /// Index of the body.
    pub body: usize,
    /// Global nodes.
    pub nodes: Vec<usize>,
    /// Prescribed total value per component (`Some(0.0)` = fixed, `None` = free).
    pub values: [Option<f64>; 3],
    /// The geometric selection the nodes came from (`None` for node lists
    /// built in code), so the constraint can be applied to another mesh of
    /// the same body (the 3D export).
    pub selection: Option<Selection>,
}

/// What a load applies, as the model file gives it: kept beside the nodal
/// forces so the same load can be discretized on another mesh.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadKind {
    /// The same force on every selected node.
    PerNode {
        /// The selection.
        selection: Selection,
        /// Force per node (N).
        force: [f64; 3],
    },
    /// A traction (Pa) on boundary faces (`total_force` becomes the traction
    /// total / area).
    Traction {
        /// The faces.
        faces: Vec<Face>,
        /// Traction vector (Pa).
        traction: [f64; 3],
    },
    /// A pressure (Pa, positive pushing into the body) on boundary faces.
    Pressure {
        /// The faces.
        faces: Vec<Face>,
        /// Pressure (Pa).
        pressure: f64,
    },
}

/// A variation of a traction or pressure along one coordinate: the load
/// times `sin(π (c − from)/(to − from))` (a half sine wave over
/// `[from, to]`, as in Navier's and Pagano's solutions of simply supported
/// members).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Profile {
    /// The coordinate (0: x, 1: y, 2: z).
    pub along: usize,
    /// Where the half wave starts (m).
    pub from: f64,
    /// Where it ends (m).
    pub to: f64,
}

impl Profile {
    /// The factor at a point.
    pub fn factor(&self, p: [f64; 3]) -> f64 {
        (std::f64::consts::PI * (p[self.along] - self.from) / (self.to - self.from)).sin()
    }
}

/// A rigid lever (`[[levers]]`, `setup/levers.rs`): a linear multi-point
/// constraint `Σ a_d u_d = value · factor(λ)` over free DOFs `d`, held by
/// the lever's force `P`, which pushes DOF `d` by `P a_d`.
#[derive(Debug, Clone)]
pub struct Lever {
    /// Name (`history_<name>.csv`, a step's `factors` key).
    pub name: String,
    /// Its displacement `Σ a_d u_d` at factor 1 (m).
    pub value: f64,
    /// `(global DOF, a_d)` in increasing DOF order: a point's coefficient
    /// over the number of its nodes.
    pub terms: Vec<(usize, f64)>,
}

impl Lever {
    /// Its displacement `Σ a_d u_d` at displacements `u` (per DOF).
    pub(crate) fn displacement(&self, u: &[f64]) -> f64 {
        self.terms.iter().map(|&(d, a)| a * u[d]).sum()
    }
}

/// A load on a node set.
#[derive(Debug, Clone)]
pub struct Load {
    /// Name.
    pub name: String,
    /// Global nodes and the total force (N) on each, at load factor 1.
    pub nodal_forces: Vec<(usize, [f64; 3])>,
    /// Index of the loaded body.
    pub body: usize,
    /// The load as given.
    pub kind: LoadKind,
    /// Its variation over the faces (`None`: uniform).
    pub profile: Option<Profile>,
}

impl Load {
    /// Sum of the nodal forces.
    pub fn resultant(&self) -> [f64; 3] {
        let mut r = [0.0; 3];
        for (_, f) in &self.nodal_forces {
            for k in 0..3 {
                r[k] += f[k];
            }
        }
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn selection_of_face_line_and_range() {
        let s = Selection {
            conditions: [None, None, Some(Condition::Equal(0.0))],
            tolerance: 1e-9,
            region: None,
            radial: None,
        };
        assert!(s.contains([3.0, 2.0, 0.0]) && !s.contains([3.0, 2.0, 1e-6]));
        let s = Selection {
            conditions: [Some(Condition::Range(0.2, 0.3)), Some(Condition::Equal(0.025)), None],
            tolerance: 1e-9,
            region: None,
            radial: None,
        };
        assert!(s.contains([0.3, 0.025, 7.0]) && !s.contains([0.31, 0.025, 7.0]));
        // a cylinder of radius 0.03 about the axis (x, z) = (0.1, −0.2):
        // measured in the x–z plane, whatever y (a slip to (x, y) fails)
        let s = Selection {
            conditions: [None; 3],
            tolerance: 1e-9,
            region: None,
            radial: Some((Condition::Equal(0.03), [0.1, -0.2])),
        };
        assert!(s.contains([0.13, 5.0, -0.2]) && s.contains([0.1, -1.0, -0.17]));
        assert!(!s.contains([0.13, 5.0, -0.19]) && !s.contains([0.1, -0.17, -0.2]));
    }
}
