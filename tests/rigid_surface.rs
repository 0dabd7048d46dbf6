//! Contact against rigid surfaces with the exact closest point of the
//! current configuration (`indenters[].method = "surface"`, issue 9 item
//! 1): finite sliding of a roller over a block, and a finite-difference
//! check of the tangent with its curvature term.

mod common;

use cufem::analysis::Structure;
use cufem::setup::Model;
use cufem::solver::newton::NonlinearProblem;

/// A plane-strain slice (1 mm thick, x held on both faces) of a block
/// 12 mm long (y, 32 B4) and 10 mm deep (z, 8 L9 graded to the top),
/// pressed 20 µm by a rigid roller (R = 10 mm, axis x) at y = 4 mm; in
/// step "slide" the block's base is moved 4 mm along −y, so that the
/// roller ends at y = 8 mm, the mirror image of its start about the
/// block's mid-plane y = 6 mm. Frictionless.
fn rolled(method: &str) -> String {
    format!(
        r#"
[solver]
increments = 2

[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "block"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.001, elements = 1 }}, z = {{ from = -0.01, to = 0.0, elements = 8, ratio = 0.1 }} }}
axis = {{ element = "B4", from = 0.0, to = 0.012, elements = 32 }}

[[constraints]]
name = "bottom"
body = "block"
where = {{ z = -0.01 }}
displacement = {{ x = 0.0, y = -0.004, z = 0.0 }}
[[constraints]]
name = "plane_x0"
body = "block"
where = {{ x = 0.0 }}
fix = ["x"]
[[constraints]]
name = "plane_x1"
body = "block"
where = {{ x = 0.001 }}
fix = ["x"]

[[indenters]]
name = "roller"
body = "block"
shape = "cylinder"
method = "{method}"
surface = {{ z = 0.0 }}
axis = "x"
center = [0.0005, 0.004, 0.01]
radius = 0.01
displacement = [0.0, 0.0, -2e-5]

[[steps]]
name = "press"
factors = {{ bottom = 0.0 }}

[[steps]]
name = "slide"
increments = 8
"#
    )
}

/// Finite sliding: the roller travels 4 mm (about 13 contact half-widths:
/// Hertz b = √(4 P' R / (π E*)) = 0.30 mm at the measured 1.53 kN/mm) over
/// the block. By the mirror symmetry of the block the force at the end
/// equals the force at the start, with f_y reversed (measured: f_z equal to
/// 1e-9, f_y = ±1.56 N); the vertical force stays within 4 % of its start
/// all along (measured 1,533–1,594 N, largest mid-block), and the
/// frictionless roller pushes the body sideways by less than 1 % of f_z.
/// The paper's node-to-node contact (pairs and normals of the reference
/// configuration) cannot follow: after the same slide it reports
/// f_z = 76 kN and f_y = 22 kN (measured), which the last assertion
/// checks to show what `method = "surface"` is for.
#[test]
fn a_roller_slides_over_a_block_with_the_exact_gap() {
    let sol = common::run(&rolled("surface"));
    let forces: Vec<[f64; 3]> = sol.history.iter().map(|h| h.contact("roller").unwrap().force).collect();
    assert_eq!(forces.len(), 10);
    let (start, end) = (forces[1], forces[9]);
    let spread = forces[1..].iter().map(|f| (f[2] / start[2] - 1.0).abs()).fold(0.0, f64::max);
    common::figure("rigid.slide.vertical_force", 100.0 * spread, "%", "< 4 % of its start at every increment");
    common::figure("rigid.slide.mirror", (end[2] / start[2] - 1.0).abs(), "", "< 1e-6 (mirror positions)");
    assert!((end[2] / start[2] - 1.0).abs() < 1e-6, "mirror positions: {start:?} vs {end:?}");
    assert!((end[1] + start[1]).abs() < 1e-6 * start[2].abs(), "f_y reverses: {start:?} vs {end:?}");
    for f in &forces[1..] {
        assert!((f[2] / start[2] - 1.0).abs() < 0.04, "vertical force {f:?} against {start:?}");
        assert!(f[1].abs() < 0.01 * f[2].abs(), "sideways force {f:?}");
    }
    let fixed = common::run(&rolled("node_to_node"));
    let f = fixed.contact("roller").unwrap().force;
    common::figure(
        "rigid.slide.node_to_node_f_z",
        f[2] / end[2],
        "",
        "> 2, or f_y > 0.1 f_z (node-to-node cannot follow)",
    );
    assert!(f[1].abs() > 0.1 * f[2].abs() || f[2] / end[2] > 2.0, "node-to-node followed the slide: {f:?}");
}

