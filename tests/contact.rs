//! Verification of the node-to-node penalty contact (issue #4).

mod common;

use cufem::analysis::{self, Silent};
use cufem::setup::Model;

fn two_blocks(penalty: &str) -> String {
    format!(
        r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "lower"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.02, elements = 2 }}, z = {{ from = 0.0, to = 0.01, elements = 2 }} }}
axis = {{ element = "B3", from = 0.0, to = 0.03, elements = 2 }}

[[bodies]]
name = "upper"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.02, elements = 2 }}, z = {{ from = 0.01, to = 0.025, elements = 2 }} }}
axis = {{ element = "B3", from = 0.0, to = 0.03, elements = 2 }}

# rollers: the uniform compression state is exact for both blocks
[[constraints]]
name = "lower_bottom"
body = "lower"
where = {{ z = 0.0 }}
fix = ["z"]
[[constraints]]
name = "lower_x"
body = "lower"
where = {{ x = 0.0 }}
fix = ["x"]
[[constraints]]
name = "lower_y"
body = "lower"
where = {{ y = 0.0 }}
fix = ["y"]
[[constraints]]
name = "upper_x"
body = "upper"
where = {{ x = 0.0 }}
fix = ["x"]
[[constraints]]
name = "upper_y"
body = "upper"
where = {{ y = 0.0 }}
fix = ["y"]

[[loads]]
name = "pressure"
body = "upper"
where = {{ z = 0.025 }}
pressure = 50e6

[[contacts]]
name = "interface"
master = {{ body = "lower", where = {{ z = 0.01 }} }}
slave = {{ body = "upper", where = {{ z = 0.01 }} }}
{penalty}
"#
    )
}

/// Contact patch test: two stacked blocks with matching meshes under a
/// uniform pressure transmit a uniform contact pressure (exact solution:
/// uniaxial compression σ_zz = −p in both blocks), and each node's
/// penetration is its force divided by its penalty.
#[test]
fn contact_patch_test_transmits_uniform_pressure() {
    let p = 50e6;
    // Newton with the default mixed-precision solves stops at its tolerance
    // (relative residual 1e-6): the pressure is uniform to that level
    // (measured 1.2e-8)
    let model = Model::parse(&two_blocks("penalty = 1e16")).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(sol.failure.is_none());
    let points = sol.contact_points("interface").unwrap();
    let worst = points.iter().fold(0.0_f64, |m, c| m.max((c.force[2] / c.area - p).abs() / p));
    common::figure("contact.patch.single_factors", worst, "", "< 1e-6 of the pressure (Newton's tolerance)");
    assert!(worst < 1e-6, "mixed precision: contact pressure deviates by {worst}");
    // issue #4's 1e-8 is about the formulation: with double-precision
    // factors the one linear solve is exact to round-off
    let model =
        Model::parse(&format!("[solver]\nfactor_precision = \"double\"\n{}", two_blocks("penalty = 1e16"))).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(sol.failure.is_none());
    let pairs = &model.contacts[0].pairs;
    assert_eq!(pairs.len(), 5 * 5, "every interface node paired");
    let mut worst: f64 = 0.0;
    for (pair, point) in pairs.iter().zip(sol.contact_points("interface").unwrap()) {
        assert!(point.active);
        let pressure = point.force[2] / point.area;
        worst = worst.max((pressure - p).abs() / p);
        // penetration = force / ε_N (eq. 20), as issue #4 asks: checks that the
        // reported gap and force belong to the same converged state
        assert!((-point.gap - point.force[2] / pair.penalty).abs() < 1e-12 * point.gap.abs());
    }
    // issue #4 asks for 1e-8
    common::figure("contact.patch.double_factors", worst, "", "< 1e-8 of the pressure (issue 4)");
    assert!(worst < 1e-8, "contact pressure deviates by {worst}");
    // the stress inside both blocks is the uniaxial compression
    let view = sol.fields(&model);
    for point in [[0.013, 0.011, 0.004], [0.007, 0.02, 0.018]] {
        let s = view.sample_point(None, point).unwrap();
        assert!((s.stress[2] + p).abs() < 1e-8 * p, "{:?}", s.stress);
        assert!(s.stress[0].abs() < 1e-8 * p && s.stress[1].abs() < 1e-8 * p);
    }
    // contact force balances the applied load and the support reaction
    let applied = 50e6 * 0.02 * 0.03;
    assert!((sol.contact("interface").unwrap().force[2] - applied).abs() < 1e-9 * applied);
    assert!((sol.reaction("lower_bottom").unwrap().force[2] - applied).abs() < 1e-8 * applied);
}

