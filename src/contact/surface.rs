//! Surface-to-surface contact between deformable bodies on non-matching
//! meshes (`contacts[].method = "surface"`): a segment-to-segment
//! formulation (Zavarise & De Lorenzis 2009; Puso & Laursen 2004 without
//! the dual basis) with slave integration points on the slave faces.
//!
//! **Geometry.** Every face is evaluated through the CUF expansion of its
//! body element: a lateral face (section edge `k` × beam element) is
//! `X(a, b) = (x(ξ(a), η(a)), y(ζ = b), z(ξ(a), η(a)))` with the section's
//! isoparametric map, an end face (section element at a beam end)
//! `X(a, b) = (x(a, b), y_end, z(a, b))`; the shape functions there are
//! `N = F_τ(ξ, η) N_i(ζ)`. Curved section edges are therefore followed
//! exactly as the elements interpolate them (`face_point`).
//!
//! **Integration points.** The slave face is cut into segments at the
//! element boundaries of the master surface — along the beam axis at the
//! master's axis-element ends, along the section edge at the master edge
//! ends projected onto it — and each segment gets a tensor Gauss rule
//! exact for the product of slave and master shape functions
//! (`max(p_s, p_m) + 1` points per direction). On flat faces this
//! integrates `∫ N_s p dA` and `∫ N_m p dA` exactly for a uniform pressure
//! `p`, so a uniform pressure is transmitted exactly (the patch test of
//! Taylor & Papadopoulos 1991; tests/surface_contact.rs). Slave end faces
//! are not segmented (a `(p + 2)²` rule on the whole face).
//!
//! **Gap and normal.** Point `q` (reference position `X_s`, slave shape
//! values `N_s`) is projected onto the master surface (closest point, by
//! Gauss–Newton on `(a, b)` over its candidate faces, `project`). With
//! the master's shape values `N_m` and the outward master normal `n` at the
//! projection (reference configuration),
//!
//! ```text
//! g = (X_s − X_m)·n + (Σ N_s u_s − Σ N_m u_m)·n ,
//! ```
//!
//! negative when penetrating. The pressure `p = λ − ε g ≥ 0` (penalty
//! `ε = α E w / h`, `w` the point's area weight, `h` the slave element's
//! depth; `λ` the augmented-Lagrangian multiplier) gives the force `p n`
//! distributed as `+N_s p n` to the slave nodes and `−N_m p n` to the
//! master nodes, and the tangent `c_a c_b ε n nᵀ` with `c = (N_s, −N_m)`.
//!
//! **Projection updates.** The projection is found in the reference
//! configuration at setup and again in the current configuration after
//! every converged increment; within an increment it is fixed, so the gap
//! is linear in `u` and the tangent above is exact (no curvature terms are
//! needed: a finite-difference check in tests/surface_contact.rs). Sliding
//! along the faces is followed from increment to increment, finite
//! sliding included as long as the point stays over its candidate faces:
//! the master faces within `search_distance` of the slave point's
//! reference position, whose nodes are coupled to the slave face's in the
//! matrix pattern at setup. A point whose projection leaves them is
//! inactive (gap NaN; counted by `project`'s callers).

use super::{cross, dot};
use crate::bc::Face;
use crate::mesh::{Body, Mesh};
use crate::quadrature::GaussRule;
use crate::shape::{Lagrange1d, Lagrange2d};
use crate::values::{FaceSide, section_point};

/// A point of a body face.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FacePoint {
    /// Reference position (m).
    pub position: [f64; 3],
    /// Outward unit normal.
    pub normal: [f64; 3],
    /// `∂X/∂a`, `∂X/∂b`.
    pub tangents: [[f64; 3]; 2],
    /// Global nodes of the face.
    pub nodes: Vec<usize>,
    /// Their shape values at the point.
    pub shapes: Vec<f64>,
}

/// Natural section coordinates `(ξ, η)` of edge `k` at edge parameter `a`.
fn edge_natural(k: usize, a: f64) -> (f64, f64) {
    match k {
        0 => (a, -1.0),
        1 => (1.0, a),
        2 => (a, 1.0),
        _ => (-1.0, a),
    }
}

