//! The assumed in-section shear strain (`formulation = "assumed_shear"`,
//! crate::values::AssumedShear) against cross-wall bending locking: a wall
//! of the section bending in the section plane, one element across its
//! width, against plate theory.

mod common;

use common::figure;
use cufem::analysis::{self, Silent};
use cufem::setup::Model;

/// A 100 × 3 mm wall (x × z), 0.3 m along y, clamped along its edge x = 0,
/// a line load `q` along z on the edge x = 0.1; u_y fixed on the two end
/// faces, so the state is one of plane strain (cylindrical bending);
/// `ratio` grades the division along x (`", ratio = 20.0"`, or empty).
fn wall(element: &str, along: usize, through: usize, formulation: &str, ratio: &str) -> String {
    format!(
        r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
[[bodies]]
name = "wall"
material = "steel"
formulation = "{formulation}"
section = {{ shape = "rectangle", element = "{element}", x = {{ from = 0.0, to = 0.1, elements = {along}{ratio} }}, z = {{ from = 0.0, to = 0.003, elements = {through} }} }}
axis = {{ element = "B4", from = 0.0, to = 0.3, elements = 2 }}
[[constraints]]
name = "edge"
body = "wall"
where = {{ x = 0.0 }}
fix = ["x", "y", "z"]
[[constraints]]
name = "end0"
body = "wall"
where = {{ y = 0.0 }}
fix = ["y"]
[[constraints]]
name = "end1"
body = "wall"
where = {{ y = 0.3 }}
fix = ["y"]
[[loads]]
name = "line"
body = "wall"
where = {{ x = 0.1 }}
total_force = [0.0, 0.0, -30.0]
"#
    )
}

/// Deflection of the loaded edge's mid-plane at mid-length.
fn deflection(text: &str) -> f64 {
    let model = Model::parse(text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    -sol.fields(&model).sample_point(None, [0.1, 0.15, 0.0015]).unwrap().u[2]
}

/// Timoshenko's cantilever in cylindrical bending (plane strain): `w = q b³
/// / (3 D) + q b / (κ G t)` with `D = E t³ / (12 (1 − ν²))`, κ = 5/6, q =
/// 100 N/m. The clamp's corners are singular: on uniform divisions along x
/// every element kind converges as h there (L16: −4.0/−2.0/−1.0/−0.5 % at
/// 1/2/4/8 elements), so the meshes here are graded towards the clamp
/// (last/first element 20), where the standard L9 mesh converges to within
/// 1 % of the theory. Two L9 along the 100 mm (the outer one 95 mm long,
/// aspect 32): the standard element locks in the wall's bending, −21.7 %
/// (the parasitic in-section shear; bench/section_locking.py strip); the
/// assumed shear −0.36 %; four: −7.2 % and −0.24 %.
#[test]
fn assumed_shear_removes_cross_wall_bending_locking() {
    let (e, nu, b, t, q) = (200e9f64, 0.3f64, 0.1f64, 0.003f64, 100.0f64);
    let d = e * t.powi(3) / (12.0 * (1.0 - nu * nu));
    let g = e / (2.0 * (1.0 + nu));
    let theory = q * b.powi(3) / (3.0 * d) + q * b / (5.0 / 6.0 * g * t);
    let err = |w: f64| (w - theory) / theory;
    let graded = ", ratio = 20.0";
    let refined = err(deflection(&wall("L9", 16, 1, "standard", graded)));
    figure(
        "assumed_shear.wall.reference",
        100.0 * refined,
        "%",
        "|·| < 1 % against Timoshenko's plane-strain cantilever",
    );
    assert!(refined.abs() < 0.01, "the reference mesh: {:+.2} %", 100.0 * refined);
    for (along, locked) in [(2, 0.15), (4, 0.05)] {
        let standard = err(deflection(&wall("L9", along, 1, "standard", graded)));
        let assumed = err(deflection(&wall("L9", along, 1, "assumed_shear", graded)));
        figure(
            &format!("assumed_shear.wall.{along}.standard"),
            100.0 * standard,
            "%",
            &format!("below −{} %", 100.0 * locked),
        );
        figure(&format!("assumed_shear.wall.{along}.assumed"), 100.0 * assumed, "%", "|·| < 1 %");
        assert!(standard < -locked, "{along} L9: the standard element locks ({:+.2} %)", 100.0 * standard);
        assert!(assumed.abs() < 0.01, "{along} L9: assumed shear {:+.2} %", 100.0 * assumed);
    }
}

/// What the formulation is not made for is refused with the key, the value
/// and what is allowed: L4 sections (one tying point would fail the patch
/// test), and at finite strain the logarithmic strain (the tying is of the
/// Green–Lagrange strain) and an imperfection; nonlinear geometry with the
/// Green–Lagrange strain is taken.
#[test]
fn assumed_shear_refuses_l4_and_the_logarithmic_strain() {
    let l4 = wall("L4", 2, 1, "assumed_shear", "");
    let e = Model::parse(&l4).map(drop).expect_err("L4 refused").to_string();
    assert!(e.contains("bodies[0].formulation") && e.contains("L4") && e.contains("L9 or L16"), "{e}");
    let nonlinear = format!("[analysis]\ngeometry = \"nonlinear\"\n{}", wall("L9", 2, 1, "assumed_shear", ""));
    Model::parse(&nonlinear).expect("nonlinear geometry with the Green–Lagrange strain");
    let log = nonlinear.replace("geometry = \"nonlinear\"", "geometry = \"nonlinear\"\nstrain = \"logarithmic\"");
    let e = Model::parse(&log).map(drop).expect_err("the logarithmic strain refused").to_string();
    assert!(e.contains("bodies[0].formulation") && e.contains("logarithmic") && e.contains("Green–Lagrange"), "{e}");
    // a stress-free imperfection is not tied (the column of examples/column_postbuckling.toml, L9)
    let column = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/column_postbuckling.toml"))
        .unwrap()
        .replacen("[[bodies]]\n", "[[bodies]]\nformulation = \"assumed_shear\"\n", 1);
    let e = Model::parse(&column).map(drop).expect_err("an imperfection refused").to_string();
    assert!(e.contains("bodies[0].formulation") && e.contains("analysis.imperfection"), "{e}");
}
