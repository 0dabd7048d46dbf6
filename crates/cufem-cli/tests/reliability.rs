//! Issue 13: never a wrong answer in silence, never a lost result. One test
//! per reproduction of the issue (each failed on the code before it: a
//! hang, a silently wrong stiffness, a silently ignored contact, unsafe or
//! lost output, no memory guard, unbounded threads, vague messages), run
//! through the `cufem` binary as a user would.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

fn cufem() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cufem"))
}

fn example(name: &str) -> String {
    let p = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples").join(name);
    std::fs::read_to_string(p).unwrap()
}

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("reliability_{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `cufem` with `args`, killing it after `limit` (a hang fails the test).
fn run_with_limit(args: &[&str], limit: Duration) -> Output {
    let mut child = cufem().args(args).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("cufem {args:?} did not finish within {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

fn write_model(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

/// `check` must fail with exit code 1 and a message holding every needle.
fn assert_rejected(dir: &Path, name: &str, text: &str, needles: &[&str]) {
    let path = write_model(dir, name, text);
    let out = run_with_limit(&["check", &path], Duration::from_secs(20));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{name}: expected exit 1, got {:?}; {err}", out.status.code());
    for n in needles {
        assert!(err.contains(n), "{name}: {n:?} not in {err:?}");
    }
    assert!(!err.contains("panicked"), "{name}: {err}");
    // one line of key, value and what is allowed: never a 200 KB echo
    assert!(err.len() < 2000, "{name}: a {} byte message", err.len());
}

fn summary(dir: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// Reproduction 1: E = 1e-300 with a plotted line hung forever in the
/// plot's tick generation; E = 1e308, a grading ratio of 1e300 and loads of
/// 1e300 ran into NaN or a "rigid-body motion" message.
#[test]
fn out_of_range_magnitudes_are_refused_at_once() {
    let dir = scratch("magnitudes");
    let cant = example("cantilever_timoshenko.toml");
    let block = example("block_indentation.toml");
    let cases = [
        (cant.replace("young_modulus = 70e9", "young_modulus = 1e-300"), "materials[0].young_modulus = 1e-300"),
        (cant.replace("young_modulus = 70e9", "young_modulus = 1e308"), "materials[0].young_modulus = 1e308"),
        (
            block.replace("elements = 6, ratio = 0.3 }", "elements = 6, ratio = 1e300 }"),
            "bodies[0].section.x.segments[0].ratio = 1e300",
        ),
        (cant.replace("[0.0, 0.0, -1000.0]", "[0.0, 0.0, -1e300]"), "loads[0].total_force = [0, 0, -1e300]"),
    ];
    for (k, (text, key)) in cases.iter().enumerate() {
        assert_rejected(&dir, &format!("m{k}.toml"), text, &[key]);
    }
    // and the run itself ends at once with the same message (it used to hang)
    let path = write_model(&dir, "tiny.toml", &cases[0].0);
    let out = run_with_limit(&["run", &path, "--out", dir.join("o").to_str().unwrap()], Duration::from_secs(20));
    assert_eq!(out.status.code(), Some(1));
}

/// Reproduction 2: a `quads` section listing the same quad twice halved the
/// tip deflection, a square plus its left half gave 2/3 of it — exit 0.
#[test]
fn duplicated_or_overlapping_quads_are_refused() {
    let dir = scratch("quads");
    let cant = example("cantilever_timoshenko.toml");
    let rect = "section = { shape = \"rectangle\", element = \"L9\", x = { from = 0.0, to = 0.1, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 2 } }";
    assert!(cant.contains(rect));
    let quads = |points: &str, quads: &str| {
        cant.replace(
            rect,
            &format!("section = {{ shape = \"quads\", element = \"L9\", points = {points}, quads = {quads} }}"),
        )
    };
    let square = "[[0.0, 0.0], [0.1, 0.0], [0.1, 0.1], [0.0, 0.1]]";
    assert_rejected(
        &dir,
        "dup.toml",
        &quads(square, "[[0, 1, 2, 3], [0, 1, 2, 3]]"),
        &["bodies[0].section.quads[1]", "100.000 % of quads[0]"],
    );
    let with_half = "[[0.0, 0.0], [0.1, 0.0], [0.1, 0.1], [0.0, 0.1], [0.05, 0.0], [0.05, 0.1]]";
    assert_rejected(
        &dir,
        "half.toml",
        &quads(with_half, "[[0, 1, 2, 3], [0, 4, 5, 3]]"),
        &["bodies[0].section.quads[1]", "50.000 % of quads[0]", "do not overlap"],
    );
}

/// Reproduction 3: a punch facing away from a flush surface (body inside
/// the punch), a roller whose axis lies on the surface through nodes (those
/// nodes were dropped) and a roller buried under the surface all ran with
/// zero contact force and exit 0; an indenter that never touches said
/// nothing.
#[test]
fn indenters_on_the_wrong_side_are_refused_and_one_that_never_touches_is_reported() {
    let dir = scratch("indenters");
    let block = example("block_indentation.toml");
    assert_rejected(
        &dir,
        "up.toml",
        &block.replace("normal = \"-z\"", "normal = \"+z\""),
        &["indenters[0].normal", "inner side of the surface", "normal = \"-z\""],
    );
    let bar = example("bending_compact_4L9.toml");
    let centre = "center = [0.005, 0.125, 0.02]";
    assert!(bar.contains(centre));
    // axis on the top face z = 0.01, through the node line x = 0.005
    assert_rejected(
        &dir,
        "on_axis.toml",
        &bar.replace(centre, "center = [0.005, 0.125, 0.01]"),
        &["indenters[2].center", "inside the indenter"],
    );
    assert_rejected(
        &dir,
        "buried.toml",
        &bar.replace(centre, "center = [0.005, 0.125, 0.004]").replace(
            "radius = 0.01\ndisplacement = [0.0, 0.0, -0.75e-3]",
            "radius = 0.002\ndisplacement = [0.0, 0.0, -0.75e-3]",
        ),
        &["indenters[2].center", "inner side of the surface"],
    );
    // a punch 1 mm above the block that moves up: legal, but it can never touch
    let away =
        block.replace("position = 0.3\n", "position = 0.301\n").replace("[0.0, 0.0, -1.0e-3]", "[0.0, 0.0, 1.0e-3]");
    assert!(away.contains("position = 0.301"));
    let path = write_model(&dir, "away.toml", &away);
    let out_dir = dir.join("away_out");
    let out = run_with_limit(&["run", &path, "--out", out_dir.to_str().unwrap(), "--quiet"], Duration::from_secs(60));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("warning: indenters[0].displacement") && err.contains("does not close its initial gap"),
        "{err}"
    );
    assert!(err.contains("never touched"), "{err}");
    let s = summary(&out_dir);
    assert!(s["warnings"].as_array().unwrap().iter().any(|w| w.as_str().unwrap().contains("never touched")));
}

/// Reproduction 4: a re-run into a folder with another model's results left
/// the old files beside the new ones, two runs into one folder mixed files,
/// summary.json was written first.
#[test]
fn a_result_folder_holds_one_complete_set_and_one_run_at_a_time() {
    let dir = scratch("folder");
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let block = write_model(&dir, "block.toml", &example("block_indentation.toml"));
    let cant = write_model(&dir, "cant.toml", &example("cantilever_timoshenko.toml"));
    assert!(run_with_limit(&["run", &block, "--out", o, "--quiet"], Duration::from_secs(120)).status.success());
    let first: Vec<String> =
        summary(&out)["files"].as_array().unwrap().iter().map(|f| f.as_str().unwrap().into()).collect();
    assert!(first.contains(&"history_punch.csv".to_string()));
    assert!(run_with_limit(&["run", &cant, "--out", o, "--quiet"], Duration::from_secs(60)).status.success());
    // exactly the second model's set: listed files plus summary.json, nothing of the first
    let s = summary(&out);
    let mut listed: Vec<String> = s["files"].as_array().unwrap().iter().map(|f| f.as_str().unwrap().into()).collect();
    listed.push("summary.json".into());
    listed.sort();
    let mut present: Vec<String> =
        std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    present.sort();
    assert_eq!(present, listed);
    assert!(!present.contains(&"history_punch.csv".to_string()));
    assert_eq!(s["title"], "Cantilever, tip shear (Timoshenko check)");

    // a second run into the same folder while the first runs fails at once
    let mut first_run = spawn_run(&["run", &block, "--out", o]);
    wait_for_line(&mut first_run, "solving");
    let second = run_with_limit(&["run", &cant, "--out", o, "--quiet"], Duration::from_secs(30));
    let err = String::from_utf8_lossy(&second.stderr);
    assert_eq!(second.status.code(), Some(3), "{err}");
    assert!(err.contains("another cufem run") && err.contains(&format!("pid {}", first_run.id())), "{err}");
    assert!(first_run.wait().unwrap().success());
    assert_eq!(summary(&out)["title"], "Block indentation by a rigid flat punch (paper §4.1)");

    // a folder with someone else's files is refused unless --force, and they survive
    let mine = dir.join("mine");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "keep me").unwrap();
    let m = mine.to_str().unwrap();
    let refused = run_with_limit(&["run", &cant, "--out", m, "--quiet"], Duration::from_secs(30));
    assert_eq!(refused.status.code(), Some(3));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("notes.txt"));
    assert!(
        run_with_limit(&["run", &cant, "--out", m, "--quiet", "--force"], Duration::from_secs(30)).status.success()
    );
    assert_eq!(std::fs::read_to_string(mine.join("notes.txt")).unwrap(), "keep me");
    assert!(mine.join("summary.json").exists());
}

/// Reads the child's stderr until a line contains `needle`, then keeps
/// draining it in a thread (a closed pipe would kill the child on its next
/// progress line); the thread returns the rest.
fn wait_for_line(child: &mut Child, needle: &str) -> std::thread::JoinHandle<String> {
    let mut reader = BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    loop {
        line.clear();
        assert!(reader.read_line(&mut line).unwrap() > 0, "the run ended before printing {needle:?}");
        if line.contains(needle) {
            break;
        }
    }
    std::thread::spawn(move || {
        let mut rest = String::new();
        let _ = std::io::Read::read_to_string(&mut reader, &mut rest);
        rest
    })
}

/// Reproduction 5: an unusable --out failed only after the whole solve,
/// with the exit code of a bad model.
#[test]
fn an_unusable_output_folder_fails_before_the_solve() {
    let dir = scratch("unusable");
    let block = write_model(&dir, "block.toml", &example("block_indentation.toml"));
    let file = dir.join("a_file");
    std::fs::write(&file, "x").unwrap();
    let below = file.join("below");
    for (out, needle) in [
        (file.to_str().unwrap(), "found a file"),
        (below.to_str().unwrap(), "is a file, not a folder"),
        ("/proc/cufem_cannot_write_here", "cannot"),
    ] {
        let t = Instant::now();
        let r = run_with_limit(&["run", &block, "--out", out], Duration::from_secs(30));
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(3), "{out}: {err}");
        assert!(err.contains(needle), "{out}: {err}");
        // nothing was solved: no increment was printed, and it took no solve's time
        assert!(!err.contains("increment"), "{err}");
        assert!(t.elapsed() < Duration::from_secs(5));
    }
}

/// Reproduction 6: Ctrl-C discarded every converged increment (exit 130,
/// nothing on disk). Now the first SIGINT stops at the next safe point and
/// writes the last converged increment; a second one exits at once.
#[test]
fn ctrl_c_keeps_the_last_converged_increment_and_a_second_one_exits_at_once() {
    let dir = scratch("ctrl_c");
    // many small increments, so the signal arrives mid-analysis
    let text = example("block_indentation.toml").replace("increments = 20", "increments = 200");
    let model = write_model(&dir, "block.toml", &text);
    let out = dir.join("out");
    let mut child = spawn_run(&["run", &model, "--out", out.to_str().unwrap()]);
    let _reader = wait_for_line(&mut child, "increment   3");
    signal(&child, "INT");
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130));
    let s = summary(&out);
    assert_eq!(s["converged"], false);
    assert_eq!(s["status"], "interrupted");
    let lambda = s["load_factor"].as_f64().unwrap();
    assert!((3.0 / 200.0 - 1e-12..1.0).contains(&lambda), "{lambda}");
    assert!(s["failure"].as_str().unwrap().contains("interrupted"));
    assert!(out.join("result.vtu").exists() && out.join("line_top.csv").exists());

    // twice: out at once, and a converged set in the folder stays as it
    // was. (Which of the two signals the run sees first is a race: if the
    // first one's graceful stop finishes before the second arrives, the
    // run writes its partial set beside the converged one, never over it;
    // an interrupted set in the folder, as above, may be replaced either way.)
    let converged = dir.join("converged");
    let block = write_model(&dir, "block20.toml", &example("block_indentation.toml"));
    let done = cufem().args(["run", &block, "--out", converged.to_str().unwrap(), "--quiet"]).status().unwrap();
    assert!(done.success());
    let mut child = spawn_run(&["run", &model, "--out", converged.to_str().unwrap()]);
    let _reader = wait_for_line(&mut child, "increment   2");
    signal(&child, "INT");
    signal(&child, "INT");
    let t = Instant::now();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130));
    assert!(t.elapsed() < Duration::from_secs(2));
    let kept = summary(&converged);
    assert_eq!((kept["converged"].as_bool(), kept["load_factor"].as_f64()), (Some(true), Some(1.0)));
}

