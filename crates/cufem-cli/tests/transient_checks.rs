//! What a transient analysis says before and when it stops: its time
//! steps against `solver.max_increments`, its memory (at most one frame
//! per time step, the history of every step), Newmark's β range, a stop
//! in seconds, an implausibly light impactor and a geometric imperfection
//! (issue 46's weaker dynamics items; each assertion failed before its fix).

#[path = "../../../tests/common/mod.rs"]
mod common;

use cufem::setup::Model;

/// `examples/rod_impact.toml` (600 steps of 1 µs; `solver.max_increments
/// = 5000`) with `from` replaced by `to`.
fn rod(from: &str, to: &str) -> String {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/rod_impact.toml");
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.contains(from), "{from}");
    text.replace(from, to)
}

fn refusal(text: &str) -> String {
    match Model::parse(text) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("accepted"),
    }
}

/// A limit below the time steps of a load step would stop the run part
/// way (a 1e5-step history stopped at 1 % by the default 1000): refused by
/// key before the run, with the steps needed; without the key each step
/// may take its time steps and 1000 more (cutbacks), and the run says up
/// front how many it takes (`cufem check`).
#[test]
fn the_time_steps_are_checked_against_max_increments() {
    let e = refusal(&rod("max_increments = 5000", "max_increments = 100"));
    assert!(e.contains("solver.max_increments = 100") && e.contains("at least the 600 time steps of steps[0]"), "{e}");
    let free = rod("max_increments = 5000\n", "").replace("increments = 600", "increments = 20000");
    let model = Model::parse(&free).unwrap();
    assert_eq!(model.steps[0].planned_increments(), 20000);
    assert_eq!(model.steps[0].settings.max_increments, 21000);
    let dir = common::scratch_dir("transient_checks", "check");
    let file = dir.join("rod.toml");
    std::fs::write(&file, &free).unwrap();
    let out = common::cufem().args(["check", file.to_str().unwrap()]).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("transient: 20,000 time steps over 6.0000e-4 s (flight: 20,000 × 3.000e-8 s)"), "{stdout}");
}

