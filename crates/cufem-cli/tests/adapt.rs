//! Adaptive refinement (`cufem::adapt`, `cufem run --adapt`): Dörfler
//! marking picks the largest estimates, the intervals holding them are the
//! ones halved, the refined meshes have the DOF counts of their divisions,
//! names survive, and the CLI runs cycles until the budget with the
//! estimate falling.

#[path = "../../../tests/common/mod.rs"]
mod common;
#[path = "stored/mod.rs"]
#[allow(dead_code)] // region_id: the report ids of roller_twins.rs and fidelity.rs
mod stored;

use std::path::Path;
use std::process::Command;

use cufem::adapt::mark;
use cufem::setup::{Limits, MeshPlan, Model, SectionPlan};

fn example(name: &str) -> String {
    std::fs::read_to_string(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples").join(name))
        .unwrap()
}

/// The Timoshenko cantilever with `nx` × `nz` L9 over the section and `ny`
/// B4 along the axis.
fn cantilever(nx: usize, nz: usize, ny: usize) -> String {
    let text = example("cantilever_timoshenko.toml");
    let section = "x = { from = 0.0, to = 0.1, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 2 }";
    assert!(text.contains(section) && text.contains("to = 1.0, elements = 5 }"));
    text.replace(
        section,
        &format!("x = {{ from = 0.0, to = 0.1, elements = {nx} }}, z = {{ from = 0.0, to = 0.1, elements = {nz} }}"),
    )
    .replace("to = 1.0, elements = 5 }", &format!("to = 1.0, elements = {ny} }}"))
}

/// DOF of one body of L9 × B4 on `nx` × `nz` × `ny` intervals.
fn dof_l9_b4(nx: usize, nz: usize, ny: usize) -> usize {
    3 * (2 * nx + 1) * (2 * nz + 1) * (3 * ny + 1)
}

fn planned(text: &str, plan: &MeshPlan) -> Model {
    Model::parse_planned(text, Limits::none(), Path::new("."), plan).unwrap()
}

#[test]
fn dorfler_marks_the_fewest_largest_elements() {
    // η² = 0.01, 9, 0.04, 4, 1: total 14.05
    let eta = [0.1, 3.0, 0.2, 2.0, 1.0];
    assert_eq!(mark::dorfler(&eta, 0.5), vec![1], "9 ≥ 0.5 · 14.05 alone");
    assert_eq!(mark::dorfler(&eta, 0.8), vec![1, 3], "9 + 4 ≥ 11.24, 9 < 11.24");
    assert_eq!(mark::dorfler(&eta, 0.95), vec![1, 3, 4], "14 ≥ 13.35");
    assert_eq!(mark::dorfler(&eta, 1.0).len(), 5);
    assert!(mark::dorfler(&[0.0; 4], 0.5).is_empty(), "nothing to refine where the estimate is zero");
}

#[test]
fn split_halves_only_the_marked_intervals() {
    let lines = [0.0, 1.0, 3.0, 4.0];
    assert_eq!(mark::split(&lines, &[false, true, false]), vec![0.0, 1.0, 2.0, 3.0, 4.0]);
    assert_eq!(mark::split(&lines, &[true, false, true]), vec![0.0, 0.5, 1.0, 3.0, 3.5, 4.0]);
    assert_eq!(mark::split(&lines, &[false; 3]), lines.to_vec());
}

/// The model's own plan rebuilds the same mesh: refinement starts from
/// what the file describes (graded divisions included), each coordinate
/// within the `10⁻¹²` of the block's size to which the planned file writes
/// its lines (`setup::plan_file`, without their round-off digits).
#[test]
fn the_plan_of_a_file_rebuilds_its_mesh() {
    let text = example("block_indentation.toml");
    let model = Model::parse_with(&text, Limits::none()).unwrap();
    let again = planned(&text, &model.plan);
    assert_eq!(again.n_dofs(), model.n_dofs());
    let (a, b) = (&model.mesh.bodies[0], &again.mesh.bodies[0]);
    let close = |a: &[f64], b: &[f64]| a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12);
    assert!(a.section.nodes.len() == b.section.nodes.len());
    assert!(a.section.nodes.iter().zip(&b.section.nodes).all(|(p, q)| close(p, q)));
    assert!(close(&a.axis.nodes, &b.axis.nodes));
    let SectionPlan::Grid { x, z, .. } = &model.plan.bodies[0].section else { panic!("the block is a grid") };
    assert_eq!((x.len() - 1, z.len() - 1, model.plan.bodies[0].axis.len() - 1), (18, 6, 1));
}

/// One element with a large estimate in a known place: its x, z and axis
/// intervals — and only they — are split, and the refined mesh has the
/// DOF count of the new divisions; probes, lines and constraints are still
/// there by name.
#[test]
fn the_marked_element_s_intervals_are_split() {
    let (nx, nz, ny) = (4, 3, 5);
    let text = cantilever(nx, nz, ny);
    let model = Model::parse_with(&text, Limits::none()).unwrap();
    assert_eq!(model.n_dofs(), dof_l9_b4(nx, nz, ny));
    let body = &model.mesh.bodies[0];
    // section element (i = 2, j = 1) in beam element 3
    let (i, j, k) = (2, 1, 3);
    let hot = k * body.section.n_elements() + j * nx + i;
    let mut eta = vec![1e-3; model.mesh.n_elements()];
    eta[hot] = 1.0;
    let second = (k + 1) * body.section.n_elements() + 3; // a smaller one elsewhere: (3, 0) in k + 1
    eta[second] = 0.5;
    let marked = mark::dorfler(&eta, 0.5);
    assert_eq!(marked, vec![hot]);
    let marks = mark::intervals(&model.mesh, &model.plan, &marked);
    let m = &marks[0];
    assert_eq!(m.x, (0..nx).map(|a| a == i).collect::<Vec<_>>());
    assert_eq!(m.z, (0..nz).map(|b| b == j).collect::<Vec<_>>());
    assert_eq!(m.axis, (0..ny).map(|c| c == k).collect::<Vec<_>>());
    let plan = mark::refine(&model.plan, &marks);
    let SectionPlan::Grid { x, .. } = &plan.bodies[0].section else { panic!() };
    let h = 0.1 / nx as f64;
    assert!((x[i + 1] - (i as f64 + 0.5) * h).abs() < 1e-15, "the new x line halves interval {i}: {x:?}");
    let refined = planned(&text, &plan);
    assert_eq!(refined.n_dofs(), dof_l9_b4(nx + 1, nz + 1, ny + 1));
    // with θ = 0.9 the second element joins: its intervals too
    let plan = mark::refine(&model.plan, &mark::intervals(&model.mesh, &model.plan, &mark::dorfler(&eta, 0.9)));
    assert_eq!(planned(&text, &plan).n_dofs(), dof_l9_b4(nx + 2, nz + 2, ny + 2));
    assert!(refined.probes.iter().any(|p| p.name == "tip"));
    assert_eq!(refined.constraints.len(), model.constraints.len());
    assert_eq!(refined.constraints[0].name, model.constraints[0].name);
}

