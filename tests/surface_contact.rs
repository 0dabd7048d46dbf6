//! Surface-to-surface contact on non-matching meshes (issue 9, item 1):
//! the contact patch test of Taylor & Papadopoulos (1991), a
//! finite-difference check of the assembled contact tangent and Newton's
//! convergence rate.

mod common;

use cufem::analysis::{self, Silent, Solution};
use cufem::setup::Model;

/// Two stacked blocks 20 × 30 mm, the lower (z ∈ [0, 10] mm) meshed with
/// 3 × 2 L9 and 3 B3 elements, the upper (z ∈ [10, 25] mm) with 2 × 3 L16
/// and 2 B4 elements: no node of the interface faces another, and the
/// element boundaries of the two sides cross. Rollers leave the uniform
/// compression state exact in both blocks; a uniform pressure `p` on the
/// upper block's top face.
fn stacked_blocks(contact_keys: &str, extra: &str) -> String {
    format!(
        r#"
[solver]
increments = 1

[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
{extra}

[[bodies]]
name = "lower"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.02, elements = 3 }}, z = {{ from = 0.0, to = 0.01, elements = 2 }} }}
axis = {{ element = "B3", from = 0.0, to = 0.03, elements = 3 }}

[[bodies]]
name = "upper"
material = "steel"
section = {{ shape = "rectangle", element = "L16", x = {{ from = 0.0, to = 0.02, elements = 2 }}, z = {{ from = 0.01, to = 0.025, elements = 3 }} }}
axis = {{ element = "B4", from = 0.0, to = 0.03, elements = 2 }}

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

[[contacts]]
name = "interface"
method = "surface"
master = {{ body = "lower", where = {{ z = 0.01 }} }}
slave = {{ body = "upper", where = {{ z = 0.01 }} }}
{contact_keys}
"#
    )
}

const P: f64 = 50e6;

/// A Float64 array of a VTU written by cufem (binary: base64 of a UInt64
/// byte count and the little-endian values).
fn vtu_array(text: &str, name: &str) -> Vec<f64> {
    use base64::Engine;
    let start = text.find(&format!("Name=\"{name}\"")).unwrap();
    let body = &text[start..];
    let body = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
    let bytes = base64::engine::general_purpose::STANDARD.decode(body.trim()).unwrap();
    bytes[8..].chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
}
const PRESSURE: &str = "[[loads]]\nname = \"pressure\"\nbody = \"upper\"\nwhere = { z = 0.025 }\npressure = 50e6\n";

fn run(text: &str) -> (Model, Solution) {
    let model = Model::parse(text).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(sol.failure.is_none(), "{:?}", sol.failure);
    (model, sol)
}

/// The largest relative deviation of the contact pressure `|f|/w` of the
/// interface's points from `p`, and of the transmitted force from `p A`.
fn pressure_error(sol: &Solution) -> (f64, f64, usize) {
    let points = sol.contact_points("interface").unwrap();
    let worst = points.iter().map(|c| {
        let f = (c.force[0].powi(2) + c.force[1].powi(2) + c.force[2].powi(2)).sqrt();
        (f / c.area / P - 1.0).abs()
    });
    let worst = worst.fold(0.0, f64::max);
    let total = sol.contact("interface").unwrap().force[2];
    (worst, (total / (P * 0.02 * 0.03) - 1.0).abs(), points.iter().filter(|c| c.active).count())
}

