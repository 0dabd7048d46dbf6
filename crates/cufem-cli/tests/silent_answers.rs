//! Issue 46: inputs that used to give a wrong answer without a word — a
//! symmetry plane the structure does not have (a velocity, a load, a tool
//! or a laminate that is not its own mirror image), a second velocity for
//! one body, modes that do not exist, analysis combinations that are not
//! supported, the effective masses of a half model — and messages that
//! named what the user never wrote. Each is now refused by key (exit 1) or
//! warned about; where a model stays legal, its answer is checked against
//! an independent one (theory, or the full model of which it is the half).

#[path = "../../../tests/common/mod.rs"]
mod common;

use cufem::analysis::{self, Silent, Solution};
use cufem::setup::Model;

fn solve(text: &str) -> (Model, Solution) {
    let model = Model::parse(text).unwrap_or_else(|e| panic!("{e}"));
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(sol.failure.is_none(), "{:?}", sol.failure);
    (model, sol)
}

/// The displacement at the model's first probe.
fn tip(model: &Model, sol: &Solution) -> [f64; 3] {
    sol.fields(model).sample_probe(&model.probes[0]).unwrap().u
}

fn refused(text: &str) -> String {
    match Model::parse(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// Asserts that `message` holds every one of `parts`.
fn holds(message: &str, parts: &[&str]) {
    for p in parts {
        assert!(message.contains(p), "{p:?} not in: {message}");
    }
}

const STEEL: &str = r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.0
density = 8000.0
"#;

/// A free steel rod 1 m long along y, 10 × 10 mm, flying at `velocity`
/// for 0.6 ms (60 steps), with `extra` appended.
fn flying_rod(velocity: &str, extra: &str) -> String {
    format!(
        r#"
[analysis]
type = "transient"
initial_velocities = [{{ body = "rod", velocity = {velocity} }}]
{STEEL}
[[bodies]]
name = "rod"
material = "steel"
section = {{ shape = "rectangle", element = "L4", x = {{ from = -0.005, to = 0.005, elements = 2 }}, z = {{ from = 0.0, to = 0.01, elements = 1 }} }}
axis = {{ element = "B2", from = 0.0, to = 1.0, elements = 20 }}

[[steps]]
name = "flight"
factor = 1.0
duration = 6e-4
increments = 60

[[probes]]
name = "tip"
point = [0.005, 1.0, 0.005]
{extra}
"#
    )
}

fn plane(name: &str, plane: &str, keep: &str) -> String {
    format!("\n[[symmetry]]\nname = \"{name}\"\nplane = {plane}\nkeep = \"{keep}\"\n")
}

#[test]
fn a_velocity_across_a_symmetry_plane_is_refused_and_one_along_it_is_exact() {
    // the issue's case: cut at y = 0.5, the rod moving along y (the half
    // reported u_y = −1.5e-6 m at the tip where the rod moves 6e-4 m)
    let e = refused(&flying_rod("[0.0, 1.0, 0.0]", &plane("mid", "{ y = 0.5 }", "above")));
    holds(&e, &["analysis.initial_velocities[0].velocity", "[0.0, 1.0, 0.0]", "\"mid\"", "y = 0.5", "velocity[1] = 0"]);
    // a plane normal to x through the section: the same for a lateral velocity
    let e = refused(&flying_rod("[2.0, 0.0, 0.0]", &plane("side", "{ x = 0.0 }", "above")));
    holds(&e, &["analysis.initial_velocities[0].velocity", "\"side\"", "velocity[0] = 0"]);
    // a velocity along the plane is the full rod's: a rigid translation,
    // u = v t = 6e-4 m at the tip after 0.6 ms (free flight, no load)
    let (model, sol) = solve(&flying_rod("[0.0, 1.0, 0.0]", &plane("side", "{ x = 0.0 }", "above")));
    let u = tip(&model, &sol);
    assert!((u[1] - 6e-4).abs() < 1e-9, "{u:?}");
    // its energy: the half's kinetic energy is half the rod's ½ m v² =
    // ½ · (8000 kg/m³ · 1e-4 m³) · (1 m/s)² = 0.4 J, the full structure's all of it
    let summary = cufem::io::full_summary(&model, &sol).unwrap();
    let (part, full) = (summary.energy.unwrap(), summary.full_structure_energy.unwrap());
    let kinetic = (part.get("kinetic").unwrap(), full.get("kinetic").unwrap());
    assert!((kinetic.0 - 0.2).abs() < 1e-9 && (kinetic.1 - 0.4).abs() < 1e-9, "{part:?} {full:?}");
    // the same instant (0.6 ms), every energy of the two images twice the half's
    assert_eq!(full.get("time"), part.get("time"));
    assert!((part.get("time").unwrap() - 6e-4).abs() < 1e-12, "{part:?}");
    for ((name, e), (_, f)) in part.0.iter().zip(&full.0).filter(|((name, _), _)| name != "time") {
        assert_eq!(*f, 2.0 * e, "{name}");
    }
}

#[test]
fn two_velocities_for_one_body_are_refused() {
    let text = flying_rod("[0.0, 1.0, 0.0]", "").replace(
        "initial_velocities = [{ body = \"rod\", velocity = [0.0, 1.0, 0.0] }]",
        "initial_velocities = [{ body = \"rod\", velocity = [0.0, 1.0, 0.0] }, { body = \"rod\", velocity = [0.0, -1.0, 0.0] }]",
    );
    let e = refused(&text);
    holds(&e, &["analysis.initial_velocities[1].body", "\"rod\"", "analysis.initial_velocities[0]"]);
}

/// A steel cantilever (x from −10 to 10 mm, z from 0 to 10 mm, 0.2 m),
/// clamped at y = 0, cut by a plane x = 0, with `extra` appended.
fn half_cantilever(extra: &str) -> String {
    format!(
        r#"
{STEEL}
[[bodies]]
name = "beam"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = -0.01, to = 0.01, elements = 2 }}, z = {{ from = 0.0, to = 0.01, elements = 1 }} }}
axis = {{ element = "B4", from = 0.0, to = 0.2, elements = 4 }}

