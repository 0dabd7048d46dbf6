//! The CUF element kernel: element displacement → internal force and tangent.
//!
//! For a body element made of section element `e_s` (functions `F_τ`) and
//! beam element `e_b` (functions `N_i`), the 3D shape functions are the
//! products `N_a = F_τ N_i` (paper eq. 6). With the strain–displacement
//! operator `D` of eq. (4), the strain is `ε = Σ_a B_a u_a` where, for node
//! `a` with gradient `(g_x, g_y, g_z) = (F_τ,x N_i, F_τ N_i,y, F_τ,z N_i)`,
//!
//! ```text
//!        | g_x  0    0   |      rows in Voigt order
//!        | 0    g_y  0   |      xx, yy, zz, xy, xz, yz
//!  B_a = | 0    0    g_z |      (engineering shear)
//!        | g_y  g_x  0   |
//!        | g_z  0    g_x |
//!        | 0    g_z  g_y |
//! ```
//!
//! The internal force of node `a` is `f_a = ∫ B_aᵀ σ dV` (eq. 8) and the
//! tangent block between nodes `a = (τ, i)` and `b = (s, j)` is the
//! **fundamental nucleus** of eq. (11),
//! `k_{ijτs} = ∫_l ∫_A B_aᵀ C^cep B_b dA dy`, a 3×3 matrix whose form does not
//! depend on the expansion. `C^cep` is the full 6×6 consistent tangent of the
//! material point (no orthotropic shortcut), so an elastoplastic tangent
//! enters unchanged. Integration is by Gauss rules with `p + 1` points per
//! direction.
//!
//! The kernel writes into a reusable [`Workspace`] and never allocates; the
//! assembly only scatters what it computes.

mod geometry;

pub use geometry::{AxisGeometry, BodyGeometry, SectionGeometry, SectionPoint, section_point};

use crate::materials::{Material, PointState};
use crate::voigt::{self, Matrix6, Voigt};

/// Errors of the element layer.
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

/// Reusable buffers of the element kernel (one per thread).
#[derive(Debug, Clone, Default)]
pub struct Workspace {
    grads: Vec<[f64; 3]>,
    cb: Vec<[f64; 18]>,
    tangents: Vec<Matrix6>,
    /// Element internal force, 3 entries per node (node-major).
    pub force: Vec<f64>,
    /// Element tangent, row-major `n × n` with `n = 3 · nodes`; the blocks of
    /// node pairs `a ≤ b` are written (so every entry `(p, q)` with `p ≤ q`
    /// is valid; the lower half of the diagonal blocks is written too).
    pub tangent: Vec<f64>,
}

impl Workspace {
    /// Sizes the buffers for elements with `nodes` nodes and `points` Gauss points.
    pub fn resize(&mut self, nodes: usize, points: usize) {
        self.grads.resize(nodes, [0.0; 3]);
        self.cb.resize(nodes, [0.0; 18]);
        self.tangents.resize(points, [[0.0; 6]; 6]);
        self.force.resize(3 * nodes, 0.0);
        self.tangent.resize(9 * nodes * nodes, 0.0);
    }
}

/// Which tangent the kernel must compute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TangentMode {
    /// Internal force only.
    None,
    /// Always compute the tangent.
    Always,
    /// Compute it unless every Gauss point returned the elastic tangent (the
    /// caller then uses its cached elastic element matrix).
    UnlessElastic,
}

/// What the kernel hands back besides the buffers.
#[derive(Debug, Clone, Copy, Default)]
pub struct ElementStats {
    /// Gauss points whose update was plastic.
    pub plastic_points: usize,
    /// True if `Workspace::tangent` was computed.
    pub tangent_computed: bool,
}

/// Gauss-point data of one element that the kernel reads and writes.
pub struct PointData<'a> {
    /// Committed states (read).
    pub committed: &'a [PointState],
    /// Trial states (written).
    pub trial: &'a mut [PointState],
    /// Stresses (written).
    pub stress: &'a mut [Voigt],
}

/// Gradients `∇(F_τ N_i)` of the 3D shape functions at Gauss point
/// `(gb, gs)` of element `(es, eb)`, local node `a = i · n_sec + τ`.
fn gradients(geom: &BodyGeometry, es: usize, eb: usize, gb: usize, gs: usize, grads: &mut [[f64; 3]]) -> f64 {
    let (sg, ag) = (&geom.section, &geom.axis);
    let (ns, nb) = (sg.n_fun, ag.n_fun);
    let ab = (eb * ag.n_gp + gb) * nb;
    let (n, ny) = (&ag.n[ab..ab + nb], &ag.ny[ab..ab + nb]);
    let sb = (es * sg.n_gp + gs) * ns;
    let (f, fx, fz) = (&sg.f[sb..sb + ns], &sg.fx[sb..sb + ns], &sg.fz[sb..sb + ns]);
    for i in 0..nb {
        for t in 0..ns {
            grads[i * ns + t] = [fx[t] * n[i], f[t] * ny[i], fz[t] * n[i]];
        }
    }
    ag.weight[eb * ag.n_gp + gb] * sg.weight[es * sg.n_gp + gs]
}

