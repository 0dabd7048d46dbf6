//! Surface contact between deformable bodies in the current configuration
//! (`contacts[].method = "surface"` with `analysis.geometry = "nonlinear"`):
//! every slave integration point of [`super::surface`] is projected onto
//! the *deformed* master surface at every evaluation, its gap measured
//! along the deformed surface's normal, and the gap's second variation
//! enters the tangent (large sliding over the candidate faces, normals
//! that turn with the bodies).
//!
//! **Geometry.** A master face is `x(ξ) = Σ_B N_B(ξ) x_B`, `ξ = (a, b)`,
//! with the current nodal positions `x_B = X_B + u_B` and the face's shape
//! functions ([`FaceJet`]: values, first and second derivatives, tensor
//! products of 1D Lagrange polynomials — the section edge's in `a` and the
//! beam element's in `b` on a lateral face, the section element's on an
//! end face). Tangents `a_α = x_,α`, metric `m_αβ = a_α·a_β`, unit normal
//! `n ∥ a_1 × a_2` oriented outward as in the reference, curvature
//! `b_αβ = n·x_,αβ`.
//!
//! **Gap.** The slave point `x_s = Σ_A N_A x_A` (its shape values fixed on
//! the slave face) is projected to the closest point `ξ̄` of the master
//! surface, `(x_s − x(ξ̄))·a_α = 0` (Newton on `ξ`); the gap is
//! `g = (x_s − x(ξ̄))·n`, negative when penetrating.
//!
//! **Variations** (Wriggers, *Computational Contact Mechanics*, 2nd ed.,
//! 2006, §4.3 and §9.4; Laursen 2002, §5.2). With `c_I = N_A` for a slave
//! node and `−N_B(ξ̄)` for a master node, `d_Iα = 0` for a slave node and
//! `N_B,α(ξ̄)` for a master node,
//!
//! ```text
//! δg    = Σ_I c_I n·δu_I
//! D_α   = Σ_I c_I a_α·δu_I ,   N_α = Σ_I d_Iα n·δu_I
//! A     = m − g b ,   Δξ = A⁻¹ (D(Δu) + g N(Δu))
//! Δδg   = −[N A⁻¹ Dᵀ + D A⁻¹ Nᵀ + g N A⁻¹ Nᵀ + D m⁻¹ b A⁻¹ Dᵀ]
//! ```
//!
//! (the last from `Δn = −m^(αβ) (n·Δa_α) a_β`; the form is symmetric as a
//! Hessian must be: `m⁻¹ b A⁻¹` is). A contact force `p` (N) on the
//! weighted gap then contributes `p ∂δg` besides the penalty's `ε δg Δg`
//! (`crate::contact::assembly`, tests/current_contact.rs: the tangent
//! against finite differences on bodies turned by 60°).

use crate::bc::Face;
use crate::mesh::Body;
use crate::shape::Lagrange1d;
use crate::values::FaceSide;

use super::surface::{Projection, SlavePoint, SurfaceContact, face_point};
use super::{cross, dot};

/// Shape functions of a face at one point with their derivatives in the
/// face coordinates `(a, b)`.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceJet {
    /// Global nodes of the face (the order of `face_point`).
    pub nodes: Vec<usize>,
    /// `N_B`.
    pub n: Vec<f64>,
    /// `[N_B,a, N_B,b]`.
    pub d: Vec<[f64; 2]>,
    /// `[N_B,aa, N_B,ab, N_B,bb]`.
    pub(crate) dd: Vec<[f64; 3]>,
}

/// 1D Lagrange values, first and second derivatives of order `p` at `t`.
fn line(p: usize, t: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let l = Lagrange1d::new(p);
    let (mut n, mut d, mut dd) = (vec![0.0; p + 1], vec![0.0; p + 1], vec![0.0; p + 1]);
    l.eval(t, &mut n, &mut d);
    l.second_derivatives(t, &mut dd);
    (n, d, dd)
}