[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[symmetry]]
name = "mid_x"
plane = {{ x = 0.0 }}
keep = "above"
{extra}
"#
    )
}

#[test]
fn loads_and_tools_that_are_not_their_own_mirror_image_are_refused() {
    let load = |body: &str| format!("[[loads]]\nname = \"tip\"\nbody = \"beam\"\n{body}");
    // a traction across the plane with a component along its normal
    let e = refused(&half_cantilever(&load("where = { y = 0.2 }\ntraction = [1e5, 0.0, -1e5]")));
    holds(&e, &["loads[0].traction", "\"mid_x\"", "no x component"]);
    // … which is fine along the plane
    Model::parse(&half_cantilever(&load("where = { y = 0.2 }\ntraction = [0.0, 0.0, -1e5]"))).unwrap();
    // a pressure on the cut face, which is inside the full structure
    let e = refused(&half_cantilever(&load("where = { x = 0.0 }\npressure = 1e5")));
    holds(&e, &["loads[0].where", "lying in symmetry plane \"mid_x\""]);
    // a sine profile across the plane that is not centred on it
    let e = refused(&half_cantilever(&load(
        "where = { z = 0.01 }\npressure = 1e5\nprofile = { shape = \"sine\", along = \"x\", from = -0.01, to = 0.02 }",
    )));
    holds(&e, &["loads[0].profile", "from = -0.01, to = 0.02", "(from + to)/2 = 0"]);
    let ball = |center: &str, motion: &str| {
        format!(
            "[[indenters]]\nname = \"ball\"\nbody = \"beam\"\nshape = \"sphere\"\nsurface = {{ z = 0.01 }}\n\
             center = {center}\nradius = 0.01\ndisplacement = {motion}"
        )
    };
    // a ball across the plane off its centre, or moving across it
    let e = refused(&half_cantilever(&ball("[0.001, 0.1, 0.02]", "[0.0, 0.0, -1e-4]")));
    holds(&e, &["indenters[0].center", "crosses symmetry plane \"mid_x\"", "x = 0"]);
    let e = refused(&half_cantilever(&ball("[0.0, 0.1, 0.02]", "[1e-5, 0.0, -1e-4]")));
    holds(&e, &["indenters[0].displacement", "displacement[0] = 0"]);
    // a ball clear of the plane is a separate tool with a mirror image,
    // which may move towards the plane
    Model::parse(&half_cantilever(&ball("[0.015, 0.1, 0.02]", "[-1e-5, 0.0, -1e-4]"))).unwrap();
    // a punch whose extent across the plane is off its centre
    let punch = "[[indenters]]\nname = \"punch\"\nbody = \"beam\"\nshape = \"flat\"\nsurface = { z = 0.01 }\n\
                 normal = \"-z\"\nposition = 0.01\nx = [-0.005, 0.01]\ndisplacement = [0.0, 0.0, -1e-4]";
    holds(&refused(&half_cantilever(punch)), &["indenters[0].x", "crosses symmetry plane"]);
    // a tool or a contact on the cut face, which the plane's u_x = 0 holds (inside the full
    // structure there is no surface to press)
    let side = "[[indenters]]\nname = \"side\"\nbody = \"beam\"\nshape = \"flat\"\nsurface = { x = 0.0 }\n\
                normal = \"+x\"\nposition = -0.001\ndisplacement = [2e-3, 0.0, 0.0]";
    holds(&refused(&half_cantilever(side)), &["indenters[0].surface", "lying in symmetry plane \"mid_x\""]);
    let pad = "[[bodies]]\nname = \"pad\"\nmaterial = \"steel\"\nsection = { shape = \"rectangle\", element = \"L9\", \
               x = { from = 0.0, to = 0.01, elements = 1 }, z = { from = 0.01, to = 0.02, elements = 1 } }\n\
               axis = { element = \"B4\", from = 0.0, to = 0.2, elements = 4 }\n\
               [[contacts]]\nname = \"c\"\nmaster = { body = \"pad\", where = { x = 0.0 } }\n\
               slave = { body = \"beam\", where = { z = 0.01 } }";
    holds(&refused(&half_cantilever(pad)), &["contacts[0].master.where", "lying in symmetry plane \"mid_x\""]);
}