/// A thin-walled tube is refined as a whole (every count doubled) when the
/// marked elements are spread over its ring, and only along the axis when
/// they lie in a few of its elements.
#[test]
fn a_parametric_section_is_doubled_or_kept() {
    let text = example("bending_tube_20L9.toml");
    let model = Model::parse_with(&text, Limits::none()).unwrap();
    let body = &model.mesh.bodies[0];
    let ns = body.section.n_elements();
    assert_eq!(ns, 20);
    assert_eq!(
        model.plan.bodies[0].section,
        SectionPlan::Doubled { shape: "tube", times: 0, parts: Default::default(), junction: None }
    );
    // marked: every section element of beam element 0
    let all: Vec<usize> = (0..ns).collect();
    let plan = mark::refine(&model.plan, &mark::intervals(&model.mesh, &model.plan, &all));
    assert_eq!(
        plan.bodies[0].section,
        SectionPlan::Doubled { shape: "tube", times: 1, parts: Default::default(), junction: None }
    );
    let refined = planned(&text, &plan);
    assert_eq!(refined.mesh.bodies[0].section.n_elements(), 36, "around = 4 + 4·8");
    assert_eq!(refined.mesh.bodies[0].axis.n_elements(), 23);
    // the refined model keeps its plan: a second doubling counts from the
    // file's counts again (around = 4 + 4·4·4), not from the first's
    assert_eq!(refined.plan, plan);
    let ns2 = refined.mesh.bodies[0].section.n_elements();
    let all2: Vec<usize> = (0..ns2).collect();
    let plan2 = mark::refine(&refined.plan, &mark::intervals(&refined.mesh, &refined.plan, &all2));
    assert_eq!(
        plan2.bodies[0].section,
        SectionPlan::Doubled { shape: "tube", times: 2, parts: Default::default(), junction: None }
    );
    assert_eq!(planned(&text, &plan2).mesh.bodies[0].section.n_elements(), 68, "around = 4 + 4·16");
    // marked: half the ring less one, over two slices
    let some: Vec<usize> = (0..ns / 2 - 1).map(|s| 5 * ns + s).chain([7 * ns]).collect();
    let plan = mark::refine(&model.plan, &mark::intervals(&model.mesh, &model.plan, &some));
    assert_eq!(
        plan.bodies[0].section,
        SectionPlan::Doubled { shape: "tube", times: 0, parts: Default::default(), junction: None }
    );
    let n_section_nodes = body.section.n_nodes();
    assert_eq!(planned(&text, &plan).n_dofs(), 3 * n_section_nodes * (3 * 24 + 1));
}

#[test]
fn the_adapt_table_is_typed_and_checked() {
    let base = cantilever(2, 2, 5);
    let with = |table: &str| Model::parse_with(&format!("{base}\n[adapt]\n{table}\n"), Limits::none());
    let m = with("tolerance = 0.02\nmax_dof = 9000\nmax_cycles = 3").unwrap();
    let a = m.adapt.unwrap();
    assert_eq!((a.tolerance, a.max_dof, a.max_cycles, a.fraction), (0.02, 9000, 3, 0.5));
    assert!(Model::parse_with(&base, Limits::none()).unwrap().adapt.is_none());
    let err = with("tolerence = 0.02").unwrap_err().to_string();
    assert!(err.contains("tolerence") && err.contains("max_dof") && err.contains("fraction"), "{err}");
    for (table, key) in [
        ("tolerance = 1.5", "adapt.tolerance"),
        ("tolerance = -0.1", "adapt.tolerance"),
        ("max_dof = 0", "adapt.max_dof"),
        ("max_cycles = 99", "adapt.max_cycles"),
        ("fraction = 0.0", "adapt.fraction"),
    ] {
        let err = with(table).unwrap_err().to_string();
        assert!(err.contains(key) && err.contains("expected"), "{table}: {err}");
    }
}

/// `cufem run --adapt` through the CLI: cycles until the DOF budget stops
/// it, the estimate falling from cycle to cycle, every mesh within the
/// budget, the cycles in summary.json and the last cycle's results written
/// (its DOF, its probe). The budget binds before `max_cycles = 5` does: the
/// cantilever's error lies along z and the axis, so its x interval is
/// never split (`mark::by_direction`) and five cycles reach 3,366 DOF.
#[test]
fn cli_run_adapt_refines_until_the_budget() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("adapt_cli");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("cantilever.toml");
    std::fs::write(&model, cantilever(1, 1, 2)).unwrap();
    let budget = 2500;
    let out = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", model.to_str().unwrap(), "--adapt", "0.001", "--max-dof", &budget.to_string(), "--out"])
        .arg(dir.join("out"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stderr}\n{stdout}");
    assert!(stderr.contains("cycle 0:") && stderr.contains("cycle 1:"), "{stderr}");
    assert!(stdout.contains("adaptive run stopped: the next mesh"), "{stdout}");
    // where the adapted mesh went, on the console and in the report (a new user found it in summary.json only)
    assert!(stdout.contains("as a model file: ") && stdout.contains("adapted.toml\n"), "{stdout}");
    let html = std::fs::read_to_string(dir.join("out/report.html")).unwrap();
    assert!(html.contains("as a model file, adapted.toml"), "the report's adaptive section");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap()).unwrap();
    let cycles = s["adapt"].as_array().unwrap();
    assert!(cycles.len() >= 3, "{cycles:?}");
    for (k, c) in cycles.iter().enumerate() {
        assert_eq!(c["cycle"].as_u64().unwrap() as usize, k);
        assert!(c["dof"].as_u64().unwrap() as usize <= budget);
    }
    for w in cycles.windows(2) {
        assert!(w[1]["dof"].as_u64() > w[0]["dof"].as_u64());
        let (a, b) = (w[0]["estimate"].as_f64().unwrap(), w[1]["estimate"].as_f64().unwrap());
        assert!(b < a, "the estimate did not fall: {a} → {b}");
    }
    let last = cycles.last().unwrap();
    assert_eq!(s["dof"], last["dof"], "the results are the last cycle's");
    assert_eq!(s["error_estimate"]["relative_energy_norm"], last["estimate"]);
    assert!(s["adapt_stop"].as_str().unwrap().contains("budget"));
    // the run's time is all its cycles', `wall_time_s` the last one's (a
    // new user read the last cycle's as the run's), on the console too
    let times: f64 = cycles.iter().map(|c| c["time_s"].as_f64().unwrap()).sum();
    assert!((s["adapt_time_s"].as_f64().unwrap() - times).abs() <= 1e-9 * times, "{}", s["adapt_time_s"]);
    assert!(s["wall_time_s"].as_f64().unwrap() < times);
    let all = format!("cycles: {}, {:.1} s in all (the Model row above: the last cycle's)", cycles.len(), times);
    assert!(stdout.contains(&all), "{stdout}");
    assert_eq!(s["probes"][0]["name"], "tip");
    // the adapted mesh as a model file: the user's file (its comments kept)
    // with the last cycle's divisions, which solves to the same result,
    // under a header that says what it is
    let adapted = std::fs::read_to_string(dir.join("out/adapted.toml")).unwrap();
    let original = std::fs::read_to_string(&model).unwrap();
    let comments =
        |t: &str| t.lines().filter(|l| l.trim_start().starts_with('#')).map(str::to_owned).collect::<Vec<_>>();
    let kept = comments(&adapted);
    assert!(!comments(&original).is_empty() && comments(&original).iter().all(|c| kept.contains(c)), "{adapted}");
    let last_dof = cufem::io::report::thousands(last["dof"].as_u64().unwrap() as usize);
    let header = format!("of its cycle {} ({last_dof} DOF, estimate ", cycles.len() - 1);
    assert!(
        adapted.starts_with("# Written by `cufem run` with adaptive refinement") && adapted.contains(&header),
        "{adapted}"
    );
    assert!(adapted.contains("settings came from the command line (`--adapt`)"), "{adapted}");
    assert!(s["files"].as_array().unwrap().iter().any(|f| f == "adapted.toml"), "{}", s["files"]);
    let out = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", dir.join("out/adapted.toml").to_str().unwrap(), "--quiet", "--out"])
        .arg(dir.join("again"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let again: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("again/summary.json")).unwrap()).unwrap();
    assert_eq!(again["dof"], s["dof"]);
    assert_eq!(again["error_estimate"]["relative_energy_norm"], s["error_estimate"]["relative_energy_norm"]);
    assert_eq!(again["probes"][0]["values"], s["probes"][0]["values"]);
    // a single run has neither key
    let out = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", model.to_str().unwrap(), "--quiet", "--out"])
        .arg(dir.join("single"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let single = std::fs::read_to_string(dir.join("single/summary.json")).unwrap();
    assert!(!single.contains("\"adapt\""));
}

/// An adaptive transient run without frames is measured by its end alone,
/// and says so before its first cycle (a new user's review: the cycle line
/// named `end` and nothing more); with frames it does not.
#[test]
fn an_adaptive_transient_run_without_frames_says_its_end_alone_is_measured() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("adapt_transient_no_frames");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/rod_impact.toml");
    let with_frames = std::fs::read_to_string(path).unwrap();
    assert!(with_frames.contains("\noutput_interval = 5e-5\n"));
    let without = with_frames.replace("\noutput_interval = 5e-5\n", "\n");
    let said = "a transient run without frames: each cycle is measured by its end alone";
    for (name, text, says) in [("without", &without, true), ("with", &with_frames, false)] {
        let model = dir.join(format!("{name}.toml"));
        std::fs::write(&model, text).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_cufem"))
            .args(["run", model.to_str().unwrap(), "--adapt", "0.9", "--out"])
            .arg(dir.join(name))
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        // the progress lines (stderr), with the adaptive run's own first line
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("adaptive run: until the estimate is below 90.00 %"), "{stderr}");
        assert_eq!(stderr.contains(said), says, "{stderr}");
    }
}

