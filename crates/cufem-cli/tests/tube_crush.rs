//! A thin-walled tube crushed by a rigid cylinder past its peak load
//! (examples/tube_crush.toml, issue 26): cufem's force–displacement curve
//! against the CalculiX NLGEOM twin's: within 1.8 % of the 3D peak up to
//! it and 2.6 % past it (issue 26's 5 % up to and past the peak; tests
//! below). With the paper's element instead of B-bar it is 15.0 % past it.
//! The example models half the section (a `[[symmetry]]` plane at
//! x = 0.015); the stored 3D curve is of the whole section, compared with
//! the example's full-structure force (`full_f_z` of its history).
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
//! d the roller's displacement in m, forces on the tube in N; that twin
//! was of the example with the whole section, 20 L9 around it and the
//! plane x = 0.015 a `u_x = 0` constraint). The crush takes seconds and is
//! checked with the tests; the whole section's run takes half a minute and
//! is run by `bench/validate` (step `slow`); the CalculiX twin takes half an
//! hour and re-makes the stored 3D curve (`bench/validate --references`).

#[path = "../../../tests/common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

const EXAMPLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/tube_crush.toml");
const STORED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/tube_crush_ccx_force.csv");

fn out_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("tube_crush_{name}"));
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

/// The example is a valid model of the size its header states, and the
/// stored 3D curve is the one of its 9 mm crush: 45 CalculiX increments, the
/// first the example's 1/1152 of the stroke, its peak passed.
#[test]
fn the_example_and_its_stored_curve_are_consistent() {
    let check = Command::new(env!("CARGO_BIN_EXE_cufem")).args(["check", EXAMPLE]).output().unwrap();
    assert!(check.status.success(), "{}", String::from_utf8_lossy(&check.stderr));
    // the half section x ≥ 0.015 (the `[[symmetry]]` plane), 10 of the 20 L9
    assert!(String::from_utf8_lossy(&check.stdout).contains("150 elements, 2,898 nodes, 8,694 DOF"));
    let theirs = curve(&std::fs::read_to_string(STORED).unwrap(), "d", "ccx_f_z");
    assert_eq!(theirs.len(), 45);
    assert!((theirs[0].0 - 9e-3 / 1152.0).abs() < 1e-9);
    assert!((theirs.last().unwrap().0 - 9e-3).abs() < 1e-9);
    let peak = theirs.iter().map(|p| p.1).fold(0.0, f64::max);
    assert!(theirs.last().unwrap().1 < 0.9 * peak);
}

/// The example through the CLI against the stored 3D curve, issue 26's
/// criterion: at every 3D increment the force within 5 % of the 3D peak,
/// up to the peak (measured 1.73 %, from the first 3D increment of 7.8 µm)
/// and past it (measured 2.59 %, at 8.85 mm); cufem's largest force within
/// 5 % of the 3D peak (measured −0.8 %: 1,201.2 against 1,211.4 N); the 3D
/// curve well past its peak (its last force 14 % below it); and the run
/// without a cutback in at most 205 Newton iterations (measured 44
/// increments, 177 iterations). The paper's element (no B-bar) fails it:
/// 15.0 % past the peak.
#[test]
fn the_crush_follows_the_calculix_curve_to_its_peak() {
    let out = out_dir("tube_crush");
    let status = Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", EXAMPLE, "--quiet", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    // the force on the whole section (both sides of the symmetry plane
    // x = 0.015), as the 3D twin's: f_z is the modelled half's
    let ours = curve(&std::fs::read_to_string(out.join("history_load.csv")).unwrap(), "d_z", "full_f_z");
    // the mid-span constraint touches the plane too: its full-structure
    // reaction doubles r_y and cancels r_x (bc::symmetry::full_structure)
    let mid = common::csv_columns(&out.join("history_symmetry_y.csv"));
    let last = |c: &str| *mid[c].last().unwrap();
    let (r_y, full_r_y) = (last("r_y"), last("full_r_y"));
    assert!(r_y.abs() > 100.0 && (full_r_y - 2.0 * r_y).abs() <= 1e-12 * r_y.abs(), "{full_r_y} against 2 × {r_y}");
    assert_eq!(last("full_r_x"), 0.0);
    let stored = std::fs::read_to_string(STORED).unwrap();
    let theirs = curve(&stored, "d", "ccx_f_z");
    let peak = |c: &[(f64, f64)]| c.iter().copied().fold((0.0, 0.0), |m, p| if p.1 > m.1 { p } else { m });
    let (p3, pc) = (peak(&theirs), peak(&ours));
    common::figure("crush.peak_3d", p3.1, "N", "stored CalculiX NLGEOM curve (tests/data/tube_crush_ccx_force.csv)");
    common::figure("crush.peak", pc.1, "N", "within 5 % of the 3D peak");
    common::figure("crush.peak_at", pc.0 * 1e3, "mm", "reported");
    common::figure("crush.peak_3d_at", p3.0 * 1e3, "mm", "stored CalculiX NLGEOM curve");
    let (mut before, mut after): ((f64, f64), (f64, f64)) = ((0.0, 0.0), (0.0, 0.0));
    for &(d, f) in &theirs {
        let diff = 100.0 * (at(&ours, d) - f).abs() / p3.1;
        let worst = if d <= p3.0 { &mut before } else { &mut after };
        if diff > worst.1 {
            *worst = (d, diff);
        }
    }
    common::figure("crush.before_peak", before.1, "%", "< 5 % of the 3D peak up to it (issue 26)");
    common::figure("crush.after_peak", after.1, "%", "< 5 % of the 3D peak past it (issue 26)");
    assert!(before.1 < 5.0, "{:.2} % at {:.2} mm", before.1, before.0 * 1e3);
    assert!((pc.1 - p3.1).abs() < 0.05 * p3.1);
    assert!(after.1 < 5.0, "{:.2} % at {:.2} mm", after.1, after.0 * 1e3);
    let last = theirs.last().unwrap();
    assert!(last.1 < 0.95 * p3.1 && last.0 > 2.0 * p3.0, "not past the peak: {last:?} against {p3:?}");
    // the path of docs/performance.md's two rules (measured: no cutback,
    // 177 Newton iterations): without the line search 8 increments are cut
    // back, without the kept contact of a secant start (contact::assembly::rigid)
    // it takes 242 iterations
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let iterations = summary["newton_iterations"].as_u64().unwrap();
    common::figure("crush.iterations", iterations as f64, "", "≤ 205 Newton iterations, no cutback");
    common::figure("crush.increments", summary["increments"].as_f64().unwrap(), "", "reported");
    assert_eq!(summary["cutbacks"].as_u64(), Some(0));
    assert!(iterations <= 205, "{iterations} Newton iterations");
}

