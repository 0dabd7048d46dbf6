//! Tests of the kernel with the logarithmic strain
//! (`Kinematics::TotalLagrangianLog`): the tangent against finite
//! differences (elastic, plastic, repeated principal stretches, a plastic
//! history not coaxial with the current stretch) and objectivity of a
//! plastically pre-strained element.

use super::tests::single_element_body;
use super::*;
use crate::materials::Hardening;
use crate::mesh::Body;
use crate::shape::{BeamElementKind, SectionElementKind};

const LOG: Kinematics = Kinematics::TotalLagrangianLog;

/// Force, tangent, Gauss-point Cauchy stresses and trial states.
pub(super) fn evaluate(
    geom: &CellValues,
    mat: &Material,
    u: &[f64],
    committed: &[PointState],
) -> (Vec<f64>, Vec<f64>, Vec<Voigt>, Vec<PointState>) {
    let run = super::tests::kernel(geom, mat, u, committed, LOG, None);
    (run.ws.force, run.ws.tangent, run.stress, run.trial)
}

/// The nodal displacement of a map `x → u(x)` over the element's nodes.
pub(super) fn field(body: &Body, f: &dyn Fn([f64; 3]) -> [f64; 3]) -> Vec<f64> {
    let mut el = Vec::new();
    body.element_nodes(0, &mut el);
    el.iter().flat_map(|&g| f(body.local_coords(g))).collect()
}

/// Largest difference between the tangent and central differences of the
/// force, relative to the largest tangent entry.
pub(super) fn tangent_error(geom: &CellValues, mat: &Material, u: &[f64], committed: &[PointState]) -> f64 {
    let (_, k, _, _) = evaluate(geom, mat, u, committed);
    super::tests::difference_error(&k, u, 1e-9, |u| evaluate(geom, mat, u, committed).0)
}

/// Uniaxial stretch `λ` along the axis y with the lateral stretch `μ` in
/// both x and z: `F = diag(μ, λ, μ)` at every point, two equal principal
/// stretches exactly.
pub(super) fn uniaxial(body: &Body, lambda: f64, mu: f64) -> Vec<f64> {
    field(body, &|x| [(mu - 1.0) * x[0], (lambda - 1.0) * (x[1] - 0.1), (mu - 1.0) * x[2]])
}

/// The kernel's tangent with the logarithmic strain is the derivative of
/// its force within 1e-6 relative: at a large rotation (0.6 rad) with
/// stretch and shear; at a uniaxial stretch of e^0.2 with equal lateral
/// stretches (repeated eigenvalues of C at every Gauss point); elastic and
/// plastic; and from a committed plastic state of that stretch under the
/// rotated, sheared deformation (a plastic strain not coaxial with C, so
/// T is not either). Without the term `T : ∂²E_log/∂E²` or with a wrong
/// confluent limit it fails (the point-level test in
/// `kinematics::hencky` shows both matter).
#[test]
fn log_strain_tangent_matches_finite_differences() {
    let body = single_element_body(SectionElementKind::L9, BeamElementKind::B3);
    let geom = CellValues::new(&body).unwrap();
    let virgin = vec![PointState::default(); geom.gp_per_element()];
    let (s, c) = 0.6f64.sin_cos();
    let rotated = field(&body, &|[x, y, z]| {
        let (yr, zr) = (0.1 + c * (y - 0.1) - s * z, s * (y - 0.1) + c * z);
        [0.02 * y * z / 0.01 + 0.01 * x, yr - y + 0.03 * (y - 0.1) + 0.01 * x, zr - z - 0.01 * (y - 0.1).powi(2) / 0.03]
    });
    let stretched = uniaxial(&body, 0.2f64.exp(), (-0.1f64).exp());
    let elastic = Material::new("m", 70e9, 0.3, None);
    let plastic = Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 }));
    let (_, _, _, history) = evaluate(&geom, &plastic, &stretched, &virgin);
    assert!(history.iter().all(|p| p.peeq > 0.1), "the stretch is plastic");
    for (name, mat, u, committed) in [
        ("rotated, elastic", &elastic, &rotated, &virgin),
        ("rotated, plastic", &plastic, &rotated, &virgin),
        ("uniaxial, elastic", &elastic, &stretched, &virgin),
        ("uniaxial, plastic", &plastic, &stretched, &virgin),
        ("rotated after the stretch", &plastic, &rotated, &history),
    ] {
        let worst = tangent_error(&geom, mat, u, committed);
        eprintln!("{name}: relative tangent error {worst:e}");
        assert!(worst < 1e-6, "{name}: relative tangent error {worst:e}");
    }
}

