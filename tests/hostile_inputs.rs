//! Issue 13: every shipped example, mutated thousands of times — numbers
//! scaled by extreme factors, keys dropped, arrays reshaped, strings and
//! counts replaced — must give either a clean error that names a model-file
//! key, or a run that finishes (converged, not converged or stopped by its
//! deadline) with finite results written to disk. Never a panic, never a
//! hang: every case has a time bound.
//!
//! Cases: `CUFEM_FUZZ_CASES` (default 500 in CI; the validation run's
//! `mutated_examples_at_length` takes the first 10,000 of the same seed, a
//! superset). Every `CUFEM_FUZZ_RUN_EVERY`-th
//! valid model (default 6) is also solved, with its analysis stopped after 300 ms through the same
//! interrupt Ctrl-C uses, and its results written (the plot of a line once
//! hung on extreme values). The seed is fixed (`CUFEM_FUZZ_SEED`, default
//! 13) so CI is repeatable; other seeds explore other mutants. A longer run
//! is reported in the closing note.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use cufem::analysis::{self, RunOptions, Silent};
use cufem::setup::{Limits, Model, ModelError};
use cufem::solver::Interrupt;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use toml::Value;

/// The shipped examples as TOML trees.
fn examples() -> Vec<(String, toml::Table)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut out: Vec<(String, toml::Table)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read_to_string(&p).unwrap().parse().unwrap(),
            )
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// One change to a model tree: which node (an index into the list of all
/// nodes, taken modulo its length) and what to do to it.
#[derive(Debug, Clone)]
enum Mutation {
    /// Multiply a number (integers become floats) by a factor.
    Scale(usize, f64),
    /// Remove a key of a table or an element of an array.
    Drop(usize),
    /// Append a copy of an array's first element (or wrap a scalar in an array).
    Grow(usize),
    /// Keep only the first `n` elements of an array.
    Truncate(usize, usize),
    /// Replace a value by another kind of value.
    Replace(usize, Value),
}

fn factor() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(-1.0),
        Just(1e-300),
        Just(1e300),
        Just(1e-9),
        Just(1e9),
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(-1e-3),
        (0.5f64..2.0),
    ]
}

fn value() -> impl Strategy<Value = Value> {
    prop_oneof![
        Just(Value::Integer(0)),
        Just(Value::Integer(-1)),
        Just(Value::Integer(i64::MAX)),
        Just(Value::Integer(100_000)),
        Just(Value::Float(f64::NAN)),
        Just(Value::Float(-0.0)),
        Just(Value::String(String::new())),
        Just(Value::String("L9".into())),
        Just(Value::String("B3".into())),
        Just(Value::String("cylinder".into())),
        Just(Value::String("+z".into())),
        Just(Value::String("x".into())),
        Just(Value::String("table".into())),
        Just(Value::Array(vec![])),
        Just(Value::Array(vec![Value::Float(1.0); 7])),
        Just(Value::Table(toml::Table::new())),
        Just(Value::Boolean(true)),
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let at = any::<usize>();
    prop_oneof![
        4 => (at, factor()).prop_map(|(i, f)| Mutation::Scale(i, f)),
        2 => at.prop_map(Mutation::Drop),
        1 => at.prop_map(Mutation::Grow),
        1 => (at, 0usize..3).prop_map(|(i, n)| Mutation::Truncate(i, n)),
        2 => (at, value()).prop_map(|(i, v)| Mutation::Replace(i, v)),
    ]
}

/// Paths to every value of the tree (table keys and array indices).
fn paths(v: &Value, prefix: &mut Vec<PathStep>, out: &mut Vec<Vec<PathStep>>) {
    match v {
        Value::Table(t) => {
            for (k, c) in t {
                prefix.push(PathStep::Key(k.clone()));
                out.push(prefix.clone());
                paths(c, prefix, out);
                prefix.pop();
            }
        }
        Value::Array(a) => {
            for (i, c) in a.iter().enumerate() {
                prefix.push(PathStep::Index(i));
                out.push(prefix.clone());
                paths(c, prefix, out);
                prefix.pop();
            }
        }
        _ => {}
    }
}

#[derive(Debug, Clone)]
enum PathStep {
    Key(String),
    Index(usize),
}

fn get_mut<'a>(root: &'a mut Value, path: &[PathStep]) -> Option<&'a mut Value> {
    let mut v = root;
    for s in path {
        v = match (s, v) {
            (PathStep::Key(k), Value::Table(t)) => t.get_mut(k)?,
            (PathStep::Index(i), Value::Array(a)) => a.get_mut(*i)?,
            _ => return None,
        };
    }
    Some(v)
}