/// The example's half section against the whole section it stands for (the
/// same file with the plane x = 0.015 a `u_x = 0` constraint on all 20 L9,
/// 16,560 DOF): the same problem, so the same curve up to the plastic
/// path's dependence on the steps the two runs take (43 increments against
/// 44) — within 1 % of the peak (measured 0.54 %) — and the same end state
/// (the probes' u_z within 1e-4, measured 1.2e-5). This is the claim of
/// the README and docs/performance.md that the half is the whole's answer.
#[test]
#[ignore = "validate: slow — the whole section's crush (about half a minute)"]
fn the_half_section_gives_the_whole_sections_curve() {
    let half = std::fs::read_to_string(EXAMPLE).unwrap();
    let plane = "[[symmetry]]\nname = \"symmetry_x\"\nplane = { x = 0.015 }\nkeep = \"above\"\n";
    assert!(half.contains(plane));
    let constraint = "[[constraints]]\nname = \"symmetry_x\"\nbody = \"tube\"\nwhere = { x = 0.015 }\nfix = [\"x\"]\n";
    let whole = half.replace(plane, constraint);
    let (half_out, half_summary) = common::run_text("tube_crush", "half", &half);
    let (whole_out, whole_summary) = common::run_text("tube_crush", "whole", &whole);
    assert_eq!(whole_summary["dof"], 16560);
    let read = |out: &Path, f: &str| curve(&std::fs::read_to_string(out.join("history_load.csv")).unwrap(), "d_z", f);
    let (ours, theirs) = (read(&half_out, "full_f_z"), read(&whole_out, "f_z"));
    let peak = theirs.iter().map(|p| p.1).fold(0.0, f64::max);
    let worst = theirs.iter().skip(1).map(|&(d, f)| (at(&ours, d) - f).abs() / peak).fold(0.0, f64::max);
    common::figure("crush.half_vs_whole", 100.0 * worst, "%", "< 1 % of the whole section's peak");
    assert!(worst < 0.01, "{:.2} % of the peak", 100.0 * worst);
    for (a, b) in half_summary["probes"].as_array().unwrap().iter().zip(whole_summary["probes"].as_array().unwrap()) {
        let (a, b) = (a["u"][2].as_f64().unwrap(), b["u"][2].as_f64().unwrap());
        assert!((a - b).abs() < 1e-4 * b.abs(), "probe u_z {a:e} against {b:e}");
    }
}

