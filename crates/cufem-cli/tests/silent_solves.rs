//! Analyses that used to end with a wrong answer and exit 0 (issue 46,
//! "silent wrong answers"): each is now refused by key (exit 1), stopped
//! honestly (exit 2, the last converged state written, the reason named)
//! or warned about (summary.json `warnings` and stderr).

use std::path::{Path, PathBuf};

#[path = "../../../tests/common/mod.rs"]
mod common;

const EXAMPLES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples");

fn example(name: &str) -> String {
    std::fs::read_to_string(Path::new(EXAMPLES).join(name)).unwrap()
}

/// `text` replaced at `from` (which must occur).
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} not in the model");
    text.replacen(from, to, 1)
}

/// A run of `cufem run` on a model written from `text`.
struct Run {
    code: Option<i32>,
    stderr: String,
    out: PathBuf,
}

impl Run {
    fn summary(&self) -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(self.out.join("summary.json")).unwrap()).unwrap()
    }

    /// The warnings of summary.json that mention every one of `words`.
    fn warnings_with(&self, words: &[&str]) -> Vec<String> {
        let s = self.summary();
        let all = s["warnings"].as_array().unwrap().iter().map(|w| w.as_str().unwrap().to_string());
        all.filter(|w| words.iter().all(|k| w.contains(k))).collect()
    }
}

fn run(name: &str, text: &str, args: &[&str]) -> Run {
    let dir = common::scratch_dir("silent", name);
    let model = dir.join(format!("{name}.toml"));
    std::fs::write(&model, text).unwrap();
    let out = dir.join("out");
    let o = common::cufem()
        .args(["run", model.to_str().unwrap(), "--quiet", "--out", out.to_str().unwrap()])
        .args(args)
        .output()
        .unwrap();
    Run { code: o.status.code(), stderr: String::from_utf8_lossy(&o.stderr).into_owned(), out }
}

// ---------------------------------------------------------------- arc length

/// `solver.arc_length` of 1 m and 1 km on the arch (the linear path to
/// λ = 1 is 0.0505 m long at its start): the first increment alone would
/// carry λ to 20 and 2e4. They used to end "converged" at λ = 13.19 and
/// 2.3e6 (|σ| = 1.6e14 Pa), past max_load_factor = 1 and over the
/// snap-through at λ = 0.977 without a word; now refused by key, with the
/// bound.
#[test]
fn an_arc_length_too_long_for_the_model_is_refused() {
    for (value, shown) in [("1.0", "1 m"), ("1e3", "1000 m")] {
        let text = edit(&example("arch_snap_through.toml"), "increments = 20", &format!("arc_length = {value}"));
        let r = run(&format!("arc_{value}"), &text, &[]);
        assert_eq!(r.code, Some(1), "{}", r.stderr);
        assert!(r.stderr.contains(&format!("solver.arc_length = {shown}")), "{}", r.stderr);
        assert!(r.stderr.contains("at most 5.051e-2 m"), "{}", r.stderr);
    }
}