fn punch(extra: &str) -> String {
    format!(
        r#"
[[materials]]
name = "al"
young_modulus = 70e9
poisson_ratio = 0.3

[[bodies]]
name = "block"
material = "al"
section = {{ shape = "rectangle", element = "L9", x = {{ lines = [0.0, 0.02, 0.035, 0.04, 0.045, 0.05, 0.055, 0.06, 0.065, 0.08, 0.1] }}, z = {{ segments = [{{ from = 0.0, to = 0.05, elements = 3, ratio = 0.4 }}] }} }}
axis = {{ element = "B3", from = 0.0, to = 0.02, elements = 1 }}

[[constraints]]
name = "bottom"
body = "block"
where = {{ z = 0.0 }}
fix = ["x", "y", "z"]
{extra}
"#
    )
}

/// A rigid flat punch on an elastic block: as ε_N grows, the punch force
/// tends to that of the same model with u_z prescribed on the punched nodes
/// (in-plane components free), with an error proportional to 1/ε_N.
#[test]
fn flat_punch_force_converges_to_the_prescribed_displacement_solution() {
    let delta = 1e-5;
    let direct = Model::parse(&punch(&format!(
        "[[constraints]]\nname = \"punched\"\nbody = \"block\"\nwhere = {{ z = 0.05, x = [0.04, 0.06] }}\ndisplacement = {{ z = {} }}\n",
        -delta
    )))
    .unwrap();
    let reference =
        analysis::run(&direct, &Default::default(), &mut Silent).unwrap().reaction("punched").unwrap().force[2];
    assert!(reference < 0.0);
    let mut errors = Vec::new();
    for alpha in [1e2, 1e3, 1e4] {
        let model = Model::parse(&punch(&format!(
            "[[indenters]]\nname = \"punch\"\nbody = \"block\"\nshape = \"flat\"\nsurface = {{ z = 0.05 }}\n\
             normal = \"-z\"\nposition = 0.05\nx = [0.04, 0.06]\ndisplacement = [0.0, 0.0, {}]\npenalty_factor = {alpha}\n",
            -delta
        )))
        .unwrap();
        let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
        let force = sol.contact("punch").unwrap().force[2];
        // global equilibrium: punch force balances the support reaction
        // global equilibrium: punch force balances the support reaction. The
        // imbalance is round-off amplified by the penalty (3e-12 at α = 1e2,
        // 5e-9 at α = 1e4), so the check uses the issue's 1e-6.
        assert!((force + sol.reaction("bottom").unwrap().force[2]).abs() < 1e-6 * force.abs());
        errors.push((force - reference).abs() / reference.abs());
    }
    for (alpha, e) in ["1e2", "1e3", "1e4"].iter().zip(&errors) {
        let check = "each tenfold α divides it by 10 ± 1.5; < 1e-3 at α = 1e4";
        common::figure(&format!("contact.punch.alpha_{alpha}"), *e, "", check);
    }
    // error ∝ 1/ε_N: each tenfold penalty divides the error by about ten
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        assert!((ratio - 10.0).abs() < 1.5, "error ratio {ratio} (errors {errors:?})");
    }
    assert!(errors[2] < 1e-3);
}

