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
//! **Computed as one product.** Summed over the Gauss points `j` the nuclei
//! of all node pairs are `K = Σ_j B̄_jᵀ (w_j C_j B̄_j) = Bᵀ (C B)` with
//! `B = [B̄_1; …; B̄_Q]` stacked (6Q × element DOFs): the kernel fills `B`,
//! forms `w C B̄_j` point by point as small products (element DOFs × 6
//! times 6 × 6), and hands `Bᵀ (C B)` to a blocked dense GEMM (faer, upper
//! triangle only). That ignores the zeros of `B̄_a` (half its entries) but
//! runs at the machine's vector speed, where the node-pair loop it replaced
//! ran at the speed of loads and stores of the element matrix: the elastic
//! matrices of tube 28 L9 took 94 → 52 ms (`cufem bench`, back to back).
//! With nonlinear geometry the operator depends on `F` and the tangent
//! gains the geometric term: there the kernel forms the 3 × 3 nuclei per
//! point and component pair instead and contracts them with the gradients
//! by sum factorization over the axis points (`nucleus`), without `B`.
//!
//! **The stress of the geometric stiffness** after a linear step: [`linearized`].
//!
//! Shape functions, gradients and weights come from [`crate::values`], the
//! same code that post-processing and face integrals use. The kernel writes
//! into a reusable [`Workspace`] and never allocates; the assembly only
//! scatters what it computes.

mod assumed_large;
mod bbar;
mod damaged;
mod fbar;
mod linearized;
mod nucleus;
mod product;
mod softening;
pub use damaged::DamagePoints;
pub(crate) use nucleus::geometric_matrix;

use crate::kinematics::{Kinematics, LogStrain, Tensor};
use crate::materials::{Material, PointState, Predictor};
use crate::values::CellValues;
pub use crate::values::ElementError;
use crate::voigt::{Matrix6, Voigt};
use bbar::volumetric_projection;

/// Reusable buffers of the element kernel (one per thread).
#[derive(Debug, Clone, Default)]
pub struct Workspace {
    grads: Vec<[f64; 3]>,
    /// Sum factorization: `v_τ, v'_τ, h_τ, h'_τ` at one axis point (3 each).
    contracted: Vec<[f64; 3]>,
    /// The small-strain tangent as one product: B̄ per Gauss point (`bt`,
    /// element DOF × 6 · points, row-major) and w C B̄ (`cbt`, same layout).
    bt: Vec<f64>,
    cbt: Vec<f64>,
    tangents: Vec<Matrix6>,
    /// B-bar: `(b̄_a − g_a)` per Gauss point and node (the correction of
    /// the volumetric row; at finite strain `d_a = Π g̃_a − g̃_a`), and the
    /// projection's small matrices (at finite strain `G_l = ∫ ψ_l g̃`).
    bbar: Vec<[f64; 3]>,
    proj_g: Vec<f64>,
    /// B-bar at finite strain (`fbar`): per point and node `g̃_a = F⁻ᵀ ∇N_a`;
    /// `w ψ_l` per point in the projection, then `p̄ − p` per point in the
    /// tangent (`proj_w`); per point `θ̄ − θ`, the weight, the projection's
    /// coefficients `c_l` (4 each), `p = tr T / 3`, and the coupling
    /// `(Lᵀ D m, mᵀ D m / 9)`.
    spatial: Vec<[f64; 3]>,
    proj_w: Vec<f64>,
    dilatation: Vec<f64>,
    weights: Vec<f64>,
    proj_c: Vec<f64>,
    /// ... and in the tangent the projections `Z_l` (rows `(l, c)` ×
    /// nodes) and the update's factors `[U | G]`, `[G | U]`
    /// (`fbar::add_projected`).
    proj_z: Vec<f64>,
    proj_u: Vec<f64>,
    pressure: Vec<f64>,
    coupling: Vec<(Voigt, f64)>,
    /// Total Lagrangian: the deformation gradient `F` and the second
    /// Piola–Kirchhoff stress `S` per Gauss point (for the nuclei).
    frames: Vec<Tensor>,
    pk2: Vec<Voigt>,
    /// The total-Lagrangian tangent by sum factorization (`nucleus`), per
    /// axis point: the section values as rows, the rows of `M ĝ`, the
    /// section sums `S`, their expansion along `j` (`T`) and with B-bar the
    /// section parts `ẑ_l` of the projections; per element the pair blocks.
    gradients: Vec<f64>,
    nucleus_rows: Vec<f64>,
    nuclei: Vec<f64>,
    section_sums: Vec<f64>,
    section_t: Vec<f64>,
    section_z: Vec<f64>,
    /// The assumed shear at finite strain (`assumed_large`): `(g_ξ, g_η)`
    /// at the tying points of one axis point (of `u`, and of the last
    /// step), `D_τ` per point and section function, the stacked `Z`
    /// and `A` (points × element DOF), `Z Aᵀ`, and the geometric sums.
    tying: Vec<crate::values::Covariant>,
    tying_step: Vec<crate::values::Covariant>,
    assumed: Vec<[f64; 3]>,
    assumed_z: Vec<f64>,
    assumed_a: Vec<f64>,
    assumed_k: Vec<f64>,
    assumed_g: Vec<f64>,
    /// A damaging element's loading points' rank-one tangent terms, and
    /// after the tangent their vectors `Bᵀs`, `Bᵀg` (`softening`, whose
    /// sums use `skew_h`): the unsymmetric rest the assembly scatters.
    pub(crate) softening: Vec<softening::Term>,
    pub(crate) skew: Vec<f64>,
    skew_h: Vec<[f64; 3]>,
    /// Element internal force, 3 entries per node (node-major).
    pub force: Vec<f64>,
    /// Element tangent, row-major `n × n` with `n = 3 · nodes`; the upper
    /// triangle (entries `(p, q)` with `p ≤ q`) is written.
    pub tangent: Vec<f64>,
}

