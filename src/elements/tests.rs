//! Tests of the element kernel.

use super::log_tests::field;
use super::*;
use crate::mesh::{BeamAxis, Body, CrossSection, Division};
use crate::shape::{BeamElementKind, SectionElementKind};

pub(super) fn single_element_body(sk: SectionElementKind, bk: BeamElementKind) -> Body {
    // a distorted quad section (straight edges) and a single beam element
    let corners = [[0.0, 0.0], [0.012, 0.001], [0.010, 0.011], [-0.001, 0.009]];
    let section = CrossSection::from_quads(sk, &corners, &[[0, 1, 2, 3]], "s").unwrap();
    let lines = Division::uniform(0.1, 0.13, 1).lines("y").unwrap();
    Body::new("b", section, BeamAxis::from_lines(bk, &lines), 0)
}

fn response(body: &Body, mat: &Material, u: &[f64], committed: &[PointState]) -> (Vec<f64>, Vec<f64>) {
    response_with(&CellValues::new(body).unwrap(), mat, u, committed)
}

fn response_with(geom: &CellValues, mat: &Material, u: &[f64], committed: &[PointState]) -> (Vec<f64>, Vec<f64>) {
    let (f, k, _) = response_kin(geom, mat, u, committed, Kinematics::Linear);
    (f, k)
}

/// Force, tangent and Gauss-point stresses with the given kinematics.
pub(super) fn response_kin(
    geom: &CellValues,
    mat: &Material,
    u: &[f64],
    committed: &[PointState],
    kinematics: Kinematics,
) -> (Vec<f64>, Vec<f64>, Vec<Voigt>) {
    let run = kernel(geom, mat, u, committed, kinematics, None);
    (run.ws.force, run.ws.tangent, run.stress)
}

/// One call of the kernel with a full tangent, from a fresh workspace.
pub(super) struct KernelRun {
    /// The workspace after the call (force, tangent, per-point data).
    pub ws: Workspace,
    /// Gauss-point stresses (Cauchy with nonlinear geometry) and trial states.
    pub stress: Vec<Voigt>,
    pub trial: Vec<PointState>,
    pub stats: ElementStats,
}

/// Runs the kernel on element 0 of `geom` with a full tangent.
pub(super) fn kernel(
    geom: &CellValues,
    mat: &Material,
    u: &[f64],
    committed: &[PointState],
    kinematics: Kinematics,
    initial: Option<&[f64]>,
) -> KernelRun {
    let ngp = geom.gp_per_element();
    let mut trial = vec![PointState::default(); ngp];
    let mut stress = vec![[0.0; 6]; ngp];
    let mut ws = Workspace::default();
    let points = PointData {
        committed,
        trial: &mut trial,
        stress: &mut stress,
        predictor: Predictor::Loading,
        kinematics,
        initial,
        step: None,
        damage: None,
    };
    let stats = element_response(geom, 0, 1, u, mat, points, TangentMode::Always, &mut ws);
    KernelRun { ws, stress, trial, stats }
}

#[test]
fn volume_and_rigid_body_modes() {
    let mat = Material::new("m", 70e9, 0.3, None);
    for (sk, bk, body) in single_element_bodies() {
        let geom = CellValues::new(&body).unwrap();
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
        // small rotation θ about an arbitrary axis: u = θ × x
        let th = [1e-4, -2e-4, 3e-4];
        let u = field(&body, &|[x, y, z]| [th[1] * z - th[2] * y, th[2] * x - th[0] * z, th[0] * y - th[1] * x]);
        let ngp = geom.gp_per_element();
        let (f, _) = response(&body, &mat, &u, &vec![PointState::default(); ngp]);
        let fmax = f.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        assert!(fmax < 1e-6, "{sk:?}{bk:?}: {fmax}");
    }
}

#[test]
fn tangent_matches_finite_difference_of_force_elastoplastic() {
    for bbar in [false, true] {
        tangent_check(bbar);
    }
}