/// Evaluates face `face` of `body` at face coordinates `(a, b) ∈ [−1, 1]²`
/// (lateral: `a` along the section edge, `b = ζ` along the beam element;
/// end: `a = ξ`, `b = η`).
pub(crate) fn face_point(body: &Body, face: &Face, a: f64, b: f64) -> FacePoint {
    let section = &body.section;
    let basis = Lagrange2d::new(section.kind.order());
    let m = basis.len();
    let (mut f, mut dxi, mut deta) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
    let el = section.element(face.section_element);
    let p = body.axis.kind.order();
    let first = body.axis.first_node(face.beam_element);
    let (y0, y1) = body.axis.element_span(face.beam_element);
    let (local, axis_nodes, zeta, (xi, eta)): (Vec<usize>, Vec<usize>, f64, (f64, f64)) = match face.side {
        FaceSide::Lateral(k) => (section.edge_local_nodes(k), (0..=p).collect(), b, edge_natural(k, a)),
        FaceSide::End(end) => ((0..m).collect(), vec![if end { p } else { 0 }], if end { 1.0 } else { -1.0 }, (a, b)),
    };
    let sp = section_point(section, &basis, face.section_element, xi, eta, &mut f, &mut dxi, &mut deta);
    let axis_basis = Lagrange1d::new(p);
    let (mut n, mut dn) = (vec![0.0; p + 1], vec![0.0; p + 1]);
    axis_basis.eval(zeta, &mut n, &mut dn);
    let mut nodes = Vec::with_capacity(local.len() * axis_nodes.len());
    let mut shapes = Vec::with_capacity(nodes.capacity());
    for &i in &axis_nodes {
        for &t in &local {
            nodes.push(body.node(first + i, el[t]));
            shapes.push(f[t] * n[i]);
        }
    }
    let position = [sp.position[0], y0 + 0.5 * (zeta + 1.0) * (y1 - y0), sp.position[1]];
    let [[x_xi, z_xi], [x_eta, z_eta]] = sp.tangents;
    let (tangents, normal) = match face.side {
        FaceSide::Lateral(k) => {
            // the edge runs along ξ (edges 0, 2) or η (edges 1, 3); the
            // other natural direction points into the element
            let (d, inward, sign) = match k {
                0 => ([x_xi, z_xi], [x_eta, z_eta], -1.0),
                2 => ([x_xi, z_xi], [x_eta, z_eta], 1.0),
                1 => ([x_eta, z_eta], [x_xi, z_xi], 1.0),
                _ => ([x_eta, z_eta], [x_xi, z_xi], -1.0),
            };
            let ds = d[0].hypot(d[1]);
            let mut n2 = [d[1] / ds, -d[0] / ds];
            if sign * (n2[0] * inward[0] + n2[1] * inward[1]) < 0.0 {
                n2 = [-n2[0], -n2[1]];
            }
            ([[d[0], 0.0, d[1]], [0.0, 0.5 * (y1 - y0), 0.0]], [n2[0], 0.0, n2[1]])
        }
        FaceSide::End(end) => ([[x_xi, 0.0, z_xi], [x_eta, 0.0, z_eta]], [0.0, if end { 1.0 } else { -1.0 }, 0.0]),
    };
    FacePoint { position, normal, tangents, nodes, shapes }
}

/// A slave integration point.
#[derive(Debug, Clone, PartialEq)]
pub struct SlavePoint {
    /// Slave face nodes.
    pub nodes: Vec<usize>,
    /// Their shape values at the point.
    pub shapes: Vec<f64>,
    /// Reference position (m).
    pub position: [f64; 3],
    /// Area weight (m²).
    pub weight: f64,
    /// Penalty ε (N/m) of the point (`ε_A w`).
    pub penalty: f64,
    /// Candidate master faces (indices into `SurfaceContact::master_faces`).
    pub candidates: Vec<usize>,
}