/// Objectivity with a plastic history: an element pre-strained plastically
/// (its trial states committed) and then deformed further, rotated
/// rigidly by 90° about (1, 1, 1)/√3 (u₂ = R(X + u) − X), has its nodal
/// forces rotated and its Cauchy stress rotated, to 1e-8 relative (as
/// `total_lagrangian_is_objective` for the Green–Lagrange strain).
#[test]
fn log_strain_is_objective_with_a_plastic_history() {
    let body = single_element_body(SectionElementKind::L9, BeamElementKind::B4);
    let geom = CellValues::new(&body).unwrap();
    let mat = Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 }));
    let pre = |x: [f64; 3]| [0.05 * x[1] * x[2] / 0.01, 0.1 * (x[1] - 0.1) + 0.01 * x[0], 0.02 * x[0]];
    let more = |x: [f64; 3]| {
        let d = pre(x);
        [1.3 * d[0] - 0.01 * x[2], 1.2 * d[1], 1.1 * d[2] + 0.02 * (x[1] - 0.1)]
    };
    let virgin = vec![PointState::default(); geom.gp_per_element()];
    let (_, _, _, history) = evaluate(&geom, &mat, &field(&body, &pre), &virgin);
    assert!(history.iter().all(|p| p.peeq > 1e-3), "the pre-strain is plastic");
    let smax = assert_objective(&geom, &mat, &body, &more, &history);
    assert!(smax > 100e6, "the element is stressed past yield: {smax:e}");
}

/// Evaluates the element deformed by `deform` (displacement of the
/// reference point) and the same deformation turned rigidly by 90° about
/// (1, 1, 1)/√3 (`u₂ = R(X + u) − X`) from the states `committed`, and
/// asserts that the nodal forces and the Cauchy stresses turn with it, to
/// 1e-8 of their largest entry. Returns the largest stress component.
pub(super) fn assert_objective(
    geom: &CellValues,
    mat: &Material,
    body: &Body,
    deform: &dyn Fn([f64; 3]) -> [f64; 3],
    committed: &[PointState],
) -> f64 {
    let r = {
        let t = 1.0 / 3.0;
        let (p, m) = (t + 1.0 / 3f64.sqrt(), t - 1.0 / 3f64.sqrt());
        [[t, m, p], [p, t, m], [m, p, t]]
    };
    let rot = |v: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2]) };
    let u = field(body, deform);
    let u2 = field(body, &|x| {
        let d = deform(x);
        let moved = rot([x[0] + d[0], x[1] + d[1], x[2] + d[2]]);
        std::array::from_fn(|k| moved[k] - x[k])
    });
    let (f, _, s, _) = evaluate(geom, mat, &u, committed);
    let (f2, _, s2, _) = evaluate(geom, mat, &u2, committed);
    let fmax = f.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    for a in 0..f.len() / 3 {
        let expected = rot([f[3 * a], f[3 * a + 1], f[3 * a + 2]]);
        for k in 0..3 {
            assert!((f2[3 * a + k] - expected[k]).abs() < 1e-8 * fmax, "node {a} component {k}");
        }
    }
    let smax = s.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
    for (sq, s2q) in s.iter().zip(&s2) {
        let st = crate::voigt::stress_tensor(sq);
        let got = crate::voigt::stress_tensor(s2q);
        for i in 0..3 {
            for j in 0..3 {
                let expected: f64 =
                    (0..3).flat_map(|k| (0..3).map(move |l| (k, l))).map(|(k, l)| r[i][k] * st[k][l] * r[j][l]).sum();
                assert!((got[i][j] - expected).abs() < 1e-8 * smax, "{i}{j}");
            }
        }
    }
    smax
}

/// Uniaxial strain `F = diag(1, λ, 1)`, λ = e^0.2, elastic: the logarithmic
/// kernel's Cauchy stress is the closed form `σ_yy = (λ_L + 2G) ln λ / λ`
/// (Hencky's law, Kirchhoff stress over J = λ) at every Gauss point to
/// 1e-10; the Green–Lagrange kernel's (Saint Venant–Kirchhoff,
/// `λ (λ_L + 2G)(λ² − 1)/2`) is more than 5 % away, and so are its forces.
#[test]
fn the_two_measures_differ_at_finite_strain() {
    let body = single_element_body(SectionElementKind::L9, BeamElementKind::B3);
    let geom = CellValues::new(&body).unwrap();
    let virgin = vec![PointState::default(); geom.gp_per_element()];
    let mat = Material::new("m", 70e9, 0.3, None);
    let u = uniaxial(&body, 0.2f64.exp(), 1.0);
    let (f_log, _, s_log, _) = evaluate(&geom, &mat, &u, &virgin);
    let (f_gl, _, s_gl) = super::tests::response_kin(&geom, &mat, &u, &virgin, Kinematics::TotalLagrangian);
    let fmax = f_log.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(f_log.iter().zip(&f_gl).any(|(a, b)| (a - b).abs() > 0.05 * fmax));
    // uniaxial strain, elastic: σ_yy = (λ + 2G) ln λ / λ (Kirchhoff over J = λ)
    let (lame, g) = (70e9 * 0.3 / (1.3 * 0.4), 70e9 / 2.6);
    let expected = (lame + 2.0 * g) * 0.2 / 0.2f64.exp();
    for (sl, sg) in s_log.iter().zip(&s_gl) {
        assert!((sl[1] - expected).abs() < 1e-10 * expected, "{} {expected}", sl[1]);
        assert!((sg[1] - expected).abs() > 0.05 * expected);
    }
}