fn apply(root: &mut Value, m: &Mutation) {
    let mut all = Vec::new();
    paths(root, &mut Vec::new(), &mut all);
    if all.is_empty() {
        return;
    }
    let pick = |i: usize| all[i % all.len()].clone();
    match m {
        Mutation::Scale(i, f) => {
            // pick the i-th numeric leaf rather than any node
            let numeric: Vec<&Vec<PathStep>> = all
                .iter()
                .filter(|p| {
                    let mut r = root.clone();
                    matches!(get_mut(&mut r, p), Some(Value::Float(_) | Value::Integer(_)))
                })
                .collect();
            if numeric.is_empty() {
                return;
            }
            let p = numeric[i % numeric.len()].clone();
            if let Some(v) = get_mut(root, &p) {
                let new = match &*v {
                    Value::Float(x) => Value::Float(x * f),
                    Value::Integer(n) => {
                        let x = *n as f64 * f;
                        if x.is_finite() && x.abs() < 9e18 && x.fract() == 0.0 {
                            Value::Integer(x as i64)
                        } else {
                            Value::Float(x)
                        }
                    }
                    other => other.clone(),
                };
                *v = new;
            }
        }
        Mutation::Drop(i) => {
            let p = pick(*i);
            let (last, parent) = p.split_last().unwrap();
            if let Some(v) = get_mut(root, parent) {
                match (last, v) {
                    (PathStep::Key(k), Value::Table(t)) => {
                        t.remove(k);
                    }
                    (PathStep::Index(j), Value::Array(a)) => {
                        a.remove(*j);
                    }
                    _ => {}
                }
            }
        }
        Mutation::Grow(i) => {
            if let Some(v) = get_mut(root, &pick(*i)) {
                match v {
                    Value::Array(a) if !a.is_empty() => {
                        let first = a[0].clone();
                        a.push(first);
                    }
                    Value::Table(_) => {}
                    other => *other = Value::Array(vec![other.clone()]),
                }
            }
        }
        Mutation::Truncate(i, n) => {
            if let Some(Value::Array(a)) = get_mut(root, &pick(*i)) {
                a.truncate(*n);
            }
        }
        Mutation::Replace(i, new) => {
            if let Some(v) = get_mut(root, &pick(*i)) {
                *v = new.clone();
            }
        }
    }
}

/// Outcome of one case, computed on a worker thread so a hang is caught:
/// `Ok(true)` for a valid model (solved if `run`), `Ok(false)` for a clean
/// error naming a key.
fn check_case(text: String, valid: &AtomicUsize, run_every: usize, out: PathBuf) -> Result<bool, String> {
    let model = match Model::parse_with(&text, Limits { max_memory: Some(2 << 30) }) {
        Ok(m) => m,
        Err(e) => {
            let msg = e.to_string();
            let names_key = match &e {
                ModelError::Invalid { key, allowed, .. } => !key.is_empty() && !allowed.is_empty(),
                ModelError::Parse(m) => {
                    m.contains("TOML parse error") || m.contains("missing field") || m.contains("unknown field")
                }
                ModelError::Mesh(_) => msg.contains(" = ") && msg.contains("expected"),
                ModelError::Element(_) => msg.contains("bodies."),
                ModelError::TooLarge { .. } => msg.contains("--max-memory"),
                _ => false,
            };
            return if names_key { Ok(false) } else { Err(format!("error without a key: {msg}")) };
        }
    };
    if !valid.fetch_add(1, Ordering::Relaxed).is_multiple_of(run_every) {
        return Ok(true);
    }
    let interrupt = Interrupt::new();
    let stop = interrupt.clone();
    std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(300));
        stop.request();
    });
    let options = RunOptions { interrupt, max_memory: Some(2 << 30) };
    let solution = match analysis::run(&model, &options, &mut Silent) {
        Ok(s) => s,
        Err(e) => return if e.to_string().is_empty() { Err("empty analysis error".into()) } else { Ok(true) },
    };
    if solution.u.iter().any(|v| !v.is_finite()) {
        return Err(format!("non-finite displacements (failure: {:?})", solution.failure.map(|f| f.to_string())));
    }
    let _ = std::fs::remove_dir_all(&out);
    cufem::io::write_results(&model, &solution, &out).map_err(|e| format!("writing failed: {e}"))?;
    let s = cufem::io::summary(&model, &solution);
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    for p in &s.probes {
        if !(finite(&p.u) && finite(&p.stress) && p.von_mises.is_finite() && p.peeq.is_finite()) {
            return Err(format!("probe {} is not finite: {p:?}", p.name));
        }
    }
    if !s.reactions.iter().chain(&s.contact).all(|f| finite(&f.force)) {
        return Err("a reaction or contact force is not finite".into());
    }
    Ok(true)
}