/// Segment-to-segment contact data of one `[[contacts]]` entry.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceContact {
    /// Master body index.
    pub(crate) master_body: usize,
    /// Master faces.
    pub(crate) master_faces: Vec<Face>,
    /// Slave integration points.
    pub points: Vec<SlavePoint>,
    /// Search distance (m) around a slave point for its candidate faces.
    pub search_distance: f64,
    /// Slave integration points with no master face within the search distance.
    pub unpaired: usize,
    /// The slave face nodes (sorted): one contact constraint each.
    pub slave_nodes: Vec<usize>,
    /// Their tributary areas `A_a = Σ_q w_q N_a(q)` (m²).
    pub areas: Vec<f64>,
    /// Their penalties `ε_a = Σ_q ε_q N_a(q)` (N/m).
    pub(crate) penalties: Vec<f64>,
}

/// The weighted (mortar) gap of one slave node `a` at fixed projections:
/// `g̃_a = Σ_q w_q N_a(q) g_q = gap0 + Σ_b grad_b · u_b` (m³).
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct NodeGap {
    /// `Σ_q w_q N_a(q) (X_s − X_m)·n` (m³).
    pub(crate) gap0: f64,
    /// `∂g̃_a/∂u_b` per node `b` (m²), slave and master nodes.
    pub(crate) grad: Vec<(usize, [f64; 3])>,
    /// The tangential counterpart `Σ_q w_q N_a(q) c_b(q) (I − n_q n_qᵀ)`
    /// per node `b` of `grad` (m²): the weighted tangential relative
    /// displacement is `Σ_b T_b u_b` (for friction).
    pub tangential: Vec<[[f64; 3]; 3]>,
    /// `m_a = Σ_q w_q N_a(q) n_q` (m²): the force of the node is `P_a m_a / A_a`.
    pub moment: [f64; 3],
}

impl SurfaceContact {
    /// The weighted gaps of all slave nodes from the points' projections
    /// (points without a projection contribute nothing).
    pub(crate) fn node_gaps(&self, projections: &[Option<Projection>]) -> Vec<NodeGap> {
        type Entry = ([f64; 3], [[f64; 3]; 3]);
        let mut out: Vec<std::collections::BTreeMap<usize, Entry>> = vec![Default::default(); self.slave_nodes.len()];
        let mut gaps = vec![NodeGap::default(); self.slave_nodes.len()];
        for (p, proj) in self.points.iter().zip(projections) {
            let Some(proj) = proj else { continue };
            for (&a, &na) in p.nodes.iter().zip(&p.shapes) {
                let ia = self.slave_nodes.binary_search(&a).expect("slave node listed");
                let w = p.weight * na;
                let g = &mut gaps[ia];
                g.gap0 += w * proj.gap0;
                for k in 0..3 {
                    g.moment[k] += w * proj.normal[k];
                }
                let sides = [(&p.nodes, &p.shapes, 1.0), (&proj.nodes, &proj.shapes, -1.0)];
                for (nodes, shapes, sign) in sides {
                    for (&b, &nb) in nodes.iter().zip(shapes.iter()) {
                        let e = out[ia].entry(b).or_insert(([0.0; 3], [[0.0; 3]; 3]));
                        let c = sign * w * nb;
                        let n = proj.normal;
                        for k in 0..3 {
                            e.0[k] += c * n[k];
                            for l in 0..3 {
                                e.1[k][l] += c * (f64::from(u8::from(k == l)) - n[k] * n[l]);
                            }
                        }
                    }
                }
            }
        }
        for (g, map) in gaps.iter_mut().zip(out) {
            let kept: Vec<(usize, Entry)> = map
                .into_iter()
                .filter(|(_, v)| v.0.iter().any(|x| *x != 0.0) || v.1.iter().flatten().any(|x| *x != 0.0))
                .collect();
            g.grad = kept.iter().map(|(b, v)| (*b, v.0)).collect();
            g.tangential = kept.iter().map(|(_, v)| v.1).collect();
        }
        gaps
    }
}

