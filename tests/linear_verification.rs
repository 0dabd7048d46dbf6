//! Verification of the linear CUF solver against exact and beam-theory
//! solutions (issue #2).

use cufem::analysis::{self, Silent};
use cufem::bc::Constraint;
use cufem::setup::Model;

mod common;

/// A distorted section of four quads (moved interior point and skewed
/// outer corners), element type `sk`, swept along 3 beam elements of type `bk`.
fn distorted_block(sk: &str, bk: &str) -> String {
    format!(
        r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "block"
material = "steel"
axis = {{ element = "{bk}", lines = [0.0, 0.013, 0.031, 0.05] }}
[bodies.section]
shape = "quads"
element = "{sk}"
points = [[0.0, 0.0], [0.011, 0.001], [0.02, 0.0], [-0.001, 0.012], [0.0087, 0.0114], [0.021, 0.009], [0.001, 0.02], [0.01, 0.022], [0.019, 0.02]]
quads = [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]]

# replaced by the test with the patch's boundary values
[[constraints]]
name = "placeholder"
body = "block"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]
"#
    )
}

/// An arbitrary linear displacement field `u = a + B x`.
fn linear_field(x: [f64; 3]) -> [f64; 3] {
    let a = [1e-5, -2e-5, 3e-5];
    let b = [[1e-3, -4e-4, 2e-4], [3e-4, -8e-4, 5e-4], [-6e-4, 7e-4, 9e-4]];
    [0, 1, 2].map(|i| a[i] + (0..3).map(|j| b[i][j] * x[j]).sum::<f64>())
}

/// Patch test: the linear field imposed on every boundary node is reproduced
/// at interior nodes and interior points to round-off, with a constant strain
/// equal to the field's symmetric gradient.
#[test]
fn patch_test_distorted_sections_all_beam_types() {
    let mut largest: f64 = 0.0;
    for sk in ["L9", "L16"] {
        for bk in ["B2", "B3", "B4"] {
            let mut model = Model::parse(&distorted_block(sk, bk)).unwrap();
            let body = &model.mesh.bodies[0];
            let boundary: std::collections::BTreeSet<usize> =
                cufem::bc::boundary_faces(body).iter().flat_map(|f| cufem::bc::integrate_face(body, f).nodes).collect();
            let interior = body.n_nodes() - boundary.len();
            assert!(interior > 0, "{sk}{bk}: the patch needs interior nodes");
            let constraints: Vec<Constraint> = boundary
                .iter()
                .map(|&n| Constraint {
                    name: format!("n{n}"),
                    body: 0,
                    nodes: vec![n],
                    values: linear_field(model.mesh.coords(n)).map(Some),
                    selection: None,
                })
                .collect();
            model.set_constraints(constraints);
            let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
            let scale = 3e-5; // largest constant term of the field (m)
            let mut worst: f64 = 0.0;
            for n in 0..model.mesh.n_nodes() {
                let exact = linear_field(model.mesh.coords(n));
                for k in 0..3 {
                    worst = worst.max((sol.u[3 * n + k] - exact[k]).abs() / scale);
                }
            }
            largest = largest.max(worst);
            // issue #2 asks for 1e-10 relative; observed ≤ 6e-15 (round-off)
            assert!(worst < 1e-10, "{sk}{bk}: nodal error {worst:e}");
            // strain at interior points is the symmetric gradient
            let view = sol.fields(&model);
            let s = view.sample_point(None, [0.0093, 0.022, 0.0101]).unwrap();
            let exact = [1e-3, -8e-4, 9e-4, -4e-4 + 3e-4, 2e-4 - 6e-4, 5e-4 + 7e-4];
            for k in 0..6 {
                assert!(
                    (s.strain[k] - exact[k]).abs() < 1e-10 * 1e-3,
                    "{sk}{bk}: strain {k}: {} vs {}",
                    s.strain[k],
                    exact[k]
                );
            }
        }
    }
    // issue #2 asks for 1e-10 relative
    common::figure("linear.patch.nodal_error", largest, "", "< 1e-10 of the field at every node (issue 2)");
}

fn cantilever(nx: usize, ny: usize) -> String {
    format!(
        r#"
[[materials]]
name = "al"
young_modulus = 70e9
poisson_ratio = 0.3
[[bodies]]
name = "beam"
material = "al"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.1, elements = {nx} }}, z = {{ from = 0.0, to = 0.1, elements = {nx} }} }}
axis = {{ element = "B4", from = 0.0, to = 1.0, elements = {ny} }}
[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]
[[loads]]
name = "tip"
body = "beam"
where = {{ y = 1.0 }}
total_force = [0.0, 0.0, -1000.0]
"#
    )
}