#[test]
fn mutated_examples_give_a_clean_error_or_finite_results() {
    // 500 cases keep CI within its budget (about 15 s); the validation's
    // slow step runs 10,000 (`mutated_examples_at_length`)
    fuzz_examples(500);
}

#[test]
#[ignore = "validate: slow — 10,000 mutated models, every sixth valid one solved for 300 ms (about 4 min)"]
fn mutated_examples_at_length() {
    fuzz_examples(10_000);
}

/// `default_cases` mutated examples (or `CUFEM_FUZZ_CASES`) from the seed:
/// each a clean error or a finished run with finite results.
fn fuzz_examples(default_cases: u32) {
    let cases: u32 = std::env::var("CUFEM_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(default_cases);
    let run_every: usize = std::env::var("CUFEM_FUZZ_RUN_EVERY").ok().and_then(|v| v.parse().ok()).unwrap_or(6);
    let examples = examples();
    assert!(examples.len() >= 8, "expected every shipped example");
    let out_root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("hostile_inputs_{}", std::process::id()));
    let counter = AtomicUsize::new(0);
    let (valid, runs) = (Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(0)));
    // a fixed seed by default, so that CI is repeatable; CUFEM_FUZZ_SEED explores others
    let seed: u64 = std::env::var("CUFEM_FUZZ_SEED").ok().and_then(|v| v.parse().ok()).unwrap_or(13);
    let mut bytes = [0u8; 32];
    bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &bytes);
    let config = Config { cases, failure_persistence: None, ..Config::default() };
    let mut runner = TestRunner::new_with_rng(config, rng);
    let strategy = (0..examples.len(), proptest::collection::vec(mutation(), 1..4));
    let result = runner.run(&strategy, |(which, mutations)| {
        let n = counter.fetch_add(1, Ordering::Relaxed);
        let mut root = Value::Table(examples[which].1.clone());
        for m in &mutations {
            apply(&mut root, m);
        }
        let text = toml::to_string(&root).unwrap_or_default();
        let out = out_root.join(format!("case{}", n % 4));
        let (tx, rx) = mpsc::channel();
        let t = text.clone();
        let (valid, runs) = (valid.clone(), runs.clone());
        std::thread::spawn(move || {
            let before = valid.load(Ordering::Relaxed);
            let r = std::panic::catch_unwind(|| check_case(t, &valid, run_every, out));
            if matches!(r, Ok(Ok(true))) && before.is_multiple_of(run_every) {
                runs.fetch_add(1, Ordering::Relaxed);
            }
            let _ = tx.send(r);
        });
        // validation takes milliseconds; a run is stopped after 300 ms, then
        // writes its results: 60 s means it hung
        match rx.recv_timeout(Duration::from_secs(60)) {
            Err(_) => prop_assert!(false, "{}: hung on\n{text}", examples[which].0),
            Ok(Err(_)) => prop_assert!(false, "{}: panicked on\n{text}", examples[which].0),
            Ok(Ok(Err(e))) => prop_assert!(false, "{}: {e} on\n{text}", examples[which].0),
            Ok(Ok(Ok(_))) => {}
        }
        Ok(())
    });
    eprintln!(
        "seed {seed}: {} mutated models: {} valid, {} of them solved and written",
        counter.load(Ordering::Relaxed),
        valid.load(Ordering::Relaxed),
        runs.load(Ordering::Relaxed)
    );
    let _ = std::fs::remove_dir_all(&out_root);
    if let Err(e) = result {
        panic!("seed {seed}: {e}");
    }
}

