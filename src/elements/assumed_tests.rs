//! Tests of the assumed in-section shear strain in the kernel
//! ([`crate::values::AssumedShear`]): consistent tangent, patch test, no
//! spurious zero-energy modes.

use super::log_tests::field;
use super::tests::{difference_error, kernel, single_element_body};
use super::*;
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