/// The shape functions of `face` of `body` at `(a, b)` with their first
/// and second derivatives.
pub fn face_jet(body: &Body, face: &Face, a: f64, b: f64) -> FaceJet {
    let section = &body.section;
    let (ps, pb) = (section.kind.order(), body.axis.kind.order());
    let el = section.element(face.section_element);
    let first = body.axis.first_node(face.beam_element);
    let mut jet = FaceJet { nodes: Vec::new(), n: Vec::new(), d: Vec::new(), dd: Vec::new() };
    let mut push = |node: usize, (f, fd, fdd): (f64, f64, f64), (g, gd, gdd): (f64, f64, f64)| {
        jet.nodes.push(node);
        jet.n.push(f * g);
        jet.d.push([fd * g, f * gd]);
        jet.dd.push([fdd * g, fd * gd, f * gdd]);
    };
    match face.side {
        FaceSide::Lateral(k) => {
            // the edge's nodes run along a (section::edge_local_nodes), the
            // beam element's along b = ζ
            let (fa, da, dda) = line(ps, a);
            let (gb, db, ddb) = line(pb, b);
            let local = section.edge_local_nodes(k);
            for i in 0..=pb {
                for (t, &lt) in local.iter().enumerate() {
                    push(body.node(first + i, el[lt]), (fa[t], da[t], dda[t]), (gb[i], db[i], ddb[i]));
                }
            }
        }
        FaceSide::End(end) => {
            // the section element's tensor basis, local node j·m + i ↔ (ξ_i, η_j)
            let (fa, da, dda) = line(ps, a);
            let (gb, db, ddb) = line(ps, b);
            let beam_node = first + if end { pb } else { 0 };
            for j in 0..=ps {
                for i in 0..=ps {
                    let lt = j * (ps + 1) + i;
                    push(body.node(beam_node, el[lt]), (fa[i], da[i], dda[i]), (gb[j], db[j], ddb[j]));
                }
            }
        }
    }
    jet
}

/// The deformed face at one point: position, tangents, second derivatives.
struct Deformed {
    x: [f64; 3],
    a: [[f64; 3]; 2],
    /// `[x_,aa, x_,ab, x_,bb]`.
    xx: [[f64; 3]; 3],
}

fn deformed(jet: &FaceJet, position: &impl Fn(usize) -> [f64; 3]) -> Deformed {
    let mut out = Deformed { x: [0.0; 3], a: [[0.0; 3]; 2], xx: [[0.0; 3]; 3] };
    for (i, &node) in jet.nodes.iter().enumerate() {
        let p = position(node);
        for k in 0..3 {
            out.x[k] += jet.n[i] * p[k];
            for (al, d) in jet.d[i].iter().enumerate() {
                out.a[al][k] += d * p[k];
            }
            for (s, dd) in jet.dd[i].iter().enumerate() {
                out.xx[s][k] += dd * p[k];
            }
        }
    }
    out
}

/// Inverse of a symmetric 2×2 matrix `[m00, m01, m11]`; `None` if singular.
fn inverse(m: [f64; 3]) -> Option<[[f64; 2]; 2]> {
    let det = m[0] * m[2] - m[1] * m[1];
    (det.abs() > 0.0 && det.is_finite()).then(|| [[m[2] / det, -m[1] / det], [-m[1] / det, m[0] / det]])
}

/// A slave point projected onto the deformed master surface, with what the
/// gap's second variation needs.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CurrentProjection {
    /// The projection in the form the weighted gap uses: the current normal,
    /// and `gap0` such that `gap0 + (Σ N_s u_s − Σ N_m u_m)·n` is the
    /// current gap (the gap linearized at the present state).
    pub projection: Projection,
    /// The current gap `g` (m).
    pub gap: f64,
    /// Master shape derivatives `N_B,α` at the projection.
    derivatives: Vec<[f64; 2]>,
    /// Current tangents `a_α`.
    tangents: [[f64; 3]; 2],
    /// `A⁻¹` and `m⁻¹ b A⁻¹`.
    a_inv: [[f64; 2]; 2],
    w: [[f64; 2]; 2],
}