/// The memory estimate counts at most one frame per time step (a 100-step
/// run with a tiny `output_interval` was refused as 38.8 GiB), and a
/// record per time step; when the frames are what does not fit, the
/// refusal says to raise `analysis.output_interval`, not to coarsen the
/// mesh.
#[test]
fn the_memory_estimate_counts_one_frame_per_time_step_at_most() {
    let tiny = rod("output_interval = 5e-5", "output_interval = 6e-10");
    let model = Model::parse(&tiny.replace("increments = 600", "increments = 100")).unwrap();
    let sizes = cufem::analysis::plan(&model).unwrap();
    assert_eq!((sizes.snapshots, sizes.history_rows), (100, 100));
    assert!(sizes.memory().total() < 100 << 20, "{:?}", sizes.memory());
    // 20,000 frames of the rod's fields: a few hundred MiB, refused at 100 MiB
    let dir = common::scratch_dir("transient_checks", "memory");
    let file = dir.join("rod.toml");
    let long = tiny.replace("increments = 600", "increments = 20000").replace("max_increments = 5000", "");
    std::fs::write(&file, long).unwrap();
    let out = common::cufem()
        .args(["run", file.to_str().unwrap(), "--out", dir.join("out").to_str().unwrap(), "--max-memory", "100M"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(4), "{stderr}");
    assert!(stderr.contains("step ends and frames") && stderr.contains("raise analysis.output_interval"), "{stderr}");
    assert!(!stderr.contains("coarser mesh"), "{stderr}");
}

/// γ = 1 needs β ≥ ¼ (γ + ½)² = 0.5625 for unconditional stability (Hughes,
/// *The Finite Element Method*, §9.1.2): the range offered is no longer
/// empty ("from 0.5625 to 0.5"), the message names γ and the range, and a
/// β in it is taken.
#[test]
fn newmarks_beta_range_follows_gamma() {
    let newmark = |b: f64, g: f64| {
        rod("type = \"transient\"", &format!("type = \"transient\"\nnewmark = {{ beta = {b}, gamma = {g} }}"))
    };
    let e = refusal(&newmark(0.5, 1.0));
    assert!(
        e.contains("analysis.newmark.beta = 0.5")
            && e.contains("analysis.newmark.gamma = 1")
            && e.contains("from ¼ (γ + ½)² = 0.5625")
            && e.contains("to 1"),
        "{e}"
    );
    Model::parse(&newmark(0.6, 1.0)).unwrap();
}

/// A transient stop names the time in seconds, not a load factor: the
/// rod with one Newton iteration allowed and a residual tolerance that one
/// correction does not meet (`1e-14`: its first correction leaves about
/// `1e-7`) cannot converge its first time step, cuts back below
/// `solver.min_increment` and stops. (With the default tolerance it
/// converged or failed at the wall depending on the factor's round-off.)
#[test]
fn a_transient_stop_is_reported_in_seconds() {
    let text = rod("max_increments = 5000", "max_increments = 5000\nmax_iterations = 1\nresidual_tolerance = 1e-14");
    let model = Model::parse(&text).unwrap();
    let sol = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    let failure = sol.failure.expect("stopped").to_string();
    println!("{failure}");
    assert!(
        failure.starts_with("time step 1 ") && failure.contains(" at t = ") && failure.contains(" s (Δt = "),
        "{failure}"
    );
    assert!(!failure.contains("load factor"), "{failure}");
}

/// An impactor lighter than a billionth of the body it strikes is refused
/// by key: a 1e-30 kg one stopped with a generic Newton message at first
/// contact. 1 g on the 0.8 kg rod is taken.
#[test]
fn an_implausibly_light_impactor_is_refused_by_key() {
    let text = common::step_loaded_bar(20, 0.0, 1e-4, 100, "").replace(
        "[[loads]]\nname = \"end\"\nbody = \"bar\"\nwhere = { y = 1.0 }\ntotal_force = [0.0, 0.0, 0.0]\n",
        "[[indenters]]\nname = \"hammer\"\nbody = \"bar\"\nshape = \"flat\"\nsurface = { y = 1.0 }\nnormal = \"-y\"\n\
         position = 1.00001\nmass = 1e-30\nvelocity = [0.0, -1.0, 0.0]\n",
    );
    assert!(text.contains("hammer"));
    let e = refusal(&text);
    assert!(e.contains("indenters[0].mass = 1e-30") && e.contains("at least 8.00e-10 kg"), "{e}");
    Model::parse(&text.replace("mass = 1e-30", "mass = 1e-3")).unwrap();
}

/// A transient analysis of an imperfect column (`analysis.imperfection`)
/// takes its buckling mode from the static state of the loads: it ran a
/// transient buckling analysis without densities and reported the given
/// density as missing.
#[test]
fn a_transient_analysis_takes_an_imperfection() {
    let path =
        std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/column_postbuckling.toml");
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("imperfection = ", "type = \"transient\"\nduration = 1e-3\nimperfection = ")
        .replace("poisson_ratio = 0.3", "poisson_ratio = 0.3\ndensity = 7850.0")
        .replace("increments = 40", "increments = 10");
    let model = Model::parse(&text).unwrap();
    let sol = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    assert!(sol.failure.is_none(), "{:?}", sol.failure);
    // the column's Euler load: the mode the imperfection took
    let b = sol.buckling.expect("the imperfection's buckling factors");
    assert!(b.factors[0] > 0.5 && b.factors[0] < 1.0, "{:?}", b.factors);
    assert_eq!(sol.energy.map(|e| e.len()), Some(11));
}

/// Mass redistribution where it cannot apply: a rod pressed by walls on
/// both lateral faces, one L4 through its height, has every node on a
/// contact surface, so no element has a node to take a contact node's
/// mass; they keep it and the model warns by key. The key given without
/// any contact warns too.
#[test]
fn contact_nodes_without_a_neighbour_keep_their_mass_with_a_warning() {
    let walls = "[[indenters]]\nname = \"below\"\nbody = \"rod\"\nshape = \"flat\"\nsurface = { z = 0.0 }\n\
                 normal = \"+z\"\nposition = -1e-5\ndisplacement = [0.0, 0.0, 0.0]\n\n[[indenters]]\nname = \"above\"\n\
                 body = \"rod\"\nshape = \"flat\"\nsurface = { z = 0.01 }\nnormal = \"-z\"\nposition = 0.01001\n\
                 displacement = [0.0, 0.0, 0.0]\n\n[[steps]]";
    let model = Model::parse(&rod("[[steps]]", walls)).unwrap();
    let w = model.warnings.iter().find(|w| w.key == "analysis.contact_mass").expect("a warning");
    assert!(w.message.contains("404 of the 404 contact nodes keep part of their mass"), "{w}");
    let text = rod("type = \"transient\"", "type = \"transient\"\ncontact_mass = \"kept\"");
    let free = format!("{}{}", &text[..text.find("[[indenters]]").unwrap()], &text[text.find("[[steps]]").unwrap()..]);
    let model = Model::parse(&free).unwrap();
    assert!(model.warnings.iter().any(|w| w.key == "analysis.contact_mass"), "{:?}", model.warnings);
}