/// Patch test on non-matching meshes: the slave integration points cut at
/// the master's element boundaries integrate `∫ N p dA` exactly on both
/// sides, so the uniform state (σ_zz = −p in both blocks, uniform
/// penetration) solves the discrete equations: every point carries `p`
/// within round-off, with the penalty alone and with the augmented
/// Lagrangian (whose penetration is then below its tolerance). Measured
/// with double-precision factors (each linear solve exact to round-off):
/// pressure deviations of order 1e-13 (penalty) and 1e-12 (augmented);
/// asserted 1e-6 (the issue's bound). Every point is active. With the
/// default mixed precision Newton stops at its tolerance (relative
/// residual 1e-6): measured 1.6e-6 with the augmented Lagrangian, asserted
/// below 1e-5 at the end.
#[test]
fn patch_test_transmits_a_uniform_pressure_across_non_matching_meshes() {
    let double = |text: String| {
        let t = text.replace("[solver]\n", "[solver]\nfactor_precision = \"double\"\n");
        assert!(t.contains("factor_precision"), "the model has no [solver] table to put the key in");
        t
    };
    for keys in ["", "penetration_tolerance = 1e-9"] {
        let (model, sol) = run(&double(stacked_blocks(keys, "") + PRESSURE));
        let (worst, total, active) = pressure_error(&sol);
        let n = sol.contact_points("interface").unwrap().len();
        let pen = sol.contact("interface").unwrap().max_penetration;
        let id = if keys.is_empty() { "surface.patch.penalty" } else { "surface.patch.augmented" };
        common::figure(&format!("{id}.pressure"), worst, "", "< 1e-6 of p at every point (double-precision factors)");
        if !keys.is_empty() {
            common::figure(&format!("{id}.penetration"), pen, "m", "≤ 1e-9 m (the augmented Lagrangian's tolerance)");
        }
        assert_eq!(active, n, "every point carries the pressure");
        assert!(worst < 1e-6 && total < 1e-6, "{worst:e} {total:e}");
        if !keys.is_empty() {
            assert!(pen <= 1e-9, "{pen:e}");
        }
        // contact_<name>.vtu: one vertex per slave node with its pressure p
        let k = sol.contact_sets.iter().position(|c| c.name == "interface").unwrap();
        let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("surface_patch_contact.vtu");
        cufem::io::write_contact_vtu(&path, &model, &sol, k).unwrap();
        let vtu = std::fs::read_to_string(&path).unwrap();
        assert!(vtu.contains(&format!("NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\"")));
        let pressure = vtu_array(&vtu, "pressure");
        assert_eq!(pressure.len(), n);
        assert!(pressure.iter().all(|v| (v / P - 1.0).abs() < 1e-6), "{pressure:?}");
        assert!(vtu_array(&vtu, "traction").iter().all(|v| v.abs() < 1e-6 * P), "frictionless: no traction");
        // the support reaction under the lower block is p A (equilibrium)
        let r = sol.reaction("lower_bottom").unwrap().force[2];
        assert!((r / (P * 0.02 * 0.03) - 1.0).abs() < 1e-9, "{r}");
        // σ_zz = −p inside the lower (master) block, away from the interface
        let fields = sol.fields(&model);
        for point in [[0.003, 0.007, 0.004], [0.017, 0.021, 0.006]] {
            let loc = cufem::values::locate_in_model(&model.mesh, Some(0), point);
            let szz = fields.sample(&loc[0]).stress[2];
            assert!((szz / -P - 1.0).abs() < 1e-6, "σ_zz {szz} at {point:?}");
        }
    }
    let (_, sol) = run(&(stacked_blocks("penetration_tolerance = 1e-9", "") + PRESSURE));
    let (worst, total, _) = pressure_error(&sol);
    common::figure("surface.patch.single_factors", worst, "", "< 1e-5 of p (Newton's tolerance)");
    assert!(worst < 1e-5 && total < 1e-5, "{worst:e} {total:e}");
}

/// The stacked blocks under a roller instead of the pressure (a graded
/// contact pressure), plastic, at their converged state.
fn plastic_roller() -> String {
    stacked_blocks(
        "penalty = 1e15",
        "plasticity = { yield_stress = 200e6, hardening = \"linear\", hardening_modulus = 2e9 }",
    ) + "[[indenters]]\nname = \"roller\"\nbody = \"upper\"\nshape = \"cylinder\"\nsurface = { z = 0.025 }\naxis = \"x\"\ncenter = [0.01, 0.015, 0.035]\nradius = 0.01\ndisplacement = [0.0, 0.0, -4e-5]\n"
}

