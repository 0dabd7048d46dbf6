//! Whole-field fidelity of the shipped examples against stored 3D fields.
//!
//! Each `tests/data/<example>_field_3d.csv` holds CalculiX's displacement,
//! von Mises stress and peeq at the CUF Gauss points and contact-face
//! points of the shipped mesh (with their weights and the singular zones
//! left out), made by the `cufem verify` command in its header. The test
//! runs the example and compares over the whole field with the same norms
//! as `verify` (`cufem::verify::compare_stored`). Tolerances: issue 23's —
//! relative L2 difference of u over the body ≤ 2 %, the largest difference
//! of u on every contact surface ≤ 5 % of the body's largest |u|, von Mises
//! relative L2 difference over the plastic zone ≤ 10 % — where the shipped
//! model meets them; where it does not yet, the measured value with a
//! margin, named as such (a regression guard until the element or the
//! contact improves).

mod common;

use std::path::PathBuf;

use cufem::verify::FieldRow;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `examples/<name>.toml` and compares it with the stored 3D fields.
fn whole_field(name: &str) -> Vec<FieldRow> {
    let model = cufem::model::Model::from_file(&root().join("examples").join(format!("{name}.toml"))).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let rows = cufem::verify::compare_stored(&model, &solution.fields(&model), &stored_3d(name)).unwrap();
    for r in &rows {
        eprintln!(
            "{name}: {:<28} {:<10} L2 {:6.2} %  max {:6.2} %  ({} points, {} excluded)",
            r.region, r.quantity, r.l2_percent, r.max_percent, r.points, r.excluded
        );
    }
    rows
}

/// The stored 3D fields of `examples/<name>.toml`: `tests/data/<name>_field_3d.csv`,
/// or the same gzipped (`.csv.gz`) when large.
fn stored_3d(name: &str) -> String {
    let plain = root().join("tests/data").join(format!("{name}_field_3d.csv"));
    if plain.exists() {
        return std::fs::read_to_string(plain).unwrap();
    }
    let gz = std::fs::File::open(root().join("tests/data").join(format!("{name}_field_3d.csv.gz"))).unwrap();
    let mut text = String::new();
    std::io::Read::read_to_string(&mut flate2::read::GzDecoder::new(gz), &mut text).unwrap();
    text
}

/// Runs `examples/<name>.toml` and compares it with the stored 3D fields of
/// `examples/<stored>.toml`, another mesh of the same bodies (the stored
/// points located by position).
fn whole_field_on(name: &str, stored: &str) -> Vec<FieldRow> {
    compare_on(name, stored).0
}

/// [`whole_field_on`], with the model and its solution.
fn compare_on(name: &str, stored: &str) -> (Vec<FieldRow>, cufem::model::Model, cufem::analysis::Solution) {
    let model_of =
        |n: &str| cufem::model::Model::from_file(&root().join("examples").join(format!("{n}.toml"))).unwrap();
    let (model, stored_on) = (model_of(name), model_of(stored));
    let solution = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let rows =
        cufem::verify::compare_stored_on(&stored_on, &model, &solution.fields(&model), &stored_3d(stored)).unwrap();
    for r in &rows {
        eprintln!(
            "{name} on {stored}'s 3D: {:<28} {:<10} L2 {:6.2} %  max {:6.2} %  ({} points, {} excluded)",
            r.region, r.quantity, r.l2_percent, r.max_percent, r.points, r.excluded
        );
    }
    (rows, model, solution)
}

/// A regression guard: each `(region, quantity, measured L2 %)` at most
/// 10 % above its measured value (where issue 23's criteria are not met yet).
fn guard(rows: &[FieldRow], measured: &[(&str, &str, f64)]) {
    for &(region, q, value) in measured {
        let r = row(rows, region, q);
        assert!(r.points > 100 && r.l2_percent <= 1.1 * value, "{region} {q}: {r:?} (measured {value} %)");
    }
}

fn row<'a>(rows: &'a [FieldRow], region: &str, quantity: &str) -> &'a FieldRow {
    rows.iter()
        .find(|r| r.region == region && r.quantity == quantity)
        .unwrap_or_else(|| panic!("no row {region} {quantity}"))
}