#[test]
fn a_conflict_with_a_plane_names_the_constraint_and_the_plane() {
    let pull = "[[constraints]]\nname = \"pull\"\nbody = \"beam\"\nwhere = { y = 0.2 }\ndisplacement = { x = 1e-4 }";
    let e = refused(&half_cantilever(pull));
    holds(&e, &["constraints[1].displacement.x", "0.0001", "symmetry[0] \"mid_x\"", "\"pull\""]);
    // the plane's own constraint is internal: its index (constraints[2]) is no key of the file
    assert!(!e.contains("constraints[2]"), "{e}");
}

const PLY: &str = r#"
[[materials]]
name = "ply"
orthotropic = { e1 = 140e9, e2 = 10e9, e3 = 10e9, g12 = 5e9, g13 = 5e9, g23 = 3.5e9, nu12 = 0.3, nu13 = 0.3, nu23 = 0.4 }
density = 1600.0
"#;

/// A two-ply laminate cantilever (x from −10 to 10 mm, plies of 2 mm from
/// z = −2 mm at angles `a1`, `a2`), 0.2 m, loaded at its tip by `traction`.
fn laminate(a1: f64, a2: f64, traction: &str, extra: &str) -> String {
    format!(
        r#"
{PLY}
[[bodies]]
name = "lam"
section = {{ shape = "laminate", element = "L9", x = {{ from = -0.01, to = 0.01, elements = 2 }}, z0 = -0.002, plies = [
  {{ thickness = 0.002, material = "ply", angle = {a1}, elements = 1 }},
  {{ thickness = 0.002, material = "ply", angle = {a2}, elements = 1 }},
] }}
axis = {{ element = "B4", from = 0.0, to = 0.2, elements = 4 }}

[[constraints]]
name = "root"
body = "lam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]

[[loads]]
name = "tip"
body = "lam"
where = {{ y = 0.2 }}
traction = {traction}

[[probes]]
name = "tip"
point = [0.0, 0.2, 0.0]
{extra}
"#
    )
}