/// The tangent of the exact-gap contact against central differences of
/// the residual, mid-slide (base moved 1.2 mm, solved, not committed), at
/// every DOF of the active nodes: the block `ε n nᵀ − p ∂n/∂y` per node,
/// whose curvature term `p (P⊥ − n nᵀ)/ρ` is what turns the force as a
/// node slides over the roller. Measured: 5.2e-10 of the largest penalty;
/// with the curvature term dropped 5.2e-6 (it is p/ρ against ε; h = 1e-9 m,
/// where round-off stays below 1e-9 ε). Asserted 1e-7, between the two.
/// Largest difference between the assembled tangent (symmetric part and
/// skew terms) and central differences of the residual at every DOF of the
/// active nodes, relative to the largest penalty, mid-slide (base moved
/// 1.2 mm, solved, not committed); with the numbers of active and sliding
/// points.
fn tangent_error(text: &str, path: &[(f64, bool)], h: f64) -> (f64, usize, usize) {
    let model = Model::parse(text).unwrap();
    let mut s = Structure::of_model(&model, None).unwrap();
    common::solve_path(&mut s, path);
    s.evaluate().unwrap();
    let points = s.contact_points().to_vec();
    let active: Vec<usize> = points.iter().filter(|p| p.active).map(|p| p.node).collect();
    assert!(active.len() >= 5, "{} active points", active.len());
    let columns: Vec<(usize, usize)> = active
        .iter()
        .flat_map(|&n| (0..3).map(move |c| 3 * n + c))
        .filter_map(|d| s.equation(d).map(|e| (d, e)))
        .collect();
    let penalty = model.indenters[0].nodes.iter().map(|c| c.penalty).fold(0.0, f64::max);
    let (worst, _) = common::tangent_vs_differences(&mut s, &columns, h, penalty);
    let sliding = points.iter().filter(|p| p.active && p.sliding).count();
    (worst, active.len(), sliding)
}

#[test]
fn the_exact_gap_tangent_matches_finite_differences() {
    let (worst, _, _) =
        tangent_error(&rolled("surface"), &[(0.5, true), (1.0, true), (1.15, true), (1.3, false)], 1e-9);
    common::figure("rigid.tangent", worst, "ε", "< 1e-7 ε against central differences");
    assert!(worst < 1e-7, "tangent differs from finite differences by {worst:e} of the largest penalty");
}

/// The same with Coulomb friction μ = 0.3 on the roller, whose block now
/// holds `−∂t/∂y` of `contact::turning_friction`: the tangential penalty,
/// the turning of the tangent plane with the normal and, while sliding, the
/// unsymmetric pressure coupling. Two states: just after the slide starts
/// (base moved 4 µm) the contact partly sticks and partly slides
/// (asserted), with points near the cone where the force curves sharply,
/// so h = 1e-11 m (the difference falls as h²: 2.8e-5, 2.8e-7, 7.5e-8 ε at
/// h = 1e-9, 1e-10, 1e-11 — truncation, then round-off); at 40 µm every
/// point slides and h = 1e-9 m resolves the small turning terms. Measured
/// 7.5e-8 and 6.4e-10 ε; with the turning terms (`(n·v) ∂n/∂y`,
/// `n vᵀ ∂n/∂y`) dropped 1.6e-6 and 1.5e-6 ε: both checks fail.
#[test]
fn the_exact_gap_friction_tangent_matches_finite_differences() {
    let text = rolled("surface")
        .replace("displacement = [0.0, 0.0, -2e-5]", "displacement = [0.0, 0.0, -2e-5]\nfriction = 0.3");
    assert!(text.contains("friction = 0.3"));
    let (worst, active, sliding) = tangent_error(&text, &[(0.5, true), (1.0, true), (1.001, false)], 1e-11);
    assert!(sliding > 0 && sliding < active, "partial slip: {sliding} of {active} sliding");
    common::figure("rigid.friction_tangent.partial_slip", worst, "ε", "< 1e-6 ε against central differences");
    assert!(worst < 1e-6, "partial slip: tangent differs from finite differences by {worst:e} of the largest penalty");
    let (worst, active, sliding) = tangent_error(&text, &[(0.5, true), (1.0, true), (1.01, false)], 1e-9);
    assert_eq!(sliding, active);
    common::figure("rigid.friction_tangent.sliding", worst, "ε", "< 1e-7 ε against central differences");
    assert!(worst < 1e-7, "sliding: tangent differs from finite differences by {worst:e} of the largest penalty");
}