impl Workspace {
    /// Sizes the buffers for elements with `nodes` nodes and `points` Gauss points.
    pub(crate) fn resize(&mut self, nodes: usize, points: usize) {
        self.grads.resize(nodes, [0.0; 3]);
        self.tangents.resize(points, [[0.0; 6]; 6]);
        self.frames.resize(points, [[0.0; 3]; 3]);
        self.pk2.resize(points, [0.0; 6]);
        self.pressure.resize(points, 0.0);
        self.coupling.resize(points, ([0.0; 6], 0.0));
        self.bbar.resize(points * nodes, [0.0; 3]);
        self.proj_g.resize(4 * 3 * nodes, 0.0);
        self.force.resize(3 * nodes, 0.0);
        self.tangent.resize(9 * nodes * nodes, 0.0);
    }
}

/// Which tangent the kernel must compute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TangentMode {
    /// Internal force only.
    None,
    /// Always compute the tangent.
    Always,
    /// Only the correction `K_e − K_e^el` to the element's elastic matrix,
    /// `Σ_q w_q B̄_qᵀ (C_q − C^el) B̄_q` over the Gauss points whose tangent
    /// is not the elastic one (the caller holds the elastic matrices
    /// assembled); nothing when every point is elastic.
    UnlessElastic,
}

/// What the kernel hands back besides the buffers.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct ElementStats {
    /// Gauss points whose update was plastic.
    pub plastic_points: usize,
    /// True if `Workspace::tangent` was computed.
    pub tangent_computed: bool,
    /// True if every Gauss point's tangent is the elastic one (the
    /// element's tangent is then its elastic matrix), whatever `mode`.
    pub all_elastic: bool,
    /// Time in the first pass (B-bar's projection, strain, material
    /// update, internal force).
    pub stress_pass: std::time::Duration,
    /// Time forming the element tangent (zero if not computed).
    pub tangent_pass: std::time::Duration,
}

/// Gauss-point data of one element that the kernel reads and writes.
pub struct PointData<'a> {
    /// Committed states (read).
    pub committed: &'a [PointState],
    /// Trial states (written).
    pub trial: &'a mut [PointState],
    /// Stresses (written).
    pub stress: &'a mut [Voigt],
    /// Tangent branch of points on their yield surface.
    pub predictor: Predictor,
    /// Strain measure: small strain, or total Lagrangian (then `stress`
    /// receives the Cauchy stress, the material's `S` stays internal).
    pub kinematics: Kinematics,
    /// Total Lagrangian: the element's stress-free initial displacement
    /// `u₀` (a geometric imperfection; 3 per node): the strain is
    /// `E(∇(u + u₀)) − E(∇u₀)` and `F = I + ∇(u + u₀)` — the strain energy of
    /// the shape `X + u₀` to first order in `u₀`.
    pub initial: Option<&'a [f64]>,
    /// Total Lagrangian: the displacement change of the last linear step (3
    /// per node; [`linearized`]), `None` for none.
    pub step: Option<&'a [f64]>,
    /// The ply damage of the element's points (`None` unless its material
    /// damages).
    pub damage: Option<DamagePoints<'a>>,
}