#[test]
fn a_laminate_that_is_not_its_own_mirror_image_refuses_the_plane() {
    // [30/−30] cut at x = 0: each ply faces itself at 30° across the plane,
    // whose mirror image is −30° (the half was 2–4 % off and lost the twist)
    let e = refused(&laminate(30.0, -30.0, "[0.0, 0.0, -1.25e5]", &plane("cut", "{ x = 0.0 }", "above")));
    holds(&e, &["symmetry[0].plane", "x = 0", "\"lam\"", "bodies[0].section.plies[0]", "angle 30°", "\"ply\""]);
    // [0/90] cut at the ply interface: ply 1 faces ply 2 (w ≈ 0 against −6.9 mm)
    let e = refused(&laminate(0.0, 90.0, "[0.0, 1.25e7, 0.0]", &plane("cut", "{ z = 0.0 }", "above")));
    holds(&e, &["symmetry[0].plane", "z = 0", "bodies[0].section.plies[0]", "bodies[0].section.plies[1]", "angle 90°"]);
    // [30/−30] cut across the axis: every ply is turned by the mirror
    let e = refused(&laminate(30.0, -30.0, "[0.0, 0.0, -1.25e5]", &plane("cut", "{ y = 0.1 }", "below")));
    holds(&e, &["symmetry[0].plane", "y = 0.1", "not its own mirror image"]);
    // [30/30] is its own mirror image across z = 0 (but a bending load is
    // not: a traction along z on faces touching the plane is refused)
    let e = refused(&laminate(30.0, 30.0, "[0.0, 0.0, -1.25e5]", &plane("cut", "{ z = 0.0 }", "above")));
    holds(&e, &["loads[0].traction", "no z component"]);
}

#[test]
fn a_cross_ply_laminate_cut_at_its_mirror_plane_is_its_full_model() {
    // [0/90] about x = 0 is its own mirror image: the half gives the full
    // model's tip deflection and axial stretch (a mirror-symmetric problem
    // has a mirror-symmetric solution; crates/cufem-cli/tests/symmetry.rs for isotropic bars)
    for traction in ["[0.0, 0.0, -1.25e5]", "[0.0, 1.25e7, 0.0]"] {
        let (fm, full) = solve(&laminate(0.0, 90.0, traction, ""));
        let (hm, half) = solve(&laminate(0.0, 90.0, traction, &plane("cut", "{ x = 0.0 }", "above")));
        let (f, h) = (tip(&fm, &full), tip(&hm, &half));
        let scale = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for k in 0..3 {
            assert!((f[k] - h[k]).abs() < 1e-6 * scale, "{traction}: full {f:?}, half {h:?}");
        }
    }
}

#[test]
fn a_body_written_on_one_side_only_warns_about_its_mirrored_plies() {
    let text = laminate(30.0, -30.0, "[0.0, 0.0, -1.25e5]", &plane("cut", "{ x = 0.0 }", "above"))
        .replace("x = { from = -0.01, to = 0.01, elements = 2 }", "x = { from = 0.0, to = 0.01, elements = 1 }");
    let model = Model::parse(&text).unwrap();
    let w = model.warnings.iter().find(|w| w.key == "symmetry[0]").expect("a warning on symmetry[0]");
    holds(&w.message, &["\"lam\"", "one side", "bodies[0].section.plies[0]", "−θ"]);
    // an isotropic body written on one side has nothing to warn about
    let iso =
        half_cantilever("").replace("from = -0.01, to = 0.01, elements = 2", "from = 0.0, to = 0.01, elements = 1");
    assert!(Model::parse(&iso).unwrap().warnings.iter().all(|w| w.key != "symmetry[0]"));
}

