//! Frictionless node-to-node contact enforced by a penalty (paper §3).
//!
//! For a contact point with gap `g_N` (eq. 13, negative when penetrating)
//! and unit normal `n`, the penalty energy `½ ε_N ⟨−g_N⟩²` (eq. 16) gives
//!
//! * the contact force `F = −ε_N g_N n` on the slave side (eq. 20; the sign
//!   makes it push the bodies apart), `−F` on the master side;
//! * the penalty stiffness `k = ε_N n nᵀ` (eq. 19) in the slave–slave and
//!   master–master blocks, `−ε_N n nᵀ` in the coupling blocks.
//!
//! Two kinds of contact are supported:
//!
//! * **rigid indenters** — a flat rectangular punch or a cylinder (roller)
//!   whose axis is parallel to x, y or z, moved by a prescribed displacement
//!   scaled by the load factor. Every node of the body's contact surface is a
//!   candidate; its gap is measured to the rigid surface along the surface
//!   normal. For the cylinder the normal turns with the contact point, which
//!   adds the geometric term `ε_N (g_N/d)(P − n nᵀ)` to the tangent
//!   (`d` = distance to the axis, `P` = projector normal to the axis);
//! * **node pairs** between two deformable bodies — slave nodes paired with
//!   master nodes on matching surfaces (or listed), normal from the master
//!   surface and initial gap from the geometry (eq. 14), both in the
//!   reference configuration (small displacements).
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
//! [`DEFAULT_PENALTY_FACTOR`]. A penetration then compresses the contact
//! layer about `α` times less than the element layer behind it. Alternatively
//! `penalty` gives `ε_N / A` directly (Pa/m). Scaling by the tributary area
//! makes a uniform pressure produce a uniform penetration `p A_i / ε_i`.

use crate::bc::FaceIntegral;

/// Default dimensionless penalty factor α.
pub const DEFAULT_PENALTY_FACTOR: f64 = 100.0;

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
}

/// Gap of a point to a rigid surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GapEval {
    /// Signed normal gap (m), negative when penetrating.
    pub gap: f64,
    /// Unit normal of the rigid surface at the closest point, pointing to the body.
    pub normal: [f64; 3],
    /// For curved surfaces, `(g/d, axis)`: the geometric tangent factor.
    pub curvature: Option<(f64, usize)>,
}

impl RigidSurface {
    /// Gap of the current point `x` to the surface moved by `offset`, or
    /// `None` where the point is beyond the surface's extent.
    pub fn gap(&self, x: [f64; 3], offset: [f64; 3], tol: f64) -> Option<GapEval> {
        match self {
            Self::Flat { axis, sign, position, bounds } => {
                for k in 0..3 {
                    if k == *axis {
                        continue;
                    }
                    if let Some([a, b]) = bounds[k] {
                        let v = x[k] - offset[k];
                        if v < a - tol || v > b + tol {
                            return None;
                        }
                    }
                }
                let mut normal = [0.0; 3];
                normal[*axis] = *sign;
                Some(GapEval { gap: sign * (x[*axis] - (position + offset[*axis])), normal, curvature: None })
            }
            Self::Cylinder { axis, center, radius, length } => {
                let mut r = [x[0] - center[0] - offset[0], x[1] - center[1] - offset[1], x[2] - center[2] - offset[2]];
                if let Some([a, b]) = length
                    && (x[*axis] - offset[*axis] < a - tol || x[*axis] - offset[*axis] > b + tol)
                {
                    return None;
                }
                r[*axis] = 0.0;
                let d = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
                if d == 0.0 {
                    return None;
                }
                let gap = d - radius;
                Some(GapEval { gap, normal: r.map(|v| v / d), curvature: Some((gap / d, *axis)) })
            }
        }
    }
}