/// Finite-difference check of the assembled tangent (central differences)
/// with surface contact between the non-matching blocks: the columns of
/// the slave and master face nodes of active points check the blocks
/// `c_a c_b ε n nᵀ` with `c = (N_s, −N_m)` — within the slave face, within
/// the master face and across. Within an increment the projection is fixed
/// and the gap linear in `u`, so the contact part is exact (no curvature
/// term is dropped); the elements are plastic (consistent tangent).
#[test]
fn surface_contact_tangent_matches_finite_differences() {
    use cufem::solver::newton::{self, NewtonSettings, NonlinearProblem};
    use cufem::solver::stepping::Incremental;
    let model = Model::parse(&plastic_roller()).unwrap();
    let mut s = analysis::Structure::of_model(&model, None).unwrap();
    s.set_load_factor(1.0);
    let report = newton::solve(&mut s, &NewtonSettings::default(), &Default::default());
    assert!(report.converged(), "{report:?}");
    s.evaluate().unwrap();
    assert!(s.plastic_points() > 0, "the state should be plastic");
    let nl = model.mesh.bodies[0].n_nodes();
    let interface = |s: &analysis::Structure| -> Vec<cufem::analysis::ContactPoint> {
        s.contact_sets().find(|(n, _, _)| *n == "interface").unwrap().2.to_vec()
    };
    let active: Vec<usize> = interface(&s).iter().filter(|c| c.active).map(|c| c.node).collect();
    assert!(active.len() > 10, "{} active points", active.len());
    let k = s.tangent_values().to_vec();
    let eq: Vec<usize> = (0..s.displacements().len()).map(|d| s.equation(d).unwrap_or(usize::MAX)).collect();
    let scale = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    // slave nodes of active points, and lower-block (master) nodes on the interface z = 0.01
    let mut nodes: Vec<usize> = active.clone();
    nodes.sort_unstable();
    nodes.dedup();
    nodes.truncate(8);
    let master: Vec<usize> =
        (0..nl).filter(|&n| (model.mesh.coords(n)[2] - 0.01).abs() < 1e-12).step_by(5).take(8).collect();
    nodes.extend(&master);
    let dofs: Vec<usize> =
        nodes.iter().flat_map(|&n| [3 * n, 3 * n + 1, 3 * n + 2]).filter(|&d| eq[d] != usize::MAX).collect();
    let columns: Vec<(usize, usize)> = dofs.iter().map(|&d| (d, eq[d])).collect();
    let contact_columns = columns.len();
    let (worst, _) = common::tangent_vs_differences(&mut s, &columns, 1e-11, scale);
    // a wrong block (sign, factor, missing coupling) gives O(1e-3..1); the
    // bound leaves room for round-off as in tests/contact.rs
    let check = format!("< 1e-8 of the largest entry over {contact_columns} columns, against central differences");
    common::figure("surface.tangent", worst, "", &check);
    assert!(worst < 1e-8, "tangent differs from finite differences by {worst:e} of its largest entry");
}