/// Coulomb on the exact-gap roller: once the block slides under the roller
/// (base moved 0.5–4 mm) every active point slides and the tangential
/// resultant is μ times the normal one (μ = 0.3; Coulomb's law, the
/// resultants as summary.json reports them). Measured 0.3 to 1e-9 from the
/// third slide increment on.
#[test]
fn a_roller_dragged_with_friction_resists_with_mu_times_the_normal_force() {
    // 16 B4 along the block instead of 32: the resultants, not the pressure
    // profile, are checked
    let text = rolled("surface")
        .replace("displacement = [0.0, 0.0, -2e-5]", "displacement = [0.0, 0.0, -2e-5]\nfriction = 0.3")
        .replace("elements = 32", "elements = 16");
    assert!(text.contains("elements = 16"));
    let sol = common::run(&text);
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let mut worst: f64 = 0.0;
    for h in &sol.history[3..] {
        let c = h.contact("roller").unwrap();
        let ratio = norm(c.tangential_force) / norm(c.normal_force);
        worst = worst.max((ratio - 0.3).abs());
        assert!((ratio - 0.3).abs() < 1e-6, "λ = {}: f_t / f_n = {ratio}", h.lambda);
    }
    common::figure("rigid.friction.ratio", worst, "", "|f_t/f_n − μ| < 1e-6 at every sliding increment");
    let points = &sol.contact_sets.iter().find(|s| s.name == "roller").unwrap().points;
    assert!(points.iter().filter(|p| p.active).all(|p| p.sliding));
}

/// Force control with the exact gap: a ball pushed with the force that a
/// displacement-controlled run measured (quarter model of a 10 mm block,
/// coarser than examples/hertz_ball.toml) ends at that run's displacement
/// (the bordered Newton system of `structure/force.rs` uses the contact
/// blocks, curvature terms included). Measured: 2.8e-8 apart; asserted 1e-6.
#[test]
fn a_ball_under_force_control_reaches_the_displacement_controlled_state() {
    let text =
        std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/hertz_ball.toml"))
            .unwrap()
            .replace("to = 0.03, elements = 10, ratio = 60.0", "to = 0.01, elements = 6, ratio = 20.0")
            .replace(
                "from = -0.03, to = 0.0, elements = 10, ratio = 0.0166667",
                "from = -0.01, to = 0.0, elements = 6, ratio = 0.05",
            )
            .replace("where = { z = -0.03 }", "where = { z = -0.01 }");
    assert!(text.contains("elements = 6, ratio = 0.05") && text.contains("z = -0.01 }"));
    let displaced = common::run(&text);
    let force = displaced.contact("ball").unwrap().force;
    let pushed =
        common::run(&text.replace("displacement = [0.0, 0.0, -5e-5]", &format!("force = [0.0, 0.0, {:e}]", force[2])));
    let d = pushed.history.last().unwrap().contact("ball").unwrap().displacement[2];
    common::figure("rigid.force_control", (d / -5e-5 - 1.0).abs(), "", "< 1e-6 of the displacement-controlled run's");
    assert!((d / -5e-5 - 1.0).abs() < 1e-6, "force control reached {d} m");
}

/// The tangent with the material, geometric (initial-stress) and contact
/// terms at once, at large rotation: a cantilever (1 m, 10 × 10 mm,
/// elastic, ν = 0, `geometry = "nonlinear"`) given the displacement field
/// of uniform bending to curvature κ = 0.5 /m (its axis an arc, the tip
/// turned by 29°, fibres stretched by −κ t), and a rigid roller (R = 50 mm,
/// axis x, `method = "surface"`) placed against the deformed top face at
/// y = 0.7 m, 0.2 mm deep along the turned normal (it starts above the
/// straight beam and is moved there at λ = 1). Not an equilibrium
/// state (none is needed to compare a tangent with the residual's
/// derivative), so the active set is set by the geometry: the three nodes
/// across the top at y = 0.7 penetrate 0.2 mm, their neighbours 11 mm
/// away stay 1 mm clear, and no perturbation switches a point. Assembled
/// tangent against central differences of the residual in every component
/// of the active nodes and of four axis nodes, relative to the largest
/// tangent entry (h = 1e-9 m): issue 26's "finite-difference check of the
/// tangent with the geometric and contact terms ≤ 1e-6".
#[test]
fn large_rotation_contact_tangent_matches_finite_differences() {
    let (kappa, s0, radius, depth) = (0.5f64, 0.7f64, 0.05, 2e-4);
    // axis point and unit normal (+z in the reference) at arc length s
    let axis = |s: f64| [(kappa * s).sin() / kappa, 0.005 - (1.0 - (kappa * s).cos()) / kappa];
    let normal = |s: f64| [(kappa * s).sin(), (kappa * s).cos()];
    let (a, n) = (axis(s0), normal(s0));
    let centre = [0.005, a[0] + (0.005 + radius - depth) * n[0], a[1] + (0.005 + radius - depth) * n[1]];
    let text = format!(
        r#"
[analysis]
geometry = "nonlinear"

[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.0

[[bodies]]
name = "beam"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.01, elements = 1 }}, z = {{ from = 0.0, to = 0.01, elements = 1 }} }}
axis = {{ element = "B4", from = 0.0, to = 1.0, elements = 10 }}