/// Starts `cufem` with its progress on a pipe (read it with [`wait_for_line`]).
fn spawn_run(args: &[&str]) -> Child {
    cufem().args(args).stdout(Stdio::null()).stderr(Stdio::piped()).spawn().unwrap()
}

fn signal(child: &Child, name: &str) {
    let ok = Command::new("kill").args([&format!("-{name}"), &child.id().to_string()]).status().unwrap();
    assert!(ok.success());
}

/// Reproduction 7: `check` on a 1000 × 1000 L16 × 1000 B4 body allocated past
/// 6 GB, and with counts at their caps aborted; nothing stopped a model
/// that cannot fit. Now both are refused from the counts (exit 4) before
/// any mesh is built, and `--max-memory` sets the limit for any model.
#[test]
fn a_model_that_cannot_fit_is_refused_before_it_is_built() {
    let dir = scratch("memory");
    let cant = example("cantilever_timoshenko.toml");
    let huge = cant
        .replace("element = \"L9\", x = { from = 0.0, to = 0.1, elements = 2 }, z = { from = 0.0, to = 0.1, elements = 2 }", "element = \"L16\", x = { from = 0.0, to = 0.1, elements = 1000 }, z = { from = 0.0, to = 0.1, elements = 1000 }")
        .replace("to = 1.0, elements = 5 }", "to = 1.0, elements = 1000 }");
    let caps = huge.replace("elements = 1000", "elements = 100000");
    for (name, text) in [("huge.toml", huge), ("caps.toml", caps)] {
        let path = write_model(&dir, name, &text);
        let t = Instant::now();
        let out = run_with_limit(&["check", &path], Duration::from_secs(20));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(4), "{name}: {err}");
        assert!(err.contains("the model needs at least") && err.contains("--max-memory"), "{err}");
        assert!(t.elapsed() < Duration::from_secs(2), "{name}: refused only after {:?}", t.elapsed());
    }
    // a normal model under a too-small limit: refused after the symbolic
    // factorization, with the estimate; a sufficient limit lets it run
    let block = write_model(&dir, "block.toml", &example("block_indentation.toml"));
    let out_dir = dir.join("o");
    let o = out_dir.to_str().unwrap();
    // 44 MiB: above the validation stage's lower bound (38 MiB), below the
    // estimate after the symbolic factorization (48 MiB)
    let r = run_with_limit(&["run", &block, "--out", o, "--max-memory", "44M"], Duration::from_secs(30));
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(4), "{err}");
    assert!(err.contains("the analysis needs about") && err.contains("Cholesky factor"), "{err}");
    assert!(!out_dir.join("summary.json").exists());
    let r = run_with_limit(&["check", &block], Duration::from_secs(30));
    let text = String::from_utf8_lossy(&r.stdout);
    assert!(text.contains("nnz(L) 1,149,984") && text.contains("memory estimate"), "{text}");
}

