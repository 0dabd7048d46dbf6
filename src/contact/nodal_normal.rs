//! Node-to-node contact between deformable bodies in the current
//! configuration (`contacts[]` of the default method with
//! `analysis.geometry = "nonlinear"`): the pair keeps its two nodes (small
//! sliding, as the paper's pairs), but its normal turns with the master
//! surface and its gap is measured between the current positions.
//!
//! **Normal.** In the reference configuration the master node's normal is
//! `Σ_f W_f n_f` normalized (`SurfaceNodes::from_faces`: `W_f = ∫_f N_m dA`
//! over the contact faces `f` around the node, `n_f` the face's mean
//! normal `∫_f A_1 × A_2 dξ / |…|`). Its current counterpart
//!
//! ```text
//! ñ(u) = Σ_f W_f s_f ∫_f a_1 × a_2 dξ / |∫_f A_1 × A_2 dξ| = Σ_(B,C) Q_BC x_B × x_C ,   n = ñ/|ñ|
//! ```
//!
//! (`a_α = Σ_B N_B,α x_B` at the current nodal positions, `s_f = ±1` the
//! outward orientation) equals it at `u = 0` and is bilinear in the
//! positions of the faces' nodes, `Q` antisymmetric and constant
//! (`Q_BC = ½ Σ_f W_f s_f (M_BC − M_CB)/|…|`, `M_BC = ∫ N_B,1 N_C,2 dξ`).
//!
//! **Gap and variations.** `g = d·n` with `d = x_s − x_m`. With
//! `y_B = Σ_C Q_BC x_C`, `δñ = Σ_B J_B δx_B`, `J_B = −2 [y_B]×`,
//! `L = |ñ|`, `P = I − n nᵀ`, `e = P d / L`:
//!
//! ```text
//! δg   = n·(δx_s − δx_m) + Σ_B (2 y_B × e)·δx_B
//! Δδg  = Dᵀ (P/L) J + Jᵀ (P/L) D + E + Jᵀ S J
//! E_BC = −2 Q_BC [e]× ,   S = −(n dᵀ + d nᵀ + (d·n)(I − 3 n nᵀ)) / L²
//! ```
//!
//! (`D`: `+I` at the slave node, `−I` at the master node; `S` the second
//! derivative of `d·ñ/|ñ|` in `ñ`). The pair's force `p = λ − ε g ≥ 0` on
//! `δg` and the tangent `ε ∇g ∇gᵀ − p Δδg` are then exact
//! (tests/current_contact.rs).

use crate::bc::integrate_face;
use crate::mesh::Mesh;
use crate::quadrature::GaussRule;

use super::current::face_jet;
use super::{ContactSurface, cross, dot};

/// The current normal of one master node: the nodes of its contact faces
/// and the antisymmetric `Q` of `ñ = Σ Q_BC x_B × x_C`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NodalNormal {
    /// The nodes of the contact faces around the master node.
    pub nodes: Vec<usize>,
    /// `Q`, row-major `nodes × nodes`.
    q: Vec<f64>,
}

/// `[v]×`, the matrix of `w ↦ v × w`.
fn skew(v: [f64; 3]) -> [[f64; 3]; 3] {
    [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]]
}