/// The projection of a slave point onto the master surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Projection {
    /// Master face (index into `SurfaceContact::master_faces`).
    pub face: usize,
    /// Face coordinates `(a, b)`.
    pub(crate) param: [f64; 2],
    /// Master outward normal there (reference configuration; the deformed
    /// master's in the current configuration, `contact::current`).
    pub normal: [f64; 3],
    /// The gap at zero displacement along `n`, `(X_s − X_m)·n` (m); in the
    /// current configuration the value that makes `gap0 + (u_s − u_m)·n`
    /// the current gap.
    pub(crate) gap0: f64,
    /// Master face nodes.
    pub nodes: Vec<usize>,
    /// Their shape values at the projection.
    pub shapes: Vec<f64>,
}

fn interpolate(nodes: &[usize], shapes: &[f64], u: &[f64]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (&n, &s) in nodes.iter().zip(shapes) {
        for k in 0..3 {
            out[k] += s * u[3 * n + k];
        }
    }
    out
}

/// Closest point of `face` to the current position `x` (master at
/// displacements `u`): Gauss–Newton on `(a, b)` with the reference
/// tangents; `None` if it converges outside the face (beyond `slack`).
fn project_on_face(body: &Body, face: &Face, x: [f64; 3], u: &[f64], slack: f64) -> Option<(FacePoint, [f64; 2])> {
    let (mut a, mut b) = (0.0, 0.0);
    for _ in 0..50 {
        let fp = face_point(body, face, a, b);
        let um = interpolate(&fp.nodes, &fp.shapes, u);
        let r: [f64; 3] = std::array::from_fn(|k| x[k] - fp.position[k] - um[k]);
        let [t0, t1] = fp.tangents;
        let (g00, g01, g11) = (dot(t0, t0), dot(t0, t1), dot(t1, t1));
        let (r0, r1) = (dot(t0, r), dot(t1, r));
        let det = g00 * g11 - g01 * g01;
        if !(det > 0.0) {
            return None;
        }
        let (da, db) = ((g11 * r0 - g01 * r1) / det, (g00 * r1 - g01 * r0) / det);
        // keep the iterate near the face (a far-away face converges outside)
        a = (a + da).clamp(-2.0, 2.0);
        b = (b + db).clamp(-2.0, 2.0);
        if da.abs() + db.abs() < 1e-13 {
            break;
        }
    }
    if a.abs() > 1.0 + slack || b.abs() > 1.0 + slack {
        return None;
    }
    let (a, b) = (a.clamp(-1.0, 1.0), b.clamp(-1.0, 1.0));
    Some((face_point(body, face, a, b), [a, b]))
}

/// Projects slave point `p` (slave displacements and master displacements
/// both read from `u`) onto the nearest of its candidate faces; `None` if
/// no candidate face holds its closest point.
pub(crate) fn project(contact: &SurfaceContact, mesh: &Mesh, p: &SlavePoint, u: &[f64]) -> Option<Projection> {
    let body = &mesh.bodies[contact.master_body];
    let us = interpolate(&p.nodes, &p.shapes, u);
    let x: [f64; 3] = std::array::from_fn(|k| p.position[k] + us[k]);
    let mut best: Option<(f64, Projection)> = None;
    for &f in &p.candidates {
        let Some((fp, param)) = project_on_face(body, &contact.master_faces[f], x, u, 1e-9) else { continue };
        let um = interpolate(&fp.nodes, &fp.shapes, u);
        let d: [f64; 3] = std::array::from_fn(|k| x[k] - fp.position[k] - um[k]);
        let dist = dot(d, d).sqrt();
        if best.as_ref().is_none_or(|(bd, _)| dist < *bd) {
            let d0: [f64; 3] = std::array::from_fn(|k| p.position[k] - fp.position[k]);
            let proj = Projection {
                face: f,
                param,
                normal: fp.normal,
                gap0: dot(d0, fp.normal),
                nodes: fp.nodes,
                shapes: fp.shapes,
            };
            best = Some((dist, proj));
        }
    }
    best.map(|(_, p)| p)
}

/// Gap of a projected point at displacements `u`.
pub fn gap(p: &SlavePoint, proj: &Projection, u: &[f64]) -> f64 {
    let us = interpolate(&p.nodes, &p.shapes, u);
    let um = interpolate(&proj.nodes, &proj.shapes, u);
    proj.gap0 + (0..3).map(|k| (us[k] - um[k]) * proj.normal[k]).sum::<f64>()
}

