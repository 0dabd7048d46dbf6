//! Cohesive interfaces between plies (issue 48, `src/interfaces`): the
//! patch test (a uniform normal traction crosses an interface exactly: the
//! nodal areas are ∫N), the tangent of the interface points against central
//! differences in every branch of the law, face selections at an
//! interface, and the model keys' errors.

mod common;

use cufem::analysis::Structure;
use cufem::setup::Model;
use cufem::solver::newton::NonlinearProblem;

/// Two isotropic plies (E = 1 GPa, ν = 0.3) of 1 mm over a 4 mm width and
/// 20 mm along y, their interface cohesive (K = 50 E/t = 5e13 Pa/m by
/// default; N = 10 MPa, G_Ic = 100 J/m²: δ0 = 2e-7 m, δf = 2e-5 m), with
/// `extra` appended.
fn laminate(element: &str, beam: &str, extra: &str) -> String {
    format!(
        r#"
[[materials]]
name = "ply"
young_modulus = 1e9
poisson_ratio = 0.3

[[materials]]
name = "glue"
cohesive = {{ gic = 100.0, giic = 200.0, bk_exponent = 2.0, normal_strength = 10e6 }}

[[bodies]]
name = "stack"
section = {{ shape = "laminate", element = "{element}", x = {{ from = 0.0, to = 0.004, elements = 2 }}, plies = [
  {{ thickness = 0.001, material = "ply" }}, {{ thickness = 0.001, material = "ply" }} ], interfaces = "cohesive", interface_material = "glue" }}
axis = {{ element = "{beam}", from = 0.0, to = 0.02, elements = 3 }}
{extra}
"#
    )
}

/// Roller supports on three faces (z = 0, x = 0, y = 0) and a uniform
/// traction q on the top face: the stress is σ_zz = q everywhere.
const PULLED: &str = r#"
[[constraints]]
name = "bottom"
body = "stack"
where = { z = 0.0 }
fix = ["z"]

[[constraints]]
name = "side"
body = "stack"
where = { x = 0.0 }
fix = ["x"]

[[constraints]]
name = "end"
body = "stack"
where = { y = 0.0 }
fix = ["y"]

[[loads]]
name = "pull"
body = "stack"
where = { z = 0.002 }
traction = [0.0, 0.0, 1e6]
"#;

/// The patch test: under a uniform traction q = 1 MPa (a tenth of the
/// onset traction: elastic) every interface point opens by exactly q/K and
/// does not slide, and the points' areas add up to the interface's, for
/// quadratic and cubic elements (Newton–Cotes weights 1/6, 4/6, 1/6 and
/// 1/8, 3/8, 3/8, 1/8) and bilinear ones. Measured: 8.9e-13 at worst
/// (round-off); asserted 1e-9.
#[test]
fn a_uniform_traction_crosses_the_interface_exactly() {
    let q = 1e6;
    for (element, beam) in [("L9", "B3"), ("L16", "B4"), ("L4", "B2")] {
        let model = Model::parse(&laminate(element, beam, PULLED)).unwrap();
        let sol = common::run(&laminate(element, beam, PULLED));
        let interface = &model.interfaces[0];
        let k = interface.law.penalty;
        assert!((k - 50.0 * 1e9 / 0.001).abs() < 1e-3 * k, "default penalty {k}");
        let area: f64 = interface.points.iter().map(|p| p.area).sum();
        assert!((area - 0.004 * 0.02).abs() < 1e-15, "{element}: area {area}");
        let mut worst: f64 = 0.0;
        for p in &interface.points {
            let d: Vec<f64> = (0..3).map(|c| sol.u[3 * p.upper + c] - sol.u[3 * p.lower + c]).collect();
            worst = worst.max((d[2] * k / q - 1.0).abs()).max(d[0].abs() * k / q).max(d[1].abs() * k / q);
        }
        eprintln!("{element}×{beam}: {} points, largest deviation from δ3 = q/K {worst:.1e}", interface.points.len());
        assert!(worst < 1e-9, "{element}: {worst}");
    }
}