/// Computes the internal force (and the tangent, per `mode`) of body
/// element `e` from its nodal displacements `u` (3 per node, node-major in
/// the order of [`crate::mesh::Body::element_nodes`]).
///
/// Two passes over the Gauss points: the first evaluates strains, the
/// material update and the internal force; the second — only when a
/// tangent is needed — accumulates the fundamental nuclei with the tangents
/// kept from the first.
#[allow(clippy::too_many_arguments)] // the kernel's inputs are the terms of eq. (11); bundling them adds nothing
pub fn element_response(
    geom: &BodyGeometry,
    e: usize,
    n_section_elements: usize,
    u: &[f64],
    material: &Material,
    points: PointData<'_>,
    mode: TangentMode,
    ws: &mut Workspace,
) -> ElementStats {
    let (es, eb) = (e % n_section_elements, e / n_section_elements);
    let (sg, ag) = (&geom.section, &geom.axis);
    let nodes = sg.n_fun * ag.n_fun;
    let n_points = sg.n_gp * ag.n_gp;
    ws.resize(nodes, n_points);
    ws.force.fill(0.0);
    let ndof = 3 * nodes;
    let mut stats = ElementStats::default();
    let mut all_elastic = true;

    for gb in 0..ag.n_gp {
        for gs in 0..sg.n_gp {
            let w = gradients(geom, es, eb, gb, gs, &mut ws.grads[..nodes]);
            let mut eps = [0.0; 6];
            for (a, g) in ws.grads[..nodes].iter().enumerate() {
                voigt::add_nodal_strain(&mut eps, *g, [u[3 * a], u[3 * a + 1], u[3 * a + 2]]);
            }
            let q = gb * sg.n_gp + gs;
            let r = material.update(&eps, &points.committed[q]);
            points.trial[q] = r.state;
            points.stress[q] = r.stress;
            ws.tangents[q] = r.tangent;
            all_elastic &= r.elastic_tangent;
            stats.plastic_points += usize::from(r.plastic);

            // f_a += w B_aᵀ σ
            let s = r.stress;
            for (a, g) in ws.grads[..nodes].iter().enumerate() {
                ws.force[3 * a] += w * (g[0] * s[0] + g[1] * s[3] + g[2] * s[4]);
                ws.force[3 * a + 1] += w * (g[1] * s[1] + g[0] * s[3] + g[2] * s[5]);
                ws.force[3 * a + 2] += w * (g[2] * s[2] + g[0] * s[4] + g[1] * s[5]);
            }
        }
    }

    stats.tangent_computed = match mode {
        TangentMode::None => false,
        TangentMode::Always => true,
        TangentMode::UnlessElastic => !all_elastic,
    };
    if !stats.tangent_computed {
        return stats;
    }
    ws.tangent.fill(0.0);
    for gb in 0..ag.n_gp {
        for gs in 0..sg.n_gp {
            let w = gradients(geom, es, eb, gb, gs, &mut ws.grads[..nodes]);
            // CB_b = w C B_b (6×3, stored column-major: [col x | col y | col z])
            let c = &ws.tangents[gb * sg.n_gp + gs];
            for (b, g) in ws.grads[..nodes].iter().enumerate() {
                let cb = &mut ws.cb[b];
                for row in 0..6 {
                    let cr = &c[row];
                    cb[row] = w * (cr[0] * g[0] + cr[3] * g[1] + cr[4] * g[2]);
                    cb[6 + row] = w * (cr[1] * g[1] + cr[3] * g[0] + cr[5] * g[2]);
                    cb[12 + row] = w * (cr[2] * g[2] + cr[4] * g[0] + cr[5] * g[1]);
                }
            }
            // Fundamental nucleus K_ab += B_aᵀ (C B_b) for a ≤ b (upper blocks).
            for b in 0..nodes {
                let cb = &ws.cb[b];
                for a in 0..=b {
                    let [gx, gy, gz] = ws.grads[a];
                    let base = 3 * a * ndof + 3 * b;
                    for col in 0..3 {
                        let v = &cb[6 * col..6 * col + 6];
                        ws.tangent[base + col] += gx * v[0] + gy * v[3] + gz * v[4];
                        ws.tangent[base + ndof + col] += gy * v[1] + gx * v[3] + gz * v[5];
                        ws.tangent[base + 2 * ndof + col] += gz * v[2] + gx * v[4] + gy * v[5];
                    }
                }
            }
        }
    }
    stats
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{BeamAxis, Body, CrossSection, Division};
    use crate::shape::{BeamElementKind, SectionElementKind};

    fn single_element_body(sk: SectionElementKind, bk: BeamElementKind) -> Body {
        // a distorted quad section (straight edges) and a single beam element
        let corners = [[0.0, 0.0], [0.012, 0.001], [0.010, 0.011], [-0.001, 0.009]];
        let section = CrossSection::from_quads(sk, &corners, &[[0, 1, 2, 3]], "s").unwrap();
        let lines = Division::uniform(0.1, 0.13, 1).lines("y").unwrap();
        Body {
            name: "b".into(),
            section,
            axis: BeamAxis::from_lines(bk, &lines),
            material: 0,
            node_offset: 0,
            element_offset: 0,
        }
    }

    fn response(body: &Body, mat: &Material, u: &[f64], committed: &[PointState]) -> (Vec<f64>, Vec<f64>) {
        let geom = BodyGeometry::new(body).unwrap();
        let ngp = geom.gp_per_element();
        let mut trial = vec![PointState::default(); ngp];
        let mut stress = vec![[0.0; 6]; ngp];
        let mut ws = Workspace::default();
        element_response(
            &geom,
            0,
            1,
            u,
            mat,
            PointData { committed, trial: &mut trial, stress: &mut stress },
            TangentMode::Always,
            &mut ws,
        );
        (ws.force.clone(), ws.tangent.clone())
    }

    #[test]
    fn volume_and_rigid_body_modes() {
        let mat = Material::new("m", 70e9, 0.3, None);
        for sk in [SectionElementKind::L4, SectionElementKind::L9, SectionElementKind::L16] {
            for bk in [BeamElementKind::B2, BeamElementKind::B3, BeamElementKind::B4] {
                let body = single_element_body(sk, bk);
                let geom = BodyGeometry::new(&body).unwrap();
                // shoelace area of the quad × length
                let area = 0.5
                    * ((0.0 * 0.001 - 0.012 * 0.0)
                        + (0.012 * 0.011 - 0.010 * 0.001)
                        + (0.010 * 0.009 - (-0.001) * 0.011)
                        + (-0.001 * 0.0 - 0.0 * 0.009));
                let vol: f64 = (0..geom.section.n_gp)
                    .flat_map(|s| (0..geom.axis.n_gp).map(move |a| (s, a)))
                    .map(|(s, a)| geom.section.weight[s] * geom.axis.weight[a])
                    .sum();
                assert!((vol - area * 0.03).abs() < 1e-15, "{sk:?}{bk:?}");
                // rigid rotation about y gives zero force
                let nodes = body.nodes_per_element();
                let mut el = Vec::new();
                body.element_nodes(0, &mut el);
                let mut u = vec![0.0; 3 * nodes];
                for (a, &g) in el.iter().enumerate() {
                    let [x, y, z] = body.local_coords(g);
                    // small rotation θ about an arbitrary axis: u = θ × x
                    let th = [1e-4, -2e-4, 3e-4];
                    u[3 * a] = th[1] * z - th[2] * y;
                    u[3 * a + 1] = th[2] * x - th[0] * z;
                    u[3 * a + 2] = th[0] * y - th[1] * x;
                }
                let ngp = geom.gp_per_element();
                let (f, _) = response(&body, &mat, &u, &vec![PointState::default(); ngp]);
                let fmax = f.iter().fold(0.0f64, |a, b| a.max(b.abs()));
                assert!(fmax < 1e-6, "{sk:?}{bk:?}: {fmax}");
            }
        }
    }

    #[test]
    fn tangent_matches_finite_difference_of_force_elastoplastic() {
        use crate::materials::Hardening;
        let body = single_element_body(SectionElementKind::L9, BeamElementKind::B3);
        let mat = Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 }));
        let nodes = body.nodes_per_element();
        let mut el = Vec::new();
        body.element_nodes(0, &mut el);
        // a displacement that yields part of the element
        let mut u = vec![0.0; 3 * nodes];
        for (a, &g) in el.iter().enumerate() {
            let [x, y, z] = body.local_coords(g);
            u[3 * a] = 3e-3 * y * z / 0.01 + 1e-5 * (x * 100.0).sin();
            u[3 * a + 1] = -2e-3 * (z - 0.005) + 1e-3 * x * y;
            u[3 * a + 2] = 1e-5 * (y * 50.0).cos() + 2e-3 * x;
        }
        let geom = BodyGeometry::new(&body).unwrap();
        let ngp = geom.gp_per_element();
        let committed = vec![PointState::default(); ngp];
        let (_, k) = response(&body, &mat, &u, &committed);
        let n = 3 * nodes;
        let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let h = 1e-9;
        let mut worst: f64 = 0.0;
        for q in 0..n {
            let (mut up, mut um) = (u.clone(), u.clone());
            up[q] += h;
            um[q] -= h;
            let (fp, _) = response(&body, &mat, &up, &committed);
            let (fm, _) = response(&body, &mat, &um, &committed);
            for p in 0..n {
                let fd = (fp[p] - fm[p]) / (2.0 * h);
                let kk = if p <= q { k[p * n + q] } else { k[q * n + p] };
                worst = worst.max((fd - kk).abs() / kmax);
            }
        }
        assert!(worst < 1e-6, "relative tangent error {worst}");
    }
}