/// B-bar: rigid motions give no force, a linear field (constant
/// volumetric strain, in every pressure space) gives the standard
/// element's force, and a field with non-constant divergence does not.
#[test]
fn bbar_reduces_to_the_standard_element_for_constant_dilatation() {
    let mat = Material::new("m", 70e9, 0.3, None);
    for (sk, bk, body) in single_element_bodies() {
        let std = CellValues::new(&body).unwrap();
        let bar = CellValues::new(&body).unwrap().with_bbar(&body);
        let committed = vec![PointState::default(); std.gp_per_element()];
        let mut el = Vec::new();
        body.element_nodes(0, &mut el);
        let field = |f: &dyn Fn([f64; 3]) -> [f64; 3]| -> Vec<f64> {
            el.iter().flat_map(|&g| f(body.local_coords(g))).collect()
        };
        let linear = field(&|x| [1e-3 * x[0] + 2e-4 * x[2], -5e-4 * x[1] + 1e-4 * x[0], 3e-4 * x[2] - 2e-4 * x[1]]);
        let (fs, _) = response_with(&std, &mat, &linear, &committed);
        let (fb, _) = response_with(&bar, &mat, &linear, &committed);
        let scale = fs.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let diff = fs.iter().zip(&fb).fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        assert!(diff < 1e-10 * scale, "{sk:?}{bk:?}: {diff:e}");
        let rotation = field(&|x| [2e-4 * x[2] - 3e-4 * x[1], 3e-4 * x[0] - 1e-4 * x[2], 1e-4 * x[1] - 2e-4 * x[0]]);
        let (fr, _) = response_with(&bar, &mat, &rotation, &committed);
        assert!(fr.iter().fold(0.0f64, |a, b| a.max(b.abs())) < 1e-6, "{sk:?}{bk:?}");
    }
    // a dilatation that varies to second order is projected, so B-bar differs
    let body = single_element_body(SectionElementKind::L9, BeamElementKind::B4);
    let (std, bar) = (CellValues::new(&body).unwrap(), CellValues::new(&body).unwrap().with_bbar(&body));
    let committed = vec![PointState::default(); std.gp_per_element()];
    let mut el = Vec::new();
    body.element_nodes(0, &mut el);
    let u: Vec<f64> = el
        .iter()
        .flat_map(|&g| {
            let x = body.local_coords(g);
            [1e1 * x[0] * x[0] * x[1] * x[1], 0.0, 0.0]
        })
        .collect();
    let (fs, _) = response_with(&std, &mat, &u, &committed);
    let (fb, _) = response_with(&bar, &mat, &u, &committed);
    let scale = fs.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(fs.iter().zip(&fb).any(|(x, y)| (x - y).abs() > 1e-3 * scale));
}

/// A single-element body of every section and beam element kind.
fn single_element_bodies() -> impl Iterator<Item = (SectionElementKind, BeamElementKind, Body)> {
    use {BeamElementKind::*, SectionElementKind::*};
    [L4, L9, L16].into_iter().flat_map(|sk| [B2, B3, B4].map(|bk| (sk, bk, single_element_body(sk, bk))))
}

/// Largest difference between the symmetric tangent `k` (n × n, its upper
/// triangle read) and central differences of `force` with step `h` about
/// `u`, relative to the largest entry of `k`.
pub(super) fn difference_error(k: &[f64], u: &[f64], h: f64, mut force: impl FnMut(&[f64]) -> Vec<f64>) -> f64 {
    let n = u.len();
    let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(kmax > 0.0, "a zero tangent");
    let mut worst: f64 = 0.0;
    for q in 0..n {
        let (mut up, mut um) = (u.to_vec(), u.to_vec());
        up[q] += h;
        um[q] -= h;
        let (fp, fm) = (force(&up), force(&um));
        for p in 0..n {
            let kk = if p <= q { k[p * n + q] } else { k[q * n + p] };
            worst = worst.max(((fp[p] - fm[p]) / (2.0 * h) - kk).abs() / kmax);
        }
    }
    worst
}