/// The structure's tangent against central differences of its residual
/// (h = 1e-11 m) in the columns of interface nodes, with the interface
/// opened by δ3 = −1e-6, 1e-7, 5e-6, 3e-5 m at successive beam nodes:
/// closing, elastic, softening (the consistent tangent) and fully separated
/// points at once,
/// from an intact committed state. Measured 1.8e-11 of the largest entry;
/// asserted 1e-6.
#[test]
fn interface_tangent_matches_central_differences() {
    let model = Model::parse(&laminate(
        "L9",
        "B3",
        "[[constraints]]\nname = \"end\"\nbody = \"stack\"\nwhere = { y = 0.0 }\nfix = [\"x\", \"y\", \"z\"]\n",
    ))
    .unwrap();
    let mut s = Structure::of_model(&model, None).unwrap();
    let interface = &model.interfaces[0];
    // beam node by beam node: closing, elastic, softening, separated
    let opening = |y: f64| [-1e-6, 1e-7, 5e-6, 3e-5][(y / (0.02 / 6.0)).round() as usize % 4];
    let mut branches = [0usize; 4];
    let (d0, df) = (2e-7, 2e-5);
    for p in &interface.points {
        let d = opening(p.position[1]);
        s.displacements_mut()[3 * p.upper + 2] = 0.5 * d;
        s.displacements_mut()[3 * p.lower + 2] = -0.5 * d;
        branches[if d < 0.0 {
            0
        } else if d < d0 {
            1
        } else if d < df {
            2
        } else {
            3
        }] += 1;
    }
    assert!(branches.iter().all(|&n| n > 0), "every branch: {branches:?}");
    s.evaluate().unwrap();
    let columns: Vec<(usize, usize)> = interface
        .points
        .iter()
        .step_by(3)
        .flat_map(|p| [p.lower, p.upper])
        .flat_map(|n| (0..3).map(move |c| 3 * n + c))
        .filter_map(|d| s.equation(d).map(|e| (d, e)))
        .collect();
    let scale = s.tangent_values().iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let (worst, skew) = common::tangent_vs_differences(&mut s, &columns, 1e-11, scale);
    eprintln!("{} columns, branches {branches:?}: largest difference {worst:.2e}, asymmetry {skew:.1e}", columns.len());
    assert!(worst < 1e-6, "tangent differs from central differences by {worst:e}");
}

/// The step control's damage measure (`solver.step_control.damage`) of
/// the interfaces: from the intact committed state, every point opened in
/// mode I by δ3 = 5e-6 m has the bilinear law's damage
/// `d = δf (δ − δ0) / (δ (δf − δ0))` = `0.9697` (δ0 = 2e-7, δf = 2e-5 m),
/// and that is the largest increment the structure reports; one point more
/// open, at 1e-5 m (`d = 0.9899`), sets it.
#[test]
fn the_damage_measure_is_the_interfaces_largest_damage_increment() {
    use cufem::solver::stepping::Incremental;
    let model = Model::parse(&laminate(
        "L9",
        "B3",
        "[[constraints]]\nname = \"end\"\nbody = \"stack\"\nwhere = { y = 0.0 }\nfix = [\"x\", \"y\", \"z\"]\n",
    ))
    .unwrap();
    let (d0, df) = (2e-7, 2e-5);
    let law = |delta: f64| df * (delta - d0) / (delta * (df - d0));
    let interface = &model.interfaces[0];
    for widest in [5e-6, 1e-5] {
        let mut s = Structure::of_model(&model, None).unwrap();
        for (k, p) in interface.points.iter().enumerate() {
            let delta = if k == 7 { widest } else { 5e-6 };
            s.displacements_mut()[3 * p.upper + 2] = 0.5 * delta;
            s.displacements_mut()[3 * p.lower + 2] = -0.5 * delta;
        }
        s.evaluate().unwrap();
        let measured = s.measure().damage;
        eprintln!("widest opening {widest:e} m: largest damage increment {measured:.6}, law {:.6}", law(widest));
        assert!((measured - law(widest)).abs() < 1e-9, "{measured} against {}", law(widest));
    }
}