/// The Timoshenko cantilever with its section, axis, load point and probe
/// replaced: a small model for the validation tests below.
fn cantilever(section: &str, axis_to: f64, probe: [f64; 3]) -> String {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let text = std::fs::read_to_string(dir.join("cantilever_timoshenko.toml")).unwrap();
    let text = text.split("[[lines]]").next().unwrap();
    let rectangle = "x = { from = 0.0, to = 0.1, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 2 }";
    assert!(text.contains(rectangle) && text.contains("where = { y = 1.0 }"));
    text.replace(rectangle, section)
        .replace("from = 0.0, to = 1.0, elements = 5", &format!("from = 0.0, to = {axis_to:?}, elements = 5"))
        .replace("where = { y = 1.0 }", &format!("where = {{ y = {axis_to:?} }}"))
        .replace("point = [0.05, 1.0, 0.05]", &format!("point = {probe:?}"))
}

/// The rigid-body check judged restraint against the body's size: a flat
/// body (a 100 m × 5 mm section) or a long thin one (100 m of 5 × 5 mm)
/// clamped at its root was refused as "free to move as a rigid body". It
/// must accept them and still catch the same bodies held along a line only
/// (free to rotate about it) or held in y and z only (free along x).
#[test]
fn thin_bodies_are_judged_by_their_shape_not_their_size() {
    let flat = cantilever(
        "x = { from = 0.0, to = 100.0, elements = 4 }, z = { from = 0.0, to = 0.005, elements = 1 }",
        1.0,
        [50.0, 1.0, 0.0025],
    );
    let long = cantilever(
        "x = { from = 0.0, to = 0.005, elements = 1 }, z = { from = 0.0, to = 0.005, elements = 1 }",
        100.0,
        [0.0025, 100.0, 0.0025],
    );
    for (name, text) in [("flat", &flat), ("long", &long)] {
        if let Err(e) = Model::parse(text) {
            panic!("{name}: a clamped body refused: {e}");
        }
    }
    let clamp = "where = { y = 0.0 }";
    let cases = [
        (flat.replace(clamp, "where = { y = 0.0, z = 0.0 }"), "(rotation about x)"),
        (flat.replace("fix = [\"x\", \"y\", \"z\"]", "fix = [\"y\", \"z\"]"), "(translation along x)"),
        (long.replace(clamp, "where = { y = 0.0, x = 0.0, z = 0.0 }"), "rotation about y"),
    ];
    for (text, motion) in cases {
        let e = Model::parse(&text).map(|_| ()).unwrap_err().to_string();
        assert!(e.contains("bodies[0] = \"beam\", free to move as a rigid body") && e.contains(motion), "{e}");
    }
}

/// A sphere whose centre lies inside the body was told about "the
/// cylinder's axis": the message must name the sphere's centre.
#[test]
fn a_buried_sphere_is_told_about_its_centre() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let ball = std::fs::read_to_string(dir.join("hertz_ball.toml")).unwrap();
    let buried = ball
        .replace("center = [0.0, 0.0, 0.01]", "center = [0.0, 0.0, -0.002]")
        .replace("radius = 0.01\ndisplacement", "radius = 0.001\ndisplacement");
    assert_ne!(buried, ball);
    let e = Model::parse(&buried).map(|_| ()).unwrap_err().to_string();
    assert!(
        e.contains("indenters[0].center = an indenter on the inner side of the surface")
            && e.contains("expected the sphere's centre on the outer side of the selected surface")
            && !e.contains("cylinder"),
        "{e}"
    );
}