/// Closest point of `face` (master body `body`) to `x`, all at displacements
/// `u`: Newton on `ξ` for `½|x − x(ξ)|²`; `None` if it converges outside
/// the face.
fn project_on_face(body: &Body, face: &Face, x: [f64; 3], u: &[f64]) -> Option<(FaceJet, Deformed, [f64; 2])> {
    let position = |node: usize| {
        let r = body.local_coords(node - body.node_offset);
        [r[0] + u[3 * node], r[1] + u[3 * node + 1], r[2] + u[3 * node + 2]]
    };
    let (mut a, mut b) = (0.0, 0.0);
    let mut converged = false;
    for _ in 0..50 {
        let jet = face_jet(body, face, a, b);
        let s = deformed(&jet, &position);
        let r: [f64; 3] = std::array::from_fn(|k| x[k] - s.x[k]);
        let [t0, t1] = s.a;
        // Hessian of ½|r|²: m − r·x_,αβ (Gauss–Newton's m far from the surface)
        let h = [dot(t0, t0) - dot(r, s.xx[0]), dot(t0, t1) - dot(r, s.xx[1]), dot(t1, t1) - dot(r, s.xx[2])];
        let h = if h[0] * h[2] - h[1] * h[1] > 0.0 && h[0] > 0.0 { h } else { [dot(t0, t0), dot(t0, t1), dot(t1, t1)] };
        let inv = inverse(h)?;
        let (r0, r1) = (dot(t0, r), dot(t1, r));
        let (da, db) = (inv[0][0] * r0 + inv[0][1] * r1, inv[1][0] * r0 + inv[1][1] * r1);
        a = (a + da).clamp(-2.0, 2.0);
        b = (b + db).clamp(-2.0, 2.0);
        if da.abs() + db.abs() < 1e-14 {
            converged = true;
            break;
        }
    }
    // not converged (the gap and its variations would not belong to one
    // closest point), or converged outside the face: not this face's point
    if !converged || a.abs() > 1.0 + 1e-9 || b.abs() > 1.0 + 1e-9 {
        return None;
    }
    let (a, b) = (a.clamp(-1.0, 1.0), b.clamp(-1.0, 1.0));
    let jet = face_jet(body, face, a, b);
    let s = deformed(&jet, &position);
    Some((jet, s, [a, b]))
}

/// Projects slave point `p` onto the nearest of its candidate master faces
/// in the configuration `u`; `None` if no candidate holds its closest point
/// (the point is then out of contact, as in the reference configuration).
pub(crate) fn project(contact: &SurfaceContact, body: &Body, p: &SlavePoint, u: &[f64]) -> Option<CurrentProjection> {
    let mut us = [0.0; 3];
    for (&node, &s) in p.nodes.iter().zip(&p.shapes) {
        for k in 0..3 {
            us[k] += s * u[3 * node + k];
        }
    }
    let x: [f64; 3] = std::array::from_fn(|k| p.position[k] + us[k]);
    let mut best: Option<(f64, CurrentProjection)> = None;
    for &f in &p.candidates {
        let Some((jet, s, param)) = project_on_face(body, &contact.master_faces[f], x, u) else { continue };
        let d: [f64; 3] = std::array::from_fn(|k| x[k] - s.x[k]);
        let dist = dot(d, d).sqrt();
        if best.as_ref().is_none_or(|(bd, _)| dist < *bd)
            && let Some(cp) = closest_point(body, &contact.master_faces[f], f, (x, us), (jet, s, param), u)
        {
            best = Some((dist, cp));
        }
    }
    best.map(|(_, cp)| cp)
}

