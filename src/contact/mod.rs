//! Node-to-node contact enforced by a penalty (paper §3), frictionless
//! unless Coulomb friction is given (module `friction`: return map and its
//! unsymmetric tangent).
//!
//! For a contact point with gap `g_N` (eq. 13, negative when penetrating)
//! and unit normal `n`, the penalty energy `½ ε_N ⟨−g_N⟩²` (eq. 16) gives
//!
//! * the contact force `F = −ε_N g_N n` on the slave side (eq. 20; the sign
//!   makes it push the bodies apart), `−F` on the master side;
//! * the penalty stiffness `k = ε_N n nᵀ` (eq. 19) in the slave–slave and
//!   master–master blocks, `−ε_N n nᵀ` in the coupling blocks.
//!
//! Every contact point is a node pair in the sense of eq. (13):
//! `g_N = g_init + (u_s − u_m)·n` with the normal `n` and the initial gap
//! `g_init` (eq. 14) fixed in the reference configuration (small
//! displacements). Two kinds are supported:
//!
//! * **rigid indenters** — a flat rectangular punch or a cylinder (roller)
//!   whose axis is parallel to x, y or z, moved by a prescribed displacement
//!   `λ d` that plays the role of `u_m`. Each node of the body's contact
//!   surface that faces the indenter is paired once, at the start, with the
//!   closest point of the rigid surface: `g_init` is its distance along the
//!   surface normal there, `n` that normal (pointing to the body). Keeping
//!   the pair and its normal fixed is the paper's node-to-node formulation;
//!   it also keeps a node that slides a few micrometres along a roller from
//!   losing contact through the `s²/2R` rise of the exact gap, which
//!   otherwise releases every support node at once in three-point bending;
//! * **node pairs** between two deformable bodies — slave nodes paired with
//!   master nodes on matching surfaces (or listed), normal from the master
//!   surface and initial gap from the geometry.
//!
//! **Active set.** A point is active when `g_N ≤ 0` (touching counts, so a
//! body that only rests on its supports is restrained from the first
//! iteration). The set is re-evaluated at every Newton iteration; an
//! increment is accepted only when the set did not change in its last
//! iteration. Points that keep switching make Newton run out of iterations,
//! and the load stepping then cuts the increment back, which is what stops
//! chattering.
//!
//! **Penalty.** `ε_N` of a node is `α Σ_f E w_f / h_f` with `w_f = ∫ N dA` the
//! node's tributary area on face `f` of the contact surface and `h_f` the
//! depth of the element behind that face; `α` (`penalty_factor`) defaults to
//! `DEFAULT_PENALTY_FACTOR`. A penetration then compresses the contact
//! layer about `α` times less than the element layer behind it. Alternatively
//! `penalty` gives `ε_N / A` directly (Pa/m). Scaling by the tributary area
//! makes a uniform pressure produce a uniform penetration `p A_i / ε_i`.

use crate::bc::FaceIntegral;

pub mod assembly;
pub mod current;
mod friction;
mod impactor;
pub mod nodal_normal;
pub use assembly::{ContactPoint, Contacts};
pub use friction::{Friction, FrictionResponse, turning_friction};
pub(crate) use friction::{friction_response, stick_block};
pub use impactor::Impactor;
pub mod surface;