/// Computes the internal force (and the tangent, per `mode`) of body
/// element `e` from its nodal displacements `u` (3 per node, node-major in
/// the order of [`crate::mesh::Body::element_nodes`]).
///
/// Two passes over the Gauss points: the first evaluates strains, the
/// material update and the internal force; the second — only when a
/// tangent is needed — forms the nuclei with the tangents kept from the
/// first: in small strain by gathering `B̄` and `w C B̄` of the points that
/// contribute (all, or those not elastic) into one product, with nonlinear
/// geometry as 3 × 3 nuclei per point, summed section by section
/// (`nucleus`; module docs).
#[allow(clippy::too_many_arguments)] // the kernel's inputs are the terms of eq. (11); bundling them adds nothing
pub(crate) fn element_response(
    geom: &CellValues,
    e: usize,
    n_section_elements: usize,
    u: &[f64],
    material: &Material,
    points: PointData<'_>,
    mode: TangentMode,
    ws: &mut Workspace,
) -> ElementStats {
    let el = Element::new(geom, e, n_section_elements);
    ws.resize(el.nodes, el.n_points);
    ws.force.fill(0.0);
    let kinematics = points.kinematics;
    // what the model reader refuses (crate::setup's bodies), for library callers
    assert!(
        geom.volumetric.is_none()
            || !kinematics.is_nonlinear()
            || (kinematics.is_logarithmic() && points.initial.is_none()),
        "B-bar at finite strain needs the logarithmic strain and no initial displacement"
    );
    assert!(
        geom.shear.is_none()
            || !kinematics.is_nonlinear()
            || (!kinematics.is_logarithmic() && points.initial.is_none()),
        "the assumed in-section shear at finite strain needs the Green–Lagrange strain and no initial displacement"
    );
    assert!(
        !(kinematics.is_nonlinear() && mode == TangentMode::UnlessElastic),
        "nonlinear geometry has no elastic tangent to correct"
    );
    // the first pass: B-bar's projection, then the points
    let start = std::time::Instant::now();
    if let Some(ps) = geom.volumetric.as_ref() {
        if kinematics.is_nonlinear() {
            fbar::dilatation_projection(geom, ps, (el.es, el.eb, el.nodes), u, ws);
        } else {
            volumetric_projection(geom, ps, el.es, el.eb, el.nodes, ws);
        }
    }
    let (all_elastic, plastic_points) = stresses_and_forces(geom, &el, u, material, points, ws);
    let stressed = std::time::Instant::now();
    let tangent_computed = match mode {
        TangentMode::None => false,
        TangentMode::Always => true,
        TangentMode::UnlessElastic => !all_elastic,
    };
    if tangent_computed && kinematics.is_nonlinear() {
        // material, geometric (and B-bar's) terms as 3×3 nuclei (nucleus)
        nucleus::large_tangent(geom, (el.es, el.eb, el.nodes), geom.volumetric.as_ref(), ws);
        assumed_large::add_terms(geom, &el, ws);
    } else if tangent_computed {
        let contributing = product::gather_operators(geom, &el, material, mode == TangentMode::UnlessElastic, ws);
        product::tangent_product(&el, contributing, ws);
    }
    if tangent_computed {
        softening::operators(geom, &el, ws);
    } else {
        ws.skew.clear();
    }
    let stress_pass = stressed - start;
    let tangent_pass = if tangent_computed { stressed.elapsed() } else { std::time::Duration::ZERO };
    ElementStats { plastic_points, tangent_computed, all_elastic, stress_pass, tangent_pass }
}

/// Where an element sits and how big it is.
struct Element {
    /// Section and beam element.
    es: usize,
    eb: usize,
    /// Nodes (section functions × beam functions) and Gauss points.
    nodes: usize,
    n_points: usize,
}