fn tangent_check(bbar: bool) {
    use crate::materials::Hardening;
    let body = single_element_body(SectionElementKind::L9, BeamElementKind::B3);
    let mat = Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 }));
    // a displacement that yields part of the element
    let u = field(&body, &|[x, y, z]| {
        [
            3e-3 * y * z / 0.01 + 1e-5 * (x * 100.0).sin(),
            -2e-3 * (z - 0.005) + 1e-3 * x * y,
            1e-5 * (y * 50.0).cos() + 2e-3 * x,
        ]
    });
    let geom = CellValues::new(&body).unwrap();
    let geom = if bbar { geom.with_bbar(&body) } else { geom };
    let ngp = geom.gp_per_element();
    let committed = vec![PointState::default(); ngp];
    let (_, k) = response_with(&geom, &mat, &u, &committed);
    let worst = difference_error(&k, &u, 1e-9, |u| response_with(&geom, &mat, u, &committed).0);
    assert!(worst < 1e-6, "relative tangent error {worst} (B-bar: {bbar})");
}

/// Total Lagrangian: the tangent (material and geometric parts) is the
/// derivative of the internal force at a large deformation — a rotation of
/// 0.6 rad about x plus stretching and shear, elastic and elastoplastic.
/// Dropping the geometric term or using the small-strain `B` fails it.
#[test]
fn total_lagrangian_tangent_matches_finite_difference() {
    use crate::materials::Hardening;
    let body = single_element_body(SectionElementKind::L9, BeamElementKind::B3);
    let nodes = body.nodes_per_element();
    let mut el = Vec::new();
    body.element_nodes(0, &mut el);
    let (s, c) = 0.6f64.sin_cos();
    let mut u = vec![0.0; 3 * nodes];
    for (a, &g) in el.iter().enumerate() {
        let [x, y, z] = body.local_coords(g);
        // rotate about x through (y, z) = (0.1, 0), then strain a little
        let (yr, zr) = (0.1 + c * (y - 0.1) - s * z, s * (y - 0.1) + c * z);
        u[3 * a] = 2e-3 * y * z / 0.01 + 1e-3 * x;
        u[3 * a + 1] = yr - y + 3e-3 * (y - 0.1) + 1e-3 * x;
        u[3 * a + 2] = zr - z - 1e-3 * (y - 0.1) * (y - 0.1) / 0.03;
    }
    let geom = CellValues::new(&body).unwrap();
    let committed = vec![PointState::default(); geom.gp_per_element()];
    for mat in [
        Material::new("m", 70e9, 0.3, None),
        Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 })),
    ] {
        let (_, k, _) = response_kin(&geom, &mat, &u, &committed, Kinematics::TotalLagrangian);
        let worst =
            difference_error(&k, &u, 1e-9, |u| response_kin(&geom, &mat, u, &committed, Kinematics::TotalLagrangian).0);
        assert!(worst < 1e-6, "relative tangent error {worst} (plastic: {})", mat.is_plastic());
    }
}

