//! Tests of the assumed in-section shear strain in the kernel
//! ([`crate::values::AssumedShear`]): consistent tangent, patch test, no
//! spurious zero-energy modes.

use super::log_tests::field;
use super::tests::{difference_error, kernel, single_element_body};
use super::*;
use crate::kinematics::tests::rotation;
use crate::materials::Hardening;
use crate::shape::{BeamElementKind, SectionElementKind};

fn kinds() -> [(SectionElementKind, BeamElementKind); 4] {
    use {BeamElementKind::*, SectionElementKind::*};
    [(L9, B2), (L9, B3), (L9, B4), (L16, B4)]
}

fn assumed(body: &crate::mesh::Body) -> CellValues {
    CellValues::new(body).unwrap().with_assumed_shear(body)
}

fn force(geom: &CellValues, mat: &Material, u: &[f64]) -> Vec<f64> {
    let committed = vec![PointState::default(); geom.gp_per_element()];
    kernel(geom, mat, u, &committed, Kinematics::Linear, None).ws.force
}

/// The tangent is the derivative of the internal force, elastic and at a
/// state where part of the element yields (the assumed strain enters the
/// material's strain, the force and both columns of the operator: dropping
/// it from any one of them fails this), on a distorted element.
#[test]
fn assumed_shear_tangent_matches_finite_difference() {
    for (sk, bk) in kinds() {
        let body = single_element_body(sk, bk);
        let geom = assumed(&body);
        let committed = vec![PointState::default(); geom.gp_per_element()];
        // cross-wall bending (u_z ∝ x³) plus axial bending and noise
        let u = field(&body, &|[x, y, z]| {
            [
                -3.0 * x * x * (z - 0.005) * 40.0 + 3e-3 * y * z / 0.01,
                -2e-3 * (z - 0.005) + 1e-3 * x * y,
                400.0 * x * x * x,
            ]
        });
        for mat in [
            Material::new("m", 70e9, 0.3, None),
            Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 })),
        ] {
            let run = kernel(&geom, &mat, &u, &committed, Kinematics::Linear, None);
            if mat.is_plastic() {
                assert!(run.stats.plastic_points > 0, "{sk:?} × {bk:?}: the state yields");
            }
            let worst = difference_error(&run.ws.tangent, &u, 1e-9, |u| force(&geom, &mat, u));
            assert!(worst < 1e-6, "{sk:?} × {bk:?}: relative tangent error {worst:e} (plastic: {})", mat.is_plastic());
        }
    }
}

/// Patch test: on a distorted straight-sided element a linear displacement
/// (constant strain) gives exactly the standard element's force — its
/// covariant shear is bilinear there and the tying interpolation
/// reproduces it; the change does no work under a constant stress (`m`
/// from the element's centre: with `m` at each point the force differs by
/// 3e-4 of its largest entry on this element) — while a field whose
/// in-section shear is cubic (`γ_xz = x³`, beyond both interpolations) does not.
#[test]
fn assumed_shear_passes_the_patch_test() {
    let mat = Material::new("m", 70e9, 0.3, None);
    for (sk, bk) in kinds() {
        let body = single_element_body(sk, bk);
        let (standard, geom) = (CellValues::new(&body).unwrap(), assumed(&body));
        let a = [[1e-3, -2e-3, 3e-3], [0.5e-3, 2e-3, -1e-3], [-4e-3, 1e-3, 2.5e-3]];
        let linear =
            field(&body, &|x| std::array::from_fn(|i| 1e-4 + a[i][0] * x[0] + a[i][1] * x[1] + a[i][2] * x[2]));
        let (f0, f1) = (force(&standard, &mat, &linear), force(&geom, &mat, &linear));
        let fmax = f0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = f0.iter().zip(&f1).fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        assert!(worst < 1e-10 * fmax, "{sk:?} × {bk:?}: constant strain changed by {worst:e} of {fmax:e}");
        let shear = field(&body, &|[x, _, z]| [z * x * x * x * 1e4, 0.0, 0.0]);
        let (g0, g1) = (force(&standard, &mat, &shear), force(&geom, &mat, &shear));
        let gmax = g0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let moved = g0.iter().zip(&g1).fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        assert!(moved > 1e-3 * gmax, "{sk:?} × {bk:?}: a cubic shear is not changed ({moved:e})");
    }
}