impl Element {
    fn new(geom: &CellValues, e: usize, n_section_elements: usize) -> Self {
        let (sg, ag) = (&geom.section, &geom.axis);
        Self {
            es: e % n_section_elements,
            eb: e / n_section_elements,
            nodes: sg.n_fun * ag.n_fun,
            n_points: sg.n_gp * ag.n_gp,
        }
    }
}

/// First pass: at every Gauss point the strain, the material update (trial
/// state, stress and the tangent the element uses, kept in `ws.tangents`)
/// and the point's share of the internal force, by sum factorization (the
/// tensor-product structure of `N_a = F_τ N_i`): the beam direction is
/// contracted first, once per axis point, so that a Gauss point costs
/// `O(n_section)` instead of `O(n_section · n_beam)`.
///
/// ```text
/// v_τ = Σ_i N_i u_(i,τ),  v'_τ = Σ_i N_i,y u_(i,τ)          at the axis point
/// ∂u/∂x = Σ_τ F_τ,x v_τ,  ∂u/∂y = Σ_τ F_τ v'_τ,  ∂u/∂z = Σ_τ F_τ,z v_τ
/// h_τ = Σ_gs w (σ_·x F_τ,x + σ_·z F_τ,z),  h'_τ = Σ_gs w σ_·y F_τ
/// f_(i,τ) = Σ_gb N_i h_τ + N_i,y h'_τ
/// ```
///
/// Returns whether every point's tangent is the elastic one, and the number
/// of plastic points.
fn stresses_and_forces(
    geom: &CellValues,
    el: &Element,
    u: &[f64],
    material: &Material,
    mut points: PointData<'_>,
    ws: &mut Workspace,
) -> (bool, usize) {
    let (sg, ag) = (&geom.section, &geom.axis);
    let bbar = geom.volumetric.is_some();
    let large = points.kinematics.is_nonlinear();
    let (ns, nodes) = (sg.n_fun, el.nodes);
    let (mut all_elastic, mut plastic_points) = (true, 0);
    ws.softening.clear();
    let step = points.step.filter(|_| large && !points.kinematics.is_logarithmic());
    ws.contracted.resize(8 * ns, [0.0; 3]);
    let shear_large = geom.shear.as_ref().filter(|_| large);
    if shear_large.is_some() {
        ws.assumed.resize(el.n_points * ns, [0.0; 3]);
    }
    for gb in 0..ag.n_gp {
        let at = ag.point(el.eb, gb);
        let (v, rest) = ws.contracted.split_at_mut(ns);
        let (vy, rest) = rest.split_at_mut(ns);
        let (h, rest) = rest.split_at_mut(ns);
        let (hy, rest) = rest.split_at_mut(ns);
        let (v0, rest) = rest.split_at_mut(ns);
        let (vy0, rest) = rest.split_at_mut(ns);
        let (vd, vyd) = rest.split_at_mut(ns);
        contract_axis(&at, u, v, vy);
        if let Some(u0) = points.initial {
            contract_axis(&at, u0, v0, vy0);
        }
        if let Some(d) = step {
            contract_axis(&at, d, vd, vyd);
        }
        if let Some(sh) = shear_large {
            sh.tying_covariants(v, &mut ws.tying);
            if step.is_some() {
                sh.tying_covariants(vd, &mut ws.tying_step);
            }
        }
        h.fill([0.0; 3]);
        hy.fill([0.0; 3]);
        for gs in 0..sg.n_gp {
            let sp = sg.point(el.es, gs);
            let w = sp.weight * at.weight;
            let q = gb * sg.n_gp + gs;
            let g0 = points.initial.map(|_| point_gradient(&sp, v0, vy0));
            let (grad, mut eps, log) = point_strain(points.kinematics, point_gradient(&sp, v, vy), g0);
            if bbar {
                let shift = dilatation_shift((&ws.bbar, &ws.dilatation), q, nodes, u, large);
                for e in eps.iter_mut().take(3) {
                    *e += shift / 3.0;
                }
            }
            match (&geom.shear, large) {
                (Some(sh), true) => sh.add_large_strain(el.es, gs, v, &ws.tying, &mut eps),
                (Some(sh), false) => sh.add_strain(el.es, gs, v, &mut eps),
                (None, _) => {}
            }
            // the physical stress where the force takes another (a damaged ply point's end-of-step stress)
            let (mut r, physical) = damaged::update_point(material, &mut points, &eps, (q, w), &mut ws.softening);
            // the mean stress conjugate to the dilatation (T's, before any pull-back)
            ws.pressure[q] = (r.stress[0] + r.stress[1] + r.stress[2]) / 3.0;
            if let Some(log) = &log {
                pull_back(log, bbar, &mut r, &mut ws.coupling[q]);
            }
            points.trial[q] = r.state;
            ws.tangents[q] = r.tangent;
            all_elastic &= r.elastic_tangent;
            plastic_points += usize::from(r.plastic);
            // the stress whose rows meet the reference gradients: σ, or P = F S
            let rows = if large {
                let f = crate::kinematics::deformation_gradient(&grad);
                // after a step, its quadratic strain with the assumed shear's share
                let geometric = step.map_or(r.stress, |_| {
                    let extra =
                        shear_large.map(|sh| (sh.quadratic_change(gs, vd, &ws.tying_step), sh.direction(el.es)));
                    linearized::stress(&r.stress, &r.tangent, &point_gradient(&sp, vd, vyd), extra)
                });
                (ws.frames[q], ws.pk2[q]) = (f, geometric);
                // σ = F S Fᵀ / J̄ with B-bar (fbar), J̄ = J e^(θ̄ − θ)
                let scale = if bbar { (-ws.dilatation[q]).exp() } else { 1.0 };
                points.stress[q] = crate::kinematics::cauchy(&f, &r.stress).map(|s| s * scale);
                crate::kinematics::first_piola(&f, &r.stress)
            } else {
                points.stress[q] = r.stress;
                crate::voigt::stress_tensor(&r.stress)
            };
            add_point_force(&sp, w, &rows, h, hy);
            match (&geom.shear, large) {
                (Some(sh), true) => {
                    let d = &mut ws.assumed[q * ns..(q + 1) * ns];
                    assumed_large::add_force(sh, (el.es, gs), w, &r.stress, (v, &ws.tying), (d, h));
                }
                (Some(sh), false) => sh.add_force(el.es, gs, w, &points.stress[q], h),
                (None, _) => {}
            }
            if let Some(s) = physical {
                points.stress[q] = s;
            }
            if bbar {
                // f_a += w d_a p, p = tr σ / 3 (tr T / 3 at finite strain)
                let tr = ws.pressure[q];
                for a in 0..nodes {
                    let da = ws.bbar[q * nodes + a];
                    for k in 0..3 {
                        ws.force[3 * a + k] += w * tr * da[k];
                    }
                }
            }
        }
        expand_force(&at, h, hy, &mut ws.force);
    }
    (all_elastic, plastic_points)
}

