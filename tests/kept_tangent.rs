//! A tangent kept from one evaluation to the next where every part's
//! stiffness is unchanged (`analysis::structure::evaluation`, a constant
//! tangent): elements of a plastic material in small strain while every
//! Gauss point stays on its elastic tangent. Kept at an elastic state after
//! yielding it is the elastic stiffness; at a state where points yield
//! again it must not be: `NonlinearProblem::evaluate` forms the
//! elastoplastic tangent there (checked against central differences), while
//! Newton's `evaluate_for_correction` keeps the elastic one for that one
//! correction and the evaluation after it forms theirs.

use cufem::analysis::Structure;
use cufem::setup::Model;
use cufem::solver::newton::NonlinearProblem;
use cufem::solver::stepping::Incremental;

mod common;

/// A steel column (`20 × 20` mm, `1` m) clamped at `y = 0`, yielding at
/// `250` MPa with hardening.
fn column() -> Model {
    let material = r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
plasticity = { yield_stress = 250e6, hardening = "table", table = [[0.0, 250e6], [0.1, 450e6]] }
"#;
    let text = common::clamped_column("", material, [0.01, 0.01], 1, 4, "total_force = [0.0, 0.0, 0.0]", "");
    Model::parse(&text).unwrap()
}

/// Pure bending about z of curvature `2 c`: `u_x = c y²`, `u_y = −2 c x y`
/// (the axial strain `−2 c x`, no shear), at every node.
fn bend(s: &mut Structure<'_>, model: &Model, c: f64) {
    for n in 0..model.mesh.n_nodes() {
        let [x, y, _] = model.mesh.coords(n);
        let u = s.displacements_mut();
        u[3 * n] = c * y * y;
        u[3 * n + 1] = -2.0 * c * x * y;
        u[3 * n + 2] = 0.0;
    }
}

/// Central differences of the residual against the tangent at the present
/// state, over a few columns of the outer fibres' axial DOFs (relative to
/// the largest tangent entry).
fn difference(s: &mut Structure<'_>, model: &Model) -> f64 {
    let columns: Vec<(usize, usize)> = (0..model.mesh.n_nodes())
        .filter(|&n| model.mesh.coords(n)[0].abs() > 0.009 && model.mesh.coords(n)[1] < 0.3)
        .filter_map(|n| s.equation(3 * n + 1).map(|e| (3 * n + 1, e)))
        .take(4)
        .collect();
    assert_eq!(columns.len(), 4);
    let scale = s.tangent_values().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    common::tangent_vs_differences(s, &columns, 1e-9, scale).0
}

#[test]
fn a_kept_elastic_tangent_gives_way_where_points_yield_again() {
    let model = column();
    let mut s = Structure::of_model(&model, None).unwrap();
    // yield the outer fibres (strain 2.5e-3, twice the yield strain), commit
    let c = 0.125;
    bend(&mut s, &model, c);
    s.evaluate().unwrap();
    assert!(s.plastic_points() > 0);
    Incremental::commit(&mut s);
    // unload elastically: the elastic stiffness, formed, then kept
    bend(&mut s, &model, 0.9 * c);
    s.evaluate().unwrap();
    assert_eq!(s.plastic_points(), 0);
    let elastic = s.tangent_values().to_vec();
    bend(&mut s, &model, 0.8 * c);
    s.evaluate().unwrap();
    assert_eq!(s.tangent_values(), elastic, "unloaded further: the same tangent");
    let unloaded = difference(&mut s, &model);
    assert!(unloaded < 1e-6, "the kept tangent against differences at an elastic state: {unloaded:e}");
    // reload past the committed state: points yield, and the tangent is theirs
    bend(&mut s, &model, 1.1 * c);
    s.evaluate().unwrap();
    assert!(s.plastic_points() > 0);
    let softer = s.tangent_values().iter().zip(&elastic).filter(|(a, b)| a != b).count();
    assert!(softer > 0, "the elastoplastic tangent was formed");
    let reloaded = difference(&mut s, &model);
    assert!(reloaded < 1e-6, "the tangent against differences where points yield: {reloaded:e}");
    // formed where points yield, it is not kept at the elastic state after
    // (reached here by an evaluation without the tangent, as Newton's last)
    bend(&mut s, &model, 0.9 * c);
    s.evaluate_residual().unwrap();
    s.evaluate().unwrap();
    assert_eq!(s.plastic_points(), 0);
    assert_eq!(s.tangent_values(), elastic, "the elastic stiffness again");
    // Newton's evaluation from an elastic state into yield keeps the elastic
    // stiffness for one correction; the next evaluation forms the tangent
    bend(&mut s, &model, 1.1 * c);
    s.evaluate_for_correction().unwrap();
    assert!(s.plastic_points() > 0);
    assert_eq!(s.tangent_values(), elastic, "the elastic stiffness for this correction");
    s.evaluate_for_correction().unwrap();
    assert!(s.tangent_values() != elastic, "formed at the next evaluation");
    assert!(difference(&mut s, &model) < 1e-6);
}