/// Reference bounding box of a face (from its nodes).
fn face_box(body: &Body, face: &Face) -> ([f64; 3], [f64; 3]) {
    let fp = face_point(body, face, 0.0, 0.0);
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &n in &fp.nodes {
        let x = body.local_coords(n - body.node_offset);
        for k in 0..3 {
            lo[k] = lo[k].min(x[k]);
            hi[k] = hi[k].max(x[k]);
        }
    }
    (lo, hi)
}

/// Breakpoints in `(−1, 1)` of a slave lateral face: master axis-element
/// ends along `b`, master edge ends (projected onto the slave edge in the
/// x–z plane) along `a`.
fn breakpoints(slave: &Body, face: &Face, master: &Body, master_faces: &[Face], reach: f64) -> [Vec<f64>; 2] {
    let (y0, y1) = slave.axis.element_span(face.beam_element);
    let tol = 1e-9;
    let mut along_b: Vec<f64> = vec![-1.0, 1.0];
    for e in 0..master.axis.n_elements() {
        let (m0, m1) = master.axis.element_span(e);
        for y in [m0, m1] {
            let z = 2.0 * (y - y0) / (y1 - y0) - 1.0;
            if z.abs() < 1.0 - tol {
                along_b.push(z);
            }
        }
    }
    let mut along_a: Vec<f64> = vec![-1.0, 1.0];
    if let FaceSide::Lateral(k) = face.side {
        let section = &slave.section;
        let basis = Lagrange2d::new(section.kind.order());
        let m = basis.len();
        let (mut f, mut dxi, mut deta) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        for mf in master_faces {
            let FaceSide::Lateral(mk) = mf.side else { continue };
            let loc = master.section.edge_local_nodes(mk);
            let el = master.section.element(mf.section_element);
            for t in [loc[0], loc[loc.len() - 1]] {
                let target = master.section.nodes[el[t]];
                // closest point of the slave edge to the master edge end
                let mut a = 0.0;
                for _ in 0..50 {
                    let (xi, eta) = edge_natural(k, a);
                    let sp = section_point(section, &basis, face.section_element, xi, eta, &mut f, &mut dxi, &mut deta);
                    let d = if k == 0 || k == 2 { sp.tangents[0] } else { sp.tangents[1] };
                    let r = [target[0] - sp.position[0], target[1] - sp.position[1]];
                    let da = (d[0] * r[0] + d[1] * r[1]) / (d[0] * d[0] + d[1] * d[1]);
                    a = (a + da).clamp(-2.0, 2.0);
                    if da.abs() < 1e-14 {
                        let off = (r[0] - da * d[0]).hypot(r[1] - da * d[1]);
                        if a.abs() < 1.0 - tol && off <= reach {
                            along_a.push(a);
                        }
                        break;
                    }
                }
            }
        }
    }
    for v in [&mut along_a, &mut along_b] {
        v.sort_by(f64::total_cmp);
        v.dedup_by(|x, y| (*x - *y).abs() < tol);
    }
    [along_a, along_b]
}

/// The slave side of a surface contact: its faces with their depth `h`,
/// the penalty per area `ε_A` of a face from its depth.
pub struct SlaveSide<'a> {
    /// Slave body.
    pub body: &'a Body,
    /// Its contact faces.
    pub faces: &'a [Face],
    /// Depth of the element behind each face (m).
    pub(crate) depths: &'a [f64],
}