/// `f_(i,τ) += N_i h_τ + N_i,y h'_τ` at one axis point.
fn expand_force(at: &crate::values::AxisAt<'_>, h: &[[f64; 3]], hy: &[[f64; 3]], force: &mut [f64]) {
    let ns = h.len();
    for (i, (&n, &ny)) in at.n.iter().zip(at.ny).enumerate() {
        let fi = &mut force[3 * i * ns..3 * (i + 1) * ns];
        for ((fa, ht), hyt) in fi.chunks_exact_mut(3).zip(h.iter()).zip(hy.iter()) {
            for k in 0..3 {
                fa[k] += n * ht[k] + ny * hyt[k];
            }
        }
    }
}

/// The logarithmic strain's material response `(T, ∂T/∂E_log)` as
/// `(S, ∂S/∂E)`, after which the rest is the Green–Lagrange kernel's; with
/// B-bar also fbar's coupling of the dilatation row `(Lᵀ D m, mᵀ D m / 9)`.
fn pull_back(log: &LogStrain, bbar: bool, r: &mut crate::materials::Response, coupling: &mut (Voigt, f64)) {
    if bbar {
        let dm: Voigt = std::array::from_fn(|i| r.tangent[i][0] + r.tangent[i][1] + r.tangent[i][2]);
        *coupling = (log.pull_back_stress(&dm), (dm[0] + dm[1] + dm[2]) / 9.0);
    }
    (r.stress, r.tangent) = log.pull_back(&r.stress, &r.tangent);
    r.elastic_tangent = false;
}