/// A face selection at the interface's z finds no face, as in the
/// shared-node laminate: the twin edges are inner surfaces, not two faces
/// of the boundary. A node selection there takes both twins.
#[test]
fn a_selection_at_an_interface_finds_no_face_and_both_twins() {
    let load = "[[loads]]\nname = \"inside\"\nbody = \"stack\"\nwhere = { z = 0.001 }\npressure = 1e5\n";
    let perfect = laminate("L9", "B3", load).replace("interfaces = \"cohesive\", interface_material = \"glue\"", "");
    let shared = Model::parse(&perfect).unwrap_err().to_string();
    let twins = Model::parse(&laminate("L9", "B3", load)).unwrap_err().to_string();
    assert!(shared.contains("loads[0].where"), "{shared}");
    assert_eq!(shared, twins);
    let fixed =
        "[[constraints]]\nname = \"mid\"\nbody = \"stack\"\nwhere = { z = 0.001 }\nfix = [\"x\", \"y\", \"z\"]\n";
    let count = |text: &str| Model::parse(text).unwrap().constraints[0].nodes.len();
    let perfect = laminate("L9", "B3", fixed).replace("interfaces = \"cohesive\", interface_material = \"glue\"", "");
    assert_eq!(count(&laminate("L9", "B3", fixed)), 2 * count(&perfect));
}

/// Each bad key is refused with its key, its value and what is allowed.
#[test]
fn bad_interface_keys_are_refused_by_key() {
    let base = laminate("L9", "B3", PULLED);
    let every = "interfaces = \"cohesive\", interface_material = \"glue\"";
    let glue = "cohesive = { gic = 100.0, giic = 200.0, bk_exponent = 2.0, normal_strength = 10e6 }";
    let cases: Vec<(String, &str, &str)> = vec![
        (base.replace(every, "interfaces = \"glued\""), "glued", "perfect"),
        (base.replace(every, "interfaces = [{ ply = 2, material = \"glue\" }]"), "interfaces[0].ply", "1..=1"),
        (base.replace(every, "interfaces = \"cohesive\""), "interface_material", "(missing)"),
        (
            base.replace(every, "interfaces = \"perfect\", interface_material = \"glue\""),
            "interface_material",
            "given with perfect",
        ),
        (
            base.replace("interface_material = \"glue\"", "interface_material = \"ply\""),
            "interface_material",
            "with cohesive",
        ),
        (
            base.replace(
                "{ thickness = 0.001, material = \"ply\" }, {",
                "{ thickness = 0.001, material = \"glue\" }, {",
            ),
            "plies[0].material",
            "interface material",
        ),
        (
            base.replace(glue, &format!("young_modulus = 1e9\n{glue}")),
            "materials[1].young_modulus",
            "given with cohesive",
        ),
        (base.replace("gic = 100.0", "gic = 0.0"), "materials[1].cohesive.gic", "(0, 1e6]"),
        (base.replace("bk_exponent = 2.0", "bk_exponent = 20.0"), "materials[1].cohesive.bk_exponent", "1e1"),
        (
            base.replace("normal_strength = 10e6 }", "normal_strength = 10e6, penalty = 1e5 }"),
            "materials[1].cohesive.penalty",
            "1e10",
        ),
        (
            base.replace("normal_strength = 10e6", "normal_strength = 1e9"),
            "materials[1].cohesive.normal_strength",
            "penalty",
        ),
        (
            base.replace(every, "interfaces = [{ ply = 1, material = \"glue\", crack = { from = 0.01, to = 0.005 } }]"),
            "interfaces[0].crack.to",
            "above from",
        ),
        (
            base.replace("normal_strength = 10e6 }", "normal_strength = 10e6, viscosity = 2.0 }"),
            "materials[1].cohesive.viscosity",
            "1e0",
        ),
        // the dissipation constraint only with arc length (a viscosity is
        // allowed with arc length: its time is the path's pseudo-time)
        (base.clone() + "\n[solver]\nconstraint = \"dissipation\"\n", "solver.constraint", "arc_length"),
    ];
    for (text, key, allowed) in cases {
        let e = Model::parse(&text).unwrap_err().to_string();
        eprintln!("{e}");
        assert!(e.contains(key) && e.contains(allowed), "expected {key} and {allowed:?} in: {e}");
    }
}