/// Issue 23's whole-field criteria for one body.
fn assert_issue_criteria(rows: &[FieldRow], body: &str) {
    let u = row(rows, &format!("body {body}"), "u");
    assert!(u.points > 100 && u.l2_percent <= 2.0, "u over the body: {u:?}");
    let vm = row(rows, &format!("plastic zone {body}"), "von_mises");
    assert!(vm.points > 0 && vm.l2_percent <= 10.0, "von Mises over the plastic zone: {vm:?}");
    for s in rows.iter().filter(|r| r.region.starts_with("surface ") && r.quantity == "u") {
        assert!(s.points > 0 && s.max_percent <= 5.0, "u on {}: {s:?}", s.region);
    }
}

/// §4.2 compact bar, 10 B4 × 4 L9 against 3D at refine 2 (C3D20R, 55,755
/// DOF), the roller lines left out by one 3D element (1.87 mm). Measured:
/// u 0.24 % over the bar and at most 0.20 % on the roller surfaces, von
/// Mises 1.87 % over the plastic zone — issue 23's criteria with room. The
/// rollers impose the displacement, so u barely moves with the stiffness:
/// with E 10 % too high u stays at 0.49 %, but von Mises over the bar goes
/// from 2.16 % to 3.31 % and peeq over the plastic zone from 6.2 % to
/// 18.7 %; the bounds 3 % and 10 % catch that.
#[test]
fn bending_compact_4l9_whole_field_agrees_with_3d() {
    let rows = whole_field("bending_compact_4L9");
    assert_issue_criteria(&rows, "bar");
    let vm = row(&rows, "body bar", "von_mises");
    assert!(vm.l2_percent <= 3.0, "von Mises over the bar: {vm:?}");
    let peeq = row(&rows, "plastic zone bar", "peeq");
    assert!(peeq.l2_percent <= 10.0, "peeq over the plastic zone: {peeq:?}");
}

/// §4.1 block, the shipped mesh (1 B4 × 108 L9, B-bar, projected fields)
/// against 3D at refine 2 (C3D20R, 145,767 DOF), the punch edges left out
/// by one 3D element (11.3 mm). A regression guard, not issue 23's
/// criteria, which the shipped block does not meet: measured u 19.0 % over
/// the block and 24.4 % on the top face, von Mises 7.5 % and peeq 36 % over
/// the plastic zone. Most of the displacement difference is the squeeze-out
/// along the beam axis under the punch — u_y there is about half of the 3D
/// value (−0.33 against −0.59 mm at y = 33 mm): one B4 element along y
/// cannot follow the plastic flow out of the punch's footprint, while u_z
/// under the punch agrees to 0.05 %. Bounds: the measured values + 10 %;
/// a better element or mesh lowers them (then tighten these).
#[test]
fn block_indentation_whole_field_against_3d() {
    let rows = whole_field("block_indentation");
    guard(
        &rows,
        &[
            ("body block", "u", 19.02),
            ("surface punch", "u", 24.36),
            ("plastic zone block", "von_mises", 7.54),
            ("plastic zone block", "peeq", 36.40),
        ],
    );
}

