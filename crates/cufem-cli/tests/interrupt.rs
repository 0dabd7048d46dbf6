//! Interrupted runs and converged results (issue 24, item 3): Ctrl-C into a
//! folder that holds a converged result set used to replace it with an
//! all-zero "interrupted" set (SIGINT 0.05 s into the run: exit 130, 0
//! increments in place of the converged set), and a second Ctrl-C left the
//! lock file and the staging folder behind.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

fn cufem() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cufem"))
}

fn scratch(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("interrupt_{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn example(name: &str) -> String {
    std::fs::read_to_string(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples").join(name))
        .unwrap()
}

/// Every file of a folder (recursively) with its bytes, sorted by path.
fn contents(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(contents(&p));
        } else {
            out.push((p.clone(), std::fs::read(&p).unwrap()));
        }
    }
    out.sort();
    out
}

/// Names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut n: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    n.sort();
    n
}

fn sigint(pid: u32) {
    assert!(Command::new("kill").args(["-INT", &pid.to_string()]).status().unwrap().success());
}

/// A converged set (the compact bar, 4 L9) in `dir/res`, and a long model
/// (the block with 300 increments) to interrupt.
fn setup(dir: &Path) -> (PathBuf, PathBuf) {
    let quick = dir.join("quick.toml");
    std::fs::write(&quick, example("bending_compact_4L9.toml")).unwrap();
    let long = dir.join("long.toml");
    std::fs::write(&long, example("block_indentation.toml").replace("increments = 20", "increments = 300")).unwrap();
    let res = dir.join("res");
    let st =
        cufem().args(["run", quick.to_str().unwrap(), "--out", res.to_str().unwrap(), "--quiet"]).status().unwrap();
    assert!(st.success());
    (long, res)
}

/// `cufem run model --out res`, its messages on a pipe.
fn start(model: &Path, res: &Path) -> Child {
    cufem()
        .args(["run", model.to_str().unwrap(), "--out", res.to_str().unwrap(), "--quiet"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// SIGINT 0.05, 0.5 and 2 s into a run into a folder holding a converged
/// set: exit 130, the converged set byte for byte as it was, the partial
/// result where the message says (beside the folder, `res.partial`) or —
/// for a signal before the analysis began — nothing written and the message
/// saying so; no lock or staging folder left.
#[test]
fn an_interrupted_run_never_replaces_a_converged_set() {
    for delay in [0.05, 0.5, 2.0] {
        let dir = scratch(&format!("once_{delay}"));
        let (long, res) = setup(&dir);
        let before = contents(&res);
        let child = start(&long, &res);
        std::thread::sleep(Duration::from_secs_f64(delay));
        sigint(child.id());
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(130), "SIGINT at {delay} s: {err}");
        assert!(contents(&res) == before, "SIGINT at {delay} s: the converged set changed\n{err}");
        let partial = dir.join("res.partial");
        if err.contains("nothing written") {
            assert!(!partial.exists(), "{err}");
        } else {
            assert!(err.contains(&format!("are in {}", partial.display())), "{err}");
            assert!(err.contains("were kept"), "{err}");
            let s: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(partial.join("summary.json")).unwrap()).unwrap();
            assert_eq!(s["converged"], false);
            assert_eq!(s["status"], "interrupted");
        }
        let left: Vec<String> =
            names(&dir).into_iter().filter(|n| n.contains("cufem-lock") || n.contains("staging")).collect();
        assert!(left.is_empty(), "SIGINT at {delay} s left {left:?}");
    }
}

/// Two SIGINTs: out at once (exit 130), the converged set untouched, and
/// neither the lock file nor the staging folder left beside it (they were,
/// until the next run into the same folder).
#[test]
fn a_double_ctrl_c_leaves_no_lock_or_staging_folder() {
    let dir = scratch("twice");
    let (long, res) = setup(&dir);
    let before = contents(&res);
    let child = start(&long, &res);
    std::thread::sleep(Duration::from_millis(700));
    // the staging folder exists while the run goes on
    assert!(names(&dir).iter().any(|n| n.contains("cufem-staging")), "{:?}", names(&dir));
    sigint(child.id());
    std::thread::sleep(Duration::from_millis(20));
    sigint(child.id());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(contents(&res) == before);
    assert_eq!(names(&dir), ["long.toml", "quick.toml", "res"]);
}