/// The assembled tangent in the middle of an increment of the crush —
/// finite-strain plasticity on the logarithmic strain, B-bar's projected
/// dilatation, the geometric term and the rollers' surface contact at once —
/// against central differences of the residual (h = 1 nm), in the columns
/// where it matters most: the 6 equations with the largest residual after
/// two Newton iterations of the increment from λ = 0.1 (nodes of the fold,
/// where the iterations go) and those of the two contact points pressed
/// hardest. Each column within 1e-6 of its largest entry (measured
/// 1.2e-7): so the 3–8 iterations per increment are not lost to an inexact
/// tangent (docs/performance.md). Checked by breaking it: with 0.45 for
/// the ½ of B-bar's projected update a column is off by 9e-2, without the
/// rollers' curvature term by 3e-4.
#[test]
fn the_crush_tangent_matches_finite_differences_mid_increment() {
    use cufem::solver::newton::NonlinearProblem;
    use cufem::solver::stepping::{self, Increment, Incremental, Observer};
    struct Quiet;
    impl<P> Observer<P> for Quiet {
        fn converged(&mut self, _: &P, _: &Increment) {}
    }
    let model = cufem::setup::Model::from_file(Path::new(EXAMPLE)).unwrap();
    let mut s = cufem::analysis::Structure::of_model(&model, None).unwrap();
    let (settings, newton_settings) = (&model.steps[0].settings, &model.solver.newton);
    let done = stepping::run_span(&mut s, (0.0, 0.1), 1, settings, newton_settings, &mut Quiet, &Default::default());
    let last = done.unwrap().last().unwrap().dlambda;
    // the next increment, started on the secant as the stepping does and
    // stopped after two iterations: points that flow plastically within it
    // (Δγ > 0) and contact not yet settled
    let dlambda = 1.0 / 36.0;
    s.set_load_factor(0.1 + dlambda);
    s.extrapolate(dlambda / last);
    // two corrections as Newton makes them (its own loop would go on past
    // two where the second evaluation only opens contact points: those
    // corrections do not count against max_iterations)
    for _ in 0..2 {
        s.evaluate_for_correction().unwrap();
        s.correct().unwrap();
    }
    let ev = s.evaluate().unwrap();
    assert!(ev.residual_norm > newton_settings.residual_tolerance * ev.force_scale, "not converged yet: {ev:?}");
    let n_eq = s.n_equations();
    let dofs: Vec<(usize, usize)> =
        (0..s.displacements().len()).filter_map(|d| s.equation(d).map(|e| (d, e))).collect();
    let largest = |key: &dyn Fn(usize) -> f64, k: usize| {
        let mut v = dofs.clone();
        v.sort_by(|a, b| key(b.1).total_cmp(&key(a.1)));
        v.truncate(k);
        v
    };
    let residual = s.residual().to_vec();
    let mut columns = largest(&|e| residual[e].abs(), 6);
    // the nodes of the two points in contact that carry most
    let mut pressed: Vec<_> = s.contact_points().iter().filter(|p| p.active).collect();
    let size = |f: [f64; 3]| f.iter().map(|v| v * v).sum::<f64>();
    pressed.sort_by(|a, b| size(b.force).total_cmp(&size(a.force)));
    assert!(pressed.len() >= 2);
    for p in &pressed[..2] {
        columns.extend((0..3).filter_map(|c| s.equation(3 * p.node + c).map(|e| (3 * p.node + c, e))));
    }
    let mut worst: f64 = 0.0;
    for &(d, e) in &columns {
        let size = (0..n_eq).map(|r| s.tangent_entry(r, e).abs()).fold(0.0, f64::max);
        let (diff, _) = common::tangent_vs_differences(&mut s, &[(d, e)], 1e-9, size);
        eprintln!("DOF {d} (node {}, component {}): {diff:.1e} of the column's largest entry", d / 3, d % 3);
        worst = worst.max(diff);
    }
    assert!(worst < 1e-6, "the tangent differs from central differences by {worst:e} of a column");
}

/// The same comparison made by `cufem verify` itself, CalculiX included:
/// its force-history row for the loading roller — the peaks within 5 %
/// and the largest difference over the whole curve below 5 % of the 3D
/// peak (issue 26's criterion; measured: peaks −0.84 %, largest difference
/// 2.60 % at 8.85 mm; docs/verification.md). The twin is the example's
/// half section in 3D (the plane exported as `u_x = 0`).
#[test]
#[ignore = "validate: references — runs CalculiX with NLGEOM on 19,789 nodes (half an hour)"]
fn verify_compares_the_crush_with_calculix_nlgeom() {
    if common::ccx_missing() {
        return;
    }
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
    let (peak, max) =
        (load["peak_difference_percent"].as_f64().unwrap(), load["max_difference_percent"].as_f64().unwrap());
    common::figure("crush_verify.peak", peak, "%", "|difference| < 5 % (issue 26)");
    common::figure("crush_verify.max", max, "%", "< 5 % of the 3D peak over the curve (issue 26)");
    assert!(peak.abs() < 5.0 && max < 5.0, "{load}");
}