/// A candidate contact node with its tributary area and penalty.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactNode {
    /// Global node.
    pub node: usize,
    /// Tributary area `Σ ∫ N dA` on the contact surface (m²).
    pub area: f64,
    /// Penalty stiffness ε_N (N/m).
    pub penalty: f64,
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
    /// Rigid displacement at load factor 1 (m).
    pub displacement: [f64; 3],
    /// Candidate nodes.
    pub nodes: Vec<ContactNode>,
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
    pub gap0: f64,
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
pub struct SurfaceNodes {
    /// `(node, area, stiffness scale, normal sum)` sorted by node.
    pub nodes: Vec<(usize, f64, f64, [f64; 3])>,
}

impl SurfaceNodes {
    /// Accumulates face integrals (with Young's modulus `young` of the body).
    pub fn from_faces(faces: &[FaceIntegral], young: f64) -> Self {
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
pub fn match_pairs(
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
            if t <= tol && best.is_none_or(|(bt, _)| t < bt) {
                best = Some((t, k));
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

/// Force on the body node and the 3×3 tangent block of one rigid contact
/// point (for the residual `f_int − f_ext − f_c`). `None` if inactive.
pub fn rigid_response(g: &GapEval, penalty: f64) -> Option<([f64; 3], [[f64; 3]; 3])> {
    if g.gap > 0.0 {
        return None;
    }
    let n = g.normal;
    let force = n.map(|v| -penalty * g.gap * v);
    let mut k = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            k[i][j] = penalty * n[i] * n[j];
        }
    }
    if let Some((factor, axis)) = g.curvature {
        // ε (g/d) (P − n nᵀ), P = I − a aᵀ
        for i in 0..3 {
            for j in 0..3 {
                let p = if i == j && i != axis { 1.0 } else { 0.0 };
                k[i][j] += penalty * factor * (p - n[i] * n[j]);
            }
        }
    }
    Some((force, k))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central-difference check of the rigid contact tangent, flat and curved.
    #[test]
    fn rigid_tangent_matches_finite_differences() {
        let surfaces = [
            RigidSurface::Flat { axis: 2, sign: -1.0, position: 0.3, bounds: [Some([0.2, 0.3]), None, None] },
            RigidSurface::Cylinder { axis: 0, center: [0.0, 0.125, 0.02], radius: 0.01, length: None },
            RigidSurface::Cylinder { axis: 1, center: [0.01, 0.0, -0.01], radius: 0.01, length: None },
        ];
        let points = [[0.25, 0.05, 0.3002], [0.003, 0.1262, 0.0101], [0.0105, 0.7, -0.0002]];
        let eps = 1e9;
        for (s, x) in surfaces.iter().zip(points) {
            let off = [0.0, 0.0, 0.0];
            let g = s.gap(x, off, 1e-12).unwrap();
            let (_, k) = rigid_response(&g, eps).expect("penetrating point");
            let h = 1e-9;
            for j in 0..3 {
                let (mut xp, mut xm) = (x, x);
                xp[j] += h;
                xm[j] -= h;
                let fp = rigid_response(&s.gap(xp, off, 1e-12).unwrap(), eps).unwrap().0;
                let fm = rigid_response(&s.gap(xm, off, 1e-12).unwrap(), eps).unwrap().0;
                for i in 0..3 {
                    // tangent of −f_c
                    let fd = -(fp[i] - fm[i]) / (2.0 * h);
                    assert!((fd - k[i][j]).abs() < 1e-6 * eps, "{s:?} ({i},{j}): {fd} vs {}", k[i][j]);
                }
            }
        }
    }

    #[test]
    fn flat_punch_gap_and_extent() {
        let s = RigidSurface::Flat { axis: 2, sign: -1.0, position: 0.3, bounds: [Some([0.2, 0.3]), None, None] };
        // punch moved down 1 mm: a top node at z = 0.3 penetrates by 1 mm
        let g = s.gap([0.25, 0.05, 0.3], [0.0, 0.0, -1e-3], 1e-9).unwrap();
        assert!((g.gap + 1e-3).abs() < 1e-15 && g.normal == [0.0, 0.0, -1.0]);
        assert!(s.gap([0.31, 0.05, 0.3], [0.0; 3], 1e-9).is_none());
        let (f, _) = rigid_response(&g, 1e8).unwrap();
        // pushes the body down (−z) with ε|g|
        assert!((f[2] + 1e5).abs() < 1e-6);
    }
}