/// `a · b` of 3-vectors (the contact geometry's points, tangents, normals).
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a × b` of 3-vectors.
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// Default dimensionless penalty factor α.
pub(crate) const DEFAULT_PENALTY_FACTOR: f64 = 100.0;

/// Shape of a rigid indenter, in its reference position.
#[derive(Debug, Clone, PartialEq)]
pub enum RigidSurface {
    /// A flat rectangle lying in the plane `x[axis] = position`, facing the
    /// body along `sign · e_axis`; optional bounds on the in-plane coordinates.
    Flat {
        /// Axis normal to the punch face (0 = x, 1 = y, 2 = z).
        axis: usize,
        /// +1 if the face looks towards +axis, −1 towards −axis.
        sign: f64,
        /// Coordinate of the face plane (m).
        position: f64,
        /// Bounds on x, y, z of the face (the normal component is ignored).
        bounds: [Option<[f64; 2]>; 3],
    },
    /// A cylinder of `radius` around an axis parallel to `e_axis` through `center`.
    Cylinder {
        /// Direction of the cylinder axis (0 = x, 1 = y, 2 = z).
        axis: usize,
        /// A point on the axis (m).
        center: [f64; 3],
        /// Radius (m).
        radius: f64,
        /// Optional extent along the axis.
        length: Option<[f64; 2]>,
    },
    /// A sphere (ball indenter) of `radius` around `center`.
    Sphere {
        /// Centre (m).
        center: [f64; 3],
        /// Radius (m).
        radius: f64,
    },
}

impl std::fmt::Display for RigidSurface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        const AXES: [&str; 3] = ["x", "y", "z"];
        match self {
            Self::Flat { axis, sign, position, bounds } => {
                let sign = if *sign > 0.0 { "+" } else { "-" };
                write!(f, "flat punch in the plane {} = {position} m facing {sign}{}", AXES[*axis], AXES[*axis])?;
                for (k, b) in bounds.iter().enumerate() {
                    if let Some([a, b]) = b
                        && k != *axis
                    {
                        write!(f, ", {} ∈ [{a}, {b}] m", AXES[k])?;
                    }
                }
                Ok(())
            }
            Self::Cylinder { axis, center, radius, length } => {
                write!(f, "cylinder of radius {radius} m, axis along {} through {center:?} m", AXES[*axis])?;
                if let Some([a, b]) = length {
                    write!(f, ", {} ∈ [{a}, {b}] m", AXES[*axis])?;
                }
                Ok(())
            }
            Self::Sphere { center, radius } => write!(f, "sphere of radius {radius} m centred at {center:?} m"),
        }
    }
}

impl RigidSurface {
    /// Pairs a node with the rigid surface in the reference configuration:
    /// the initial gap to the closest surface point (along its normal) and
    /// that normal, pointing to the body; `None` where the node does not face
    /// the surface (beyond a punch's bounds or a cylinder's length). A node
    /// on a cylinder's axis gets the gap `−radius` and a zero normal.
    pub(crate) fn reference_gap(&self, x0: [f64; 3], tol: f64) -> Option<(f64, [f64; 3])> {
        self.current_gap(x0, tol).map(|(g, n, _)| (g, n))
    }

    /// Radius of a cylinder or sphere (0 for a flat punch).
    fn radius(&self) -> f64 {
        match self {
            Self::Flat { .. } => 0.0,
            Self::Cylinder { radius, .. } | Self::Sphere { radius, .. } => *radius,
        }
    }

    /// Exact gap of a point `y` (the body point's current position minus
    /// the indenter's rigid displacement, i.e. in the indenter's reference
    /// frame) to the surface, the unit normal `n` at its closest point
    /// (pointing to the body) and the normal's derivative `∂n/∂y` (for
    /// `method = "surface"`: the projection follows the deformation). The
    /// gap is the signed distance, so `∂g/∂y = n`, and
    ///
    /// * flat: `g = s (y_a − position)`, `n = s e_a`, `∂n/∂y = 0`;
    /// * cylinder: `g = ρ − R` with `ρ = ‖P⊥ (y − c)‖`, `n = P⊥ (y − c)/ρ`,
    ///   `∂n/∂y = (P⊥ − n nᵀ)/ρ` (`P⊥` removes the axis component);
    /// * sphere: `g = ρ − R` with `ρ = ‖y − c‖`, `n = (y − c)/ρ`,
    ///   `∂n/∂y = (I − n nᵀ)/ρ`.
    ///
    /// `None` outside a punch's bounds or a cylinder's length (the point
    /// has left the indenter); on a cylinder's axis or a sphere's centre the
    /// gap `−R` with a zero normal.
    pub(crate) fn current_gap(&self, y: [f64; 3], tol: f64) -> Option<(f64, [f64; 3], [[f64; 3]; 3])> {
        let curved = |r: [f64; 3], keep: [f64; 3]| {
            let d = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
            if d == 0.0 {
                // on the axis / at the centre: inside by the whole radius,
                // no normal (the model rejects such a placement)
                return Some((-self.radius(), [0.0; 3], [[0.0; 3]; 3]));
            }
            let n = r.map(|v| v / d);
            let dn = std::array::from_fn(|i| {
                std::array::from_fn(|j| (keep[i] * f64::from(u8::from(i == j)) - n[i] * n[j]) / d)
            });
            Some((d - self.radius(), n, dn))
        };
        match self {
            Self::Flat { axis, sign, position, bounds } => {
                for k in (0..3).filter(|k| k != axis) {
                    if let Some([a, b]) = bounds[k]
                        && (y[k] < a - tol || y[k] > b + tol)
                    {
                        return None;
                    }
                }
                let mut normal = [0.0; 3];
                normal[*axis] = *sign;
                Some((sign * (y[*axis] - position), normal, [[0.0; 3]; 3]))
            }
            Self::Cylinder { axis, center, length, .. } => {
                if let Some([a, b]) = length
                    && (y[*axis] < a - tol || y[*axis] > b + tol)
                {
                    return None;
                }
                let mut r = [y[0] - center[0], y[1] - center[1], y[2] - center[2]];
                r[*axis] = 0.0;
                let mut keep = [1.0; 3];
                keep[*axis] = 0.0;
                curved(r, keep)
            }
            Self::Sphere { center, .. } => curved([y[0] - center[0], y[1] - center[1], y[2] - center[2]], [1.0; 3]),
        }
    }
}

/// A body node paired with a rigid indenter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactNode {
    /// Global node.
    pub node: usize,
    /// Tributary area `Σ ∫ N dA` on the contact surface (m²).
    pub area: f64,
    /// Penalty stiffness ε_N (N/m).
    pub penalty: f64,
    /// Initial gap to the rigid surface (m).
    pub(crate) gap0: f64,
    /// Rigid-surface normal at the paired point, pointing to the body.
    pub normal: [f64; 3],
}

/// A rigid indenter and its candidate nodes.
#[derive(Debug, Clone)]
pub struct Indenter {
    /// Name.
    pub name: String,
    /// Body index.
    pub body: usize,
    /// Geometry in the reference position.
    pub surface: RigidSurface,
    /// Rigid displacement at load factor 1 (m); zero under force control.
    pub displacement: [f64; 3],
    /// Force control: the force (N) the indenter applies to the body at
    /// load factor 1. Its rigid displacement along this force is then an
    /// unknown of the analysis; `None`: displacement control.
    pub force: Option<[f64; 3]>,
    /// Candidate nodes.
    pub nodes: Vec<ContactNode>,
    /// Augmented Lagrangian: the largest penetration (m) accepted; `None`
    /// for pure penalty (the paper's method).
    pub penetration_tolerance: Option<f64>,
    /// Coulomb friction; `None`: frictionless (the paper's contact).
    pub friction: Option<Friction>,
    /// The body's boundary faces the indenter may touch.
    pub faces: Vec<crate::bc::Face>,
    /// `method = "surface"`: gap and normal from the exact closest point of
    /// the current configuration at every evaluation
    /// (`RigidSurface::current_gap`); `false`: node-to-node, fixed at the
    /// reference configuration (the paper's method).
    pub(crate) updated: bool,
    /// A rigid impactor's mass and velocity (transient analysis; module
    /// `impactor`); `None`: no mass of its own.
    pub impactor: Option<Impactor>,
}

/// The boundary faces of one side of a contact.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSurface {
    /// Body index.
    pub body: usize,
    /// Its boundary faces on this side.
    pub faces: Vec<crate::bc::Face>,
}

/// A slave–master node pair between deformable bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodePair {
    /// Slave node (global).
    pub slave: usize,
    /// Master node (global).
    pub master: usize,
    /// Master-surface unit normal, pointing towards the slave body.
    pub normal: [f64; 3],
    /// Initial gap `(X_s − X_m)·n` (m).
    pub(crate) gap0: f64,
    /// Tributary area of the slave node (m²).
    pub area: f64,
    /// Penalty ε_N (N/m).
    pub penalty: f64,
}

/// Node-to-node contact between two deformable bodies.
#[derive(Debug, Clone)]
pub struct PairContact {
    /// Name.
    pub name: String,
    /// The pairs.
    pub pairs: Vec<NodePair>,
    /// Augmented Lagrangian: the largest penetration (m) accepted; `None`
    /// for pure penalty (the paper's method).
    pub penetration_tolerance: Option<f64>,
    /// Coulomb friction; `None`: frictionless (the paper's contact).
    pub friction: Option<Friction>,
    /// Slave-surface nodes that found no master node (not in contact).
    pub unpaired: usize,
    /// The master side's faces.
    pub master: ContactSurface,
    /// The slave side's faces.
    pub slave: ContactSurface,
    /// `method = "surface"`: segment-to-segment contact (then `pairs` is empty).
    pub surface: Option<surface::SurfaceContact>,
    /// An interference fit (`interference = true`): the initial overlap (m,
    /// ≥ 0) of each contact point (pair, or slave node of a surface
    /// contact), removed gradually over the first load step
    /// (`PairContact::overlap_relief`); empty otherwise.
    pub(crate) initial_overlap: Vec<f64>,
}

impl PairContact {
    /// What is added to the gap of point `j` at load factor `λ`: the part of
    /// its initial overlap not yet imposed, `(1 − min(λ, 1)) · overlap`, so
    /// that an interference fit starts just touching and is fully
    /// overlapped from the end of the first step on (small increments and
    /// cutbacks then apply to it as to any load).
    pub(crate) fn overlap_relief(&self, j: usize, lambda: f64) -> f64 {
        self.initial_overlap.get(j).map_or(0.0, |o| (1.0 - lambda.clamp(0.0, 1.0)) * o)
    }

    /// Node pairs the matrix pattern must couple: the node pairs, or the
    /// slave–master couplings of a surface contact's candidate faces; with
    /// `current` (nonlinear geometry) a node pair couples its slave node and
    /// every node of the master faces around its master node (whose
    /// positions turn its normal, [`nodal_normal`]).
    pub(crate) fn couplings(&self, mesh: &crate::mesh::Mesh, current: bool) -> Vec<(usize, usize)> {
        match &self.surface {
            Some(s) => s.couplings(&mesh.bodies[s.master_body]),
            None if current => {
                let masters: Vec<usize> = self.pairs.iter().map(|p| p.master).collect();
                let normals = nodal_normal::NodalNormal::for_nodes(mesh, &self.master, &masters);
                let mut set = std::collections::BTreeSet::new();
                for (p, n) in self.pairs.iter().zip(&normals) {
                    let all: Vec<usize> = std::iter::once(p.slave).chain(n.nodes.iter().copied()).collect();
                    for (i, &a) in all.iter().enumerate() {
                        for &b in &all[i + 1..] {
                            set.insert((a.min(b), a.max(b)));
                        }
                    }
                }
                set.into_iter().collect()
            }
            None => self.pairs.iter().map(|p| (p.slave, p.master)).collect(),
        }
    }

    /// Penalty ε (N/m) of point `j`.
    pub fn point_penalty(&self, j: usize) -> f64 {
        match &self.surface {
            Some(s) => s.penalties[j],
            None => self.pairs[j].penalty,
        }
    }
}

/// How ε_N is chosen for a contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Penalty {
    /// `ε_N = α Σ E w / h` (dimensionless α).
    Factor(f64),
    /// `ε_N = value · A` with `value` in Pa/m.
    PerArea(f64),
}

/// Candidate nodes of a contact surface: every node of the selected faces
/// with its accumulated tributary area, stiffness scale `Σ E w/h` and
/// area-weighted outward normal.
#[derive(Debug, Clone, Default)]
pub(crate) struct SurfaceNodes {
    /// `(node, area, stiffness scale, normal sum)` sorted by node.
    pub nodes: Vec<(usize, f64, f64, [f64; 3])>,
}

impl SurfaceNodes {
    /// Accumulates face integrals (with Young's modulus `young` of the body).
    pub(crate) fn from_faces(faces: &[FaceIntegral], young: f64) -> Self {
        let mut map: std::collections::BTreeMap<usize, (f64, f64, [f64; 3])> = Default::default();
        for f in faces {
            for (&n, &w) in f.nodes.iter().zip(&f.weights) {
                let e = map.entry(n).or_insert((0.0, 0.0, [0.0; 3]));
                e.0 += w;
                e.1 += young * w / f.depth;
                for k in 0..3 {
                    e.2[k] += w * f.normal[k];
                }
            }
        }
        Self { nodes: map.into_iter().map(|(n, (a, s, nn))| (n, a, s, nn)).collect() }
    }

    /// Penalty of an entry.
    pub fn penalty(entry: &(usize, f64, f64, [f64; 3]), penalty: Penalty) -> f64 {
        match penalty {
            Penalty::Factor(a) => a * entry.2,
            Penalty::PerArea(p) => p * entry.1,
        }
    }
}

/// Pairs slave nodes with master nodes: for each slave node, the master node
/// whose position differs from it only along the master normal (within
/// `tol`). Unmatched slave nodes are returned separately.
pub(crate) fn match_pairs(
    slave: &SurfaceNodes,
    master: &SurfaceNodes,
    coords: impl Fn(usize) -> [f64; 3],
    slave_penalty: impl Fn(&(usize, f64, f64, [f64; 3])) -> f64,
    tol: f64,
) -> (Vec<NodePair>, Vec<usize>) {
    let mut pairs = Vec::new();
    let mut unmatched = Vec::new();
    let masters: Vec<([f64; 3], [f64; 3], usize)> = master
        .nodes
        .iter()
        .map(|m| {
            let nn = m.3;
            let l = (nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]).sqrt();
            (coords(m.0), nn.map(|v| v / l), m.0)
        })
        .collect();
    for s in &slave.nodes {
        let xs = coords(s.0);
        let mut best: Option<(f64, usize)> = None;
        for (k, (xm, n, _)) in masters.iter().enumerate() {
            let d = [xs[0] - xm[0], xs[1] - xm[1], xs[2] - xm[2]];
            let dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
            let t = ((d[0] - dn * n[0]).powi(2) + (d[1] - dn * n[1]).powi(2) + (d[2] - dn * n[2]).powi(2)).sqrt();
            // among the masters on the slave's normal line, the nearest one
            // along the normal (a thin master body has one on each face)
            if t <= tol && best.is_none_or(|(bd, _)| dn.abs() < bd) {
                best = Some((dn.abs(), k));
            }
        }
        match best {
            Some((_, k)) => {
                let (xm, n, m) = masters[k];
                let gap0 = (xs[0] - xm[0]) * n[0] + (xs[1] - xm[1]) * n[1] + (xs[2] - xm[2]) * n[2];
                pairs.push(NodePair { slave: s.0, master: m, normal: n, gap0, area: s.1, penalty: slave_penalty(s) });
            }
            None => unmatched.push(s.0),
        }
    }
    (pairs, unmatched)
}

/// Gap `g = g_init + (u_s − u_m)·n` of a pair (eq. 13).
pub fn gap(gap0: f64, normal: &[f64; 3], u_slave: [f64; 3], u_master: [f64; 3]) -> f64 {
    gap0 + (0..3).map(|k| (u_slave[k] - u_master[k]) * normal[k]).sum::<f64>()
}

/// A point's force on the slave node and its block `K = −∂f/∂u_slave`.
pub(crate) type Response = ([f64; 3], [[f64; 3]; 3]);

/// The augmented-Lagrangian form (Simo & Laursen 1992): with the multiplier
/// `λ ≥ 0` (N) of the point, force `(λ − ε g) n` while positive, block
/// `ε n nᵀ`; `λ = 0` is the pure penalty (eqs. 19–20). Between
/// Newton solves the multiplier is updated to the force, `λ ← λ − ε g`
/// (Uzawa), until the penetration is below the contact's tolerance: the
/// answer then no longer depends on `ε`. A NaN gap counts as touching.
pub(crate) fn augmented_response(g: f64, normal: &[f64; 3], penalty: f64, multiplier: f64) -> Option<Response> {
    let open = multiplier - penalty * g < 0.0 || (multiplier == 0.0 && g > 0.0);
    (!open).then(|| penalty_law(g, normal, penalty, multiplier))
}

/// [`augmented_response`]'s law without its inequality (a tension where
/// `λ − ε g < 0`: a point kept in contact at a secant start, `assembly::rigid`).
pub(crate) fn penalty_law(g: f64, normal: &[f64; 3], penalty: f64, multiplier: f64) -> Response {
    let p = multiplier - penalty * g;
    (normal.map(|v| p * v), normal.map(|a| normal.map(|b| penalty * a * b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Force `−ε g n` (eq. 20) and block `ε n nᵀ` (eq. 19) of an active pair, `None` if open.
    fn penalty_response(g: f64, normal: &[f64; 3], penalty: f64) -> Option<Response> {
        augmented_response(g, normal, penalty, 0.0)
    }

    #[test]
    fn reference_gap_to_a_roller_and_to_a_punch() {
        // node 3 mm beside the line where a roller of radius 10 mm touches a bottom face
        let roller = RigidSurface::Cylinder { axis: 0, center: [0.005, 0.025, -0.01], radius: 0.01, length: None };
        let (g, n) = roller.reference_gap([0.002, 0.028, 0.0], 1e-12).unwrap();
        let d = (0.003f64.powi(2) + 0.01f64.powi(2)).sqrt();
        assert!((g - (d - 0.01)).abs() < 1e-15);
        assert!((n[1] - 0.003 / d).abs() < 1e-15 && (n[2] - 0.01 / d).abs() < 1e-15 && n[0] == 0.0);
        let punch = RigidSurface::Flat { axis: 2, sign: -1.0, position: 0.3, bounds: [Some([0.2, 0.3]), None, None] };
        assert_eq!(punch.reference_gap([0.25, 0.05, 0.3], 1e-9), Some((0.0, [0.0, 0.0, -1.0])));
        assert!(punch.reference_gap([0.31, 0.05, 0.3], 1e-9).is_none());
    }

    /// `current_gap`: the gap's gradient is the normal and the normal's
    /// derivative is `∂n/∂y`, by central differences at an oblique point of
    /// a sphere and of a cylinder (axis y), and a punch's edge ends contact.
    #[test]
    fn the_exact_gap_its_normal_and_their_derivatives() {
        let shapes = [
            RigidSurface::Sphere { center: [0.1, 0.2, 0.3], radius: 0.05 },
            RigidSurface::Cylinder { axis: 1, center: [0.1, 0.0, 0.3], radius: 0.05, length: None },
        ];
        let y = [0.13, 0.19, 0.34];
        let h = 1e-7;
        for s in &shapes {
            let (g, n, dn) = s.current_gap(y, 1e-12).unwrap();
            let rho = match s {
                RigidSurface::Sphere { .. } => (0.03f64.powi(2) + 0.01f64.powi(2) + 0.04f64.powi(2)).sqrt(),
                _ => 0.05,
            };
            assert!((g - (rho - 0.05)).abs() < 1e-15, "{s}: gap {g}");
            for j in 0..3 {
                let mut yp = y;
                yp[j] += h;
                let mut ym = y;
                ym[j] -= h;
                let (gp, np, _) = s.current_gap(yp, 1e-12).unwrap();
                let (gm, nm, _) = s.current_gap(ym, 1e-12).unwrap();
                assert!(((gp - gm) / (2.0 * h) - n[j]).abs() < 1e-8, "{s}: ∂g/∂y_{j}");
                for i in 0..3 {
                    assert!(((np[i] - nm[i]) / (2.0 * h) - dn[i][j]).abs() < 1e-6, "{s}: ∂n_{i}/∂y_{j}");
                }
            }
        }
        let punch = RigidSurface::Flat { axis: 2, sign: -1.0, position: 0.3, bounds: [Some([0.2, 0.3]), None, None] };
        assert!(punch.current_gap([0.29, 0.0, 0.2999], 1e-9).is_some());
        assert!(punch.current_gap([0.31, 0.0, 0.2999], 1e-9).is_none(), "beyond the punch's edge");
    }

    #[test]
    fn penalty_force_and_stiffness() {
        // punch moved down 1 mm onto a node at the punch face: g = −1 mm
        let n = [0.0, 0.0, -1.0];
        let g = gap(0.0, &n, [0.0; 3], [0.0, 0.0, -1e-3]);
        assert!((g + 1e-3).abs() < 1e-18);
        let (f, k) = penalty_response(g, &n, 1e8).unwrap();
        // pushes the body down with ε|g|, stiffness ε n nᵀ
        assert!((f[2] + 1e5).abs() < 1e-6 && k[2][2] == 1e8 && k[0][2] == 0.0);
        // the tangent is the derivative of −f with respect to u_s
        let h = 1e-9;
        let fp = penalty_response(gap(0.0, &n, [0.0, 0.0, h], [0.0, 0.0, -1e-3]), &n, 1e8).unwrap().0;
        assert!((-(fp[2] - f[2]) / h - k[2][2]).abs() < 1e-6 * 1e8);
        assert!(penalty_response(1e-9, &n, 1e8).is_none());
    }

    /// Pairing across an inclined surface (normal sum (2, 3, 6)·area, along
    /// no axis): the normal is normalized, the slave on the master's normal
    /// line is paired with the exact gap, one off it is not. (cargo mutants:
    /// axis-aligned surfaces alone left the normalization untested.)
    #[test]
    fn pairs_across_an_inclined_surface() {
        let n = [2.0 / 7.0, 3.0 / 7.0, 6.0 / 7.0];
        // the master away from the origin, so that X_s − X_m differs from X_s + X_m
        let m = [0.1, 0.2, 0.3];
        let xs =
            [m, [0, 1, 2].map(|k| m[k] + 1e-3 * n[k]), [0, 1, 2].map(|k| m[k] + 1e-3 * n[k] + [1e-3, 0.0, 0.0][k])];
        let coords = |k: usize| xs[k];
        let master = SurfaceNodes { nodes: vec![(0, 2.0, 1.0, [4.0, 6.0, 12.0])] };
        let slave = SurfaceNodes { nodes: vec![(1, 1.0, 1.0, [0.0; 3]), (2, 1.0, 1.0, [0.0; 3])] };
        let (pairs, unmatched) = match_pairs(&slave, &master, coords, |_| 5.0, 1e-9);
        assert_eq!(unmatched, vec![2]);
        assert_eq!(pairs.len(), 1);
        let p = &pairs[0];
        assert_eq!((p.slave, p.master), (1, 0));
        for (a, b) in p.normal.iter().zip(n) {
            assert!((a - b).abs() < 1e-15, "{:?}", p.normal);
        }
        assert!((p.gap0 - 1e-3).abs() < 1e-14, "{}", p.gap0);
        assert_eq!((p.area, p.penalty), (1.0, 5.0));
    }

    /// A thin master body has a node on each face of the slave's normal
    /// line: the nearest one is chosen (listed second here, so that keeping
    /// the first would be wrong). And the tangential distance uses all its
    /// components: an offset of 1.2·tol along (3, −2, 0), perpendicular to
    /// the normal, is not paired.
    #[test]
    fn nearest_master_on_the_normal_line_and_the_tangential_distance() {
        let n = [2.0 / 7.0, 3.0 / 7.0, 6.0 / 7.0];
        let m = [0.1, 0.2, 0.3];
        let at = |s: f64| [0, 1, 2].map(|k| m[k] + s * n[k]);
        let xs = [at(2e-3), at(0.0), at(0.5e-3)];
        let coords = |k: usize| xs[k];
        let master = SurfaceNodes { nodes: vec![(0, 1.0, 1.0, [2.0, 3.0, 6.0]), (1, 1.0, 1.0, [2.0, 3.0, 6.0])] };
        let slave = SurfaceNodes { nodes: vec![(2, 1.0, 1.0, [0.0; 3])] };
        let (pairs, _) = match_pairs(&slave, &master, coords, |_| 1.0, 1e-9);
        assert_eq!(pairs[0].master, 1, "the nearer master");
        let k = 1.2e-3 / 13f64.sqrt();
        let off = [0, 1, 2].map(|c| m[c] + 0.5e-3 * n[c] + [3.0 * k, -2.0 * k, 0.0][c]);
        let coords = |i: usize| if i == 2 { off } else { xs[i] };
        let (pairs, unmatched) = match_pairs(&slave, &master, coords, |_| 1.0, 1e-3);
        assert!(pairs.is_empty() && unmatched == vec![2], "tangential offset 1.2e-3 > tol 1e-3");
    }
}