/// The warnings of a model that parses.
fn warnings(text: &str) -> Vec<String> {
    Model::parse(text).unwrap().warnings.iter().map(|w| w.to_string()).collect()
}

/// A constraint `tolerance` as large as the body selected every node and
/// clamped the whole body without a word (the probe warning is skipped when
/// nothing moves). The model warns, naming the key and the value; a clamp
/// of the root face alone does not.
#[test]
fn a_constraint_holding_every_node_is_warned_about() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let cant = std::fs::read_to_string(dir.join("cantilever_timoshenko.toml")).unwrap();
    let root = "where = { y = 0.0 }";
    assert!(cant.contains(root));
    assert_eq!(warnings(&cant), Vec::<String>::new());
    let cases = [
        ("where = { y = 0.0, tolerance = 1.0 }", "constraints[0].where.tolerance: tolerance = 1 m selects every node"),
        ("where = { y = [-1.0, 5.0] }", "constraints[0].where: where = { y = [-1, 5] } selects every node"),
        ("where = {}", "constraints[0]: every node of body \"beam\" is fixed or prescribed in x, y and z"),
    ];
    for (selection, expect) in cases {
        let w = warnings(&cant.replace(root, selection));
        // the tip load, on held nodes too, is warned about by its own key
        // (`a_load_that_cannot_act_is_warned_about`)
        assert!(w.len() == 2 && w[1].starts_with("loads[0]: load \"tip\" acts only on"), "{selection}: {w:?}");
        assert!(w[0].starts_with(expect) && w[0].contains("\"beam\""), "{selection}: {w:?}");
    }
}

/// A body held at every node has no free equation: its run panicked
/// (the elastic stiffness of a linear model was cached over an empty
/// pattern). It runs, with the warning above: nothing moves and the clamp
/// carries the whole tip load (statics); a transient run of such a rod
/// finishes at rest too.
#[test]
fn a_body_held_at_every_node_runs_to_rest() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let cant = std::fs::read_to_string(dir.join("cantilever_timoshenko.toml")).unwrap();
    let held = cant.replace("where = { y = 0.0 }", "where = {}");
    assert_ne!(held, cant);
    let rod = std::fs::read_to_string(dir.join("rod_impact.toml")).unwrap();
    let all = "\n[[constraints]]\nname = \"all\"\nbody = \"rod\"\nwhere = {}\nfix = [\"x\", \"y\", \"z\"]\n";
    for text in [held, rod + all] {
        let model = Model::parse(&text).unwrap();
        let s = analysis::run(&model, &RunOptions::default(), &mut Silent).unwrap();
        assert!(s.failure.is_none(), "{:?}", s.failure);
        assert!(s.u.iter().all(|&u| u == 0.0));
        if let Some(root) = s.reaction("root") {
            // the tip's total_force [0, 0, -1000] N, all on the clamp
            assert!((root.force[2] - 1000.0).abs() < 1e-9 && root.force[0].abs() < 1e-9, "{:?}", root.force);
        }
    }
}

/// A load that cannot act ran without a word: a zero `total_force`, and a
/// tip load moved onto the clamped root (the reaction carried it, the tip
/// stayed at zero). Both are warned about by the load's key; the shipped
/// cantilever is not (a new-user review).
#[test]
fn a_load_that_cannot_act_is_warned_about() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let cant = std::fs::read_to_string(dir.join("cantilever_timoshenko.toml")).unwrap();
    let (force, tip) = ("total_force = [0.0, 0.0, -1000.0]", "name = \"tip\"\nbody = \"beam\"\nwhere = { y = 1.0 }");
    assert!(cant.contains(force) && cant.contains(tip));
    assert_eq!(warnings(&cant), Vec::<String>::new());
    let cases = [
        (cant.replace(force, "total_force = [0.0, 0.0, 0.0]"), "every nodal force of load \"tip\" is zero"),
        (
            cant.replace(tip, &tip.replace("y = 1.0", "y = 0.0")),
            "load \"tip\" acts only on components the constraints hold",
        ),
    ];
    for (text, expect) in cases {
        let w = warnings(&text);
        assert!(w.len() == 1 && w[0].starts_with("loads[0]") && w[0].contains(expect), "{w:?}");
    }
}