/// Reproduction 8: `--threads 1000` turned a 0.4 s run into minutes.
#[test]
fn threads_are_capped_at_the_logical_cores_unless_forced() {
    let dir = scratch("threads");
    let cant = write_model(&dir, "cant.toml", &example("cantilever_timoshenko.toml"));
    let o = dir.join("o");
    let r = run_with_limit(&["run", &cant, "--out", o.to_str().unwrap(), "--threads", "1000"], Duration::from_secs(30));
    assert!(r.status.success());
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(err.contains("1000 threads requested") && err.contains("--force-threads"), "{err}");
    let r = run_with_limit(
        &["run", &cant, "--out", o.to_str().unwrap(), "--threads", "5000", "--force-threads"],
        Duration::from_secs(30),
    );
    assert_eq!(r.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&r.stderr).contains("--threads = 5000"));
}

/// Reproduction 9: vague or misleading messages.
#[test]
fn messages_say_what_is_wrong() {
    let dir = scratch("messages");
    let cant = example("cantilever_timoshenko.toml");
    // a body held by nothing used to get 14 cutbacks and "MaxIterations"
    let start = cant.find("[[constraints]]").unwrap();
    let end = cant.find("[[loads]]").unwrap();
    let free = format!("{}{}", &cant[..start], &cant[end..]);
    assert_rejected(
        &dir,
        "free.toml",
        &free,
        &["bodies[0]", "free to move as a rigid body", "translation along x", "rotation about z"],
    );
    // hardening-table rows of three numbers were accepted
    let bar = example("bending_compact_4L9.toml");
    assert_rejected(
        &dir,
        "row3.toml",
        &bar.replace("[0.002, 44.7e6]", "[0.002, 44.7e6, 7.0]"),
        &["table", "invalid length 3, expected an array of length 2"],
    );
    // found by the mutation test: a table segment 2e-303 wide has an
    // infinite slope, which made every Gauss-point stress NaN
    assert_rejected(
        &dir,
        "steep.toml",
        &bar.replace("[0.002, 44.7e6]", "[2e-303, 44.7e6]"),
        &["table[1] = [2e-303, 4.47e7]", "a segment slope of at most 100 E"],
    );
    // a line outside every body gave a header-only CSV
    assert_rejected(
        &dir,
        "line.toml",
        &cant.replace("from = [0.05, 0.0, 0.1]\nto = [0.05, 1.0, 0.1]", "from = [0.5, 0.0, 0.5]\nto = [0.5, 1.0, 0.5]"),
        &["lines[1]", "passes through a body"],
    );
    // a 100,000-deep nested array echoed a 200 KB line
    assert_rejected(
        &dir,
        "nested.toml",
        &format!("{cant}\nx = {}{}\n", "[".repeat(100_000), "]".repeat(100_000)),
        &["recurse"],
    );
    // binary input: said "stream did not contain valid UTF-8" twice, without a position
    let bin = dir.join("bin.toml");
    std::fs::write(&bin, b"title = \"x\"\n\xff\xfe").unwrap();
    let r = run_with_limit(&["check", bin.to_str().unwrap()], Duration::from_secs(10));
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1));
    assert!(err.contains("not UTF-8 text: invalid byte at line 2, column 1"), "{err}");
    // OS errors were printed twice
    let r = run_with_limit(&["check", "/nonexistent/model.toml"], Duration::from_secs(10));
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(err.matches("No such file").count(), 1, "{err}");
    // max_increments = 1 said "MaxIterations after 0 iterations; residuals []"
    let path = write_model(
        &dir,
        "inc.toml",
        &example("block_indentation.toml").replace("increments = 20", "increments = 20\nmax_increments = 1"),
    );
    let r =
        run_with_limit(&["run", &path, "--out", dir.join("o").to_str().unwrap(), "--quiet"], Duration::from_secs(60));
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2));
    assert!(err.contains("solver.max_increments = 1 was reached") && !err.contains("MaxIterations"), "{err}");
    // `check` printed Rust debug structs
    let path = write_model(&dir, "bar.toml", &bar);
    let r = run_with_limit(&["check", &path], Duration::from_secs(10));
    let text = String::from_utf8_lossy(&r.stdout);
    assert!(text.contains("cylinder of radius 0.01 m, axis along x") && text.contains("tabulated hardening"), "{text}");
    assert!(!text.contains(" { ") && !text.contains("Cylinder") && !text.contains("Table"), "{text}");
    // usage errors are bad input (1), not "not converged" (2)
    assert_eq!(run_with_limit(&["run"], Duration::from_secs(10)).status.code(), Some(1));
}