#[test]
fn a_body_whose_extent_is_not_symmetric_refuses_the_plane() {
    // the axis from 0 to 0.2 cut at y = 0.05: the model would solve −0.1 to 0.2
    let text =
        half_cantilever("").replace("plane = { x = 0.0 }\nkeep = \"above\"", "plane = { y = 0.05 }\nkeep = \"above\"");
    let e = refused(&text.replace("where = { y = 0.0 }", "where = { y = 0.2 }"));
    holds(&e, &["bodies[0].axis", "from y = 0 to y = 0.2", "y = -0.1 to y = 0.2"]);
    // the section from −4 to 10 mm cut at x = 0
    let e =
        refused(&half_cantilever("").replace("from = -0.01, to = 0.01, elements = 2", "lines = [-0.004, 0.0, 0.01]"));
    holds(&e, &["bodies[0].section", "its own mirror image", "\"mid_x\""]);
}

#[test]
fn messages_name_the_users_keys() {
    // plies = [] is empty, not missing
    let e = refused(&laminate(0.0, 90.0, "[0.0, 0.0, -1.0]", "").replace(
        "plies = [\n  { thickness = 0.002, material = \"ply\", angle = 0, elements = 1 },\n  { thickness = 0.002, material = \"ply\", angle = 90, elements = 1 },\n]",
        "plies = []",
    ));
    holds(&e, &["bodies[0].section.plies = [] (an empty list", "at least one ply"]);
    // an oriented ply's material is the file's `materials[0]`, not `ply@-30`
    let modal =
        laminate(-30.0, 30.0, "[0.0, 0.0, -1.0]", "[analysis]\ntype = \"modal\"\n").replace("density = 1600.0", "");
    let e = refused(&modal);
    holds(&e, &["materials[0].density", "material \"ply\""]);
    assert!(!e.contains('@'), "{e}");
    // a tube of plies too thick for it: the plies, not `thickness`, `web_thickness` or flanges
    let tube = |plies: &str| {
        format!(
            "{PLY}\n[[bodies]]\nname = \"t\"\nsection = {{ shape = \"tube\", element = \"L9\", width = 0.02, \
             height = 0.02, along_x = 1, along_z = 1, plies = {plies} }}\naxis = {{ element = \"B4\", from = 0.0, \
             to = 0.2, elements = 2 }}\n[[constraints]]\nname = \"root\"\nbody = \"t\"\nwhere = {{ y = 0.0 }}\n\
             fix = [\"x\", \"y\", \"z\"]\n"
        )
    };
    let thick = "[{ thickness = 0.006, material = \"ply\" }, { thickness = 0.006, material = \"ply\" }]";
    let e = refused(&tube(thick));
    holds(&e, &["bodies[0].section.plies", "0.012"]);
    assert!(!e.contains("web") && !e.contains("flange") && !e.contains(".thickness"), "{e}");
    // an I-beam of plies too thick for its width
    let ibeam = tube(thick)
        .replace("shape = \"tube\"", "shape = \"i_beam\"")
        .replace("height = 0.02, along_x = 1, along_z = 1,", "height = 0.05,")
        .replace("0.006", "0.012");
    let e = refused(&ibeam);
    holds(&e, &["bodies[0].section.plies = a total thickness of 0.024"]);
    assert!(!e.contains("web_thickness ="), "{e}");
}

/// A clamped–free column (20 × 20 mm, 1 m) under `load` N along −y.
fn column(load: f64, extra: &str) -> String {
    common::clamped_column("", STEEL, [0.01, 0.01], 1, 10, &format!("total_force = [0.0, -{load}, 0.0]"), extra)
}

#[test]
fn unsupported_analysis_combinations_are_refused_by_key() {
    // arc length with buckling: a 500 N load was reported with a 625 N reaction
    let arc =
        "[analysis]\ntype = \"buckling\"\n[solver]\ncontrol = \"arc_length\"\narc_length = 1e-4\nmax_load_factor = 1.2";
    holds(&refused(&column(500.0, arc)), &["solver.control = \"arc_length\"", "analysis.type = \"buckling\""]);
    // adapt.modes: modal and buckling only, at most the modes computed
    let e = refused(&flying_rod("[0.0, 1.0, 0.0]", "[adapt]\nmodes = 1"));
    holds(&e, &["adapt.modes = 1", "only with analysis.type = \"modal\" or \"buckling\""]);
    let e = refused(&column(500.0, "[adapt]\nmodes = 2"));
    holds(&e, &["adapt.modes = 2", "only with analysis.type = \"modal\" or \"buckling\""]);
    let e = refused(&column(500.0, "[analysis]\ntype = \"buckling\"\nmodes = 2\n[adapt]\nmodes = 3"));
    holds(&e, &["adapt.modes = 3", "1..=2"]);
    let e = refused(&(one_element(4) + "[adapt]\nmodes = 5\n"));
    holds(&e, &["adapt.modes = 5", "1..=4", "analysis.modes = 4"]);
    let e = refused(&(one_element(4) + "[adapt]\nmodes = 0\n"));
    holds(&e, &["adapt.modes = 0", "1..=4"]);
}