/// A model whose file holds the `[adapt]` table: `adapted.toml` leaves the
/// table out (written as comments in its header) and marks its title, so
/// that running it solves the adapted mesh again — it used to keep the
/// table and refine once more (a new user's review: 720 → 1,539 DOF, other
/// results), against model-format.md's "`cufem run adapted.toml` solves the
/// same mesh again".
#[test]
fn an_adapted_file_of_a_model_with_an_adapt_table_solves_its_mesh_again() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("adapt_table_rerun");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("cantilever.toml");
    std::fs::write(&model, format!("{}\n[adapt]\ntolerance = 0.001\nmax_cycles = 1\n", cantilever(1, 1, 2))).unwrap();
    let run = |file: &Path, out: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_cufem"))
            .args(["run", file.to_str().unwrap(), "--quiet", "--out"])
            .arg(dir.join(out))
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = std::fs::read_to_string(dir.join(out).join("summary.json")).unwrap();
        serde_json::from_str::<serde_json::Value>(&text).unwrap()
    };
    let s = run(&model, "out");
    assert_eq!(s["adapt"].as_array().unwrap().len(), 2, "{}", s["adapt"]);
    let adapted = std::fs::read_to_string(dir.join("out/adapted.toml")).unwrap();
    for line in ["# [adapt]\n# tolerance = 0.001\n# max_cycles = 1\n", "(adapted mesh: cycle 1 ("] {
        assert!(adapted.contains(line), "{line}: {adapted}");
    }
    let again = run(&dir.join("out/adapted.toml"), "again");
    assert!(again.get("adapt").is_none(), "the adapted file refined again: {}", again["adapt"]);
    assert_eq!(again["dof"], s["dof"]);
    assert_eq!(again["error_estimate"]["relative_energy_norm"], s["error_estimate"]["relative_energy_norm"]);
    assert_eq!(again["probes"][0]["values"], s["probes"][0]["values"]);
}

#[test]
fn cli_refuses_bad_adapt_options() {
    let model = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples/cantilever_timoshenko.toml");
    for (args, needle) in [
        (vec!["--adapt", "2"], "between 0 and 1"),
        (vec!["--adapt", "0.05", "--max-dof", "0"], "--max-dof"),
        (vec!["--max-dof", "1000"], "--adapt TOL or an [adapt] table"),
        // the key the user gave, not the model file's (a new-user review)
        (vec!["--adapt", "0.05", "--max-dof", "100"], "--max-dof = 100: expected at least the model's own"),
        (vec!["--adapt", "0.05", "--fraction", "0"], "Dörfler's θ"),
        (vec!["--adapt", "0.05", "--fraction", "1.5"], "Dörfler's θ"),
        (vec!["--fraction", "0.3"], "--fraction is an option of an adaptive run"),
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_cufem"))
            .arg("run")
            .arg(&model)
            .args(&args)
            .args(["--out", Path::new(env!("CARGO_TARGET_TMPDIR")).join("adapt_bad").to_str().unwrap(), "--force"])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    }
}