/// Hertz line contact: a rigid cylinder (R = 50 mm, axis along y) pressed
/// into an elastic slice held in plane strain (u_y = 0), half model with
/// u_x = 0 on x = 0. Block 20 × 20 mm (about 20 contact half-widths);
/// L9 elements of 0.1 mm (nodes every 0.05 mm ≈ a/20) over the contact
/// zone. Hertz (Johnson, *Contact Mechanics*, §5.6, rigid cylinder):
/// a = √(4 P' R / (π E*)), p₀ = 2 P' / (π a), E* = E/(1 − ν²), with P' the
/// computed force per unit length. The issue asks for 5 %; this mesh gives
/// 0.3 % on a and 0.15 % on p₀, asserted at 2 %.
#[test]
fn rigid_cylinder_on_a_plane_strain_block_matches_hertz() {
    let text = r#"
[solver]
increments = 4
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
[[bodies]]
name = "block"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { segments = [{ from = 0.0, to = 0.0015, elements = 15 }, { from = 0.0015, to = 0.02, elements = 10, ratio = 20.0 }] }, z = { segments = [{ from = -0.02, to = -0.0015, elements = 10, ratio = 0.05 }, { from = -0.0015, to = 0.0, elements = 15 }] } }
axis = { element = "B2", from = 0.0, to = 0.001, elements = 1 }
[[constraints]]
name = "plane_strain"
body = "block"
where = {}
fix = ["y"]
[[constraints]]
name = "symmetry"
body = "block"
where = { x = 0.0 }
fix = ["x"]
[[constraints]]
name = "bottom"
body = "block"
where = { z = -0.02 }
fix = ["z"]
[[indenters]]
name = "cylinder"
body = "block"
shape = "cylinder"
surface = { z = 0.0, x = [0.0, 0.003] }
axis = "y"
center = [0.0, 0.0, 0.05]
radius = 0.05
displacement = [0.0, 0.0, -4e-5]
"#;
    let model = Model::parse(text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(sol.failure.is_none());
    let (e, nu, r, t) = (200e9, 0.3, 0.05, 0.001);
    let e_star = e / (1.0 - nu * nu);
    let force = sol.contact("cylinder").unwrap().force[2].abs();
    let per_length = 2.0 * force / t; // half model
    let a_hertz = (4.0 * per_length * r / (std::f64::consts::PI * e_star)).sqrt();
    let p0_hertz = 2.0 * per_length / (std::f64::consts::PI * a_hertz);
    // nodal pressures on the y = 0 line
    let pressures: Vec<(f64, f64)> = sol
        .contact_points("cylinder")
        .unwrap()
        .iter()
        .filter(|p| p.active && model.mesh.coords(p.node)[1] < 1e-12)
        .map(|p| (model.mesh.coords(p.node)[0], p.force[2].abs().hypot(p.force[0]) / p.area))
        .collect();
    let p_max = pressures.iter().map(|p| p.1).fold(0.0, f64::max);
    // fit p² = p₀² (1 − x²/a²) over the points above 0.3 p_max
    let fit: Vec<(f64, f64)> = pressures.iter().filter(|p| p.1 > 0.3 * p_max).map(|&(x, p)| (x * x, p * p)).collect();
    let n = fit.len() as f64;
    let (mx, my) = (fit.iter().map(|f| f.0).sum::<f64>() / n, fit.iter().map(|f| f.1).sum::<f64>() / n);
    let slope =
        fit.iter().map(|f| (f.0 - mx) * (f.1 - my)).sum::<f64>() / fit.iter().map(|f| (f.0 - mx).powi(2)).sum::<f64>();
    let intercept = my - slope * mx;
    let a_fit = (-intercept / slope).sqrt();
    common::within("contact.hertz_cylinder.half_width", a_fit, a_hertz, 0.02, "Hertz (Johnson §5.6)");
    common::within("contact.hertz_cylinder.peak_pressure", p_max, p0_hertz, 0.02, "Hertz (Johnson §5.6)");
}

/// The assembled tangent is the derivative of the assembled residual:
/// central differences of `R(u)` against columns of `K`, in a state with
/// plastic Gauss points, active rigid-indenter contact and active node
/// pairs between two bodies (so the elements' consistent tangent, the
/// penalty blocks `ε n nᵀ` and the coupling blocks `−ε n nᵀ` are all checked).
#[test]
fn assembled_tangent_matches_finite_differences_with_contact_and_plasticity() {
    use cufem::solver::newton::{self, NewtonSettings, NonlinearProblem};
    use cufem::solver::stepping::Incremental;
    let text = two_blocks("penalty = 1e15")
        .replace("young_modulus = 200e9\npoisson_ratio = 0.3", "young_modulus = 200e9\npoisson_ratio = 0.3\nplasticity = { yield_stress = 200e6, hardening = \"linear\", hardening_modulus = 2e9 }")
        .replace("[[loads]]\nname = \"pressure\"\nbody = \"upper\"\nwhere = { z = 0.025 }\npressure = 50e6\n", "")
        + "[[indenters]]\nname = \"roller\"\nbody = \"upper\"\nshape = \"cylinder\"\nsurface = { z = 0.025 }\naxis = \"x\"\ncenter = [0.01, 0.015, 0.035]\nradius = 0.01\ndisplacement = [0.0, 0.0, -4e-5]\n";
    let model = Model::parse(&text).unwrap();
    let mut s = analysis::Structure::of_model(&model, None).unwrap();
    s.set_load_factor(1.0);
    let report = newton::solve(&mut s, &NewtonSettings::default(), &Default::default());
    assert!(report.converged(), "{report:?}");
    s.evaluate().unwrap();
    assert!(s.plastic_points() > 0, "the state should be plastic");
    let points = s.contact_points();
    assert!(points.iter().filter(|c| c.master.is_some() && c.active).count() > 0, "pairs should be active");
    assert!(points.iter().filter(|c| c.master.is_none() && c.active).count() > 0, "roller should be active");
    let k = s.tangent_values().to_vec();
    let eq: Vec<usize> = (0..s.displacements().len()).map(|d| s.equation(d).unwrap_or(usize::MAX)).collect();
    let scale = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    // every component of the active roller nodes (inclined normals: all
    // entries of their n nᵀ blocks), of some active node pairs, and a few others
    let active_nodes = |roller: bool| {
        s.contact_points()
            .iter()
            .filter(move |c| c.active && c.master.is_none() == roller)
            .flat_map(|c| std::iter::once(c.node).chain(c.master))
            .flat_map(|n| [3 * n, 3 * n + 1, 3 * n + 2])
            .filter(|&d| eq[d] != usize::MAX)
    };
    let mut dofs: Vec<usize> = active_nodes(true).take(24).collect();
    dofs.extend(active_nodes(false).take(12));
    dofs.extend((0..eq.len()).step_by(97).filter(|&d| eq[d] != usize::MAX).take(8));
    let columns: Vec<(usize, usize)> = dofs.iter().map(|&d| (d, eq[d])).collect();
    let (worst, _) = common::tangent_vs_differences(&mut s, &columns, 1e-11, scale);
    // 1e-8 leaves room for round-off (central differences, h = 1e-11 m)
    // while a wrong block (sign, factor, missing term) gives O(1e-3..1)
    let check = "< 1e-8 of the largest entry, against central differences";
    common::figure("contact.tangent", worst, "", check);
    assert!(worst < 1e-8, "tangent differs from finite differences by {worst:e} of its largest entry");
}