[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[indenters]]
name = "roller"
body = "beam"
shape = "cylinder"
method = "surface"
surface = {{ z = 0.01, y = [0.5, 1.0] }}
axis = "x"
center = [{}, {}, 0.1]
radius = {radius}
displacement = [0.0, 0.0, {}]
"#,
        centre[0],
        centre[1],
        centre[2] - 0.1
    );
    let model = Model::parse(&text).unwrap();
    let mut s = Structure::of_model(&model, None).unwrap();
    {
        use cufem::solver::stepping::Incremental;
        s.set_load_factor(1.0);
    }
    let n_nodes = s.displacements().len() / 3;
    for node in 0..n_nodes {
        let [_, y, z] = model.mesh.coords(node);
        let (p, m) = (axis(y), normal(y));
        let t = z - 0.005;
        s.displacements_mut()[3 * node + 1] = p[0] + t * m[0] - y;
        s.displacements_mut()[3 * node + 2] = p[1] + t * m[1] - z;
    }
    s.evaluate().unwrap();
    let points = s.contact_points().to_vec();
    let active: Vec<usize> = points.iter().filter(|p| p.active).map(|p| p.node).collect();
    assert_eq!(active.len(), 3, "active: {active:?}");
    for p in points.iter().filter(|p| p.active) {
        assert!((p.gap + depth).abs() < 1e-9, "gap {}", p.gap);
        // the roller's normal (towards the body: against the top face's
        // outward normal) has turned with the beam (sin 0.35 = 0.34)
        assert!((p.normal[1] + n[0]).abs() < 1e-9 && (p.normal[2] + n[1]).abs() < 1e-9, "{:?}", p.normal);
    }
    let nodes = active.iter().copied().chain((1..5).map(|i| i * n_nodes / 5));
    let columns: Vec<(usize, usize)> =
        nodes.flat_map(|n| (0..3).map(move |c| 3 * n + c)).filter_map(|d| s.equation(d).map(|e| (d, e))).collect();
    let scale = s.tangent_values().iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let (worst, _) = common::tangent_vs_differences(&mut s, &columns, 1e-9, scale);
    common::figure("rigid.large_rotation.tangent", worst, "", "< 1e-6 of the largest entry (issue 26)");
    assert!(worst < 1e-6, "tangent differs from finite differences by {worst:e}");
}

/// The slice of [`rolled`], its base held, pressed 20 µm by the roller at
/// mid-length.
const PRESSED: &str = r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "block"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.001, elements = 1 }, z = { from = -0.01, to = 0.0, elements = 4, ratio = 0.1 } }
axis = { element = "B4", from = 0.0, to = 0.012, elements = 8 }

[[constraints]]
name = "bottom"
body = "block"
where = { z = -0.01 }
fix = ["x", "y", "z"]
[[constraints]]
name = "planes"
body = "block"
where = { x = [0.0, 0.001] }
fix = ["x"]

[[indenters]]
name = "roller"
body = "block"
shape = "cylinder"
method = "surface"
surface = { z = 0.0 }
axis = "x"
center = [0.0005, 0.006, 0.01]
radius = 0.01
displacement = [0.0, 0.0, -2e-5]
"#;

/// Moves every node of [`PRESSED`]'s block 50 µm away from the roller
/// (more than its 20 µm stroke), so that every contact point is open.
fn lift(s: &mut Structure) {
    for (d, u) in s.displacements_mut().iter_mut().enumerate() {
        if d % 3 == 2 {
            *u -= 5e-5;
        }
    }
}

/// True if every contact point is open and carries nothing.
fn carries_nothing(s: &Structure) -> bool {
    s.contact_points().iter().all(|p| p.gap > 0.0 && !p.active && p.force == [0.0; 3])
}