/// Issue 23's "`--adapt` on the block reaches σ_zz under the punch within
/// 5 % of 3D with fewer DOF than the uniform refinements": `cufem run
/// examples/block_indentation_graded.toml --adapt 0.01 --max-dof 38325
/// --fraction 0.2` through the CLI. σ_zz along the top line under the punch
/// (x ∈ [0.21, 0.29] m) against CalculiX C3D20R (145,767 DOF,
/// tests/data/block_calculix_top.csv), in % of the 3D peak; the uniform
/// refinement of the paper's mesh needs 38,325 DOF (36 × 12 L9 × 2 B4) for
/// 4.4 % (docs/cross-check.md, bench/block_refinement.py), that of the
/// graded mesh 36,309 DOF (24 × 9 × 6 B3) for 9.4 % (crates/cufem-cli/tests/fidelity.rs).
/// Measured: cycle 0 (9,009 DOF) 6.0 %, then cycles of 20,295, 30,723 and
/// 33,957 DOF ending at 5.65 % — a known limit, asserted from both sides
/// (docs/limitations.md): the 4.41 % measured before came from cycles the
/// solver's round-off chose (the axis recovery's ties, `post::spr` `TIE`:
/// the same estimate with another factor reuse took this path). With
/// θ = 0.5 the first refinement has 46,683 DOF (3.5 %), over the budget.
#[test]
fn the_graded_block_adapts_below_the_uniform_dof() {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("adapt_block");
    let out = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .arg("run")
        .arg(root.join("examples/block_indentation_graded.toml"))
        .args(["--adapt", "0.01", "--max-dof", "38325", "--fraction", "0.2", "--quiet", "--force", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let dof = s["dof"].as_u64().unwrap();
    assert!(s["adapt"].as_array().unwrap().len() >= 2 && dof < 38_325, "{dof} DOF after {:?}", s["adapt"]);
    let (ours, reference) = (
        common::csv_columns(&dir.join("line_top.csv")),
        common::csv_columns(&root.join("tests/data/block_calculix_top.csv")),
    );
    let peak = reference["s_zz"].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = (0..reference["x"].len())
        .filter(|&i| (0.21 - 1e-9..=0.29 + 1e-9).contains(&reference["x"][i]))
        .map(|i| {
            assert!((ours["x"][i] - reference["x"][i]).abs() < 1e-12);
            (ours["s_zz"][i] - reference["s_zz"][i]).abs() / peak
        })
        .fold(0.0, f64::max);
    for (k, c) in s["adapt"].as_array().unwrap().iter().enumerate() {
        let id = format!("adapt_graded.cycle{k}");
        common::figure(&format!("{id}.dof"), c["dof"].as_f64().unwrap(), "DOF", "the last below 38,325");
        common::figure(&format!("{id}.estimate"), 100.0 * c["estimate"].as_f64().unwrap(), "%", "reported");
    }
    let what = "σ_zz under the punch, % of the 3D peak at the stations x ∈ [0.21, 0.29] m (CalculiX C3D20R), \
                issue 23 asks 5 %";
    common::known_limit("adapt_graded.s_zz", 100.0 * worst, "%", 5.0, 6.5, what);
    let punch = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap();
    let force = punch["force"][2].as_f64().unwrap();
    common::figure("adapt_graded.force", 100.0 * (force / -1.4102e6 - 1.0), "%", "reported, against 3D (1.4102 MN)");
}

/// Issue 49's "`--adapt` on each shipped bending example reaches its
/// tolerance in fewer DOF than uniform refinement", on the compact bar
/// (examples/bending_compact_4L9.toml: 2 × 2 L9 × 10 B4, 2,325 DOF,
/// plastic under the roller, estimate 5.69 %). Its uniform refinement
/// (4 × 4 L9 × 20 B4, 14,823 DOF) is estimated at 3.15 %; `--adapt` with
/// that as its tolerance gets below it at 14,553 DOF (3.08 %: x 2 → 4,
/// z 2 → 3 → 4 → 5, axis 10 → 12 → 14 → 16, each marked element split only
/// along the directions its error varies in, `mark::by_direction`), a
/// margin of 2 % in DOF. The roller force of the adapted mesh is 0.30 %
/// below the uniform mesh's (171.76 against 172.28 N; 3D 172.34 N, four
/// times the quarter's of docs/cross-check.md): the adapted axis (16 B4
/// against 20) leaves it there, a known limit held from both sides
/// (docs/limitations.md).
///
/// Mutation: `mark::DIRECTION_SHARE` at 0 (every direction of a marked
/// element split) takes 14,040 DOF for cycle 2, at 3.24 %, stops at the
/// budget above the tolerance and fails.
#[test]
fn the_compact_bar_adapts_below_its_uniform_refinement_s_estimate_with_fewer_dof() {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples");
    let text = example("bending_compact_4L9.toml");
    let grid = |n: usize| {
        format!("x = {{ from = 0.0, to = 0.01, elements = {n} }}, z = {{ from = 0.0, to = 0.01, elements = {n} }}")
    };
    assert!(text.contains(&grid(2)) && text.contains("to = 0.25, elements = 10 }"));
    let uniform = text.replace(&grid(2), &grid(4)).replace("to = 0.25, elements = 10 }", "to = 0.25, elements = 20 }");
    let model = Model::parse_in(&uniform, Limits::machine(), &dir).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    let tolerance = solution.error_estimate.as_ref().unwrap().relative();
    let load = |s: &cufem::analysis::Solution| s.contact("load").unwrap().force[2];
    let (uniform_dof, uniform_force) = (model.n_dofs(), load(&solution));
    common::figure("adapt_compact.uniform.dof", uniform_dof as f64, "", "4 × 4 L9 × 20 B4");
    common::figure("adapt_compact.uniform.estimate", 100.0 * tolerance, "%", "the adaptive run's tolerance");
    let settings =
        cufem::setup::AdaptSettings { tolerance, max_dof: uniform_dof, max_cycles: 20, fraction: 0.5, modes: None };
    let sample = |m: &Model, s: &cufem::analysis::Solution| {
        let SectionPlan::Grid { x, .. } = &m.plan.bodies[0].section else { panic!("the bar is a grid") };
        vec![load(s), (x.len() - 1) as f64]
    };
    let (rows, _) = measure("bending_compact_4L9.toml", settings, &sample);
    let (dof, estimate, _, v) = rows.last().unwrap();
    common::figure("adapt_compact.adapted.dof", *dof as f64, "", "below the uniform mesh's DOF");
    common::figure("adapt_compact.adapted.estimate", 100.0 * estimate, "%", "below the uniform mesh's estimate");
    assert!(
        *estimate < tolerance && *dof < uniform_dof,
        "{dof} DOF at {:.2} % against {uniform_dof} at {:.2} %",
        100.0 * estimate,
        100.0 * tolerance
    );
    let force = 100.0 * (v[0] / uniform_force - 1.0);
    let what = "the adapted compact bar's roller force below the uniform mesh's (its axis)";
    common::known_limit("adapt_compact.adapted.force", force, "%", -0.32, -0.29, what);
}

/// One cycle of a measured adaptive run: DOF, estimate, time (s), and the
/// quantities compared (`values`).
type Cycle = (usize, f64, f64, Vec<f64>);

/// The cycles of an adaptive run of `examples/<file>` ([`Cycle`], each
/// sampled by `sample`) and the adapted model file it wrote
/// (`Adaptivity::model_file`, the CLI's adapted.toml).
fn measure(
    file: &str,
    settings: cufem::setup::AdaptSettings,
    sample: &dyn Fn(&Model, &cufem::analysis::Solution) -> Vec<f64>,
) -> (Vec<Cycle>, String) {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples");
    let text = example(file);
    let limits = Limits::machine();
    let model = Model::parse_in(&text, limits, &dir).unwrap();
    let source = cufem::adapt::Source { text: &text, base: &dir, limits };
    let mut rows = Vec::new();
    let (_, solution) = cufem::adapt::run(
        model,
        source,
        &settings,
        &Default::default(),
        &mut cufem::analysis::Silent,
        &mut |c, m, s| {
            let values = sample(m, s);
            println!(
                "cycle {}: {} DOF, estimate {:.2} %, {:.1} s, {:?}  {}",
                c.cycle,
                c.dof,
                100.0 * c.estimate,
                c.time_s,
                &values[..values.len().min(4)],
                c.refined
            );
            rows.push((c.dof, c.estimate, c.time_s, values));
        },
    )
    .unwrap();
    let adapt = solution.adapt.unwrap();
    println!("stopped: {}", adapt.stop);
    (rows, adapt.model_file)
}

/// The block under `--adapt` from the paper's mesh against the 3D solution
/// along the top line (x ∈ [0.21, 0.29] m, σ_zz in % of the 3D peak, as
/// bench/block_refinement.py; CalculiX C3D20R refine 2,
/// tests/data/block_calculix_top.csv) and the 3D punch force (1.4102 MN),
/// with a budget of 60,000 DOF (docs/verification.md, "Adaptive
/// refinement"). What the docs claim: the punch force within 0.6 % of 3D
/// at every cycle after the first, and σ_zz under the punch within 6 % of
/// the 3D peak at the last cycle, from 14.8 % on the paper's mesh.
///
/// The surface u_z, issue 49's "within 5 % of 3D at every station", per
/// station as crates/cufem-cli/tests/fidelity.rs measures the graded
/// meshes (`common::block_u_z_error`: |u_z / u_z_3d − 1| against the 3D
/// top line tests/data/block_calculix_top_u_z.csv, each station with its
/// mirror about x = 0.25 m). 3D u_z is negative at every station (−0.030
/// mm at the far corner, −1 mm under the punch), so it never crosses zero
/// and each relative difference is defined. "Every station" is read as in
/// fidelity.rs (`block_36k.u_z_all`): x ∈ [0, 0.19] m, where the last
/// cycle is asserted within 5 % (measured 2.34 %; 109 % and 19 % at cycles
/// 0 and 1, the paper's mesh bulging up beside the punch), the top sinking
/// monotonically towards the punch, and under the punch (u_z set by it).
/// The run: cycle 1 x 18 → 22, z 6 → 8, axis 1 → 2 (16,065 DOF); cycle 2
/// x 22 → 28, z 8 → 9, axis 2 → 4 (42,237 DOF); cycle 3 x 28 → 29, z 9 →
/// 10, axis 4 → 5 (59,472 DOF); the next mesh (65,136 DOF) exceeds the
/// budget and the run stops. The yielded block's estimate (its strains
/// fitted, `post::yielded`) varies along the axis, whose end faces are
/// free, so the axis is split too. The three stations within 10 mm of each
/// punch edge, x ∈ (0.19, 0.2), where 3D u_z falls from −0.18 to −0.99 mm
/// (the near-step at the punch corner), are not within 5 % at the last
/// cycle (measured 36.4 %): 3D u_z steepens within its own last 2.5 mm
/// before the edge (−0.193 mm at 0.195 m, −0.214 at 0.1975 m, −0.99 at
/// 0.2 m), where the adapted mesh's top elements are still millimetres
/// long; a known limit asserted from both sides (docs/limitations.md).
/// Finally the model file the run writes (adapted.toml) is re-run: the
/// same DOF, punch force and u_z.
///
/// Mutations tried with the yielded block's stresses fitted (before
/// `post::yielded`): Young's modulus 10 % high in examples/block_indentation.toml
/// puts the last cycle's u_z at 9.8 % (σ_zz and the force pass) and fails;
/// marking only the axis (`mark::intervals` leaving a grid's x and z) fails
/// at cycle 1's punch force (+2.2 %), its last cycle (36,075 DOF) 49.8 %
/// in u_z (the 17 mm edge elements stay); the user's file written as the
/// adapted one (the plan not applied) fails the re-run's DOF.
#[test]
#[ignore = "validate: slow — four adaptive cycles of the block up to 60,000 DOF and a re-run (about 2 min)"]
fn block_adaptive_against_3d() {
    let settings =
        cufem::setup::AdaptSettings { tolerance: 0.01, max_dof: 60_000, max_cycles: 20, fraction: 0.5, modes: None };
    let top = BlockTop::read();
    let (x, u_z_3d) = (&top.x, &top.u_z);
    let sample = |m: &Model, s: &cufem::analysis::Solution| top.sample(m, s);
    let zones = |u_z: &[f64]| top.zones(u_z);
    let (rows, model_file) = measure("block_indentation.toml", settings, &sample);
    for (k, (dof, estimate, _, v)) in rows.iter().enumerate() {
        common::figure(&format!("adapt_block.cycle{k}.dof"), *dof as f64, "", "reported");
        common::figure(&format!("adapt_block.cycle{k}.estimate"), 100.0 * estimate, "%", "reported");
        common::figure(&format!("adapt_block.cycle{k}.s_zz"), v[0], "%", "last cycle ≤ 6 % of the 3D peak");
        common::figure(&format!("adapt_block.cycle{k}.force"), v[1], "%", "cycles 1 and later: |force − 3D| ≤ 0.6 %");
        let graded = top.force_graded(v[1]);
        common::figure(
            &format!("adapt_block.cycle{k}.force_graded"),
            graded,
            "%",
            "reported: against the graded 3D quarter",
        );
        for (zone, e) in zones(&v[2..]) {
            let check = match zone {
                "all" => "last cycle ≤ 5 % at every station x ∈ [0, 0.19] m, its mirror and under the punch",
                "beside" => "last cycle: known limit (x ∈ (0.19, 0.2) m and its mirror)",
                _ => "reported",
            };
            common::figure(&format!("adapt_block.cycle{k}.u_z_{zone}"), e, "%", check);
        }
        if k >= 1 {
            assert!(v[1].abs() <= 0.6, "cycle {k}: punch force {:+.2} % from 3D", v[1]);
        }
    }
    let last = rows.last().unwrap();
    assert!(rows.len() >= 3 && last.3[0] <= 6.0, "{} cycles; σ_zz at the last {:.2} %", rows.len(), last.3[0]);
    let (u_z, [.., (_, all), (_, beside)]) = (&last.3[2..], zones(&last.3[2..]));
    assert!(all <= 5.0, "u_z {all:.2} % from 3D at a station of x ∈ [0, 0.19] m or under the punch");
    assert!(sinks_towards_the_punch(x, u_z), "the top does not sink monotonically towards the punch");
    common::known_limit("adapt_block.u_z_beside", beside, "%", 35.0, 38.0, "u_z at x = 0.1975 m, the last cycle");

    // the written model file reproduces the last cycle when re-run
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("adapt_block_3d");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("adapted.toml"), &model_file).unwrap();
    let again = Model::from_file(&dir.join("adapted.toml")).unwrap();
    assert_eq!(again.n_dofs(), last.0, "the adapted model file is the last cycle's mesh");
    let solve = |m: &Model| {
        let s = cufem::analysis::run(m, &Default::default(), &mut cufem::analysis::Silent).unwrap();
        assert!(s.failure.is_none(), "{:?}", s.failure);
        sample(m, &s)
    };
    let rerun = solve(&again);
    let scale = u_z_3d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let force = (rerun[1] - last.3[1]).abs() / 100.0;
    let u_z_rerun = rerun[2..].iter().zip(u_z).map(|(a, b)| (a - b).abs() / scale).fold(0.0, f64::max);
    common::figure("adapt_block.rerun.force", force, "", "≤ 1e-6 of the 3D force: adapted.toml re-run");
    common::figure("adapt_block.rerun.u_z", u_z_rerun, "", "≤ 1e-6 of the largest |u_z|: adapted.toml re-run");
    assert!(force <= 1e-6 && u_z_rerun <= 1e-6, "adapted.toml re-run: force {force:e}, u_z {u_z_rerun:e}");
}

/// The 3D top line of the block (CalculiX C3D20R refine 2): σ_zz rows
/// (tests/data/block_calculix_top.csv) and u_z per station
/// (tests/data/block_calculix_top_u_z.csv), for the adaptive block tests.
struct BlockTop {
    /// `[x, σ_zz, peeq]` per station.
    reference: Vec<[f64; 3]>,
    x: Vec<f64>,
    u_z: Vec<f64>,
    /// The largest |σ_zz| of 3D along the line.
    peak: f64,
}

impl BlockTop {
    fn read() -> Self {
        let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
        let reference: Vec<[f64; 3]> = std::fs::read_to_string(root.join("tests/data/block_calculix_top.csv"))
            .unwrap()
            .lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with('x'))
            .map(|l| {
                let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
                [v[0], v[1], v[2]]
            })
            .collect();
        let mut top_3d = common::csv_columns(&root.join("tests/data/block_calculix_top_u_z.csv"));
        let (x, u_z) = (top_3d.remove("x").unwrap(), top_3d.remove("u_z").unwrap());
        assert!(x.len() == reference.len() && x.iter().zip(&reference).all(|(a, r)| (a - r[0]).abs() < 1e-12));
        assert!(u_z.iter().all(|u| *u < 0.0), "3D u_z crosses zero: a relative difference is not defined");
        let peak = reference.iter().map(|r| r[1].abs()).fold(0.0, f64::max);
        Self { reference, x, u_z, peak }
    }

    /// σ_zz under the punch (x ∈ [0.21, 0.29] m, the largest difference in
    /// % of the 3D peak), the punch force (% from 3D's 1.4102 MN), then u_z
    /// at each station of the top line.
    fn sample(&self, m: &Model, s: &cufem::analysis::Solution) -> Vec<f64> {
        let view = s.fields(m);
        let line = m.lines.iter().find(|l| l.name == "top").unwrap();
        let samples = cufem::post::sample_line(&view, line);
        let szz = self
            .reference
            .iter()
            .zip(&samples)
            .filter(|(r, _)| (0.21 - 1e-9..=0.29 + 1e-9).contains(&r[0]))
            .map(|(r, p)| (p.sample.as_ref().unwrap().stress[2] - r[1]).abs() / self.peak)
            .fold(0.0, f64::max);
        let force = s.contact("punch").unwrap().force[2];
        let u_z = samples.iter().map(|p| p.sample.as_ref().unwrap().u[2]);
        [100.0 * szz, 100.0 * (force / -1.4102e6 - 1.0)].into_iter().chain(u_z).collect()
    }

    /// The punch force in % from the 3D quarter graded to the punch edge,
    /// four times its −3.4873e5 N (tests/data/references.toml,
    /// block_edge_quarter), given it in % from the shipped mesh's 3D
    /// (`sample`'s second value).
    fn force_graded(&self, shipped: f64) -> f64 {
        100.0 * ((1.0 + shipped / 100.0) * -1.4102e6 / (4.0 * -3.4873e5) - 1.0)
    }

    /// u_z in % per zone (x ∈ [0, 0.03], [0.03, 0.15], 0.175, [0, 0.19]
    /// with the punch, (0.19, 0.2)), each with its mirror.
    fn zones(&self, u_z: &[f64]) -> [(&'static str, f64); 5] {
        let e = |a: f64, b: f64| 100.0 * common::block_u_z_error(&self.x, u_z, &self.u_z, a, b);
        [
            ("corner", e(0.0, 0.03)),
            ("near", e(0.03, 0.15)),
            ("edge", e(0.175, 0.175)),
            ("all", e(0.0, 0.19).max(e(0.2, 0.25))),
            ("beside", e(0.1925, 0.1975)),
        ]
    }
}

/// `block_adaptive_against_3d` with a budget of 300,000 DOF instead of
/// 60,000: the full third cycle (x 28 → 36, z 9 → 13, axis 4 → 8; 147,825
/// DOF) leaves the stations beside the punch edges at 6.3 %, and a fourth
/// (x 36 → 45, z 13 → 17, axis 8 → 10; 296,205 DOF, the next mesh over the
/// budget), its elements beside each edge about 1 mm wide, brings every
/// station of the top line within issue 49's 5 % of 3D, those 2.5 mm from
/// the edges included (measured 4.73 %, the others 1.98 %), σ_zz under the
/// punch within 6 % of the 3D peak as in `block_adaptive_against_3d`
/// (measured 4.78 %, from 1.75 % at cycle 3: the shipped mesh's 3D top
/// line is the reference there too; 7 to 9 min and
/// 5.0 GB on one thread: `cufem run examples/block_indentation.toml
/// --adapt 0.01 --max-dof 300000 --threads 1`). The punch force is checked
/// against the 3D quarter graded to the punch edge (1 mm C3D20R there,
/// four times its −3.4873e5 N: tests/data/references.toml,
/// block_edge_quarter; its twin with 3 hexahedra along the half depth
/// gives −3.4878e5 N), within 0.6 % (measured +0.04 %): the 3D model of
/// the shipped mesh (−1.4102 MN, refine 2, the reference of the u_z
/// stations and of `block_adaptive_against_3d`'s force) is 1.1 % stiffer
/// than that converged one at the punch. The force check does not tell a
/// run that refines from one that does not: the paper's mesh (cycle 0) is
/// +0.04 % as well, and cycles 1 to 3 +1.27, +0.86 and +0.35 %; the u_z
/// stations do (109 % at cycle 0). The written model file's re-run is
/// checked at the smaller budget (`block_adaptive_against_3d`).
#[test]
#[ignore = "validate: slow — five adaptive cycles of the block up to 300,000 DOF (about 8 min, 5 GB)"]
fn block_adaptive_reaches_every_station() {
    let settings =
        cufem::setup::AdaptSettings { tolerance: 0.01, max_dof: 300_000, max_cycles: 20, fraction: 0.5, modes: None };
    let top = BlockTop::read();
    let (rows, _) = measure("block_indentation.toml", settings, &|m, s| top.sample(m, s));
    let (dof, estimate, _, last) = rows.last().unwrap();
    let zones = top.zones(&last[2..]);
    common::figure("adapt_block_300k.dof", *dof as f64, "", "reported: the last cycle within 300,000 DOF");
    common::figure("adapt_block_300k.estimate", 100.0 * estimate, "%", "reported");
    for (k, (.., v)) in rows.iter().enumerate() {
        let graded = top.force_graded(v[1]);
        common::figure(&format!("adapt_block_300k.cycle{k}.force_graded"), graded, "%", "reported");
        common::figure(&format!("adapt_block_300k.cycle{k}.s_zz"), v[0], "%", "last cycle ≤ 6 % of the 3D peak");
    }
    let force = top.force_graded(last[1]);
    common::figure("adapt_block_300k.force_shipped_3d", last[1], "%", "reported: against the shipped mesh's 3D");
    common::figure("adapt_block_300k.force", force, "%", "|punch force − graded 3D quarter × 4| ≤ 0.6 %");
    for (zone, e) in zones {
        let check = match zone {
            "all" => "≤ 5 % at every station x ∈ [0, 0.19] m, its mirror and under the punch",
            "beside" => "≤ 5 % at the stations x ∈ (0.19, 0.2) m and their mirrors",
            _ => "reported",
        };
        common::figure(&format!("adapt_block_300k.u_z_{zone}"), e, "%", check);
    }
    let [.., (_, all), (_, beside)] = zones;
    assert!(rows.len() >= 5, "{} cycles", rows.len());
    assert!(force.abs() <= 0.6, "punch force {force:+.2} % from the graded 3D quarter");
    assert!(last[0] <= 6.0, "σ_zz under the punch {:.2} % of the 3D peak", last[0]);
    assert!(all <= 5.0 && beside <= 5.0, "u_z {all:.2} % (x ≤ 0.19 m), {beside:.2} % beside the edges");
    assert!(sinks_towards_the_punch(&top.x, &last[2..]), "the top does not sink monotonically towards the punch");
}

/// Whether u_z sinks monotonically from the far field to x = 0.19 m and
/// from the far field x = 0.5 to its mirror x = 0.31 m (as
/// crates/cufem-cli/tests/fidelity.rs; the paper's mesh bulges up there).
fn sinks_towards_the_punch(x: &[f64], u_z: &[f64]) -> bool {
    let left: Vec<f64> = (0..x.len()).filter(|&i| x[i] <= 0.19 + 1e-9).map(|i| u_z[i]).collect();
    let right: Vec<f64> = (0..x.len()).rev().filter(|&i| x[i] >= 0.31 - 1e-9).map(|i| u_z[i]).collect();
    [left, right].iter().all(|side| side.windows(2).all(|w| w[1] <= w[0]))
}

/// The thin-walled tube under `--adapt`, from the paper's uniform mesh
/// (its quarter, examples/bending_tube_28L9_quarter.toml: the same mesh
/// and answer at a quarter of the unknowns): the loading roller's force
/// and σ_yy and peeq at the contact centre per cycle against the 3D quarter
/// converged along the axis and through the wall (CalculiX C3D20R with
/// 1 mm B4 at the roller, 418.6434 N, −64.6981 MPa, 5.39991e-3:
/// tests/data/references.toml, tube_quarter_1mm; its convergence in
/// crates/cufem-cli/tests/roller_twins.rs). The marked elements lie under
/// the roller with their error across the section; each is refined along
/// its long sides (`src/adapt/tube.rs` `tube_sections`): the axis under
/// the roller twice (`11.1` mm B4 against `4.5` mm L9 along the walls),
/// then, the axis at `2.8` mm, the corner block's every side — two L9
/// through the wall, twice as many along it, the axis split again.
/// Issue 49 asks the adapted force within 2 % of 3D (from cycle 1 on:
/// measured −0.60, +1.84 and −0.69 %, from −2.08 % on the paper's mesh)
/// and the roller line's probes within 10 % (the last cycle: σ_yy −2.3 %,
/// peeq −6.7 %; σ_yy +11.7, +20.0 and +9.9 % on the paper's mesh and with
/// the axis alone split).
#[test]
#[ignore = "validate: slow — four adaptive cycles of the tube's quarter up to 42,000 DOF and a re-run (about 90 s)"]
fn tube_adaptive_roller_force() {
    let settings =
        cufem::setup::AdaptSettings { tolerance: 0.01, max_dof: 60_000, max_cycles: 3, fraction: 0.5, modes: None };
    let sample = |m: &Model, s: &cufem::analysis::Solution| {
        let probe = m.probes.iter().find(|p| p.name == "contact_centre").unwrap();
        let sample = s.fields(m).sample_probe(probe).unwrap();
        vec![-s.contact("load").unwrap().force[2], sample.stress[1], sample.peeq]
    };
    // the last cycle's u over the tube against the 3D twin refined at the
    // support as the adapted axis is (tests/data/references.toml,
    // tube_quarter_1mm_support): u follows the support's mesh on both sides
    // (crates/cufem-cli/tests/roller_twins.rs, `graded_wall2_support`)
    let field = std::cell::Cell::new(0.0);
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let twin = Model::from_file(&root.join("bench/tube_quarter_axis_1mm_support.toml")).unwrap();
    let stored = stored::field_3d("tube_quarter_axis_1mm_support");
    let sample = |m: &Model, s: &cufem::analysis::Solution| {
        let rows = cufem_ccx::verify::compare_stored_on(&twin, m, &s.fields(m), &stored).unwrap();
        field.set(rows.iter().find(|r| r.region == "body tube" && r.quantity == "u").unwrap().l2_percent);
        sample(m, s)
    };
    let (rows, model_file) = measure("bending_tube_28L9_quarter.toml", settings, &sample);
    let u = field.get();
    common::figure("adapt_tube.cycle3.u_over_tube", u, "%", "the last cycle: u over the tube ≤ 2 % of 3D (issue 49)");
    assert!(u <= 2.0, "the last cycle's u over the tube: {u:.2} % of 3D");
    // the converged 3D quarter (tests/data/references.toml, tube_quarter_1mm)
    let reference = [418.6434, -64.6981e6, 5.39991e-3];
    let names = ["force", "s_yy", "peeq"];
    assert_eq!(rows.len(), 4, "cycles 0–3");
    for (k, (dof, estimate, _, v)) in rows.iter().enumerate() {
        common::figure(&format!("adapt_tube.cycle{k}.dof"), *dof as f64, "", "reported");
        common::figure(&format!("adapt_tube.cycle{k}.estimate"), 100.0 * estimate, "%", "reported");
        for (i, name) in names.iter().enumerate() {
            let d = 100.0 * (v[i] / reference[i] - 1.0);
            let what = match (i, k) {
                (0, 1..) => "from cycle 1: |force − 3D| ≤ 2 % (issue 49)",
                (1.., 3) => "the last cycle: |probe − 3D| ≤ 10 % (issue 49)",
                _ => "reported",
            };
            common::figure(&format!("adapt_tube.cycle{k}.{name}"), d, "%", what);
            if i == 0 && k >= 1 {
                assert!(d.abs() <= 2.0, "cycle {k}: roller force {d:+.2} % from 3D");
            }
            if i >= 1 && k == 3 {
                assert!(d.abs() <= 10.0, "cycle {k}: {name} {d:+.2} % from 3D");
            }
        }
    }

    // the written model file (`around = 28` rewritten as two L9 through the
    // wall, 12 along each wall) is the last cycle's mesh and answer
    assert!(model_file.contains("through = 2") && !model_file.contains("around ="), "{model_file}");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("adapt_tube");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("adapted.toml"), &model_file).unwrap();
    let again = Model::from_file(&dir.join("adapted.toml")).unwrap();
    let last = rows.last().unwrap();
    assert_eq!(again.n_dofs(), last.0, "the adapted model file is the last cycle's mesh");
    let solution = cufem::analysis::run(&again, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let rerun = sample(&again, &solution);
    let moved = (0..3).map(|i| (rerun[i] / last.3[i] - 1.0).abs()).fold(0.0, f64::max);
    common::figure("adapt_tube.rerun", moved, "", "≤ 1e-6 relative in force, σ_yy and peeq: adapted.toml re-run");
    assert!(moved <= 1e-6, "adapted.toml re-run: {rerun:?} against {:?}", last.3);
}

/// A thin-walled profile under a pressure on one wall (100 × 50 × 3 mm,
/// 0.4 m, clamped at both ends, 2 × 2 L9): most of its section error lies
/// in the wall elements next to the junctions (the walls' transverse-shear
/// boundary layer), so the first cycle grades the walls to a 3 mm element
/// at each junction and doubles no count (`adapt::mark::JUNCTION_SHARE`);
/// the next cycle doubles the wall whose elements hold the error — the
/// channel with the pressure on its web doubles `along_web` alone — and
/// halves the element at each junction. The I-beam with the pressure on
/// its top flange, within 25,000 DOF, stops at `16,587` DOF with an
/// estimate of `19.0 %`, below the `22.1 %` of the whole section doubled
/// four times (38,025 DOF, solved here). Against references converged in
/// the section and along the axis (`python3 bench/profile_true_error.py`,
/// bench/profile_true_error_results.txt: the compliance `∫ p u_n` over the
/// pressed wall) the adapted I-beam is `11.4 %` off and the uniform one
/// `22.6 %`; the channel's adaptive path reaches `6.5 %` at 13,725 DOF
/// where the uniform 32 × 32 L9 is `18.9 %` off at 23,049 DOF.
#[test]
fn a_profile_s_loaded_wall_is_the_one_refined() {
    let beam = |shape: &str, wall: &str, flange: usize, web: usize| {
        format!(
            r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
[[bodies]]
name = "beam"
material = "steel"
section = {{ shape = "{shape}", element = "L9", origin = [0.0, -0.05], width = 0.05, height = 0.1, web_thickness = 0.003, flange_thickness = 0.003, along_flange = {flange}, along_web = {web}, through = 1 }}
axis = {{ element = "B4", from = 0.0, to = 0.4, elements = 4 }}
[[constraints]]
name = "ends"
body = "beam"
where = {{ y = [0.0, 0.0] }}
fix = ["x", "y", "z"]
[[constraints]]
name = "far"
body = "beam"
where = {{ y = 0.4 }}
fix = ["x", "y", "z"]
[[loads]]
name = "pressure"
body = "beam"
where = {wall}
pressure = 1e5
"#
        )
    };
    let flange = beam("i_beam", r#"{ z = 0.05, region = "top_flange" }"#, 2, 2);
    let web = beam("channel", r#"{ x = 0.0, region = "web" }"#, 2, 2);
    let adapt = |text: &str, settings: cufem::setup::AdaptSettings| {
        let model = Model::parse_with(text, Limits::none()).unwrap();
        let source = cufem::adapt::Source { text, base: Path::new("."), limits: Limits::none() };
        let mut plans = Vec::new();
        let (last, solution) = cufem::adapt::run(
            model,
            source,
            &settings,
            &Default::default(),
            &mut cufem::analysis::Silent,
            &mut |_, m, _| plans.push(m.plan.bodies[0].section.clone()),
        )
        .unwrap();
        // the adapted model file is the mesh solved
        let file = Model::parse_with(&solution.adapt.as_ref().unwrap().model_file, Limits::none()).unwrap();
        assert_eq!(file.n_dofs(), last.n_dofs());
        (plans, last, solution.error_estimate.unwrap().relative())
    };
    let two = cufem::setup::AdaptSettings { tolerance: 0.01, max_cycles: 2, ..Default::default() };
    let (plans, ..) = adapt(&web, two);
    let junction_and_parts = |k: usize| {
        let SectionPlan::Doubled { times, parts, junction, .. } = &plans[k] else { panic!("a profile is doubled") };
        assert_eq!(*times, 0, "cycle {k}: the whole section doubled");
        (*junction, parts.clone())
    };
    // cycle 1: graded to the junction squares' side, no count doubled
    assert_eq!(junction_and_parts(1), (Some(0.003), Default::default()));
    // cycle 2: the web alone doubled, the junction element halved
    let web_only: std::collections::BTreeMap<String, u32> = [("along_web".to_string(), 1)].into();
    assert_eq!(junction_and_parts(2), (Some(0.0015), web_only));
    let budget = cufem::setup::AdaptSettings { tolerance: 0.01, max_cycles: 5, max_dof: 25_000, ..Default::default() };
    let (_, last, local) = adapt(&flange, budget);
    let uniform =
        Model::parse_with(&beam("i_beam", r#"{ z = 0.05, region = "top_flange" }"#, 32, 32), Limits::none()).unwrap();
    assert_eq!(uniform.n_dofs(), 38_025, "the section doubled four times");
    let solved = cufem::analysis::run(&uniform, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    let whole = solved.error_estimate.unwrap().relative();
    common::figure("adapt.wall.local_dof", last.n_dofs() as f64, "DOF", "below the uniform 38,025");
    common::figure("adapt.wall.local_estimate", 100.0 * local, "%", "reported");
    common::figure("adapt.wall.uniform_estimate", 100.0 * whole, "%", "reported");
    assert!(last.n_dofs() < uniform.n_dofs(), "{} DOF", last.n_dofs());
    common::figure("adapt.wall.local_over_uniform", local / whole, "", "below 1: the adapted mesh's estimate is lower");
    assert!(local < whole, "adapted {local}, uniform {whole}");
}

/// `--adapt` on a transient run (`adapt::measure`): a cycle is measured by
/// its worst kept time — of the frames (`analysis.output_interval`) and the
/// end, the state whose estimated error `η` is largest, relative to its own
/// energy — and refined by that state's indicators. examples/rod_impact.toml
/// (100 B4 steel rod thrown against a rigid wall, a frame every 50 µs) to
/// `5 %`: measured `7.74 → 2.34 %` in one cycle, the axis element at the wall
/// halved (`100 → 101` elements); the model file written re-runs to the same
/// mesh. The frames' estimates miss the wave's phase error (effectivity
/// 0.08–0.22 against the mesh refined twice, tests/step_error.rs
/// `the_rod_frames_are_estimated`): the run stops while the true error is
/// several times the tolerance (docs/limitations.md).
#[test]
fn adapt_on_a_transient_run_follows_its_worst_kept_time() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/rod_impact.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let start = Model::parse(&text).unwrap();
    let settings = cufem::setup::AdaptSettings { tolerance: 0.05, ..Default::default() };
    let source = cufem::adapt::Source { text: &text, base: Path::new("."), limits: Limits::none() };
    let mut estimates = Vec::new();
    let (model, last) = cufem::adapt::run(
        start,
        source,
        &settings,
        &Default::default(),
        &mut cufem::analysis::Silent,
        &mut |c, _, s| {
            // the worst kept time by η, measured relative to its own energy
            assert!(!s.frames.is_empty());
            let kept = s.error_history.rows.iter().map(|r| (r.state.name(&s.steps), &r.estimate));
            let kept = kept.chain(s.error_estimate.as_ref().map(|e| ("end".to_string(), e)));
            let (state, worst) = kept.max_by(|a, b| a.1.error.total_cmp(&b.1.error)).unwrap();
            assert_eq!(c.estimate, worst.relative());
            assert!(c.modes.is_none());
            // which kept time it is, named (a new user saw three numbers for one mesh)
            assert_eq!(c.state.as_deref(), Some(state.as_str()));
            estimates.push(c.estimate);
        },
    )
    .unwrap();
    let adapt = last.adapt.as_ref().unwrap();
    assert!(adapt.stop.contains("below the tolerance 5.00 %"), "{}", adapt.stop);
    let named = format!("of the worst kept time ({})", adapt.cycles.last().unwrap().state.as_deref().unwrap());
    assert!(adapt.stop.contains(&named), "{}", adapt.stop);
    assert!(estimates.len() >= 2 && estimates[0] > 0.05, "{estimates:?}");
    assert!(*estimates.last().unwrap() < 0.05, "{estimates:?}");
    assert_eq!(Model::parse(&adapt.model_file).unwrap().n_dofs(), model.n_dofs());
}