/// A density in g/cm³ ran a modal analysis to frequencies `√1000` times
/// too high without a word (a new-user review): the wave speed its
/// constants give, `√(E/ρ)`, is warned about outside the solids' `10`–`25,000`
/// m/s, as is a Young's modulus in MPa (titanium's `110,000`); the shipped density is not.
#[test]
fn a_density_in_other_units_is_warned_about() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let modes = std::fs::read_to_string(dir.join("cantilever_modes.toml")).unwrap();
    let (rho, young) = ("density = 2700.0", "young_modulus = 70e9");
    assert!(modes.contains(rho) && modes.contains(young));
    assert_eq!(warnings(&modes), Vec::<String>::new());
    for text in [modes.replace(rho, "density = 2.7"), modes.replace(young, "young_modulus = 1.1e5")] {
        let w = warnings(&text);
        assert!(w.len() == 1 && w[0].starts_with("materials[0].density") && w[0].contains("wave speed"), "{w:?}");
    }
}

/// A roller turned onto the clamped root (`axis = "y"` for `"x"`) pressed
/// its whole travel into held nodes (`2.5e8` N), and the run blamed a soft
/// penalty (a new-user review): the warning now says that the deepest
/// point is held in x, y and z, and where.
#[test]
fn an_indenter_pressing_on_held_nodes_is_told_so() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let text = std::fs::read_to_string(dir.join("cantilevers_contact.toml")).unwrap();
    let turned = text.replacen("axis = \"x\"", "axis = \"y\"", 1);
    assert_ne!(turned, text);
    let model = Model::parse(&turned).unwrap();
    let s = analysis::run(&model, &RunOptions::default(), &mut Silent).unwrap();
    let w: Vec<String> = s.warnings.iter().map(|w| w.to_string()).collect();
    let held = w.iter().find(|w| w.starts_with("indenters[0]: contact \"indenter_7in\" ends with a penetration"));
    assert!(
        held.is_some_and(|h| h.contains("which the constraints hold in x, y and z") && !h.contains("penalty_factor")),
        "{w:?}"
    );
}

/// `analysis.duration` beside steps that each give their own was ignored
/// without a word (a new-user review): warned about by its key.
#[test]
fn an_unused_analysis_duration_is_warned_about() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let rod = std::fs::read_to_string(dir.join("rod_impact.toml")).unwrap();
    assert_eq!(warnings(&rod), Vec::<String>::new());
    let both = rod.replacen("type = \"transient\"\n", "type = \"transient\"\nduration = 1e-3\n", 1);
    assert_ne!(both, rod);
    let w = warnings(&both);
    assert!(w.len() == 1 && w[0].starts_with("analysis.duration: duration = 0.001 s is not used"), "{w:?}");
    // without the step's own, the analysis' duration is the step's: no warning
    assert_eq!(warnings(&both.replacen("duration = 6e-4\n", "", 1)), Vec::<String>::new());
}

/// Two constraints giving one component different values: refused by the
/// later one's key, naming the value of the node's owner — the first
/// constraint that prescribes it (whose reaction counts it), also when a
/// set between them agrees with it.
#[test]
fn overlapping_constraints_that_disagree_name_the_owner() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let cant = std::fs::read_to_string(dir.join("cantilever_timoshenko.toml")).unwrap();
    let tip = |name: &str, z: f64| {
        format!(
            "\n[[constraints]]\nname = \"{name}\"\nbody = \"beam\"\nwhere = {{ y = 1.0 }}\ndisplacement = {{ z = {z} }}\n"
        )
    };
    let agree = cant.clone() + &tip("pull", 1e-3) + &tip("same", 1e-3);
    Model::parse(&agree).unwrap();
    let e = Model::parse(&(agree + &tip("more", 2e-3))).map(|_| ()).unwrap_err().to_string();
    assert!(e.starts_with("constraints[3] = u_z = 0.002 at ") && e.contains("(constraint \"more\")"), "{e}");
    assert!(e.contains("the value 0.001 that constraints[1] (constraint \"pull\") prescribes at the same node"), "{e}");
}