/// Zero-energy modes: the elastic stiffness of one free element has exactly
/// the six rigid-body modes, as the fully integrated element — where
/// integrating the in-section strains at the `p × p` points would give 8
/// (L9 × B2) to 16 (L9/L16 × B4) more (bench/section_zero_modes.py).
#[test]
fn assumed_shear_has_only_the_rigid_modes() {
    let mat = Material::new("m", 70e9, 0.3, None);
    for (sk, bk) in kinds() {
        let body = single_element_body(sk, bk);
        let geom = assumed(&body);
        let n = 3 * body.nodes_per_element();
        let committed = vec![PointState::default(); geom.gp_per_element()];
        let k = kernel(&geom, &mat, &vec![0.0; n], &committed, Kinematics::Linear, None).ws.tangent;
        let full = faer::Mat::from_fn(n, n, |i, j| if i <= j { k[i * n + j] } else { k[j * n + i] });
        let lambda = full.self_adjoint_eigenvalues(faer::Side::Upper).unwrap();
        let largest = lambda.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let zero = lambda.iter().filter(|v| v.abs() < 1e-9 * largest).count();
        assert_eq!(zero, 6, "{sk:?} × {bk:?}: zero-energy modes");
        assert!(lambda.iter().all(|&v| v > -1e-9 * largest), "{sk:?} × {bk:?}: a negative eigenvalue");
    }
}

/// The displacement that turns `deform`'s placement `x + d(x)` by `r`
/// about the point `(0, 0.1, 0)`.
fn turned(r: [[f64; 3]; 3], deform: impl Fn([f64; 3]) -> [f64; 3]) -> impl Fn([f64; 3]) -> [f64; 3] {
    move |x: [f64; 3]| {
        let d = deform(x);
        let p = [x[0] + d[0], x[1] + d[1] - 0.1, x[2] + d[2]];
        std::array::from_fn(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] + [0.0, 0.1, 0.0][i] - x[i])
    }
}

/// Cross-wall bending (`u_z ∝ x³`, the strain the tying changes) with
/// axial bending, stretch and shear.
fn bent([x, y, z]: [f64; 3]) -> [f64; 3] {
    [
        -3.0 * x * x * (z - 0.005) * 40.0 + 3e-3 * y * z / 0.01 + 2e-3 * x,
        -2e-3 * (z - 0.005) + 1e-3 * x * y,
        400.0 * x * x * x + 1e-3 * z,
    ]
}

const GL: Kinematics = Kinematics::TotalLagrangian;

fn large_force(geom: &CellValues, mat: &Material, u: &[f64], committed: &[PointState]) -> Vec<f64> {
    kernel(geom, mat, u, committed, GL, None).ws.force
}

/// At finite strain the tangent is the derivative of the internal force
/// within 1e-6 (relative to its largest entry) at states turned by 90° and
/// 180° about an oblique axis, elastic and yielding, on a distorted
/// element: the assumed strain's quadratic part, its variation `D` and its
/// curvature `G` (`crate::values::AssumedShear`) each enter — leaving any
/// one out of the tangent fails (tried: without `G` 1.8e-3, without
/// `Z Aᵀ + A Zᵀ` 3e-2, without the quadratic part 3.7e-3).
#[test]
fn assumed_shear_tangent_matches_finite_difference_at_large_rotations() {
    for (sk, bk) in kinds() {
        let body = single_element_body(sk, bk);
        let geom = assumed(&body);
        let committed = vec![PointState::default(); geom.gp_per_element()];
        for angle in [0.5 * std::f64::consts::PI, std::f64::consts::PI] {
            let u = field(&body, &turned(rotation([0.3, 1.0, 0.5], angle), bent));
            for mat in [
                Material::new("m", 70e9, 0.3, None),
                Material::new("m", 70e9, 0.3, Some(Hardening::Linear { yield_stress: 100e6, modulus: 2e9 })),
            ] {
                let run = kernel(&geom, &mat, &u, &committed, GL, None);
                if mat.is_plastic() {
                    assert!(run.stats.plastic_points > 0, "{sk:?} × {bk:?}: the state yields");
                }
                let worst = difference_error(&run.ws.tangent, &u, 1e-9, |u| large_force(&geom, &mat, u, &committed));
                assert!(worst < 1e-6, "{sk:?} × {bk:?} at {angle}: relative tangent error {worst:e}");
            }
        }
    }
}

/// The patch test at finite strain: a homogeneous deformation (a stretch
/// and shear of a few percent turned by 120°) gives exactly the standard
/// element's force on the distorted element — its covariant Green–Lagrange
/// shear is bilinear there and the tying reproduces it — while the bent
/// field's force moves by more than a thousandth. And the change is
/// objective: the bent field turned rigidly gives the turned force.
#[test]
fn assumed_shear_passes_the_patch_test_at_finite_strain() {
    let mat = Material::new("m", 70e9, 0.3, None);
    let r = rotation([1.0, -0.4, 0.7], 2.1);
    let a = [[0.03, -0.02, 0.05], [0.01, 0.04, -0.02], [-0.03, 0.02, 0.025]];
    let homogeneous =
        |x: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| a[i][0] * x[0] + a[i][1] * x[1] + a[i][2] * x[2]) };
    for (sk, bk) in kinds() {
        let body = single_element_body(sk, bk);
        let (standard, geom) = (CellValues::new(&body).unwrap(), assumed(&body));
        let committed = vec![PointState::default(); geom.gp_per_element()];
        let u = field(&body, &turned(r, homogeneous));
        let (f0, f1) = (large_force(&standard, &mat, &u, &committed), large_force(&geom, &mat, &u, &committed));
        let fmax = f0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = f0.iter().zip(&f1).fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        assert!(worst < 1e-10 * fmax, "{sk:?} × {bk:?}: a homogeneous deformation changed by {worst:e} of {fmax:e}");
        let u = field(&body, &bent);
        let (g0, g1) = (large_force(&standard, &mat, &u, &committed), large_force(&geom, &mat, &u, &committed));
        let gmax = g0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let moved = g0.iter().zip(&g1).fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        assert!(moved > 1e-3 * gmax, "{sk:?} × {bk:?}: the bent field is not changed ({moved:e} of {gmax:e})");
        // objectivity: f(R ∘ bent) = R f(bent)
        let turned_force = large_force(&geom, &mat, &field(&body, &turned(r, bent)), &committed);
        for (a, (f, t)) in g1.chunks_exact(3).zip(turned_force.chunks_exact(3)).enumerate() {
            for i in 0..3 {
                let expected = r[i][0] * f[0] + r[i][1] * f[1] + r[i][2] * f[2];
                assert!((t[i] - expected).abs() < 1e-8 * gmax, "{sk:?} × {bk:?}: node {a} component {i}");
            }
        }
    }
}