/// Total Lagrangian under twist, as in a member twisted about its axis:
/// the element rotated about the axis (y) through 90° and 180° plus a
/// little stretch, shear and warping; the tangent is the derivative of the
/// force to 1e-6 of its largest entry, elastic and elastoplastic, for every
/// section and beam element kind (issue 50).
#[test]
fn total_lagrangian_tangent_matches_finite_difference_under_twist() {
    use crate::materials::Hardening;
    for (sk, bk, body) in single_element_bodies() {
        let nodes = body.nodes_per_element();
        let mut el = Vec::new();
        body.element_nodes(0, &mut el);
        let geom = CellValues::new(&body).unwrap();
        let committed = vec![PointState::default(); geom.gp_per_element()];
        for angle in [std::f64::consts::FRAC_PI_2, std::f64::consts::PI] {
            let mut u = vec![0.0; 3 * nodes];
            for (a, &g) in el.iter().enumerate() {
                let [x, y, z] = body.local_coords(g);
                // twist growing along y: angle at y = 0.13, 0.7 angle at y = 0.1
                let t = angle * (0.7 + 0.3 * (y - 0.1) / 0.03);
                let (s, c) = t.sin_cos();
                let (xs, zs) = (x * (1.0 + 1e-3 * y) + 2e-4 * z, z - 1e-3 * x);
                u[3 * a] = c * xs - s * zs - x;
                u[3 * a + 1] = 2e-3 * (y - 0.1) + 0.5 * x * z;
                u[3 * a + 2] = s * xs + c * zs - z;
            }
            for mat in [
                Material::new("m", 70e9, 0.3, None),
                Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 })),
            ] {
                let tl = Kinematics::TotalLagrangian;
                let (_, k, _) = response_kin(&geom, &mat, &u, &committed, tl);
                let worst = difference_error(&k, &u, 1e-9, |u| response_kin(&geom, &mat, u, &committed, tl).0);
                assert!(
                    worst < 1e-6,
                    "{sk:?} × {bk:?}, twist {angle:.3} rad: relative tangent error {worst:e} (plastic: {})",
                    mat.is_plastic()
                );
            }
        }
    }
}

/// Objectivity: a deformed element rotated rigidly by 90° (u₂ = R(X + u) − X)
/// has its nodal forces rotated (f₂ = R f) and its Cauchy stress rotated
/// (σ₂ = R σ Rᵀ), to 1e-8 relative; a rigid rotation alone is stress
/// free. The small-strain element fails both.
#[test]
fn total_lagrangian_is_objective() {
    use crate::materials::Hardening;
    let body = single_element_body(SectionElementKind::L9, BeamElementKind::B4);
    let nodes = body.nodes_per_element();
    let mut el = Vec::new();
    body.element_nodes(0, &mut el);
    let mat = Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 }));
    // 90° about the axis (1, 1, 1)/√3
    let r = {
        let t = 1.0 / 3.0;
        let (p, m) = (t + 1.0 / 3f64.sqrt(), t - 1.0 / 3f64.sqrt());
        [[t, m, p], [p, t, m], [m, p, t]]
    };
    let rot = |v: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2]) };
    let (mut u, mut u2, mut rigid) = (vec![0.0; 3 * nodes], vec![0.0; 3 * nodes], vec![0.0; 3 * nodes]);
    for (a, &g) in el.iter().enumerate() {
        let x = body.local_coords(g);
        let d = [3e-3 * x[1] * x[2] / 0.01, -4e-3 * (x[1] - 0.1) + 1e-3 * x[0], 2e-3 * x[0]];
        let moved = rot([x[0] + d[0], x[1] + d[1], x[2] + d[2]]);
        let turned = rot(x);
        for k in 0..3 {
            u[3 * a + k] = d[k];
            u2[3 * a + k] = moved[k] - x[k];
            rigid[3 * a + k] = turned[k] - x[k];
        }
    }
    let geom = CellValues::new(&body).unwrap();
    let committed = vec![PointState::default(); geom.gp_per_element()];
    let tl = Kinematics::TotalLagrangian;
    let (f, _, s) = response_kin(&geom, &mat, &u, &committed, tl);
    let (f2, _, s2) = response_kin(&geom, &mat, &u2, &committed, tl);
    let fmax = f.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    for a in 0..nodes {
        let expected = rot([f[3 * a], f[3 * a + 1], f[3 * a + 2]]);
        for k in 0..3 {
            assert!((f2[3 * a + k] - expected[k]).abs() < 1e-8 * fmax, "node {a} component {k}");
        }
    }
    let smax = s.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(smax > 100e6, "the element yields: {smax:e}");
    for (sq, s2q) in s.iter().zip(&s2) {
        let st = crate::voigt::stress_tensor(sq);
        let expected: [[f64; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                (0..3).flat_map(|k| (0..3).map(move |l| (k, l))).map(|(k, l)| r[i][k] * st[k][l] * r[j][l]).sum()
            })
        });
        let got = crate::voigt::stress_tensor(s2q);
        for i in 0..3 {
            for j in 0..3 {
                assert!((got[i][j] - expected[i][j]).abs() < 1e-8 * smax, "{i}{j}");
            }
        }
    }
    let (fr, _, sr) = response_kin(&geom, &mat, &rigid, &committed, tl);
    assert!(fr.iter().all(|v| v.abs() < 1e-8 * fmax) && sr.iter().flatten().all(|v| v.abs() < 1e-8 * smax));
    let (fl, _, _) = response_kin(&geom, &mat, &rigid, &committed, Kinematics::Linear);
    assert!(fl.iter().any(|v| v.abs() > fmax), "small strain: a 90° rotation strains the element");
}