/// Reproduction 10: the block's edge probe reported a von Mises stress of
/// 92.5 MPa beside a stress tensor whose von Mises value is 82.1 MPa; the
/// docs said the title is stored in result.vtu and it was not.
#[test]
fn probe_von_mises_belongs_to_its_tensor_and_the_vtu_carries_the_title() {
    let dir = scratch("small");
    let model = write_model(&dir, "block.toml", &example("block_indentation.toml"));
    let out = dir.join("o");
    assert!(
        run_with_limit(&["run", &model, "--out", out.to_str().unwrap(), "--quiet"], Duration::from_secs(120))
            .status
            .success()
    );
    let s = summary(&out);
    for p in s["probes"].as_array().unwrap() {
        let t: Vec<f64> = p["stress"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let vm = (0.5 * ((t[0] - t[1]).powi(2) + (t[1] - t[2]).powi(2) + (t[2] - t[0]).powi(2))
            + 3.0 * (t[3] * t[3] + t[4] * t[4] + t[5] * t[5]))
            .sqrt();
        let reported = p["von_mises"].as_f64().unwrap();
        assert!((vm - reported).abs() <= 1e-9 * vm, "{}: {reported} vs {vm} from its tensor", p["name"]);
    }
    let vtu = std::fs::read_to_string(out.join("result.vtu")).unwrap();
    assert!(vtu.lines().take(3).any(|l| l.contains("Block indentation by a rigid flat punch")), "title missing");
}

/// Names and sizes of the files of a result folder (summary.json's size
/// varies with the wall time, so only its presence counts).
fn listing(dir: &Path) -> Vec<(String, u64)> {
    let mut v: Vec<(String, u64)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            let size = if name == "summary.json" { 0 } else { e.metadata().unwrap().len() };
            (name, size)
        })
        .collect();
    v.sort();
    v
}