/// Under a displacement a millionth of the bent field's the finite-strain
/// kernel's force is the small-strain assumed kernel's to 1e-5, and at
/// zero displacement its tangent is the small-strain one to round-off:
/// the linear part of the change is the small strain's.
#[test]
fn assumed_shear_at_finite_strain_starts_as_the_small_strain_one() {
    let mat = Material::new("m", 70e9, 0.3, None);
    for (sk, bk) in kinds() {
        let body = single_element_body(sk, bk);
        let geom = assumed(&body);
        let committed = vec![PointState::default(); geom.gp_per_element()];
        let u: Vec<f64> = field(&body, &bent).iter().map(|x| 1e-6 * x).collect();
        let (fl, fg) = (force(&geom, &mat, &u), large_force(&geom, &mat, &u, &committed));
        let fmax = fl.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = fl.iter().zip(&fg).fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        assert!(worst < 1e-5 * fmax, "{sk:?} × {bk:?}: {worst:e} of {fmax:e}");
        let zero = vec![0.0; u.len()];
        let kl = kernel(&geom, &mat, &zero, &committed, Kinematics::Linear, None).ws.tangent;
        let kg = kernel(&geom, &mat, &zero, &committed, GL, None).ws.tangent;
        let n = u.len();
        let kmax = kl.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for p in 0..n {
            for q in p..n {
                assert!((kl[p * n + q] - kg[p * n + q]).abs() < 1e-12 * kmax, "{sk:?} × {bk:?}: ({p}, {q})");
            }
        }
    }
}

/// The geometric term's stress after a linear step `δ` (`linearized`) is
/// the stress at `u − δ` continued linearly along `δ`: exact for an
/// elastic point since `Ē`, the assumed shear's change included, is
/// quadratic in `u` — so the change's quadratic part must enter the
/// step's strain (without it this fails at the first point).
#[test]
fn assumed_shear_linearizes_the_geometric_stress_along_the_step() {
    let mat = Material::new("m", 70e9, 0.3, None);
    let body = single_element_body(crate::shape::SectionElementKind::L9, crate::shape::BeamElementKind::B3);
    let geom = assumed(&body);
    let n_gp = geom.gp_per_element();
    let committed = vec![PointState::default(); n_gp];
    let u = field(&body, &turned(rotation([0.3, 1.0, 0.5], 0.8), bent));
    let delta: Vec<f64> = field(&body, &turned(rotation([1.0, 0.2, -0.5], 0.3), |x| bent(x).map(|v| -0.5 * v)));
    let at = |u: &[f64], step: Option<&[f64]>| -> Vec<Voigt> {
        let (mut trial, mut stress) = (vec![PointState::default(); n_gp], vec![[0.0; 6]; n_gp]);
        let mut ws = Workspace::default();
        let points = PointData {
            committed: &committed,
            trial: &mut trial,
            stress: &mut stress,
            predictor: Predictor::Loading,
            kinematics: GL,
            initial: None,
            step,
            damage: None,
        };
        element_response(&geom, 0, 1, u, &mat, points, TangentMode::Always, &mut ws);
        ws.pk2[..n_gp].to_vec()
    };
    let linearized = at(&u, Some(&delta));
    let shifted = |s: f64| -> Vec<f64> { u.iter().zip(&delta).map(|(u, d)| u - d + s * d).collect() };
    let (s0, sp, sm) = (at(&shifted(0.0), None), at(&shifted(1e-3), None), at(&shifted(-1e-3), None));
    let smax = s0.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    for q in 0..n_gp {
        for i in 0..6 {
            let expected = s0[q][i] + (sp[q][i] - sm[q][i]) / 2e-3;
            assert!((linearized[q][i] - expected).abs() < 1e-9 * smax, "point {q} component {i}");
        }
    }
}