fn mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn transpose(a: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// One contact face's share of the nodal normals: its nodes, `∫ N_B dA`,
/// and `s_f M / |∫ A_1 × A_2 dξ|`.
struct FaceTerms {
    nodes: Vec<usize>,
    weights: Vec<f64>,
    m: Vec<f64>,
}

fn face_terms(mesh: &Mesh, body: usize, face: &crate::bc::Face) -> FaceTerms {
    let body_ref = &mesh.bodies[body];
    let integral = integrate_face(body_ref, face);
    // M_BC = ∫ N_B,a N_C,b over the face, exact for the products
    let p = body_ref.section.kind.order().max(body_ref.axis.kind.order());
    let rule = GaussRule::new(p + 1);
    let mut m: Vec<f64> = Vec::new();
    let mut nodes: Vec<usize> = Vec::new();
    for (ta, wa) in rule.points.iter().zip(&rule.weights) {
        for (tb, wb) in rule.points.iter().zip(&rule.weights) {
            let jet = face_jet(body_ref, face, *ta, *tb);
            let n = jet.nodes.len();
            if m.is_empty() {
                m = vec![0.0; n * n];
                nodes = jet.nodes.clone();
            }
            for b in 0..n {
                for c in 0..n {
                    m[b * n + c] += wa * wb * jet.d[b][0] * jet.d[c][1];
                }
            }
        }
    }
    let n = nodes.len();
    // ∫ A_1 × A_2 at the reference positions, for s_f and the scale
    let x: Vec<[f64; 3]> = nodes.iter().map(|&a| mesh.coords(a)).collect();
    let mut c0 = [0.0; 3];
    for b in 0..n {
        for c in 0..n {
            let v = cross(x[b], x[c]);
            for k in 0..3 {
                c0[k] += m[b * n + c] * v[k];
            }
        }
    }
    let sign = if dot(c0, integral.normal) < 0.0 { -1.0 } else { 1.0 };
    let scale = sign / dot(c0, c0).sqrt();
    let weights =
        nodes.iter().map(|a| integral.nodes.iter().position(|b| b == a).map_or(0.0, |k| integral.weights[k])).collect();
    FaceTerms { nodes, weights, m: m.into_iter().map(|v| v * scale).collect() }
}

impl NodalNormal {
    /// The normals of the master nodes `masters`, from the faces of
    /// `surface` that hold each.
    pub(crate) fn for_nodes(mesh: &Mesh, surface: &ContactSurface, masters: &[usize]) -> Vec<Self> {
        let faces: Vec<FaceTerms> = surface.faces.iter().map(|f| face_terms(mesh, surface.body, f)).collect();
        let mut around: std::collections::HashMap<usize, Vec<usize>> = Default::default();
        for (f, t) in faces.iter().enumerate() {
            for (&a, &w) in t.nodes.iter().zip(&t.weights) {
                if w != 0.0 {
                    around.entry(a).or_default().push(f);
                }
            }
        }
        masters
            .iter()
            .map(|master| {
                let list = around.get(master).map_or(&[][..], |v| v.as_slice());
                let mut nodes: Vec<usize> = list.iter().flat_map(|&f| faces[f].nodes.iter().copied()).collect();
                nodes.sort_unstable();
                nodes.dedup();
                let n = nodes.len();
                let mut q = vec![0.0; n * n];
                for &f in list {
                    let t = &faces[f];
                    let w = t.weights[t.nodes.iter().position(|a| a == master).expect("the face holds the node")];
                    let k = t.nodes.len();
                    let idx: Vec<usize> =
                        t.nodes.iter().map(|a| nodes.binary_search(a).expect("the face's nodes are listed")).collect();
                    for b in 0..k {
                        for c in 0..k {
                            q[idx[b] * n + idx[c]] += 0.5 * w * (t.m[b * k + c] - t.m[c * k + b]);
                        }
                    }
                }
                Self { nodes, q }
            })
            .collect()
    }
}

/// A node of the gap's variation: its index, `D_I` (`+1` slave, `−1`
/// master, `0`), `J_I` (none for the slave) and its index in `Q`.
type Entry = (usize, f64, Option<[[f64; 3]; 3]>, Option<usize>);

/// A node pair evaluated in the current configuration.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CurrentPair {
    /// `g = (x_s − x_m)·n` (m).
    pub gap: f64,
    /// The current master normal `n`.
    pub normal: [f64; 3],
    /// `∂g/∂u_I` for the slave node, then the master normal's nodes.
    pub gradient: Vec<(usize, [f64; 3])>,
    /// What the second variation needs.
    d: [f64; 3],
    e: [f64; 3],
    length: f64,
    y: Vec<[f64; 3]>,
}