/// Reproduction 4, the hard part: a run killed (SIGKILL) at any moment —
/// during the solve or while writing tens of megabytes — leaves the output
/// folder holding exactly the previous complete result set or the new
/// complete one: same file names and byte sizes as a complete run of that
/// model, never a mix, never a truncated file.
#[test]
fn a_killed_run_leaves_the_previous_or_the_new_complete_set() {
    let dir = scratch("kill");
    // heavy outputs (two lines of 50,000 samples: ~40 MB of CSV) so that
    // writing takes most of the run
    let heavy = example("cantilever_timoshenko.toml")
        .replace("points = 51", "points = 50000")
        .replace("points = 101", "points = 50000");
    let a = write_model(&dir, "a.toml", &heavy);
    let b = write_model(
        &dir,
        "b.toml",
        &format!(
            "{}\n[[lines]]\nname = \"bottom\"\nfrom = [0.05, 0.0, 0.0]\nto = [0.05, 1.0, 0.0]\npoints = 25000\n",
            heavy.replace("title = \"Cantilever, tip shear (Timoshenko check)\"", "title = \"B\"")
        ),
    );
    // complete reference sets
    let mut reference = Vec::new();
    let mut duration = Duration::ZERO;
    for (k, m) in [&a, &b].iter().enumerate() {
        let out = dir.join(format!("ref{k}"));
        let t = Instant::now();
        assert!(
            run_with_limit(&["run", m, "--out", out.to_str().unwrap(), "--quiet"], Duration::from_secs(120))
                .status
                .success()
        );
        duration = duration.max(t.elapsed());
        reference.push(listing(&out));
    }
    assert_ne!(reference[0], reference[1]);
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    assert!(run_with_limit(&["run", &a, "--out", o, "--quiet"], Duration::from_secs(120)).status.success());
    // a small deterministic generator: kill times spread over the whole run
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15 ^ u64::from(std::process::id());
    let mut kills = Vec::new();
    for round in 0..12 {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        let at = duration.mul_f64((seed >> 11) as f64 / (1u64 << 53) as f64 * 1.2);
        let model = if round % 2 == 0 { &b } else { &a };
        let mut child = cufem()
            .args(["run", model, "--out", o, "--quiet"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        if round % 4 == 3 {
            // now and then a run completes, so the previous set alternates
            assert!(child.wait().unwrap().success());
        }
        std::thread::sleep(at);
        let finished = child.try_wait().unwrap().is_some();
        let _ = child.kill();
        let _ = child.wait();
        kills.push((at, finished));
        let now = listing(&out);
        assert!(
            now == reference[0] || now == reference[1],
            "round {round}: killed after {at:?}: the folder holds neither complete set: {now:?}"
        );
    }
    eprintln!("kills (time, run had already finished): {kills:?}");
    // the interrupted runs left no lock behind: a new run goes through
    assert!(run_with_limit(&["run", &a, "--out", o, "--quiet"], Duration::from_secs(120)).status.success());
    assert_eq!(listing(&out), reference[0]);
    // and no staging folder is left beside it
    let leftovers: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("cufem-staging"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}