/// A stress-free initial displacement (geometric imperfection): alone it
/// gives no force; on top of a deformation the tangent is still the
/// derivative of the force (the F of the total displacement in the
/// nuclei's material and geometric terms).
#[test]
fn imperfection_is_stress_free_and_its_tangent_consistent() {
    let body = single_element_body(SectionElementKind::L9, BeamElementKind::B3);
    let nodes = body.nodes_per_element();
    let mut el = Vec::new();
    body.element_nodes(0, &mut el);
    let (mut u0, mut u) = (vec![0.0; 3 * nodes], vec![0.0; 3 * nodes]);
    for (a, &g) in el.iter().enumerate() {
        let [x, y, z] = body.local_coords(g);
        u0[3 * a] = 0.02 * (y - 0.1) * (y - 0.1) / 0.03 + 0.01 * z;
        u0[3 * a + 2] = -0.01 * x;
        u[3 * a] = 2e-3 * y * z / 0.01;
        u[3 * a + 1] = 3e-3 * (y - 0.1) + 1e-3 * x;
        u[3 * a + 2] = 0.05 * (y - 0.1);
    }
    let geom = CellValues::new(&body).unwrap();
    let committed = vec![PointState::default(); geom.gp_per_element()];
    let mat = Material::new("m", 70e9, 0.3, None);
    let tl = Kinematics::TotalLagrangian;
    let zero = vec![0.0; 3 * nodes];
    let f0 = kernel(&geom, &mat, &zero, &committed, tl, Some(&u0)).ws.force;
    assert!(f0.iter().all(|v| v.abs() < 1e-9), "the imperfect shape alone is stress free");
    let run = kernel(&geom, &mat, &u, &committed, tl, Some(&u0));
    let (f, k) = (run.ws.force, run.ws.tangent);
    let (fp, _, _) = response_kin(&geom, &mat, &u, &committed, tl);
    let fmax = f.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(f.iter().zip(&fp).any(|(a, b)| (a - b).abs() > 1e-3 * fmax), "the imperfection changes the response");
    let n = 3 * nodes;
    let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let mut worst: f64 = 0.0;
    for q in 0..n {
        let (mut up, mut um) = (u.clone(), u.clone());
        up[q] += 1e-9;
        um[q] -= 1e-9;
        let fp = kernel(&geom, &mat, &up, &committed, tl, Some(&u0)).ws.force;
        let fm = kernel(&geom, &mat, &um, &committed, tl, Some(&u0)).ws.force;
        for p in 0..n {
            let kk = if p <= q { k[p * n + q] } else { k[q * n + p] };
            worst = worst.max(((fp[p] - fm[p]) / 2e-9 - kk).abs() / kmax);
        }
    }
    assert!(worst < 1e-6, "relative tangent error {worst}");
}
