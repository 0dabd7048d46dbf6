//! Analyses that used to end with a wrong answer and exit 0 (issue 46,
//! "silent wrong answers"): each is now refused by key (exit 1), stopped
//! honestly (exit 2, the last converged state written, the reason named)
//! or warned about (summary.json `warnings` and stderr).

use std::path::{Path, PathBuf};

mod common;

const EXAMPLES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples");

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
/// displacement control, tests/path_following.rs) and the snap-back
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