/// Tip deflection of the section centroid.
fn tip_deflection(text: &str, point: [f64; 3]) -> (f64, Model, analysis::Solution) {
    let model = Model::parse(text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let uz = sol.fields(&model).sample_point(None, point).unwrap().u[2];
    (uz, model, sol)
}

/// Timoshenko: δ = P L³/(3 E I) + P L/(κ G A), κ = 5/6, for L = 1 m,
/// 0.1 × 0.1 m, E = 70 GPa, ν = 0.3, P = 1 kN: 5.759e-4 m.
#[test]
fn cantilever_tip_deflection_matches_timoshenko_and_converges() {
    let (e, nu, p, l, b) = (70e9, 0.3, 1000.0, 1.0f64, 0.1f64);
    let i = b.powi(4) / 12.0;
    let g = e / (2.0 * (1.0 + nu));
    let exact = p * l.powi(3) / (3.0 * e * i) + p * l / (5.0 / 6.0 * g * b * b);
    assert!((exact - 5.759e-4).abs() < 5e-8);
    let mut errors = Vec::new();
    for (nx, ny, id) in [(1, 2, "1x1_2B4"), (2, 5, "2x2_5B4"), (4, 10, "4x4_10B4")] {
        let (uz, model, sol) = tip_deflection(&cantilever(nx, ny), [0.05, 1.0, 0.05]);
        let err = (-uz - exact).abs() / exact;
        errors.push(err);
        let id = format!("linear.cantilever.{id}");
        if nx == 2 {
            common::within(&id, -uz, exact, 0.02, "Timoshenko, κ = 5/6");
        } else {
            common::figure(&id, 100.0 * (-uz / exact - 1.0), "%", "against Timoshenko; falls under refinement");
        }
        // reactions balance the applied load (internal forces sum to zero)
        let r = sol.reaction("root").unwrap().force;
        let applied = model.loads[0].resultant();
        for k in 0..3 {
            assert!((r[k] + applied[k]).abs() < 1e-9 * 1000.0, "reaction {k}: {} vs {}", r[k], applied[k]);
        }
    }
    // approaching the beam solution under refinement
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
}

/// Thin-walled square tube, 30 × 30 × 1.5 mm, L = 1 m (33 × depth), tip
/// load 10 N: Timoshenko with Cowper's shear coefficient for a thin square
/// box, κ = 20(1 + ν)/(48 + 39ν) (Cowper 1966).
#[test]
fn thin_walled_tube_cantilever_matches_timoshenko() {
    let text = r#"
[[materials]]
name = "al"
young_modulus = 70e9
poisson_ratio = 0.3
[[bodies]]
name = "tube"
material = "al"
section = { shape = "tube", element = "L9", width = 0.03, height = 0.03, thickness = 0.0015, around = 20 }
axis = { element = "B4", from = 0.0, to = 1.0, elements = 10 }
[[constraints]]
name = "root"
body = "tube"
where = { y = 0.0 }
fix = ["x", "y", "z"]
[[loads]]
name = "tip"
body = "tube"
where = { y = 1.0 }
total_force = [0.0, 0.0, -10.0]
"#;
    let (e, nu, p, l) = (70e9, 0.3, 10.0, 1.0f64);
    let (bo, bi) = (0.03f64, 0.027f64);
    let i = (bo.powi(4) - bi.powi(4)) / 12.0;
    let area = bo * bo - bi * bi;
    let kappa = 20.0 * (1.0 + nu) / (48.0 + 39.0 * nu);
    let g = e / (2.0 * (1.0 + nu));
    let exact = p * l.powi(3) / (3.0 * e * i) + p * l / (kappa * g * area);
    // mean of the tip deflection at the mid-wall points of the four walls
    let model = Model::parse(text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let view = sol.fields(&model);
    let pts = [[0.015, 1.0, 0.00075], [0.015, 1.0, 0.02925], [0.00075, 1.0, 0.015], [0.02925, 1.0, 0.015]];
    let uz: f64 = pts.iter().map(|&x| view.sample_point(None, x).unwrap().u[2]).sum::<f64>() / 4.0;
    // issue #2 asks for 3 %
    common::within("linear.tube.tip", -uz, exact, 0.03, "Timoshenko with Cowper's κ");
}