/// Newton converges quadratically in an increment whose active set does
/// not change: the roller's last fifth from the converged state at λ = 0.8,
/// in the plastic range (the interface's active set is the same at both
/// ends, asserted). Relative
/// residuals measured: 0.99, 2.9e-2, 2.4e-4, 3.3e-8, 2.1e-14, i.e.
/// r_{k+1}/r_k² = 0.03, 0.28, 0.57 before round-off; asserted
/// r_{k+1} ≤ 10 r_k² over the last steps above 1e-12, which a linearly
/// converging (inconsistent-tangent) iteration with rate 0.1 fails.
#[test]
fn newton_converges_quadratically_with_surface_contact() {
    use cufem::solver::newton::{self, NewtonSettings, NonlinearProblem};
    use cufem::solver::stepping::Incremental;
    let model = Model::parse(&plastic_roller()).unwrap();
    let mut s = analysis::Structure::of_model(&model, None).unwrap();
    let settings = NewtonSettings { residual_tolerance: 1e-11, displacement_tolerance: 1e-11, ..Default::default() };
    let mut active_before = 0;
    for lambda in [0.8, 1.0] {
        s.set_load_factor(lambda);
        let report = newton::solve(&mut s, &settings, &Default::default());
        assert!(report.converged(), "{report:?}");
        if lambda == 1.0 {
            let r = &report.residuals;
            for (k, v) in r.iter().enumerate() {
                common::figure(
                    &format!("surface.newton.residual{k}"),
                    *v,
                    "",
                    "r_(k+1) ≤ 10 r_k² over the last steps above 1e-12",
                );
            }
            let tail: Vec<f64> = r.iter().copied().filter(|&v| v > 1e-12).collect();
            assert!(tail.len() >= 3, "{r:?}");
            for w in tail.windows(2).skip(tail.len().saturating_sub(3)) {
                assert!(w[1] <= 10.0 * w[0] * w[0], "not quadratic: {r:?}");
            }
        }
        s.evaluate().unwrap();
        let active =
            s.contact_sets().find(|(n, _, _)| *n == "interface").unwrap().2.iter().filter(|c| c.active).count();
        if lambda == 1.0 {
            assert_eq!(active, active_before, "the active set changed");
        }
        active_before = active;
        s.commit();
    }
}

/// Issue 9's non-matching cantilevers: `examples/cantilevers_contact_nonmatching.toml`
/// (lower beam's section 5 × 3 L9 instead of 4 × 4) against the same model
/// on the matching mesh, both with `method = "surface"`, frictionless.
/// Measured: pair contact force −0.7 %, 7 in roller +0.2 %, σ_yy at the
/// probes +0.05 % and −1.8 %; asserted 2 % (the issue's bound). The 9 in
/// roller carries 942 N against 1,106 N (−15 %; 0.6 % of the rollers'
/// total, asserted below 1 %): a line contact at the upper beam's free end
/// whose share depends on the mesh under it. Two plastic runs of about
/// 15 s each on one core (31 s for the whole file, measured).
#[test]
fn non_matching_cantilevers_match_the_matching_mesh() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let nonmatching = std::fs::read_to_string(path.join("cantilevers_contact_nonmatching.toml")).unwrap();
    let matching = std::fs::read_to_string(path.join("cantilevers_contact.toml")).unwrap().replace(
        "slave = { body = \"upper\", where = { z = 0.0254 } }",
        "slave = { body = \"upper\", where = { z = 0.0254 } }\nmethod = \"surface\"",
    );
    assert!(matching.contains("method = \"surface\""));
    let (model_n, n) = run(&nonmatching);
    let (model_m, m) = run(&matching);
    let fz = |s: &Solution, name: &str| s.contact(name).unwrap().force[2];
    let probe = |model: &Model, s: &Solution, name: &str| {
        let p = model.probes.iter().find(|p| p.name == name).unwrap();
        s.fields(model).sample_probe(p).unwrap().stress[1]
    };
    let mut rows = Vec::new();
    for name in ["beams", "indenter_7in"] {
        rows.push((name.to_string(), fz(&n, name), fz(&m, name)));
    }
    for name in ["y_177.8mm", "y_228.6mm"] {
        rows.push((format!("s_yy {name}"), probe(&model_n, &n, name), probe(&model_m, &m, name)));
    }
    for ((what, a, b), id) in rows.iter().zip(["pair", "roller_7in", "s_yy_177", "s_yy_228"]) {
        common::within(&format!("surface.nonmatching.{id}"), *a, *b, 0.02, &format!("{what} on the matching mesh"));
    }
    let total = fz(&m, "indenter_7in") + fz(&m, "indenter_9in");
    let d9 = fz(&n, "indenter_9in") - fz(&m, "indenter_9in");
    common::figure("surface.nonmatching.roller_9in", 100.0 * d9 / total, "%", "< 1 % of the rollers' total force");
    assert!((d9 / total).abs() < 0.01, "9 in roller moved by {d9} N of {total} N");
}