/// One B2 × L4 element clamped at one end: 8 nodes, 4 fixed, 12 equations.
fn one_element(modes: usize) -> String {
    format!(
        r#"
[analysis]
type = "modal"
modes = {modes}
{STEEL}
[[bodies]]
name = "b"
material = "steel"
section = {{ shape = "rectangle", element = "L4", x = {{ from = 0.0, to = 0.01, elements = 1 }}, z = {{ from = 0.0, to = 0.01, elements = 1 }} }}
axis = {{ element = "B2", from = 0.0, to = 0.1, elements = 1 }}

[[constraints]]
name = "root"
body = "b"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]
"#
    )
}

#[test]
fn more_modes_than_equations_are_warned_about() {
    let (model, sol) = solve(&one_element(50));
    let w = model.warnings.iter().find(|w| w.key == "analysis.modes").expect("a warning on analysis.modes");
    holds(&w.message, &["analysis.modes = 50", "12 free equations", "at most 12 modes"]);
    assert_eq!(sol.modal.as_ref().unwrap().frequencies.len(), 12);
    // as many as there are: no warning
    let (model, _) = solve(&one_element(12));
    assert!(model.warnings.iter().all(|w| w.key != "analysis.modes"));
}

/// A cantilever (x from −10 to 10 mm, z from 0 to 15 mm, 0.3 m) in free
/// vibration, with `extra` appended.
fn vibrating(extra: &str) -> String {
    format!(
        r#"
[analysis]
type = "modal"
modes = 8
{STEEL}
[[bodies]]
name = "b"
material = "steel"
section = {{ shape = "rectangle", element = "L9", x = {{ from = -0.01, to = 0.01, elements = 2 }}, z = {{ from = 0.0, to = 0.015, elements = 1 }} }}
axis = {{ element = "B4", from = 0.0, to = 0.3, elements = 6 }}

[[constraints]]
name = "root"
body = "b"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]
{extra}
"#
    )
}

#[test]
fn a_half_model_reports_the_full_structures_effective_masses() {
    // reference: the full model, whose modes symmetric about x = 0 are the
    // half's (bending in z, axial); the half's own masses are half of them
    let (_, full) = solve(&vibrating(""));
    let (_, half) = solve(&vibrating(&plane("s", "{ x = 0.0 }", "above")));
    let (full, half) = (full.modal.unwrap(), half.modal.unwrap());
    assert!(!full.full_structure && half.full_structure);
    for k in 0..3 {
        assert!((half.free_mass[k] - full.free_mass[k]).abs() < 1e-9 * full.free_mass[k], "{k}");
    }
    let mut matched = 0;
    for (f, m) in half.frequencies.iter().zip(&half.effective_masses) {
        // along the plane's normal a symmetric mode carries no mass
        assert_eq!(m[0], 0.0);
        let Some(i) = full.frequencies.iter().position(|g| (g - f).abs() < 1e-6 * f) else { continue };
        matched += 1;
        for k in 1..3 {
            let (a, b) = (m[k], full.effective_masses[i][k]);
            assert!((a - b).abs() < 1e-6 * full.free_mass[k], "mode at {f} Hz, {k}: half {a}, full {b}");
        }
    }
    // the first four symmetric modes (z bending 1–3, axial) are in both lists
    assert!(matched >= 4, "{matched}");
}