/// B-bar's `θ̄ − θ` at point `q` (`ε̄ = ε + (θ̄ − θ)/3 · 1`): in small strain
/// `Σ_a (b̄_a − g_a)·u_a`, at finite strain the projected ln J less ln J
/// (`fbar`, computed beforehand).
fn dilatation_shift((bbar, dilatation): (&[[f64; 3]], &[f64]), q: usize, nodes: usize, u: &[f64], large: bool) -> f64 {
    if large {
        return dilatation[q];
    }
    let d = &bbar[q * nodes..(q + 1) * nodes];
    d.iter().enumerate().map(|(a, da)| da[0] * u[3 * a] + da[1] * u[3 * a + 1] + da[2] * u[3 * a + 2]).sum()
}

/// The strain the material sees at a Gauss point, from the displacement
/// gradient `grad` and, with a stress-free initial displacement, its
/// gradient `g0`: `E(∇(u + u₀)) − E(∇u₀)` (the imperfect shape is stress
/// free). Returns the gradient of the total displacement (that of `F`), the
/// strain, and with the logarithmic strain its spectral data (for the
/// pull-back of the material's stress; [`crate::kinematics::hencky`]).
fn point_strain(kinematics: Kinematics, mut grad: Tensor, g0: Option<Tensor>) -> (Tensor, Voigt, Option<LogStrain>) {
    let e0 = g0.map(|g0| {
        for (row, r0) in grad.iter_mut().zip(&g0) {
            for (a, b) in row.iter_mut().zip(r0) {
                *a += b;
            }
        }
        kinematics.strain(&g0)
    });
    let log = kinematics.is_logarithmic().then(|| LogStrain::new(&grad));
    let mut eps = match &log {
        Some(l) => l.strain(),
        None => kinematics.strain(&grad),
    };
    if let Some(e0) = e0 {
        for (e, z) in eps.iter_mut().zip(&e0) {
            *e -= z;
        }
    }
    (grad, eps, log)
}

/// `v_τ = Σ_i N_i u_(i,τ)` and `v'_τ = Σ_i N_i,y u_(i,τ)` at one axis point.
pub(crate) fn contract_axis(at: &crate::values::AxisAt<'_>, u: &[f64], v: &mut [[f64; 3]], vy: &mut [[f64; 3]]) {
    let ns = v.len();
    v.fill([0.0; 3]);
    vy.fill([0.0; 3]);
    for (i, (&n, &ny)) in at.n.iter().zip(at.ny).enumerate() {
        let ui = &u[3 * i * ns..3 * (i + 1) * ns];
        for ((vt, vyt), ua) in v.iter_mut().zip(vy.iter_mut()).zip(ui.chunks_exact(3)) {
            for k in 0..3 {
                vt[k] += n * ua[k];
                vyt[k] += ny * ua[k];
            }
        }
    }
}

/// The displacement gradient `∂u_k/∂x_d` at a section point from the
/// contracted `v_τ`, `v'_τ`.
fn point_gradient(sp: &crate::values::SectionAt<'_>, v: &[[f64; 3]], vy: &[[f64; 3]]) -> Tensor {
    // grad[k][d] = ∂u_k/∂x_d
    let mut grad = [[0.0; 3]; 3];
    for t in 0..v.len() {
        let (fx, f, fz) = (sp.fx[t], sp.f[t], sp.fz[t]);
        for k in 0..3 {
            grad[k][0] += fx * v[t][k];
            grad[k][1] += f * vy[t][k];
            grad[k][2] += fz * v[t][k];
        }
    }
    grad
}

/// A section point's share of `h_τ` and `h'_τ` (the rows of the stress
/// tensor times `w`: `σ_k· = (σ_kx, σ_ky, σ_kz)`, or of `P = F S` in the
/// total-Lagrangian formulation).
fn add_point_force(sp: &crate::values::SectionAt<'_>, w: f64, s: &Tensor, h: &mut [[f64; 3]], hy: &mut [[f64; 3]]) {
    let sig = s.map(|row| row.map(|x| w * x));
    for t in 0..h.len() {
        let (fx, f, fz) = (sp.fx[t], sp.f[t], sp.fz[t]);
        for k in 0..3 {
            h[t][k] += sig[k][0] * fx + sig[k][2] * fz;
            hy[t][k] += sig[k][1] * f;
        }
    }
}

#[cfg(test)]
mod assumed_tests;
#[cfg(test)]
mod fbar_tests;
#[cfg(test)]
mod log_tests;
#[cfg(test)]
mod nucleus_tests;
#[cfg(test)]
mod softening_tests;
#[cfg(test)]
mod tests;