/// The sliding-block model of `surface_friction_slides_at_mu_n`: the
/// upper block pressed on the lower one across non-matching meshes and
/// pushed along +x by `push` (m).
fn sliding_blocks(push: f64) -> String {
    r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "lower"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { from = -0.005, to = 0.025, elements = 3 }, z = { from = -0.01, to = 0.0, elements = 1 } }
axis = { element = "B3", from = 0.0, to = 0.01, elements = 2 }

[[bodies]]
name = "upper"
material = "steel"
section = { shape = "rectangle", element = "L16", x = { from = 0.0, to = 0.02, elements = 2 }, z = { from = 0.0, to = 0.01, elements = 1 } }
axis = { element = "B4", from = 0.0, to = 0.01, elements = 1 }

[[constraints]]
name = "base"
body = "lower"
where = { z = -0.01 }
fix = ["x", "y", "z"]

[[constraints]]
name = "symmetry"
body = "upper"
where = { y = 0.0 }
fix = ["y"]

[[constraints]]
name = "push"
body = "upper"
where = { x = 0.0 }
displacement = { x = PUSH }

[[loads]]
name = "press"
body = "upper"
where = { z = 0.01 }
pressure = 10e6

[[contacts]]
name = "interface"
method = "surface"
master = { body = "lower", where = { z = 0.0 } }
slave = { body = "upper", where = { z = 0.0 } }
friction = 0.3

[[steps]]
name = "press"
increments = 2
factors = { push = 0.0 }

[[steps]]
name = "slide"
increments = 10
"#
    .replace("PUSH", &push.to_string())
}

/// Coulomb friction on surface contact, non-matching meshes: the upper
/// block (2 × 1 L16, 1 B4) pressed by 10 MPa onto the lower one (3 × 1 L9,
/// 2 B3; clamped at its base) and pushed 0.1 mm along +x by its face
/// x = 0. Once the interface slides, the push reaction is μ N with
/// N = 10 MPa × 200 mm² = 2,000 N (vertical equilibrium; Coulomb), and
/// every contact node is sliding. Measured: 600.000000 N (asserted 1e-6,
/// as tests/friction.rs on node-to-node), 28 of 28 nodes sliding, 29
/// Newton iterations over 12 increments with the consistent unsymmetric
/// tangent (182 with its symmetric part alone, before the pressure
/// coupling was assembled).
#[test]
fn surface_friction_slides_at_mu_n() {
    let text = &sliding_blocks(1e-4);
    let (_, sol) = run(text);
    let push = sol.reaction("push").unwrap().force[0];
    let points = sol.contact_points("interface").unwrap();
    let sliding = points.iter().filter(|c| c.active && c.sliding).count();
    let active = points.iter().filter(|c| c.active).count();
    common::within("surface.friction.push", push, 600.0, 1e-6, "μN = 600 N");
    assert!((push / 600.0 - 1.0).abs() < 1e-6, "push reaction {push}");
    assert_eq!(sliding, active);
}

/// Offset bodies: the upper block of the patch test starts 1 µm above the
/// lower one (an initial gap of the projection) and its top is pushed down
/// 5 µm. Once the gap has closed both blocks carry the uniaxial stress
/// σ = −E (5 − 1) µm / (15 + 10) mm = −32 MPa (rollers: uniaxial stress,
/// the two heights in series), uniformly across the non-matching
/// interface; with the augmented Lagrangian (tolerance 1e-12 m) the
/// remaining penetration shifts σ by at most E 1e-12 / 25 mm = 8 Pa.
/// Measured: every node's pressure within 3.5e-9 of 32 MPa (asserted 1e-5).
#[test]
fn an_initial_gap_closes_and_then_transmits_a_uniform_pressure() {
    let text = stacked_blocks("penetration_tolerance = 1e-12", "")
        .replace(
            "z = { from = 0.01, to = 0.025, elements = 3 }",
            "z = { from = 0.010001, to = 0.025001, elements = 3 }",
        )
        .replace(
            "slave = { body = \"upper\", where = { z = 0.01 } }",
            "slave = { body = \"upper\", where = { z = 0.010001 } }",
        )
        + "[[constraints]]\nname = \"push\"\nbody = \"upper\"\nwhere = { z = 0.025001 }\ndisplacement = { z = -5e-6 }\n";
    assert!(text.contains("0.010001 }") && text.contains("from = 0.010001"));
    let (model, sol) = run(&text.replace("increments = 1", "increments = 4"));
    let expected = -200e9 * 4e-6 / 0.025;
    let points = sol.contact_points("interface").unwrap();
    let worst = points
        .iter()
        .map(|c| {
            let f = (c.force[0].powi(2) + c.force[1].powi(2) + c.force[2].powi(2)).sqrt();
            (f / c.area / -expected - 1.0).abs()
        })
        .fold(0.0, f64::max);
    common::figure("surface.gap_closes.pressure", worst, "", "< 1e-5 of 32 MPa at every node");
    assert!(points.iter().all(|c| c.active));
    assert!(worst < 1e-5, "{worst:e}");
    let fields = sol.fields(&model);
    let loc = cufem::values::locate_in_model(&model.mesh, Some(0), [0.011, 0.017, 0.005]);
    let szz = fields.sample(&loc[0]).stress[2];
    assert!((szz / expected - 1.0).abs() < 1e-5, "σ_zz {szz}");
}

