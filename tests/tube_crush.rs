//! A thin-walled tube crushed by a rigid cylinder past its peak load
//! (examples/tube_crush.toml, issue 26): cufem's force–displacement curve
//! against the CalculiX NLGEOM twin's: within 1.8 % of the 3D peak up to
//! it and 2.6 % past it (issue 26's 5 % up to and past the peak; tests
//! below). With the paper's element instead of B-bar it is 15.0 % past it.
//!
//! The 3D curve is stored in tests/data/tube_crush_ccx_force.csv: it is
//! `verify/history_load.csv` of
//!
//! ```text
//! cufem verify examples/tube_crush.toml --refine 1
//! ```
//!
//! (CalculiX 2.20, C3D20R × refine 1: 37,804 nodes, the same rigid rollers,
//! `*STEP, NLGEOM`; columns `lambda,d,f_x,f_y,f_z,ccx_f_x,ccx_f_y,ccx_f_z`,
//! d the roller's displacement in m, forces on the tube in N). The crush
//! takes half a minute and its CalculiX twin an hour, so the checks are
//! `#[ignore]`d and run by hand:
//!
//! ```text
//! cargo test --release --test tube_crush -- --ignored
//! ```

use std::path::{Path, PathBuf};
use std::process::Command;

const EXAMPLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/tube_crush.toml");
const STORED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/tube_crush_ccx_force.csv");

fn out_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// `(d, F)` rows of a CSV: the roller's displacement (m, positive down)
/// and the force it pushes with (N, positive), from the columns named.
fn curve(text: &str, d_col: &str, f_col: &str) -> Vec<(f64, f64)> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let (i, j) = (header.iter().position(|h| *h == d_col).unwrap(), header.iter().position(|h| *h == f_col).unwrap());
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap_or(f64::NAN)).collect();
            (v[i].abs(), -v[j])
        })
        .collect()
}

/// Linear interpolation of `path` (increasing d, from (0, 0)) at `d`.
fn at(path: &[(f64, f64)], d: f64) -> f64 {
    let mut last = (0.0, 0.0);
    for &p in path {
        if p.0 >= d {
            return last.1 + (d - last.0) / (p.0 - last.0) * (p.1 - last.1);
        }
        last = p;
    }
    panic!("d = {d} beyond the path's end {}", last.0)
}

/// The example is a valid model of the size its header states (checked
/// in every test run: the comparisons below take minutes), and the stored
/// 3D curve is the one of its 9 mm crush: 45 CalculiX increments, the
/// first the example's 1/1152 of the stroke, its peak passed.
#[test]
fn the_example_and_its_stored_curve_are_consistent() {
    let check = Command::new(env!("CARGO_BIN_EXE_cufem")).args(["check", EXAMPLE]).output().unwrap();
    assert!(check.status.success(), "{}", String::from_utf8_lossy(&check.stderr));
    assert!(String::from_utf8_lossy(&check.stdout).contains("300 elements, 5,520 nodes, 16,560 DOF"));
    let theirs = curve(&std::fs::read_to_string(STORED).unwrap(), "d", "ccx_f_z");
    assert_eq!(theirs.len(), 45);
    assert!((theirs[0].0 - 9e-3 / 1152.0).abs() < 1e-9);
    assert!((theirs.last().unwrap().0 - 9e-3).abs() < 1e-9);
    let peak = theirs.iter().map(|p| p.1).fold(0.0, f64::max);
    assert!(theirs.last().unwrap().1 < 0.9 * peak);
}

/// The example through the CLI against the stored 3D curve, issue 26's
/// criterion: at every 3D increment the force within 5 % of the 3D peak,
/// up to the peak (measured 1.76 %, from the first 3D increment of 7.8 µm)
/// and past it (measured 2.58 %, at 8.85 mm: 1,083 against 1,052 N); cufem's
/// largest force within 5 % of the 3D peak (measured −0.8 %); the 3D curve
/// well past its peak (its last force 14 % below it); and the run without
/// a cutback in at most 205 Newton iterations (measured 182). The paper's
/// element (no B-bar) fails it: 15.0 % past the peak.
#[test]
#[ignore = "half a minute: the crush to 9 mm, past its peak"]
fn the_crush_follows_the_calculix_curve_to_its_peak() {
    let out = out_dir("tube_crush");
    let status = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", EXAMPLE, "--quiet", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let ours = curve(&std::fs::read_to_string(out.join("history_load.csv")).unwrap(), "d_z", "f_z");
    let stored = std::fs::read_to_string(STORED).unwrap();
    let theirs = curve(&stored, "d", "ccx_f_z");
    let peak = |c: &[(f64, f64)]| c.iter().copied().fold((0.0, 0.0), |m, p| if p.1 > m.1 { p } else { m });
    let (p3, pc) = (peak(&theirs), peak(&ours));
    eprintln!("peaks: 3D {:.1} N at {:.2} mm, cufem {:.1} N at {:.2} mm", p3.1, p3.0 * 1e3, pc.1, pc.0 * 1e3);
    let (mut before, mut after): ((f64, f64), (f64, f64)) = ((0.0, 0.0), (0.0, 0.0));
    for &(d, f) in &theirs {
        let diff = 100.0 * (at(&ours, d) - f).abs() / p3.1;
        let worst = if d <= p3.0 { &mut before } else { &mut after };
        if diff > worst.1 {
            *worst = (d, diff);
        }
    }
    eprintln!("largest difference up to the 3D peak {:.2} % at {:.2} mm", before.1, before.0 * 1e3);
    eprintln!("largest difference past it {:.2} % at {:.2} mm", after.1, after.0 * 1e3);
    assert!(before.1 < 5.0, "{:.2} % at {:.2} mm", before.1, before.0 * 1e3);
    assert!((pc.1 - p3.1).abs() < 0.05 * p3.1);
    assert!(after.1 < 5.0, "{:.2} % at {:.2} mm", after.1, after.0 * 1e3);
    let last = theirs.last().unwrap();
    assert!(last.1 < 0.95 * p3.1 && last.0 > 2.0 * p3.0, "not past the peak: {last:?} against {p3:?}");
    // the path of docs/performance.md's two rules (measured: no cutback,
    // 182 Newton iterations): without the line search 8 increments are cut
    // back, without the kept contact of a secant start (contact::assembly::rigid)
    // it takes 229 iterations
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let iterations = summary["newton_iterations"].as_u64().unwrap();
    eprintln!("{} increments, {iterations} Newton iterations, {} cutbacks", summary["increments"], summary["cutbacks"]);
    assert_eq!(summary["cutbacks"].as_u64(), Some(0));
    assert!(iterations <= 205, "{iterations} Newton iterations");
}

/// The same comparison made by `cufem verify` itself, CalculiX included:
/// its force-history row for the loading roller — the peaks within 5 %
/// and the largest difference over the whole curve below 5 % of the 3D
/// peak (issue 26's criterion; measured in docs/cross-check.md).
#[test]
#[ignore = "about an hour: runs CalculiX with NLGEOM on 37,804 nodes"]
fn verify_compares_the_crush_with_calculix_nlgeom() {
    let out = out_dir("tube_crush_verify");
    let status = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["verify", EXAMPLE, "--refine", "1", "--quiet", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("verify/table.json")).unwrap()).unwrap();
    let load = table["force_histories"].as_array().unwrap().iter().find(|r| r["name"] == "load").unwrap();
    eprintln!("{load}");
    assert!(load["peak_difference_percent"].as_f64().unwrap().abs() < 5.0);
    assert!(load["max_difference_percent"].as_f64().unwrap() < 5.0);
}