/// A measurement for issue 23, run by hand (`cargo test --release --test
/// fidelity -- --ignored --nocapture`): the block with 1, 2 and 3 B4
/// along the beam axis (the shipped section mesh) against the stored 3D
/// fields of the shipped mesh (`compare_stored_on`: the points located by
/// position in each refined mesh). It prints the rows; it asserts only that
/// the shipped mesh gives the rows of the regular test above.
#[test]
#[ignore = "a measurement, not a check: run by hand"]
fn block_axis_refinement_against_stored_3d() {
    let path = root().join("examples/block_indentation.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let stored_on = cufem::model::Model::from_file(&path).unwrap();
    let csv = std::fs::read_to_string(root().join("tests/data/block_indentation_field_3d.csv")).unwrap();
    let axis = "axis = { element = \"B4\", from = 0.0, to = 0.1, elements = 1 }";
    assert!(text.contains(axis));
    for n in [1, 2, 3] {
        let model =
            cufem::model::Model::parse(&text.replace(axis, &axis.replace("elements = 1", &format!("elements = {n}"))))
                .unwrap();
        let solution = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
        assert!(solution.failure.is_none());
        let rows = cufem::verify::compare_stored_on(&stored_on, &model, &solution.fields(&model), &csv).unwrap();
        for r in &rows {
            eprintln!(
                "{n} B4 ({} DOF): {:<22} {:<10} L2 {:6.2} %  max {:6.2} %",
                model.n_dofs(),
                r.region,
                r.quantity,
                r.l2_percent,
                r.max_percent
            );
        }
        if n == 1 {
            let same = whole_field("block_indentation");
            for (a, b) in rows.iter().zip(&same) {
                assert!((a.l2_percent - b.l2_percent).abs() < 1e-6 * b.l2_percent.max(1e-6), "{a:?} vs {b:?}");
            }
        }
    }
}

/// The block's top line y = 0.05, z = 0.3 m of a run against the 3D line
/// (CalculiX C3D20R, 145,767 DOF: tests/data/block_calculix_top_u_z.csv and
/// block_calculix_top.csv, the same 201 stations): per station x, u_z and
/// its 3D value; the largest differences of σ_zz and peeq under the punch
/// (x ∈ [0.21, 0.29] m) in fractions of the 3D peak.
struct TopLine {
    x: Vec<f64>,
    u_z: Vec<f64>,
    u_z_3d: Vec<f64>,
    s_zz_under: f64,
    peeq_under: f64,
}

fn top_line(line_csv: &std::path::Path) -> TopLine {
    let ours = common::csv_columns(line_csv);
    let uz3 = common::csv_columns(&root().join("tests/data/block_calculix_top_u_z.csv"));
    let top3 = common::csv_columns(&root().join("tests/data/block_calculix_top.csv"));
    let x = ours["x"].clone();
    assert_eq!(x.len(), uz3["x"].len());
    assert!(x.iter().zip(&uz3["x"]).all(|(a, b)| (a - b).abs() < 1e-12));
    let under = |q: &str| {
        let peak = top3[q].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        (0..x.len())
            .filter(|&i| (0.21 - 1e-9..=0.29 + 1e-9).contains(&x[i]))
            .map(|i| (ours[q][i] - top3[q][i]).abs() / peak)
            .fold(0.0, f64::max)
    };
    TopLine {
        u_z: ours["u_z"].clone(),
        u_z_3d: uz3["u_z"].clone(),
        s_zz_under: under("s_zz"),
        peeq_under: under("peeq"),
        x,
    }
}

impl TopLine {
    /// The largest relative u_z difference over the stations in `[a, b]` (and
    /// their mirror images about the punch centre x = 0.25 m).
    fn u_z_error(&self, a: f64, b: f64) -> f64 {
        (0..self.x.len())
            .filter(|&i| {
                let x = self.x[i].min(0.5 - self.x[i]);
                (a - 1e-9..=b + 1e-9).contains(&x)
            })
            .map(|i| (self.u_z[i] / self.u_z_3d[i] - 1.0).abs())
            .fold(0.0, f64::max)
    }

    /// Whether u_z sinks monotonically from the far field to x = 0.19 m and
    /// from the far field x = 0.5 to its mirror x = 0.31 m.
    fn sinks_towards_the_punch(&self) -> bool {
        let left: Vec<f64> = (0..self.x.len()).filter(|&i| self.x[i] <= 0.19 + 1e-9).map(|i| self.u_z[i]).collect();
        let right: Vec<f64> =
            (0..self.x.len()).rev().filter(|&i| self.x[i] >= 0.31 - 1e-9).map(|i| self.u_z[i]).collect();
        [left, right].iter().all(|side| side.windows(2).all(|w| w[1] <= w[0]))
    }
}

/// §4.1 block on the graded mesh of `examples/block_indentation_graded.toml`
/// (16 × 6 L9 × 3 B3, 9,009 DOF, within issue 23's 10,000), run through
/// the CLI, against 3D at refine 2. Issue 23's criteria and what was
/// measured:
/// - punch force within 2 % (measured +0.74 %);
/// - top-line u_z within 5 % at x ∈ [0, 0.15] m: 2.5 % on [0.03, 0.15] and
///   4.1 % on [0, 0.03] (the far corner, where u_z is only −0.030 mm);
///   8 % at 0.175 m (0.2 %);
/// - sinking monotonically towards the punch edge up to x = 0.19 m and its
///   mirror image (the paper's mesh bulges up there);
/// - σ_zz and peeq under the punch within 10 % of the 3D peak (measured
///   6.0 % and 6.0 %).
///
/// Measured on purpose-broken copies (`/tmp` sweeps of the example's text):
/// Young's modulus 10 % high or low moves u_z on [0.03, 0.15] m by 9.5 % or
/// 12 % and fails (the force, set by the plastic flow, moves by 0.1 %); the
/// paper's x grading (6 elements per side, 17 mm at the edge) bulges up at
/// x = 0.19 m and fails the monotonicity; the paper's z grading (ratio 0.3)
/// puts the far corner 8.7 % off; six uniform elements under the punch
/// instead of the two graded halves put peeq 15.7 % of the peak off.
#[test]
fn block_indentation_graded_against_3d() {
    let model = root().join("examples/block_indentation_graded.toml");
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fidelity_block_graded");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", model.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet", "--force"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["dof"], 9009);
    let punch = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap();
    // 3D punch force: tests/examples.rs BLOCK_FORCE_3D (the same CalculiX run)
    let force = punch["force"][2].as_f64().unwrap() / -1.4102e6 - 1.0;
    eprintln!("punch force vs 3D {:+.2} %", 100.0 * force);
    assert!(force.abs() <= 0.02, "punch force {:+.2} % vs 3D", 100.0 * force);
    let line = top_line(&out.join("line_top.csv"));
    let (near, edge, corner) = (line.u_z_error(0.03, 0.15), line.u_z_error(0.175, 0.175), line.u_z_error(0.0, 0.03));
    eprintln!(
        "u_z: {:.1} % on [0.03, 0.15], {:.1} % at 0.175, {:.1} % on [0, 0.03]; under the punch σ_zz {:.1} %, peeq {:.1} %",
        100.0 * near,
        100.0 * edge,
        100.0 * corner,
        100.0 * line.s_zz_under,
        100.0 * line.peeq_under
    );
    eprintln!("u_z: within {:.1} % at every station x ∈ [0, 0.19] m and its mirror", 100.0 * line.u_z_error(0.0, 0.19));
    assert!(near <= 0.05 && edge <= 0.08 && corner <= 0.05, "u_z {near} {edge} {corner}");
    assert!(line.sinks_towards_the_punch(), "the top surface does not sink monotonically towards the punch");
    assert!(line.s_zz_under <= 0.10 && line.peeq_under <= 0.10, "{} {}", line.s_zz_under, line.peeq_under);
}

/// The graded block against the stored 3D fields of the paper's mesh
/// (`compare_stored_on`, points located by position). A regression guard at
/// the measured values + 10 %: u 4.76 % over the block and 3.63 % on the
/// punch face (issue 23's 2 % not met; the largest differences, 7 % of the
/// largest |u|, sit beside the punch edges at the free faces y = 0 and
/// 0.1 m), von Mises 4.49 % over the plastic zone
/// (issue 23's 10 %: met), peeq 16.4 %. The paper's mesh: 19.0 / 24.4 /
/// 7.5 / 36.4 % (test above).
#[test]
fn block_indentation_graded_whole_field_against_3d() {
    let stored_on = cufem::model::Model::from_file(&root().join("examples/block_indentation.toml")).unwrap();
    let model = cufem::model::Model::from_file(&root().join("examples/block_indentation_graded.toml")).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    let csv = std::fs::read_to_string(root().join("tests/data/block_indentation_field_3d.csv")).unwrap();
    let rows = cufem::verify::compare_stored_on(&stored_on, &model, &solution.fields(&model), &csv).unwrap();
    for r in &rows {
        eprintln!(
            "graded block: {:<28} {:<10} L2 {:6.2} %  max {:6.2} % at {:?}",
            r.region, r.quantity, r.l2_percent, r.max_percent, r.at
        );
    }
    guard(
        &rows,
        &[
            ("body block", "u", 4.76),
            ("surface punch", "u", 3.63),
            ("plastic zone block", "von_mises", 4.49),
            ("plastic zone block", "peeq", 16.37),
        ],
    );
    assert!(row(&rows, "plastic zone block", "von_mises").l2_percent <= 10.0);
}

/// Issue 23's "on a mesh you name of at most 40,000 DOF within 3 %": the
/// graded block refined to 24 × 9 L9 × 6 B3 (36,309 DOF, 21 s). Measured
/// (`cargo test --release --test fidelity -- --ignored --nocapture`): top-line
/// u_z within 1.3 % at every station x ∈ [0, 0.19] m and its mirror, punch
/// force +0.33 %, σ_zz and peeq under the punch 9.4 % and 6.6 % of the 3D
/// peak; whole field u 2.5 %, punch face 2.0 %, plastic-zone von Mises
/// 2.5 %, peeq 9.8 %.
#[test]
#[ignore = "a 36,309-DOF run (about 25 s); run by hand"]
fn block_indentation_36k_within_three_percent_of_3d() {
    let text = std::fs::read_to_string(root().join("examples/block_indentation_graded.toml")).unwrap();
    // The example's mesh replaced by 24 × 9 L9 × 6 B3 with the same kind of
    // grading (30, 14 and 6 mm towards each punch edge).
    let (x_start, x_end) = (text.find("x = { segments").unwrap(), text.find("[[constraints]]").unwrap());
    let fine = text[..x_start].replace("to = 0.1, elements = 3 }", "to = 0.1, elements = 6 }")
        + "x = { segments = [\n\
           { from = 0.0, to = 0.15, elements = 4 },\n\
           { from = 0.15, to = 0.2, elements = 4, ratio = 0.2 },\n\
           { from = 0.2, to = 0.3, elements = 8 },\n\
           { from = 0.3, to = 0.35, elements = 4, ratio = 5.0 },\n\
           { from = 0.35, to = 0.5, elements = 4 },\n\
           ] }\n\
           z = { from = 0.0, to = 0.3, elements = 9, ratio = 0.3 }\n\n"
        + &text[x_end..];
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fidelity_block_36k");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("model.toml"), &fine).unwrap();
    let out = dir.join("out");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_cufem"))
        .args(["run", dir.join("model.toml").to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet", "--force"])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["dof"], 36309);
    let punch = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "punch").unwrap();
    let force = punch["force"][2].as_f64().unwrap() / -1.4102e6 - 1.0;
    let line = top_line(&out.join("line_top.csv"));
    let u = line.u_z_error(0.0, 0.19);
    eprintln!("36,309 DOF: force {:+.2} %, u_z within {:.2} % on [0, 0.19]", 100.0 * force, 100.0 * u);
    assert!(force.abs() <= 0.02 && u <= 0.03 && line.sinks_towards_the_punch());
    assert!(line.s_zz_under <= 0.10 && line.peeq_under <= 0.10, "{} {}", line.s_zz_under, line.peeq_under);
}

/// §4.2 compact bar, the paper's fine section (10 B4 × 16 L9), against the
/// 3D fields stored for the 4 L9 mesh (refine 2, 55,755 DOF) — a finer 3D
/// model than its own verify at refine 1. Issue 23's criteria, met:
/// measured u 0.33 % over the bar, at most 0.29 % on the roller surfaces,
/// von Mises 1.86 % over the plastic zone (peeq 6.4 %).
#[test]
fn bending_compact_16l9_whole_field_agrees_with_3d() {
    let rows = whole_field_on("bending_compact_16L9", "bending_compact_4L9");
    assert_issue_criteria(&rows, "bar");
}

/// §4.2 thin-walled tube, the shipped 22 B4 × 28 L9 (33,768 DOF), against 3D
/// at refine 1 (C3D20R, 123,312 DOF; the three roller lines left out within
/// 1.8 mm). Issue 23's criteria are met for von Mises over the plastic zone
/// (measured 3.95 %) but not for the displacement: u 5.7 % over the tube and
/// up to 6.0 % (L2) on the roller surfaces; most of it is the top wall
/// between the webs, which sags off the loading roller by 0.019 mm where
/// 3D keeps it on (docs/cross-check.md). A regression guard at the
/// measured values + 10 % until the rollers improve.
#[test]
fn bending_tube_28l9_whole_field_against_3d() {
    let rows = whole_field("bending_tube_28L9");
    let vm = row(&rows, "plastic zone tube", "von_mises");
    assert!(vm.points > 100 && vm.l2_percent <= 10.0, "{vm:?}");
    guard(
        &rows,
        &[
            ("body tube", "u", 5.7),
            ("surface load", "u", 4.35),
            ("surface support_left", "u", 6.02),
            ("plastic zone tube", "von_mises", 3.95),
            ("plastic zone tube", "peeq", 26.79),
        ],
    );
}

/// §4.2 tube with the paper's coarse section (22 B4 × 20 L9) against the
/// 3D fields stored for the 28 L9 mesh. Measured: u 3.82 % over the tube
/// (closer to 3D than the 28 L9 mesh's 5.7 %: its top wall stays nearer the
/// roller), at most 3.78 % on the roller surfaces (issue 23's 5 %: met),
/// von Mises 4.31 % over the plastic zone (10 %: met), peeq 28 %. The
/// issue's 2 % for u is not met; guarded at the measured values + 10 %.
#[test]
fn bending_tube_20l9_whole_field_against_3d() {
    let rows = whole_field_on("bending_tube_20L9", "bending_tube_28L9");
    for s in rows.iter().filter(|r| r.region.starts_with("surface ") && r.quantity == "u") {
        assert!(s.points > 0 && s.max_percent <= 5.0, "u on {}: {s:?}", s.region);
    }
    guard(
        &rows,
        &[("body tube", "u", 3.82), ("plastic zone tube", "von_mises", 4.31), ("plastic zone tube", "peeq", 28.06)],
    );
    assert!(row(&rows, "plastic zone tube", "von_mises").l2_percent <= 10.0);
}

/// §4.3 two cantilevers in contact (10 B4 × 16 L9 per beam, 15,066 DOF)
/// against 3D at refine 1 (C3D20R, 56,430 DOF; both roller lines left out
/// within 4.4 mm). Measured: the upper beam meets issue 23's criteria (u
/// 0.77 % over it, at most 1.05 % on its contact surfaces, von Mises 7.89 %
/// over its plastic zone); the lower beam does not (u 3.47 %, at most 3.95 %
/// on the interface, von Mises 12.7 % over its plastic zone at its clamp,
/// peeq 50 %). Not established why; one difference seen: the 3D contacts
/// turn their normals with the deformation (3D root reactions have y
/// components of 0.6–1.1 kN, the 7 in roller 0.49 kN), which node-to-node
/// contact with normals fixed at the start does not. The lower beam is
/// guarded at the measured values + 10 %.
#[test]
fn cantilevers_contact_whole_field_against_3d() {
    let rows = whole_field("cantilevers_contact");
    assert_issue_criteria(&rows, "upper");
    guard(
        &rows,
        &[
            ("body lower", "u", 3.47),
            ("surface beams (master)", "u", 3.49),
            ("plastic zone lower", "von_mises", 12.69),
            ("plastic zone upper", "peeq", 40.81),
        ],
    );
}

/// §4.3 cantilevers on the finer axis mesh of
/// `examples/cantilevers_contact_fine.toml` (20 B4 per beam, 29,646 DOF)
/// against the 3D fields stored for the paper's mesh (refine 1, points
/// located by position). Issue 23's whole-field criteria, met for both
/// beams (measured u 0.25 % and 0.28 %, at most 0.64 % on the contact
/// surfaces, von Mises 5.5 % and 5.6 % over the plastic zones; the paper's
/// mesh: 0.77 / 3.47 %, 12.7 % on the lower beam). The 7 in roller within
/// 2 % of 3D (measured +0.53 %; CalculiX 25,769 N) and the root reactions
/// (+0.44 %, −0.17 %; 12,619 and 16,087 N); the lightly loaded 9 in roller
/// is −3.7 % (2,827 against 2,937 N), bound 5 %: it is not converged in
/// either model (docs/cross-check.md). Young's modulus 10 % high fails
/// it (checked by hand: the 9 in roller goes to −8.1 %; the 7 in one, set
/// by the plastic zone under it, only to +1.3 %, and u stays within 0.3 %).
#[test]
fn cantilevers_contact_fine_against_3d() {
    let (rows, _, solution) = compare_on("cantilevers_contact_fine", "cantilevers_contact");
    assert_issue_criteria(&rows, "upper");
    assert_issue_criteria(&rows, "lower");
    let contact = |n: &str| solution.contacts.iter().find(|c| c.name == n).unwrap().force[2];
    let reaction = |n: &str| solution.reactions.iter().find(|r| r.name == n).unwrap().force[2];
    for (name, value, ccx, bound) in [
        ("7 in roller", contact("indenter_7in"), -25_769.0, 0.02),
        ("9 in roller", contact("indenter_9in"), -2_937.2, 0.05),
        ("upper root", reaction("upper_root"), 12_619.0, 0.02),
        ("lower root", reaction("lower_root"), 16_087.0, 0.02),
    ] {
        let d = value / ccx - 1.0;
        eprintln!("{name}: {:+.2} % vs 3D", 100.0 * d);
        assert!(d.abs() <= bound, "{name} {:+.2} % vs 3D", 100.0 * d);
    }
}

/// §4.2 tube on the axis mesh graded at the loading roller
/// (`examples/bending_tube_graded.toml`, 24 B4 × 28 L9, 36,792 DOF) against
/// the 3D fields stored for the paper's mesh (refine 1, points located by
/// position). Issue 23's whole-field criteria, met (measured u 1.78 % over
/// the tube, at most 1.39 % on the roller surfaces, von Mises 2.46 % over
/// the plastic zone; the paper's mesh: 5.7 %, 5.5 %, 4.0 %); every roller
/// force within 2 % of 3D (measured −0.86 %; CalculiX: 1,698.2 N at the
/// loading roller, 849.1 N at each support; the paper's mesh −3.45 %). Not
/// met: the top wall's middle sags off the roller by 0.64 % of the travel
/// (issue: 0.5 %; 3D 0.39 %; paper's mesh 2.6 %), and σ_yy at the contact
/// centre is 17.7 % above 3D (it needs a finer ring: docs/cross-check.md).
/// Young's modulus 10 % high fails it (u over the tube 2.45 %).
#[test]
fn bending_tube_graded_against_3d() {
    let (rows, model, solution) = compare_on("bending_tube_graded", "bending_tube_28L9");
    assert_issue_criteria(&rows, "tube");
    let force = |n: &str| solution.contacts.iter().find(|c| c.name == n).unwrap().force[2];
    for (name, ccx) in [("load", -1698.2), ("support_left", 849.09), ("support_right", 849.09)] {
        let d = force(name) / ccx - 1.0;
        eprintln!("{name}: {:+.2} % vs 3D", 100.0 * d);
        assert!(d.abs() <= 0.02, "{name} {:+.2} % vs 3D", 100.0 * d);
    }
    // the middle of the top wall under the roller: 3D −0.75289 mm for the
    // 0.75 mm travel (sag 0.39 %); measured −0.75481 mm (0.64 %); bound 1 %
    // (the paper's mesh: 2.6 %)
    let centre = solution.fields(&model).sample_point(None, [0.015, 0.125, 0.03]).unwrap().u[2];
    eprintln!("contact centre u_z {:.5} mm", centre * 1e3);
    assert!((centre / -0.75e-3 - 1.0).abs() <= 0.01, "contact centre u_z {centre:e} m");
}

/// The table "The tube at its loading roller" of docs/cross-check.md, run
/// by hand (`cargo test --release --test fidelity -- --ignored
/// tube_roller_meshes --nocapture`, several minutes): the paper's tube with
/// the axis refined at the loading roller and the ring refined, against
/// the stored 3D fields of the paper's mesh.
#[test]
#[ignore = "a measurement, not a check: run by hand"]
fn tube_roller_meshes_against_stored_3d() {
    let text = std::fs::read_to_string(root().join("examples/bending_tube_28L9.toml")).unwrap();
    let stored_on = cufem::model::Model::from_file(&root().join("examples/bending_tube_28L9.toml")).unwrap();
    let start = text.find("axis = { element = \"B4\", segments = [").unwrap();
    let end = start + text[start..].find("] }").unwrap() + 3;
    let axis = |segments: &[(f64, usize)]| {
        let mut from = 0.0;
        let mut s = String::from("axis = { element = \"B4\", segments = [\n");
        for &(to, n) in segments {
            s += &format!("    {{ from = {from:?}, to = {to:?}, elements = {n} }},\n");
            from = to;
        }
        s + "] }"
    };
    let graded_33 = [(0.025, 2), (0.115, 8), (0.125, 3), (0.135, 3), (0.225, 8), (0.25, 2)];
    let graded_1 = [
        (0.025, 2),
        (0.105, 8),
        (0.115, 2),
        (0.121, 3),
        (0.125, 4),
        (0.129, 4),
        (0.135, 3),
        (0.145, 2),
        (0.225, 8),
        (0.25, 2),
    ];
    let variants = [
        ("3.3 mm within 10 mm", text[..start].to_string() + &axis(&graded_33) + &text[end..]),
        ("1 mm within 4 mm", text[..start].to_string() + &axis(&graded_1) + &text[end..]),
        (
            "the same, 52 L9",
            (text[..start].to_string() + &axis(&graded_1) + &text[end..]).replace("around = 28", "around = 52"),
        ),
    ];
    for (name, t) in variants {
        let model = cufem::model::Model::parse(&t).unwrap();
        let s = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
        let view = s.fields(&model);
        let force = s.contacts.iter().find(|c| c.name == "load").unwrap().force[2];
        let p = view.sample_point(None, [0.015, 0.125, 0.03]).unwrap();
        eprintln!(
            "{name} ({} DOF): roller {:+.2} %, sag {:.2} % of travel, s_yy {:+.1} %, peeq {:+.1} %",
            model.n_dofs(),
            100.0 * (force / -1698.2 - 1.0),
            100.0 * (p.u[2] / -0.75e-3 - 1.0),
            100.0 * (p.stress[1] / -63.8669e6 - 1.0),
            100.0 * (p.peeq / 5.27e-3 - 1.0)
        );
        let rows =
            cufem::verify::compare_stored_on(&stored_on, &model, &view, &stored_3d("bending_tube_28L9")).unwrap();
        for r in &rows {
            eprintln!("  {:<28} {:<10} L2 {:6.2} %  max {:6.2} %", r.region, r.quantity, r.l2_percent, r.max_percent);
        }
    }
}

/// The table "The cantilevers' rollers under refinement" of
/// docs/cross-check.md, run by hand (`cargo test --release --test fidelity
/// -- --ignored cantilever_meshes --nocapture`, several minutes):
/// `examples/cantilevers_contact.toml` with both beams' axes refined alike
/// (so that the node-to-node pairs keep matching) and their sections
/// refined, the rollers as shipped (node-to-node) or exact-gap rigid
/// surfaces; roller forces, the force across the interface, and the whole
/// field against the stored 3D fields of the shipped mesh.
#[test]
#[ignore = "a measurement, not a check: run by hand"]
fn cantilever_meshes_against_stored_3d() {
    let text = std::fs::read_to_string(root().join("examples/cantilevers_contact.toml")).unwrap();
    let stored_on = cufem::model::Model::from_file(&root().join("examples/cantilevers_contact.toml")).unwrap();
    let (upper, lower) = (
        "axis = { element = \"B4\", from = 0.0, to = 0.254, elements = 10 }",
        "axis = { element = \"B4\", from = 0.0762, to = 0.3302, elements = 10 }",
    );
    for (axis, section, surface) in
        [(10, 4, true), (20, 4, false), (20, 4, true), (40, 4, false), (80, 4, false), (20, 6, false), (40, 6, false)]
    {
        let elements = format!("elements = {axis} }}");
        let mut t = text
            .replace(upper, &upper.replace("elements = 10 }", &elements))
            .replace(lower, &lower.replace("elements = 10 }", &elements))
            .replace("elements = 4 }", &format!("elements = {section} }}"));
        if surface {
            t = t.replace("radius = 0.0127\n", "radius = 0.0127\nmethod = \"surface\"\n");
        }
        let model = cufem::model::Model::parse(&t).unwrap();
        let s = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
        assert!(s.failure.is_none(), "{:?}", s.failure);
        let force = |n: &str| s.contacts.iter().find(|c| c.name == n).unwrap().force[2];
        eprintln!(
            "{axis} B4, {section} x {section} L9, rollers {} ({} DOF): 7 in {:.0} N, 9 in {:.0} N, interface {:.0} N",
            if surface { "surface" } else { "node-to-node" },
            model.n_dofs(),
            -force("indenter_7in"),
            -force("indenter_9in"),
            force("beams"),
        );
        let view = s.fields(&model);
        for p in &model.probes {
            let at = view.sample_probe(p).unwrap();
            eprintln!("  probe {}: σ_yy {:.1} MPa, peeq {:.2e}", p.name, at.stress[1] / 1e6, at.peeq);
        }
        let rows =
            cufem::verify::compare_stored_on(&stored_on, &model, &view, &stored_3d("cantilevers_contact")).unwrap();
        for r in &rows {
            eprintln!("  {:<28} {:<10} L2 {:6.2} %  max {:6.2} %", r.region, r.quantity, r.l2_percent, r.max_percent);
        }
    }
}

/// Why B-bar is not the default for plastic bodies (ARCHITECTURE.md, "The
/// element"): on the compact bar it is not at least as good as the paper's
/// element against the stored 3D field. Measured: von Mises over the
/// plastic zone 2.24 % with B-bar against 1.87 % (over the bar 3.52 against
/// 2.16 %). If B-bar ever matches the paper's element here, the default
/// can be reconsidered.
#[test]
fn bbar_is_not_better_than_the_paper_element_on_the_compact_bar() {
    let text = std::fs::read_to_string(root().join("examples/bending_compact_4L9.toml")).unwrap();
    let stored = stored_3d("bending_compact_4L9");
    let plastic_zone_von_mises = |formulation: &str| {
        let t = text.replacen(
            "material = \"alloy\"\n",
            &format!("material = \"alloy\"\nformulation = \"{formulation}\"\n"),
            1,
        );
        assert!(t.contains("formulation"));
        let model =
            cufem::model::Model::parse_in(&t, cufem::model::Limits::machine(), &root().join("examples")).unwrap();
        let s = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
        let rows = cufem::verify::compare_stored(&model, &s.fields(&model), &stored).unwrap();
        row(&rows, "plastic zone bar", "von_mises").l2_percent
    };
    let (standard, bbar) = (plastic_zone_von_mises("standard"), plastic_zone_von_mises("bbar"));
    eprintln!("von Mises over the plastic zone: standard {standard:.2} %, B-bar {bbar:.2} %");
    assert!(bbar > standard, "B-bar {bbar} % vs standard {standard} %: reconsider the default");
}