/// Builds the slave integration points and their candidate master faces.
/// `penalty_per_area(h)` gives `ε_A` (Pa/m) of a face of depth `h`.
pub fn build(
    slave: SlaveSide<'_>,
    master_body: usize,
    master: &Body,
    master_faces: Vec<Face>,
    search_distance: f64,
    penalty_per_area: impl Fn(f64) -> f64,
) -> SurfaceContact {
    let boxes: Vec<([f64; 3], [f64; 3])> = master_faces.iter().map(|f| face_box(master, f)).collect();
    let mut points = Vec::new();
    let mut unpaired = 0;
    let body = slave.body;
    for (face, &h) in slave.faces.iter().zip(slave.depths) {
        let eps_a = penalty_per_area(h);
        let (ps, pm) = (body.section.kind.order(), master.section.kind.order());
        let (pbs, pbm) = (body.axis.kind.order(), master.axis.kind.order());
        let (segments, rules) = match face.side {
            FaceSide::Lateral(_) => (
                breakpoints(body, face, master, &master_faces, search_distance),
                [GaussRule::new(ps.max(pm) + 1), GaussRule::new(pbs.max(pbm) + 1)],
            ),
            FaceSide::End(_) => {
                let g = GaussRule::new(ps.max(pm) + 2);
                ([vec![-1.0, 1.0], vec![-1.0, 1.0]], [g.clone(), g])
            }
        };
        for sa in segments[0].windows(2) {
            for sb in segments[1].windows(2) {
                let (ha, hb) = (0.5 * (sa[1] - sa[0]), 0.5 * (sb[1] - sb[0]));
                for (ta, wa) in rules[0].points.iter().zip(&rules[0].weights) {
                    for (tb, wb) in rules[1].points.iter().zip(&rules[1].weights) {
                        let (a, b) = (0.5 * (sa[0] + sa[1]) + ha * ta, 0.5 * (sb[0] + sb[1]) + hb * tb);
                        let fp = face_point(body, face, a, b);
                        let [t0, t1] = fp.tangents;
                        let c = cross(t0, t1);
                        let weight = wa * wb * ha * hb * dot(c, c).sqrt();
                        let x = fp.position;
                        let candidates: Vec<usize> = boxes
                            .iter()
                            .enumerate()
                            .filter(|(_, (lo, hi))| {
                                (0..3).all(|k| x[k] >= lo[k] - search_distance && x[k] <= hi[k] + search_distance)
                            })
                            .map(|(i, _)| i)
                            .collect();
                        if candidates.is_empty() {
                            unpaired += 1;
                            continue;
                        }
                        points.push(SlavePoint {
                            nodes: fp.nodes,
                            shapes: fp.shapes,
                            position: x,
                            weight,
                            penalty: eps_a * weight,
                            candidates,
                        });
                    }
                }
            }
        }
    }
    let mut slave_nodes: Vec<usize> = points.iter().flat_map(|p| p.nodes.iter().copied()).collect();
    slave_nodes.sort_unstable();
    slave_nodes.dedup();
    let mut areas = vec![0.0; slave_nodes.len()];
    let mut penalties = vec![0.0; slave_nodes.len()];
    for p in &points {
        for (&a, &na) in p.nodes.iter().zip(&p.shapes) {
            let ia = slave_nodes.binary_search(&a).expect("slave node listed");
            areas[ia] += p.weight * na;
            penalties[ia] += p.penalty * na;
        }
    }
    SurfaceContact { master_body, master_faces, points, search_distance, unpaired, slave_nodes, areas, penalties }
}

impl SurfaceContact {
    /// Node pairs the matrix pattern must hold: the weighted gap of a slave
    /// node couples every node of its points' slave faces and candidate
    /// master faces with each other.
    pub(crate) fn couplings(&self, master: &Body) -> Vec<(usize, usize)> {
        let face_nodes: Vec<Vec<usize>> =
            self.master_faces.iter().map(|f| face_point(master, f, 0.0, 0.0).nodes).collect();
        let mut support: Vec<std::collections::BTreeSet<usize>> = vec![Default::default(); self.slave_nodes.len()];
        for p in &self.points {
            for &a in &p.nodes {
                let ia = self.slave_nodes.binary_search(&a).expect("slave node listed");
                support[ia].extend(p.nodes.iter().copied());
                for &c in &p.candidates {
                    support[ia].extend(face_nodes[c].iter().copied());
                }
            }
        }
        let mut set = std::collections::BTreeSet::new();
        for s in &support {
            let v: Vec<usize> = s.iter().copied().collect();
            for (i, &a) in v.iter().enumerate() {
                for &b in &v[i + 1..] {
                    set.insert((a, b));
                }
            }
        }
        set.into_iter().collect()
    }
}

#[cfg(test)]
#[path = "surface_tests.rs"]
mod tests;