/// [`PRESSED`] (with `friction` on the roller if given) solved to half its
/// stroke and committed, then its next increment started on the secant of
/// the first (`Incremental::extrapolate`) with the block lifted off
/// ([`lift`]) and evaluated: `check` gets the structure, whether that
/// evaluation was settled, and which points were in contact at the
/// committed state.
fn lifted_secant_start(friction: Option<f64>, check: impl FnOnce(&mut Structure, bool, &[bool])) {
    use cufem::solver::newton::{self, NewtonSettings};
    use cufem::solver::stepping::Incremental;
    let roller = "displacement = [0.0, 0.0, -2e-5]";
    let text = match friction {
        Some(mu) => PRESSED.replace(roller, &format!("{roller}\nfriction = {mu}")),
        None => PRESSED.to_string(),
    };
    let model = Model::parse(&text).unwrap();
    let mut s = Structure::of_model(&model, None).unwrap();
    s.set_load_factor(0.5);
    assert!(newton::solve(&mut s, &NewtonSettings::default(), &Default::default()).converged());
    s.commit();
    let committed: Vec<bool> = s.contact_points().iter().map(|p| p.active).collect();
    let in_contact = committed.iter().filter(|a| **a).count();
    assert!(in_contact >= 2 && in_contact < committed.len(), "{in_contact} of {}", committed.len());
    s.set_load_factor(1.0);
    s.extrapolate(1.0);
    lift(&mut s);
    let settled = s.evaluate().unwrap().settled;
    check(&mut s, settled, &committed);
}

/// An increment started on the secant of the last one where a point in
/// contact at the committed state is found open keeps that point's
/// penalty law for its first evaluation (`contact::assembly::rigid`,
/// module docs): the force `−ε g n`, a tension, its block `ε n nᵀ` in the
/// tangent, and the evaluation unsettled. At the next evaluation of the same displacements, and at an
/// increment restarted from the committed state after a secant start that
/// was never evaluated, the point is open and carries nothing.
#[test]
fn a_point_the_secant_lifts_off_keeps_its_contact_for_one_evaluation() {
    use cufem::solver::stepping::Incremental;
    let model = Model::parse(PRESSED).unwrap();
    let candidates = &model.indenters[0].nodes;
    lifted_secant_start(None, |s, settled, committed| {
        assert!(!settled);
        for ((p, c), &was) in s.contact_points().iter().zip(candidates).zip(committed) {
            assert!(p.gap > 0.0, "{p:?}");
            if !was {
                assert!(!p.active && p.force == [0.0; 3], "{p:?}");
                continue;
            }
            // −ε g along the normal into the body: pulls the node to the roller
            let expected = p.normal.map(|n| -c.penalty * p.gap * n);
            assert!(p.active, "{p:?}");
            for i in 0..3 {
                assert!((p.force[i] - expected[i]).abs() <= 1e-12 * c.penalty * p.gap, "{p:?} {expected:?}");
            }
            assert!(p.force[2] > 0.0, "a tension, toward the roller above: {p:?}");
        }
        // each kept point's u_z diagonal, then the same without the kept points
        let zz = |s: &Structure| -> Vec<f64> {
            let kept = s.contact_points().iter().zip(committed).filter(|(_, was)| **was);
            kept.map(|(p, _)| s.equation(3 * p.node + 2).map_or(f64::NAN, |e| s.tangent_entry(e, e))).collect()
        };
        let (with, normals) = (zz(s), s.contact_points().to_vec());
        s.evaluate().unwrap();
        assert!(carries_nothing(s));
        // the kept block ε n nᵀ − p ∂n/∂y: its curvature part is p/ρ (1 − n_z²)
        // here, below 1e-6 of ε n_z² (g ~ 30 µm, ρ = 10 mm, n_z² > 0.999)
        let kept = normals.iter().zip(candidates).zip(committed).filter(|(_, was)| **was);
        for ((((p, c), _), a), b) in kept.zip(&with).zip(zz(s)) {
            let expected = c.penalty * p.normal[2] * p.normal[2];
            assert!(((a - b) - expected).abs() <= 1e-6 * expected, "{} against {expected}", a - b);
        }
        // an increment retried from the committed state (a cutback) keeps
        // nothing, though its secant start was never evaluated
        s.extrapolate(1.0);
        s.restore();
        s.set_load_factor(1.0);
        lift(s);
        s.evaluate().unwrap();
        assert!(carries_nothing(s));
    });
}

/// With friction the rule is off (the Coulomb return needs a compressive
/// normal force): the same lifted secant start finds every point open.
#[test]
fn with_friction_a_point_the_secant_lifts_off_opens_at_once() {
    lifted_secant_start(Some(0.3), |s, _, _| assert!(carries_nothing(s)));
}