/// A punch placed on the wrong side (its face looking away from the body)
/// starts with every node inside it: rejected with the keys to fix.
#[test]
fn an_indenter_starting_inside_the_body_is_rejected() {
    let text = punch(
        "[[indenters]]\nname = \"punch\"\nbody = \"block\"\nshape = \"flat\"\nsurface = { z = 0.05 }\n\
         normal = \"+z\"\nposition = 0.05\nx = [0.04, 0.06]\ndisplacement = [0.0, 0.0, -1e-5]\n",
    )
    .replace("position = 0.05", "position = 0.06");
    let err = Model::parse(&text).unwrap_err().to_string();
    assert!(
        err.contains("indenters[0].position / indenters[0].normal") && err.contains("inside the indenter"),
        "{err}"
    );
}

/// examples/cantilevers_contact.toml with 80 B4 per beam along the axis
/// and 2 × 2 L9 per section (36,150 DOF), its rollers pressed 20 µm (a
/// twelfth of one of the example's increments: elastic, and less than the
/// 44 µm gap to the node rows beside each roller's line). The stacked
/// beams start bonded at zero gap and Newton peels their interface open a
/// row or two of nodes a correction (`solver::newton`, the releasing
/// iterations): more corrections than `max_iterations` (25). Before those
/// were exempt the run failed: every cutback peels the same rows (the
/// increment is elastic, a cutback scales the solution, not the set). The
/// beams then touch only where the upper beam's free end (y = 254 mm)
/// rests on the lower one, within its last element (3.2 mm): beam
/// theory's picture (the lower cantilever,
/// loaded there, turns its free part down towards y = 76.2 mm while the
/// upper one rises towards its clamp). A release that left points bonded
/// would leave a longer set, one that dropped a pressing point none.
#[test]
fn stacked_beams_peel_open_past_the_iteration_limit() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/cantilevers_contact.toml"))
        .unwrap()
        .replace("elements = 4 }", "elements = 2 }")
        .replace("elements = 10 }", "elements = 80 }")
        .replace("displacement = [0.0, 0.0, -2.5e-3]", "displacement = [0.0, 0.0, -2e-5]")
        .replace("increments = 20", "increments = 1");
    let model = Model::parse(&text).unwrap();
    assert_eq!(model.n_dofs(), 36_150);
    let s = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(s.failure.is_none(), "{:?}", s.failure);
    let corrections: Vec<usize> = s.increments.iter().map(|i| i.newton.iterations).collect();
    eprintln!("corrections per increment {corrections:?}, cutbacks {}", s.cutbacks.len());
    assert!(corrections[0] > 25, "{corrections:?}");
    let beams = s.contact_sets.iter().find(|c| c.name == "beams").unwrap();
    let touching: Vec<f64> = beams.points.iter().filter(|p| p.active).map(|p| model.mesh.coords(p.node)[1]).collect();
    eprintln!("interface points touching at y = {touching:?}");
    assert!(touching.iter().filter(|&&y| (y - 0.254).abs() < 1e-9).count() == 5, "the tip's row: {touching:?}");
    assert!(touching.iter().all(|&y| y > 0.254 - 0.254 / 80.0), "{touching:?}");
}