#[test]
fn command_line_values_are_checked_before_running() {
    let dir = common::scratch_dir("silent_answers", "cli");
    let model = dir.join("column.toml");
    std::fs::write(&model, column(1.0, "[[probes]]\nname = \"tip\"\npoint = [0.0, 1.0, 0.0]")).unwrap();
    let model = model.to_str().unwrap();
    let out = dir.join("out");
    // --ccx-results on a folder that is not there: exit 1 before the analysis, naming the option and the folder
    let missing = dir.join("no_such_folder");
    let r = common::cufem()
        .args(["verify", model, "--out", out.to_str().unwrap(), "--quiet", "--ccx-results", missing.to_str().unwrap()])
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{e}");
    holds(&e, &["--ccx-results", "no_such_folder", "no such folder", "model.inp"]);
    assert!(!out.exists(), "nothing computed or written");
    // --max-memory -5G: the option and the allowed form, not "unexpected argument '-5'"
    let r = common::cufem().args(["check", model, "--max-memory", "-5G"]).output().unwrap();
    let e = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{e}");
    holds(&e, &["--max-memory", "-5G", "positive size such as 8G"]);
}

#[test]
fn warnings_and_whose_masses_reach_summary_json_and_stderr() {
    let dir = common::scratch_dir("silent_answers", "summary");
    let model = dir.join("m.toml");
    std::fs::write(&model, one_element(50) + &plane("s", "{ x = 0.0 }", "above")).unwrap();
    let out = dir.join("out");
    let r = common::cufem()
        .args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&r.stderr);
    assert!(r.status.success(), "{e}");
    holds(&e, &["warning: analysis.modes"]);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let warnings: Vec<&str> = summary["warnings"].as_array().unwrap().iter().map(|w| w.as_str().unwrap()).collect();
    assert!(warnings.iter().any(|w| w.starts_with("analysis.modes:")), "{warnings:?}");
    assert_eq!(summary["modal"]["effective_masses_of"], "full_structure");
}

/// A steel column 1 m long, 20 mm wide in x and 16 mm thick in z (so it
/// buckles in z first), fixed at y = 0, pressed by a traction of 1 MPa on its
/// tip face (320 N), for linear buckling; `extra` appended.
fn pressed_column(extra: &str) -> String {
    let head = "[analysis]\ntype = \"buckling\"\nmodes = 2";
    common::clamped_column(head, STEEL, [0.01, 0.008], 2, 8, "traction = [0.0, -1e6, 0.0]", extra)
}

#[test]
fn a_half_model_reports_the_full_structures_critical_loads() {
    // reference: Euler's load of a cantilever buckling in z, π² E I / (4 L²)
    // with I = 0.02 · 0.016³ / 12 (3.37 kN), and the full model; the half cut
    // at x = 0 carries half the tip face and so half the load, at the same
    // factor (bending in z is symmetric about x = 0)
    let euler = std::f64::consts::PI.powi(2) * 200e9 * 0.02 * 0.016f64.powi(3) / 12.0 / 4.0;
    let summary = |text: &str| {
        let (model, sol) = solve(text);
        cufem::io::full_summary(&model, &sol).unwrap().buckling.unwrap()
    };
    let full = summary(&pressed_column(""));
    let half = summary(&pressed_column(&plane("s", "{ x = 0.0 }", "above")));
    assert!(full.full_structure_critical_loads.is_none());
    let first = |loads: &[[f64; 3]]| -loads[0][1];
    // the full model within 1 % of Euler (shear and the B4 mesh)
    assert!((first(&full.critical_loads) / euler - 1.0).abs() < 0.01, "{} vs {euler}", first(&full.critical_loads));
    // the half model's own load is half; the full structure's is the full model's
    let whole = half.full_structure_critical_loads.as_deref().unwrap();
    assert!((first(&half.critical_loads) / first(&full.critical_loads) - 0.5).abs() < 1e-6);
    assert!((first(whole) / first(&full.critical_loads) - 1.0).abs() < 1e-6, "{whole:?} vs {:?}", full.critical_loads);
    // and nothing across the plane: the x component of the full structure's load is zero
    assert_eq!(whole[0][0], 0.0);
}