/// The same 1 m arc with max_load_factor = 20 (the linear path to it is
/// 1.01 m, so the arc is allowed): its first increment converges at
/// λ = 13.19 on the inverted arch, 23° from its predictor, and is redone
/// shorter until the path passes the limit point (peak 0.977 by
/// displacement control, crates/cufem-cli/tests/path_following.rs) and the snap-back
/// minimum, each below the exact peak (a point on the path cannot exceed
/// it); the run lands on λ = 20 exactly. It used to report no limit point.
#[test]
fn a_long_arc_passes_the_limit_points_and_lands_on_the_end() {
    let text = edit(&example("arch_snap_through.toml"), "increments = 20", "arc_length = 1.0");
    let text = edit(&text, "max_load_factor = 1.0", "max_load_factor = 20.0");
    let text = edit(&text, "stop = { probe = \"crown\", component = \"z\", beyond = -0.07 }", "");
    let r = run("arc_long", &text, &[]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    let s = r.summary();
    let limits = s["path"]["limit_points"].as_array().unwrap();
    assert_eq!(limits.len(), 2, "{limits:?}");
    let (top, valley) = (limits[0][1].as_f64().unwrap(), limits[1][1].as_f64().unwrap());
    assert!(top <= 0.978 && valley < top, "{limits:?}");
    assert_eq!(s["load_factor"].as_f64(), Some(20.0));
    assert!(s["cutbacks"].as_u64().unwrap() >= 1);
}

// ------------------------------------------------------- unstable states

/// The clamped–free column of examples/column_buckling.toml (20 × 20 mm,
/// L = 1 m, E = 200 GPa) with nonlinear geometry and no imperfection,
/// under an axial load `force` in 10 increments.
fn perfect_column(force: &str) -> String {
    let text = edit(&example("column_buckling.toml"), "type = \"buckling\"\nmodes = 4", "geometry = \"nonlinear\"");
    edit(&text, "total_force = [0.0, -1.0, 0.0]", &format!("total_force = [0.0, -{force}, 0.0]"))
}

/// Euler's load of that column, P₁ = π² E I/(4 L²) = 6580 N, the same in
/// both bending planes (square section); the next, 9 P₁, is 59 kN. Under
/// 20 kN (3.04 P₁) load control stays on the straight path, which is
/// unstable with exactly two negative pivots (both planes): the run
/// converges and used to say nothing. It now warns with the count, the
/// load factor and what to do; at 6 kN (0.91 P₁) it does not.
#[test]
fn a_state_past_the_euler_load_is_called_unstable() {
    let past = run("unstable_past", &perfect_column("2e4"), &[]);
    assert_eq!(past.code, Some(0), "{}", past.stderr);
    let w = past.warnings_with(&["analysis.imperfection", "unstable", "2 negative pivots", "load factor 1.000000"]);
    assert_eq!(w.len(), 1, "{:?}", past.summary()["warnings"]);
    assert!(w[0].contains("arc_length") && w[0].contains("buckling"), "{}", w[0]);
    assert!(past.stderr.contains("warning: analysis.imperfection"), "{}", past.stderr);
    let below = run("unstable_below", &perfect_column("6e3"), &[]);
    assert_eq!(below.code, Some(0), "{}", below.stderr);
    assert!(below.warnings_with(&["unstable"]).is_empty(), "{:?}", below.summary()["warnings"]);
}

/// A modal analysis about the same state (3.04 P₁): its pre-stressed
/// tangent is indefinite, so it has no natural frequencies. It used to exit
/// 1 ("analysis failed") and write nothing; now the converged static state
/// is written (the root's reaction balances the 20 kN) and the run stops
/// with the reason (exit 2).
#[test]
fn a_modal_analysis_past_the_euler_load_keeps_the_static_state() {
    let text = edit(&perfect_column("2e4"), "geometry = \"nonlinear\"", "geometry = \"nonlinear\"\ntype = \"modal\"");
    let text = edit(&text, "poisson_ratio = 0.3", "poisson_ratio = 0.3\ndensity = 7850.0");
    let r = run("modal_past", &text, &[]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    let s = r.summary();
    assert_eq!(s["status"], "not_converged");
    let failure = s["failure"].as_str().unwrap();
    for needle in ["modal analysis", "not positive definite", "2 negative pivots", "unstable", "static results"] {
        assert!(failure.contains(needle), "{needle}: {failure}");
    }
    assert_eq!(s["load_factor"].as_f64().map(|l| (l - 1.0).abs() < 1e-12), Some(true));
    let root = s["reactions"].as_array().unwrap().iter().find(|r| r["name"] == "root").unwrap();
    assert!((root["force"][1].as_f64().unwrap() - 2e4).abs() < 1e-6 * 2e4, "{root}");
    assert!(r.out.join("result.vtu").exists());
}

// -------------------------------------------------------------- buckling

/// Buckling without loads, and with 1e-300 N: an empty table and exit 0
/// before; now refused on `loads`.
#[test]
fn buckling_without_a_load_is_refused() {
    let text = example("column_buckling.toml");
    let start = text.find("[[loads]]").unwrap();
    let end = text.find("[[probes]]").unwrap();
    let none = format!("{}{}", &text[..start], &text[end..]);
    let tiny = edit(&text, "total_force = [0.0, -1.0, 0.0]", "total_force = [0.0, -1e-300, 0.0]");
    for (name, text, value) in [("none", none, "loads = []"), ("tiny", tiny, "loads = 1 entry")] {
        let r = run(&format!("buckling_{name}"), &text, &[]);
        assert_eq!(r.code, Some(1), "{name}: {}", r.stderr);
        assert!(r.stderr.contains(value) && r.stderr.contains("analysis.type = \"buckling\""), "{}", r.stderr);
    }
}

/// The column in tension (1 N pulling) buckles at no load: a structure in
/// tension has no buckling load. With B2 axis elements the eigenproblem
/// still finds μ = 4.05e6, at which the column would strain by 5.4 %
/// (4.05e6 N over 4e-4 m² at E = 200 GPa: 5.1 % by hand): reported as a
/// buckling load before, now set apart with a warning and an empty table;
/// with B4 elements it finds none and says so. `imperfection` used that
/// factor's mode; it is now refused.
#[test]
fn a_column_in_tension_has_no_buckling_load() {
    let tension =
        edit(&example("column_buckling.toml"), "total_force = [0.0, -1.0, 0.0]", "total_force = [0.0, 1.0, 0.0]");
    for (name, text) in [("b4", tension.clone()), ("b2", edit(&tension, "\"B4\"", "\"B2\""))] {
        let r = run(&format!("tension_{name}"), &text, &[]);
        assert_eq!(r.code, Some(0), "{name}: {}", r.stderr);
        let s = r.summary();
        assert_eq!(s["buckling"]["factors"].as_array().unwrap().len(), 0, "{name}: {}", s["buckling"]);
        let w = r.warnings_with(&["analysis.type", "no buckling load"]);
        assert_eq!(w.len(), 1, "{name}: {:?}", s["warnings"]);
        if name == "b2" {
            assert!(w[0].contains("[4.049e6") && w[0].contains("5.4 %"), "{}", w[0]);
        }
    }
    let imperfect = edit(
        &edit(&tension, "\"B4\"", "\"B2\""),
        "type = \"buckling\"\nmodes = 4",
        "geometry = \"nonlinear\"\nimperfection = { mode = 1, amplitude = 1e-3 }",
    );
    let r = run("tension_imperfection", &imperfect, &[]);
    assert_eq!(r.code, Some(1), "{}", r.stderr);
    assert!(r.stderr.contains("analysis.imperfection.mode = 1") && r.stderr.contains("[4.049e6]"), "{}", r.stderr);
}

// ------------------------------------------------------------ magnitudes

/// A 0.2 m orthotropic cantilever (E = 25 GPa across, 1 GPa along its axis
/// y — the material's axis 1 is x), 10 × 10 mm, under a tip force `force`.
fn orthotropic_cantilever(force: &str) -> String {
    format!(
        r#"title = "orthotropic cantilever"
[[materials]]
name = "ply"
orthotropic = {{ e1 = 25e9, e2 = 1e9, e3 = 1e9, g12 = 0.5e9, g13 = 0.5e9, g23 = 0.2e9, nu12 = 0.25, nu13 = 0.25, nu23 = 0.25 }}
[[bodies]]
name = "beam"
material = "ply"
section = {{ shape = "rectangle", element = "L9", x = {{ from = 0.0, to = 0.01, elements = 1 }}, z = {{ from = 0.0, to = 0.01, elements = 1 }} }}
axis = {{ element = "B4", from = 0.0, to = 0.2, elements = 4 }}
[[constraints]]
name = "root"
body = "beam"
where = {{ y = 0.0 }}
fix = ["x", "y", "z"]
[[loads]]
name = "tip"
body = "beam"
where = {{ y = 0.2 }}
total_force = [0.0, 0.0, -{force}]
"#
    )
}

/// Beam theory puts that cantilever's tip at P L³/(3 E₂ I) = 320 m under
/// 100 kN (I = 8.33e-10 m⁴): a small-strain run reported it and exit 0.
/// It now warns on `analysis.geometry` (displacement beyond the body's
/// 0.2 m size, gradients far beyond small) and on the material (a von
/// Mises stress of several times its stiffest modulus). Under 10 N (tip
/// 0.032 m, rotations near 0.24 rad) it does not: within what small strain
/// is warned about.
#[test]
fn an_impossible_small_strain_answer_is_warned_about() {
    let r = run("ortho_huge", &orthotropic_cantilever("1e5"), &[]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert_eq!(r.warnings_with(&["analysis.geometry", "more than its own size"]).len(), 1);
    assert_eq!(r.warnings_with(&["analysis.geometry", "far beyond small strain"]).len(), 1);
    assert_eq!(r.warnings_with(&["materials[0]", "von Mises", "\"ply\""]).len(), 1);
    let ok = run("ortho_ok", &orthotropic_cantilever("10"), &[]);
    assert_eq!(ok.code, Some(0), "{}", ok.stderr);
    assert_eq!(ok.summary()["warnings"].as_array().unwrap().len(), 0, "{:?}", ok.summary()["warnings"]);
}

/// examples/rod_impact.toml at 1e4 m/s instead of 1 m/s: the elastic
/// impact stress ρ c v = 8000 × 5000 × 1e4 = 4e11 Pa would be twice E; the
/// small-strain run reached 1.4e11 Pa (69 % of E) and said nothing. Now
/// warned on the material.
#[test]
fn an_impact_stress_beyond_the_modulus_is_warned_about() {
    let text = edit(&example("rod_impact.toml"), "velocity = [0.0, 1.0, 0.0]", "velocity = [0.0, 1e4, 0.0]");
    let r = run("rod_1e4", &text, &[]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert_eq!(r.warnings_with(&["materials[0]", "von Mises", "\"steel\""]).len(), 1, "{:?}", r.summary()["warnings"]);
}

// ---------------------------------------------------------- conditioning

/// ν = 0.4999999 and a 1e-12 m ply used to run into a generic Newton stop
/// (the residual stalling at 1e-5 and 1e-3): refused up front by key, with
/// the bound.
#[test]
fn an_ill_conditioned_model_is_refused_by_key() {
    let nu = edit(&example("epp_cantilever.toml"), "poisson_ratio = 0.3", "poisson_ratio = 0.4999999");
    let r = run("nu_half", &nu, &[]);
    assert_eq!(r.code, Some(1), "{}", r.stderr);
    assert!(
        r.stderr.contains("materials[0].poisson_ratio = 0.4999999: expected a number in (−1, 0.4999]"),
        "{}",
        r.stderr
    );
    let ply = edit(
        &example("pagano_s4.toml"),
        "{ thickness = 0.0033333333333333335, material = \"ply\", angle = 90.0",
        "{ thickness = 1e-12, material = \"ply\", angle = 90.0",
    );
    // the top face, loaded, moves down with the middle ply gone
    let ply = edit(&ply, "where = { z = 0.005 }", "where = { z = 0.0016666666666666670 }");
    let r = run("thin_ply", &ply, &[]);
    assert_eq!(r.code, Some(1), "{}", r.stderr);
    assert!(r.stderr.contains("bodies[0].section.plies[1].thickness = 1e-12: expected at least"), "{}", r.stderr);
}

/// An L9 section with a middle element 1e-8 m thick in a 10 mm section
/// (1e-6 of it; a `quads` section, which no bound refuses): the linear
/// model stalls at a relative residual of 4e-5 — no bound is physically
/// motivated, so the stop message names the scale and its key.
#[test]
fn a_stalled_linear_model_names_its_extreme_scale() {
    let text = r#"title = "thin element"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
[[bodies]]
name = "beam"
material = "steel"
axis = { element = "B4", from = 0.0, to = 1.0, elements = 4 }
[bodies.section]
shape = "quads"
element = "L9"
points = [[0.0, 0.0], [0.01, 0.0], [0.0, 0.005], [0.01, 0.005], [0.0, 0.00500001], [0.01, 0.00500001], [0.0, 0.01], [0.01, 0.01]]
quads = [[0, 1, 3, 2], [2, 3, 5, 4], [4, 5, 7, 6]]
[[constraints]]
name = "root"
body = "beam"
where = { y = 0.0 }
fix = ["x", "y", "z"]
[[loads]]
name = "tip"
body = "beam"
where = { y = 1.0 }
total_force = [0.0, 0.0, -100.0]
"#;
    let r = run("thin_quad", text, &[]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    let failure = r.summary()["failure"].as_str().unwrap().to_string();
    for needle in
        ["the model is linear", "ill-conditioned", "section element 1 of body \"beam\"", "(bodies[0].section)"]
    {
        assert!(failure.contains(needle), "{needle}: {failure}");
    }
}

// ------------------------------------------------------------- adaptivity

/// The Timoshenko cantilever of examples/cantilever_timoshenko.toml on a
/// 1 × 1 L9 section and 2 B4: `--adapt 0.001` refines it to 189, 450, 1,053,
/// 2,160 and 3,705 DOF (z and the axis, then x once the section's shear
/// is seen across it: `post::spr`, `mark::by_direction`), whose analyses
/// need 11.7, 13.1, 16.6, 24.9 and 37.6 MiB (the console's `memory
/// estimate`).
fn coarse_cantilever() -> String {
    let text = example("cantilever_timoshenko.toml");
    let text = edit(
        &text,
        "x = { from = 0.0, to = 0.1, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 2 }",
        "x = { from = 0.0, to = 0.1, elements = 1 }, z = { from = 0.0, to = 0.1, elements = 1 }",
    );
    edit(&text, "to = 1.0, elements = 5 }", "to = 1.0, elements = 2 }")
}

/// `--max-memory 30M`: cycle 4's mesh (3,705 DOF) needs 37.6 MiB. The run
/// used to exit 4 and write nothing of the finished cycles; now it stops
/// there as the DOF budget does (exit 0) and writes cycle 3 as a complete
/// result set, saying why and which cycle.
#[test]
fn an_adaptive_run_at_the_memory_limit_keeps_its_last_cycle() {
    let r =
        run("adapt_memory", &coarse_cantilever(), &["--adapt", "0.001", "--max-dof", "100000", "--max-memory", "30M"]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    let s = r.summary();
    assert_eq!((s["status"].as_str(), s["adapt_end"].as_str()), (Some("converged"), Some("done")));
    assert_eq!((s["adapt_cycle"].as_u64(), s["dof"].as_u64()), (Some(3), Some(2160)));
    assert_eq!(s["adapt"].as_array().unwrap().len(), 4);
    let stop = s["adapt_stop"].as_str().unwrap();
    assert!(stop.contains("cycle 4 (3705 DOF)") && stop.contains("memory") && stop.contains("cycle 3's"), "{stop}");
    assert!(r.out.join("result.vtu").exists());
}

/// Ctrl-C during cycle 1 of examples/epp_cantilever.toml in 200 increments
/// (cycle 0: 1,665 DOF in 0.6 s, cycle 1: 5,400 DOF in 5 s): the run used to
/// write cycle 1's interrupted, all-zero state and lose cycle 0. Now it
/// exits 130 with cycle 0 written as a complete, converged result set.
#[test]
fn an_interrupted_adaptive_run_keeps_its_last_cycle() {
    use std::io::{BufRead, BufReader};
    let dir = common::scratch_dir("silent", "adapt_interrupt");
    let model = dir.join("epp.toml");
    std::fs::write(&model, edit(&example("epp_cantilever.toml"), "increments = 30", "increments = 200")).unwrap();
    let out = dir.join("out");
    let mut child = common::cufem()
        .args(["run", model.to_str().unwrap(), "--adapt", "0.001", "--max-dof", "6000", "--out", out.to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut seen = String::new();
    let mut line = String::new();
    while stderr.read_line(&mut line).unwrap() > 0 {
        seen.push_str(&line);
        if line.starts_with("cycle 0:") {
            break;
        }
        line.clear();
    }
    assert!(seen.contains("cycle 0:"), "{seen}");
    let kill = std::process::Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(kill.success());
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stderr, &mut rest).unwrap();
    let code = child.wait().unwrap().code();
    assert_eq!(code, Some(130), "{seen}{rest}");
    assert!(rest.contains("the results are cycle 0's"), "{rest}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!((s["status"].as_str(), s["adapt_end"].as_str()), (Some("converged"), Some("interrupted")));
    assert_eq!((s["adapt_cycle"].as_u64(), s["dof"].as_u64()), (Some(0), Some(1665)));
    // cycle 0's whole load history: the tip pushed down to 6 δ_y
    assert_eq!(s["increments"].as_u64(), Some(200));
    assert!((s["load_factor"].as_f64().unwrap() - 1.0).abs() < 1e-9);
    assert!(out.join("result.vtu").exists() && !dir.join("out.partial").exists());
}

/// A first cycle that stops early: a perfectly plastic cantilever (20 × 40 mm,
/// 0.5 m, σ_y = 250 MPa: its plastic hinge at the root carries
/// `σ_y b h² / 4 / L = 4` kN) pushed at its tip towards 12 kN with an
/// `[adapt]` table. Cycle 0 cannot pass the collapse load; the run exits 2
/// with that cycle's last converged increment, as a single run does, and
/// summary.json said `adapt_end = "done"` — the word of a run that ended as
/// asked (exit 0), so a script reading it took the collapse for a success.
#[test]
fn an_adaptive_run_whose_first_cycle_stops_early_is_not_done() {
    let text = r#"title = "A cantilever pushed past its collapse load, with an [adapt] table"
[solver]
increments = 5
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
plasticity = { yield_stress = 250e6, hardening = "perfect" }
[[bodies]]
name = "beam"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.02, elements = 1 }, z = { from = 0.0, to = 0.04, elements = 1 } }
axis = { element = "B4", from = 0.0, to = 0.5, elements = 4 }
[[constraints]]
name = "root"
body = "beam"
where = { y = 0.0 }
fix = ["x", "y", "z"]
[[loads]]
name = "tip"
body = "beam"
where = { y = 0.5 }
total_force = [0.0, 0.0, -12000.0]
[adapt]
tolerance = 0.03
max_dof = 15000
"#;
    let r = run("adapt_collapse", text, &[]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    let s = r.summary();
    assert_eq!((s["status"].as_str(), s["adapt_end"].as_str()), (Some("not_converged"), Some("stopped")));
    assert_eq!(s["adapt_cycle"].as_u64(), Some(0));
    let stop = s["adapt_stop"].as_str().unwrap();
    assert!(stop.contains("cycle 0 stopped early"), "{stop}");
    // the load reached lies past the hinge's 4 kN (the coarse section is stiffer) but short of 12 kN
    let reached = 12.0 * s["load_factor"].as_f64().unwrap();
    assert!((4.0..12.0).contains(&reached), "{reached} kN");
}