impl NodalNormal {
    /// The pair `slave`–`master` at displacements `u` (`gap_offset` is
    /// added to the gap: an interference fit's overlap not yet imposed).
    pub fn pair(&self, mesh: &Mesh, slave: usize, master: usize, u: &[f64], gap_offset: f64) -> CurrentPair {
        let x = |a: usize| {
            let r = mesh.coords(a);
            [r[0] + u[3 * a], r[1] + u[3 * a + 1], r[2] + u[3 * a + 2]]
        };
        let n = self.nodes.len();
        let xs: Vec<[f64; 3]> = self.nodes.iter().map(|&a| x(a)).collect();
        let y: Vec<[f64; 3]> = (0..n)
            .map(|b| {
                let mut v = [0.0; 3];
                for (c, xc) in xs.iter().enumerate() {
                    for k in 0..3 {
                        v[k] += self.q[b * n + c] * xc[k];
                    }
                }
                v
            })
            .collect();
        // ñ = Σ_B x_B × y_B
        let mut nt = [0.0; 3];
        for (xb, yb) in xs.iter().zip(&y) {
            let v = cross(*xb, *yb);
            for k in 0..3 {
                nt[k] += v[k];
            }
        }
        let length = dot(nt, nt).sqrt();
        let normal = nt.map(|v| v / length);
        let (ps, pm) = (x(slave), x(master));
        let d: [f64; 3] = std::array::from_fn(|k| ps[k] - pm[k]);
        let dn = dot(d, normal);
        let e: [f64; 3] = std::array::from_fn(|k| (d[k] - dn * normal[k]) / length);
        let mut gradient = vec![(slave, normal)];
        for (&b, yb) in self.nodes.iter().zip(&y) {
            let mut g = cross(*yb, e).map(|v| 2.0 * v);
            if b == master {
                for k in 0..3 {
                    g[k] -= normal[k];
                }
            }
            gradient.push((b, g));
        }
        CurrentPair { gap: dn + gap_offset, normal, gradient, d, e, length, y }
    }

    /// `scale · Δδg` of `pair` as 3×3 blocks over the nodes of
    /// `pair.gradient`, passed to `add(I, J, block)` once per unordered
    /// pair (and `I = J`).
    pub(crate) fn add_second_variation(
        &self,
        pair: &CurrentPair,
        scale: f64,
        master: usize,
        mut add: impl FnMut(usize, usize, &[[f64; 3]; 3]),
    ) {
        let (n, d, e, l) = (pair.normal, pair.d, pair.e, pair.length);
        let dn = dot(d, n);
        let p: [[f64; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|j| (f64::from(u8::from(i == j)) - n[i] * n[j]) / l));
        let s: [[f64; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let id = f64::from(u8::from(i == j));
                -(n[i] * d[j] + d[i] * n[j] + dn * (id - 3.0 * n[i] * n[j])) / (l * l)
            })
        });
        let ex = skew(e);
        // per listed node: D_I (±1 or 0) and J_I (None for the slave)
        let entries: Vec<Entry> = pair
            .gradient
            .iter()
            .enumerate()
            .map(|(k, &(node, _))| {
                if k == 0 {
                    (node, 1.0, None, None)
                } else {
                    let j = skew(pair.y[k - 1]).map(|r| r.map(|v| -2.0 * v));
                    (node, if node == master { -1.0 } else { 0.0 }, Some(j), Some(k - 1))
                }
            })
            .collect();
        let nq = self.nodes.len();
        for (x, &(ni, di, ji, qi)) in entries.iter().enumerate() {
            for &(nj, dj, jj, qj) in &entries[x..] {
                let mut block = [[0.0; 3]; 3];
                let mut add_scaled = |m: [[f64; 3]; 3], f: f64| {
                    for r in 0..3 {
                        for c in 0..3 {
                            block[r][c] += scale * f * m[r][c];
                        }
                    }
                };
                if let Some(jj) = &jj
                    && di != 0.0
                {
                    add_scaled(mul(&p, jj), di);
                }
                if let Some(ji) = &ji
                    && dj != 0.0
                {
                    add_scaled(transpose(&mul(&p, ji)), dj);
                }
                if let (Some(ji), Some(jj), Some(qi), Some(qj)) = (&ji, &jj, qi, qj) {
                    add_scaled(ex, -2.0 * self.q[qi * nq + qj]);
                    add_scaled(mul(&transpose(ji), &mul(&s, jj)), 1.0);
                }
                add(ni, nj, &block);
            }
        }
    }
}