/// The projection data at the closest point `(jet, s, param)` of master face
/// `face` (index `f`) to the slave point at `x` (displacement `us`); `None`
/// where the surface is degenerate (no normal, or `m − g b` singular).
fn closest_point(
    body: &Body,
    face: &Face,
    f: usize,
    (x, us): ([f64; 3], [f64; 3]),
    (jet, s, param): (FaceJet, Deformed, [f64; 2]),
    u: &[f64],
) -> Option<CurrentProjection> {
    // the outward normal: a_1 × a_2 oriented as the reference face's
    let reference = face_point(body, face, param[0], param[1]);
    let c = cross(s.a[0], s.a[1]);
    let sign =
        if dot(cross(reference.tangents[0], reference.tangents[1]), reference.normal) < 0.0 { -1.0 } else { 1.0 };
    let len = dot(c, c).sqrt();
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    let n = c.map(|v| sign * v / len);
    let gap = dot(std::array::from_fn(|k| x[k] - s.x[k]), n);
    let m = [dot(s.a[0], s.a[0]), dot(s.a[0], s.a[1]), dot(s.a[1], s.a[1])];
    let bc = [dot(n, s.xx[0]), dot(n, s.xx[1]), dot(n, s.xx[2])];
    let a_inv = inverse([m[0] - gap * bc[0], m[1] - gap * bc[1], m[2] - gap * bc[2]])?;
    let m_inv = inverse(m)?;
    let bm = [[bc[0], bc[1]], [bc[1], bc[2]]];
    let w: [[f64; 2]; 2] = std::array::from_fn(|i| {
        std::array::from_fn(|j| (0..2).map(|k| (0..2).map(|l| m_inv[i][k] * bm[k][l] * a_inv[l][j]).sum::<f64>()).sum())
    });
    let mut um = [0.0; 3];
    for (&node, &s) in jet.nodes.iter().zip(&jet.n) {
        for k in 0..3 {
            um[k] += s * u[3 * node + k];
        }
    }
    let projection = Projection {
        face: f,
        param,
        normal: n,
        gap0: gap - dot(std::array::from_fn(|k| us[k] - um[k]), n),
        nodes: jet.nodes,
        shapes: jet.n,
    };
    Some(CurrentProjection { projection, gap, derivatives: jet.d, tangents: s.a, a_inv, w })
}

impl CurrentProjection {
    /// The gap's second variation `∂²g/∂u_I∂u_J` times `scale`, as 3×3
    /// blocks over the slave point's nodes then the master face's, passed to
    /// `add(I, J, block)` once per unordered pair (`I` before `J` in that
    /// order, and `I = J`).
    pub(crate) fn add_second_variation(
        &self,
        slave: &SlavePoint,
        scale: f64,
        mut add: impl FnMut(usize, usize, &[[f64; 3]; 3]),
    ) {
        let p = &self.projection;
        let n = p.normal;
        let [a0, a1] = self.tangents;
        let t = [a0, a1];
        // (node, c_I, d_I)
        let nodes: Vec<(usize, f64, [f64; 2])> = slave
            .nodes
            .iter()
            .zip(&slave.shapes)
            .map(|(&a, &s)| (a, s, [0.0; 2]))
            .chain(p.nodes.iter().zip(&p.shapes).zip(&self.derivatives).map(|((&b, &s), &d)| (b, -s, d)))
            .collect();
        let (ai, w, g) = (self.a_inv, self.w, self.gap);
        for (x, &(i, ci, di)) in nodes.iter().enumerate() {
            for &(j, cj, dj) in &nodes[x..] {
                let mut block = [[0.0; 3]; 3];
                for al in 0..2 {
                    for be in 0..2 {
                        // N A⁻¹ Dᵀ + D A⁻¹ Nᵀ + g N A⁻¹ Nᵀ + D m⁻¹ b A⁻¹ Dᵀ
                        let (nd, dn) = (ai[al][be] * di[al] * cj, ai[al][be] * ci * dj[be]);
                        let (nn, dd) = (g * ai[al][be] * di[al] * dj[be], w[al][be] * ci * cj);
                        for r in 0..3 {
                            for c in 0..3 {
                                block[r][c] -= scale
                                    * (nd * n[r] * t[be][c]
                                        + dn * t[al][r] * n[c]
                                        + nn * n[r] * n[c]
                                        + dd * t[al][r] * t[be][c]);
                            }
                        }
                    }
                }
                add(i, j, &block);
            }
        }
    }
}