/// Finite-difference check of the frictional surface-contact tangent
/// (central differences of the residual against `Structure::tangent_entry`,
/// symmetric part plus the unsymmetric terms of the GMRES path) at the slave and
/// master nodes of the non-matching sliding blocks, pushed 0.2 µm so that
/// the interface partly sticks and partly slides (asserted), solved but not
/// committed so that sliding points are strictly on their cone. The
/// sliding blocks are `(T_b K_tt T_c + μ ε (T_b t̂) G_cᵀ)/A²`; without the
/// unsymmetric pressure coupling (the state before it was assembled) the
/// difference is O(μ) of ε. Measured: 5.4e-9 ε over 182 columns (7
/// sliding, 21 sticking points); with the coupling dropped 6.8e-2 ε.
/// Asserted below 1e-6 of the largest penalty (h = 1e-12 m against
/// relative displacements of 1e-7 m: the differencing error).
#[test]
fn the_frictional_surface_tangent_matches_finite_differences() {
    use cufem::solver::newton::NonlinearProblem;
    let model = Model::parse(&sliding_blocks(3e-7)).unwrap();
    let mut s = analysis::Structure::of_model(&model, None).unwrap();
    assert!(s.is_unsymmetric());
    // press (steps: λ ∈ [0, 1] presses, [1, 2] pushes), then part of the push
    common::solve_path(&mut s, &[(0.5, true), (1.0, true), (1.5, true), (1.7, false)]);
    s.evaluate().unwrap();
    let points = s.contact_points().to_vec();
    let sliding = points.iter().filter(|p| p.active && p.sliding).count();
    let sticking = points.iter().filter(|p| p.active && !p.sliding).count();
    assert!(sliding > 0 && sticking > 0, "partial slip: {sliding} sliding, {sticking} sticking");
    let nl = model.mesh.bodies[0].n_nodes();
    // the slave points and the lower block's interface nodes
    let mut nodes: Vec<usize> = points.iter().filter(|p| p.active).map(|p| p.node).collect();
    nodes.extend((0..nl).filter(|&n| model.mesh.coords(n)[2].abs() < 1e-12));
    let columns: Vec<(usize, usize)> = nodes
        .iter()
        .flat_map(|&n| (0..3).map(move |c| 3 * n + c))
        .filter_map(|d| s.equation(d).map(|e| (d, e)))
        .collect();
    let penalty = (0..points.len()).map(|j| model.contacts[0].point_penalty(j)).fold(0.0, f64::max);
    let (worst, skew) = common::tangent_vs_differences(&mut s, &columns, 1e-12, penalty);
    common::figure("surface.friction.tangent", worst, "ε", "< 1e-6 ε against central differences");
    assert!(skew > 1e-3, "sliding points should make the tangent unsymmetric");
    assert!(worst < 1e-6, "tangent differs from finite differences by {worst:e} of the largest penalty");
}
