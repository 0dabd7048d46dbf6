//! Whole-field fidelity of the shipped examples against stored 3D fields.
//!
//! Each `tests/data/<example>_field_3d.csv` holds CalculiX's displacement,
//! von Mises stress and peeq at the CUF Gauss points and contact-face
//! points of the shipped mesh (with their weights and the singular zones
//! left out), made by the `cufem verify` command in its header. The test
//! runs the example and compares over the whole field with the same norms
//! as `verify` (`cufem_ccx::verify::compare_stored`). Tolerances: issue 23's —
//! relative L2 difference of u over the body ≤ 2 %, the largest difference
//! of u on every contact surface ≤ 5 % of the body's largest |u|, von Mises
//! relative L2 difference over the plastic zone ≤ 10 % — where the shipped
//! model meets them; where it does not yet, the measured value as a known
//! limit asserted from both sides (±3 %) and listed in docs/limitations.md.
//! Every row is also a figure of the validation report (`bench/validate`).

#[path = "../../../tests/common/mod.rs"]
mod common;
#[path = "stored/mod.rs"]
mod stored;

use std::path::PathBuf;

use cufem_ccx::verify::FieldRow;

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// Runs `examples/<name>.toml` and compares it with the stored 3D fields.
fn whole_field(name: &str) -> Vec<FieldRow> {
    let model = cufem::setup::Model::from_file(&root().join("examples").join(format!("{name}.toml"))).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let rows = cufem_ccx::verify::compare_stored(&model, &solution.fields(&model), &stored::field_3d(name)).unwrap();
    report(name, &rows);
    rows
}

/// Runs `examples/<name>.toml` and compares it with the stored 3D fields of
/// `examples/<stored>.toml`, another mesh of the same bodies (the stored
/// points located by position).
fn whole_field_on(name: &str, stored: &str) -> Vec<FieldRow> {
    compare_on(name, stored).0
}

/// [`whole_field_on`], with the model and its solution.
fn compare_on(name: &str, stored: &str) -> (Vec<FieldRow>, cufem::setup::Model, cufem::analysis::Solution) {
    let model_of =
        |n: &str| cufem::setup::Model::from_file(&root().join("examples").join(format!("{n}.toml"))).unwrap();
    let (model, stored_on) = (model_of(name), model_of(stored));
    let solution = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let rows =
        cufem_ccx::verify::compare_stored_on(&stored_on, &model, &solution.fields(&model), &stored::field_3d(stored))
            .unwrap();
    report(name, &rows);
    (rows, model, solution)
}

/// Known limits where issue 23's criteria are not met yet: each
/// `(region, quantity, measured L2 %)` asserted from both sides, within
/// ±3 % of the measured value (docs/limitations.md, "Whole field against
/// 3D"): an improvement fails too, so that the range and the docs follow
/// it. The runs are deterministic to round-off (1e-8 between thread
/// counts), so the band holds only what a change of the code would move.
fn known_limits(prefix: &str, rows: &[FieldRow], limits: &[(&str, &str, f64)]) {
    for &(region, q, measured) in limits {
        let r = row(rows, region, q);
        assert!(r.points > 100, "{region} {q}: {r:?}");
        let (low, high) = ((0.97 * measured * 100.0).floor() / 100.0, (1.03 * measured * 100.0).ceil() / 100.0);
        common::known_limit(
            &field_id(prefix, region, q),
            r.l2_percent,
            "%",
            low,
            high,
            &format!("{prefix}: {region} {q}"),
        );
    }
}

/// The report id of a whole-field row: `field.<prefix>.<region>.<quantity>`
/// (the region's spaces and brackets as `_`).
fn field_id(prefix: &str, region: &str, quantity: &str) -> String {
    format!("field.{prefix}.{}.{quantity}", stored::region_id(region))
}

/// Every row as a figure of the validation report (L2 and largest
/// difference, in %), then printed.
fn report(prefix: &str, rows: &[FieldRow]) {
    for r in rows {
        let id = field_id(prefix, &r.region, &r.quantity);
        common::figure(&format!("{id}.max"), r.max_percent, "%", "measured against the stored 3D field");
        common::figure(&id, r.l2_percent, "%", "measured against the stored 3D field (relative L2)");
        eprintln!(
            "{prefix}: {:<28} {:<10} L2 {:6.2} %  max {:6.2} %  ({} points, {} excluded)",
            r.region, r.quantity, r.l2_percent, r.max_percent, r.points, r.excluded
        );
    }
}

/// One relative L2 difference in % at most `bound` (issue 23's criteria).
fn criterion(prefix: &str, rows: &[FieldRow], region: &str, quantity: &str, bound: f64) {
    let r = row(rows, region, quantity);
    common::figure(
        &field_id(prefix, region, quantity),
        r.l2_percent,
        "%",
        &format!("≤ {bound} % (relative L2, issue 23)"),
    );
    assert!(r.points > 100 && r.l2_percent <= bound, "{region} {quantity}: {r:?}");
}

fn row<'a>(rows: &'a [FieldRow], region: &str, quantity: &str) -> &'a FieldRow {
    rows.iter()
        .find(|r| r.region == region && r.quantity == quantity)
        .unwrap_or_else(|| panic!("no row {region} {quantity}"))
}

/// Issue 23's whole-field criteria for one body.
/// Issue 23's whole-field criteria for one body (`prefix` names the
/// figures as [`report`] does).
fn assert_issue_criteria(prefix: &str, rows: &[FieldRow], body: &str) {
    let check = |r: &FieldRow, what: &str, value: f64, bound: f64, suffix: &str| {
        let id = field_id(prefix, &r.region, &r.quantity) + suffix;
        common::figure(&id, value, "%", &format!("≤ {bound} % ({what}, issue 23)"));
        assert!(r.points > 0 && value <= bound, "{what}: {r:?}");
    };
    let u = row(rows, &format!("body {body}"), "u");
    assert!(u.points > 100);
    check(u, "relative L2 of u over the body", u.l2_percent, 2.0, "");
    let vm = row(rows, &format!("plastic zone {body}"), "von_mises");
    check(vm, "relative L2 of von Mises over the plastic zone", vm.l2_percent, 10.0, "");
    for s in rows.iter().filter(|r| r.region.starts_with("surface ") && r.quantity == "u") {
        check(s, "largest u difference on a contact surface, % of the largest |u|", s.max_percent, 5.0, ".max");
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
    assert_issue_criteria("bending_compact_4L9", &rows, "bar");
    criterion("bending_compact_4L9", &rows, "body bar", "von_mises", 3.0);
    criterion("bending_compact_4L9", &rows, "plastic zone bar", "peeq", 10.0);
}

/// §4.1 block, the shipped mesh (1 B4 × 108 L9, B-bar, projected fields)
/// against 3D at refine 2 (C3D20R, 145,767 DOF), the punch edges left out
/// by one 3D element (11.3 mm). Known limits, not issue 23's
/// criteria, which the shipped block does not meet: measured u 19.0 % over
/// the block and 24.4 % on the top face, von Mises 7.5 % and peeq 36 % over
/// the plastic zone. Most of the displacement difference is the squeeze-out
/// along the beam axis under the punch — u_y there is about half of the 3D
/// value (−0.33 against −0.59 mm at y = 33 mm): one B4 element along y
/// cannot follow the plastic flow out of the punch's footprint, while u_z
/// under the punch agrees to 0.05 %. Known limits (docs/limitations.md),
/// asserted from both sides; `block_axis_refinement_against_stored_3d`
/// shows the axis mesh is the cause.
#[test]
fn block_indentation_whole_field_against_3d() {
    let rows = whole_field("block_indentation");
    known_limits(
        "block_indentation",
        &rows,
        &[
            ("body block", "u", 19.02),
            ("surface punch", "u", 24.36),
            ("plastic zone block", "von_mises", 7.54),
            ("plastic zone block", "peeq", 36.40),
        ],
    );
}

/// The block with 1, 2 and 3 B4 along the beam axis (the shipped section
/// mesh) against the stored 3D fields of the shipped mesh
/// (`compare_stored_on`: the points located by position in each refined
/// mesh). The claim of the test above: one B4 along y is what keeps u 19 %
/// off 3D (the squeeze-out along the axis), so two and three B4 must each at
/// least halve the displacement difference over the block and on the punch
/// face (measured 19.0 → 8.6 and 8.0 %, 24.4 → 5.2 and 5.8 %).
#[test]
#[ignore = "validate: slow — the block with 1, 2 and 3 B4 (about a minute)"]
fn block_axis_refinement_against_stored_3d() {
    let path = root().join("examples/block_indentation.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let stored_on = cufem::setup::Model::from_file(&path).unwrap();
    let csv = stored::field_3d("block_indentation");
    let axis = "axis = { element = \"B4\", from = 0.0, to = 0.1, elements = 1 }";
    assert!(text.contains(axis));
    let mut errors = Vec::new();
    for n in [1, 2, 3] {
        let model =
            cufem::setup::Model::parse(&text.replace(axis, &axis.replace("elements = 1", &format!("elements = {n}"))))
                .unwrap();
        let solution = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
        assert!(solution.failure.is_none());
        let rows = cufem_ccx::verify::compare_stored_on(&stored_on, &model, &solution.fields(&model), &csv).unwrap();
        report(&format!("block_indentation_{n}B4"), &rows);
        let l2 = |region: &str| row(&rows, region, "u").l2_percent;
        errors.push((l2("body block"), l2("surface punch")));
    }
    let (one, two, three) = (errors[0], errors[1], errors[2]);
    assert!(two.0 < 0.5 * one.0 && two.1 < 0.5 * one.1, "2 B4 {two:?} against 1 B4 {one:?}");
    assert!(three.0 < 0.5 * one.0 && three.1 < 0.5 * one.1, "3 B4 {three:?} against 1 B4 {one:?}");
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
        common::block_u_z_error(&self.x, &self.u_z, &self.u_z_3d, a, b)
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
    // 3D punch force: crates/cufem-cli/tests/examples.rs BLOCK_FORCE_3D (the same CalculiX run)
    let source = "CalculiX C3D20R, refine 2 (tests/data/references.toml, block)";
    common::within("block_graded.punch_force", punch["force"][2].as_f64().unwrap(), -1.4102e6, 0.02, source);
    let line = top_line(&out.join("line_top.csv"));
    let (near, edge, corner) = (line.u_z_error(0.03, 0.15), line.u_z_error(0.175, 0.175), line.u_z_error(0.0, 0.03));
    let top = "the 3D top line (tests/data/block_calculix_top_u_z.csv)";
    common::figure("block_graded.u_z_near", 100.0 * near, "%", &format!("≤ 5 % on x ∈ [0.03, 0.15] m against {top}"));
    common::figure("block_graded.u_z_edge", 100.0 * edge, "%", &format!("≤ 8 % at x = 0.175 m against {top}"));
    common::figure("block_graded.u_z_corner", 100.0 * corner, "%", &format!("≤ 5 % on x ∈ [0, 0.03] m against {top}"));
    common::figure(
        "block_graded.u_z_all",
        100.0 * line.u_z_error(0.0, 0.19),
        "%",
        "reported: every station x ∈ [0, 0.19] m",
    );
    let peak = "of the 3D peak under the punch (tests/data/block_calculix_top.csv)";
    common::figure("block_graded.s_zz_under", 100.0 * line.s_zz_under, "%", &format!("≤ 10 % {peak}"));
    common::figure("block_graded.peeq_under", 100.0 * line.peeq_under, "%", &format!("≤ 10 % {peak}"));
    assert!(near <= 0.05 && edge <= 0.08 && corner <= 0.05, "u_z {near} {edge} {corner}");
    assert!(line.sinks_towards_the_punch(), "the top surface does not sink monotonically towards the punch");
    assert!(line.s_zz_under <= 0.10 && line.peeq_under <= 0.10, "{} {}", line.s_zz_under, line.peeq_under);
}

/// The top line's u_z within 10 mm of the punch edge, x ∈ (0.19, 0.2) m,
/// where the surface falls from −0.18 to −1 mm: is the whole block's 3D
/// reference (tests/data/block_calculix_top_u_z.csv, 8.5 mm hexahedra at the
/// edge) converged there, and does a CUF mesh graded to the edge meet issue
/// 49's `5 %` there? Against the block's quarter graded towards the edge in
/// 3D (bench/block_edge_quarter.toml's twin, 1 mm C3D20R at the edge, 6
/// along the half depth; and 3 along it, tests/data/block_edge_quarter_calculix_top_u_z.csv),
/// at every station x ∈ [0, 0.1975] m:
/// - the two quarters within `2.5 %` of each other (measured 1.52 %, at
///   0.1975 m) and the whole block's reference within `2.5 %` of the finer
///   (measured 2.18 %, at 0.1975 m): half the issue's bound, so the
///   reference can judge it;
/// - the CUF quarter of bench/block_edge_quarter.toml (13,671 DOF) within
///   issue 49's `5 %` of the finer 3D quarter (measured 1.95 %, at 0.19 m;
///   1.68 % on x ∈ (0.19, 0.1975] m): the mesh graded to the edge meets it at every
///   station, where `--adapt`'s halvings from the paper's mesh leave the
///   element beside the edge 4.2 mm long at its 60,000 DOF budget
///   (crates/cufem-cli/tests/adapt.rs `block_adaptive_against_3d`, a known
///   limit).
///
/// The punch forces: the CUF quarter's within 0.6 % of the graded 3D
/// quarter's (measured +0.04 %); reported, from the stored references
/// alone, the whole block's 3D model of the shipped mesh (refine 2, the
/// reference of the u_z stations) 1.1 % above four times that quarter's
/// (its edge elements are coarse, and the force checks against it, as
/// `block_adaptive_against_3d`'s 0.6 %, carry that difference) and the
/// two graded 3D quarters (6 and 3 hexahedra along the half depth) 0.01 %
/// apart.
///
/// Mutation: Young's modulus 10 % high in the bench file puts the CUF
/// quarter 9.2 % off and fails.
#[test]
fn block_edge_stations_against_a_graded_3d_quarter() {
    let quarter = common::csv_columns(&root().join("tests/data/block_edge_quarter_calculix_top_u_z.csv"));
    let whole = common::csv_columns(&root().join("tests/data/block_calculix_top_u_z.csv"));
    let (x, fine, coarse) = (&quarter["x"], &quarter["u_z"], &quarter["u_z_3_along"]);
    let stations: Vec<usize> = (0..x.len()).filter(|&i| x[i] <= 0.1975 + 1e-9).collect();
    assert_eq!(stations.len(), 80, "the stations 2.5 mm apart on x ∈ [0, 0.1975] m");
    assert!(stations.iter().all(|&i| (whole["x"][i] - x[i]).abs() < 1e-12), "the same stations");
    assert!(stations.iter().all(|&i| fine[i] < 0.0), "3D u_z crosses zero: a relative difference is not defined");
    let worst = |u: &dyn Fn(usize) -> f64| stations.iter().map(|&i| (u(i) / fine[i] - 1.0).abs()).fold(0.0, f64::max);
    let (along, reference) = (worst(&|i| coarse[i]), worst(&|i| whole["u_z"][i]));
    let path = root().join("bench/block_edge_quarter.toml");
    let model = cufem::setup::Model::from_file(&path).unwrap();
    assert_eq!(model.n_dofs(), 13_671);
    let solution = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    let view = solution.fields(&model);
    let line = model.lines.iter().find(|l| l.name == "top").unwrap();
    let samples = cufem::post::sample_line(&view, line);
    assert_eq!(samples.len(), x.len());
    let u_z: Vec<f64> = samples.iter().map(|p| p.sample.as_ref().unwrap().u[2]).collect();
    let (cuf, beside) = (
        worst(&|i| u_z[i]),
        stations.iter().filter(|&&i| x[i] > 0.19 + 1e-9).map(|&i| (u_z[i] / fine[i] - 1.0).abs()).fold(0.0, f64::max),
    );
    let quarter_3d = "the 3D quarter graded to the edge (tests/data/block_edge_quarter_calculix_top_u_z.csv)";
    common::figure(
        "block_edge.3d_along",
        100.0 * along,
        "%",
        "≤ 2.5 % at every station x ∈ [0, 0.1975] m: 3 against 6 hexahedra along the half depth",
    );
    common::figure(
        "block_edge.whole_reference",
        100.0 * reference,
        "%",
        &format!("≤ 2.5 % at every station x ∈ [0, 0.1975] m: the whole block's 3D reference against {quarter_3d}"),
    );
    common::figure(
        "block_edge.cufem",
        100.0 * cuf,
        "%",
        &format!("≤ 5 % at every station x ∈ [0, 0.1975] m: bench/block_edge_quarter.toml against {quarter_3d}"),
    );
    common::figure("block_edge.cufem_beside", 100.0 * beside, "%", "reported: the stations x ∈ (0.19, 0.1975] m");
    assert!(along <= 0.025 && reference <= 0.025, "3D references {along} {reference} apart");
    assert!(cuf <= 0.05, "the graded quarter's u_z {cuf} from 3D");
    // the punch forces (tests/data/references.toml: block_edge_quarter,
    // −3.4873e5 N, and its twin with 3 hexahedra along the half depth,
    // −3.4878e5 N, on the quarter; block, −1.4102e6 N on the whole block)
    let (graded, graded_along, shipped) = (-3.4873e5, -3.4878e5, -1.4102e6);
    let stiffer = shipped / (4.0 * graded) - 1.0;
    let force = solution.contact("punch").unwrap().force[2] / graded - 1.0;
    // two stored references against each other: reported, not a check
    common::figure(
        "block_edge.whole_reference_force",
        100.0 * stiffer,
        "%",
        "reported: the shipped mesh's 3D punch force against four times the 3D quarter graded to the edge",
    );
    common::figure(
        "block_edge.3d_along_force",
        100.0 * (graded_along / graded - 1.0),
        "%",
        "reported: the graded 3D quarter with 3 against 6 hexahedra along the half depth",
    );
    common::figure("block_edge.cufem_force", 100.0 * force, "%", "≤ 0.6 %: the CUF quarter's punch force against 3D's");
    assert!(force.abs() <= 0.006, "the graded quarter's punch force {force} from 3D");
}

/// The graded block against the stored 3D fields of the paper's mesh
/// (`compare_stored_on`, points located by position). Known limits,
/// asserted from both sides: u 4.76 % over the block and 3.63 % on the
/// punch face (issue 23's 2 % not met; the largest differences, 7 % of the
/// largest |u|, sit beside the punch edges at the free faces y = 0 and
/// 0.1 m), peeq 16.4 % over the plastic zone; von Mises 4.49 % over the
/// plastic zone meets issue 23's 10 %. The paper's mesh: 19.0 / 24.4 /
/// 7.5 / 36.4 % (test above).
#[test]
fn block_indentation_graded_whole_field_against_3d() {
    let stored_on = cufem::setup::Model::from_file(&root().join("examples/block_indentation.toml")).unwrap();
    let model = cufem::setup::Model::from_file(&root().join("examples/block_indentation_graded.toml")).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    let csv = stored::field_3d("block_indentation");
    let rows = cufem_ccx::verify::compare_stored_on(&stored_on, &model, &solution.fields(&model), &csv).unwrap();
    report("block_indentation_graded", &rows);
    known_limits(
        "block_indentation_graded",
        &rows,
        &[
            ("body block", "u", 4.76),
            ("surface punch", "u", 3.63),
            ("plastic zone block", "von_mises", 4.49),
            ("plastic zone block", "peeq", 16.37),
        ],
    );
    criterion("block_indentation_graded", &rows, "plastic zone block", "von_mises", 10.0);
}

/// Issue 23's "on a mesh you name of at most 40,000 DOF within 3 %": the
/// graded block refined to 24 × 9 L9 × 6 B3 (36,309 DOF, about 20 s).
/// Measured: top-line u_z within 1.3 % at every station x ∈ [0, 0.19] m
/// and its mirror, punch force +0.33 %, σ_zz and peeq under the punch
/// 9.4 % and 6.6 % of the 3D peak.
#[test]
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
    let source = "CalculiX C3D20R, refine 2 (tests/data/references.toml, block)";
    common::within("block_36k.punch_force", punch["force"][2].as_f64().unwrap(), -1.4102e6, 0.02, source);
    let line = top_line(&out.join("line_top.csv"));
    let u = line.u_z_error(0.0, 0.19);
    common::figure(
        "block_36k.u_z_all",
        100.0 * u,
        "%",
        "≤ 3 % at every station x ∈ [0, 0.19] m against the 3D top line",
    );
    let peak = "of the 3D peak under the punch (tests/data/block_calculix_top.csv)";
    common::figure("block_36k.s_zz_under", 100.0 * line.s_zz_under, "%", &format!("≤ 10 % {peak}"));
    common::figure("block_36k.peeq_under", 100.0 * line.peeq_under, "%", &format!("≤ 10 % {peak}"));
    assert!(u <= 0.03 && line.sinks_towards_the_punch(), "u_z {u}");
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
    assert_issue_criteria("bending_compact_16L9", &rows, "bar");
}

/// §4.2 thin-walled tube, the shipped 22 B4 × 28 L9 (33,768 DOF), against 3D
/// at refine 1 (C3D20R, 123,312 DOF; the three roller lines left out within
/// 1.8 mm). Issue 23's criteria are met for von Mises over the plastic zone
/// (measured 3.95 %) but not for the displacement: u 5.7 % over the tube and
/// up to 6.0 % (L2) on the roller surfaces; most of it is the top wall
/// between the webs, which sags off the loading roller by 0.019 mm where
/// 3D keeps it on (docs/cross-check.md). Known limits, asserted from both
/// sides (docs/limitations.md).
#[test]
fn bending_tube_28l9_whole_field_against_3d() {
    let rows = whole_field("bending_tube_28L9");
    criterion("bending_tube_28L9", &rows, "plastic zone tube", "von_mises", 10.0);
    known_limits(
        "bending_tube_28L9",
        &rows,
        &[
            ("body tube", "u", 5.71),
            ("surface load", "u", 4.35),
            ("surface support_left", "u", 6.02),
            ("plastic zone tube", "peeq", 26.79),
        ],
    );
}

/// §4.2 tube with the paper's coarse section (22 B4 × 20 L9) against the
/// 3D fields stored for the 28 L9 mesh. Measured: u 3.82 % over the tube
/// (closer to 3D than the 28 L9 mesh's 5.7 %: its top wall stays nearer the
/// roller), at most 3.78 % on the roller surfaces (issue 23's 5 %: met),
/// von Mises 4.31 % over the plastic zone (10 %: met), peeq 28 %. The
/// issue's 2 % for u is not met: known limits, asserted from both sides.
#[test]
fn bending_tube_20l9_whole_field_against_3d() {
    let rows = whole_field_on("bending_tube_20L9", "bending_tube_28L9");
    for s in rows.iter().filter(|r| r.region.starts_with("surface ") && r.quantity == "u") {
        let id = field_id("bending_tube_20L9", &s.region, "u") + ".max";
        common::figure(&id, s.max_percent, "%", "≤ 5 % (largest u difference on a contact surface, issue 23)");
        assert!(s.points > 0 && s.max_percent <= 5.0, "u on {}: {s:?}", s.region);
    }
    known_limits("bending_tube_20L9", &rows, &[("body tube", "u", 3.82), ("plastic zone tube", "peeq", 28.06)]);
    criterion("bending_tube_20L9", &rows, "plastic zone tube", "von_mises", 10.0);
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
/// a known limit, asserted from both sides (docs/limitations.md).
#[test]
fn cantilevers_contact_whole_field_against_3d() {
    let rows = whole_field("cantilevers_contact");
    assert_issue_criteria("cantilevers_contact", &rows, "upper");
    known_limits(
        "cantilevers_contact",
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
/// is −3.7 % (2,827 against 2,937 N), a known limit asserted from both
/// sides: it is not converged in either model (docs/cross-check.md). Young's modulus 10 % high fails
/// it (checked by hand: the 9 in roller goes to −8.1 %; the 7 in one, set
/// by the plastic zone under it, only to +1.3 %, and u stays within 0.3 %).
#[test]
fn cantilevers_contact_fine_against_3d() {
    let (rows, _, solution) = compare_on("cantilevers_contact_fine", "cantilevers_contact");
    assert_issue_criteria("cantilevers_contact_fine", &rows, "upper");
    assert_issue_criteria("cantilevers_contact_fine", &rows, "lower");
    let contact = |n: &str| solution.contacts.iter().find(|c| c.name == n).unwrap().force[2];
    let reaction = |n: &str| solution.reactions.iter().find(|r| r.name == n).unwrap().force[2];
    // CalculiX C3D20R, refine 1 of the paper's mesh (tests/data/references.toml, cantilevers)
    let source = "CalculiX C3D20R, refine 1 (tests/data/references.toml, cantilevers)";
    common::within("cantilevers_fine.force_7in", contact("indenter_7in"), -25_769.0, 0.02, source);
    common::within("cantilevers_fine.upper_root", reaction("upper_root"), 12_619.0, 0.02, source);
    common::within("cantilevers_fine.lower_root", reaction("lower_root"), 16_087.0, 0.02, source);
    let nine = 100.0 * (contact("indenter_9in") / -2_937.2 - 1.0);
    common::known_limit("cantilevers_fine.force_9in", nine, "%", -3.9, -3.5, "the 9 in roller against 3D");
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
/// Young's modulus 10 % high fails it (u over the tube 2.45 %). The 3D
/// model of the paper's mesh is itself 1.4 % stiff at the roller: against
/// the converged 3D quarter u over the tube is 2.66 % (one L9 through the
/// wall; crates/cufem-cli/tests/roller_twins.rs).
#[test]
fn bending_tube_graded_against_3d() {
    let (rows, model, solution) = compare_on("bending_tube_graded", "bending_tube_28L9");
    assert_issue_criteria("bending_tube_graded", &rows, "tube");
    let force = |n: &str| solution.contacts.iter().find(|c| c.name == n).unwrap().force[2];
    let source = "CalculiX C3D20R, refine 1 (tests/data/references.toml, tube)";
    for (name, ccx) in [("load", -1698.2), ("support_left", 849.09), ("support_right", 849.09)] {
        common::within(&format!("tube_graded.force_{name}"), force(name), ccx, 0.02, source);
    }
    // the middle of the top wall under the roller: 3D −0.75289 mm for the
    // 0.75 mm travel (sag 0.39 %); measured −0.75481 mm (0.64 %); bound 1 %
    // (the paper's mesh: 2.6 %)
    let centre = solution.fields(&model).sample_point(None, [0.015, 0.125, 0.03]).unwrap().u[2];
    let sag = 100.0 * (centre / -0.75e-3 - 1.0);
    common::figure("tube_graded.sag", sag, "%", "≤ 1 % of the 0.75 mm travel (3D: 0.39 %)");
    assert!(sag.abs() <= 1.0, "contact centre u_z {centre:e} m");
}

/// The table "The tube at its loading roller" of docs/cross-check.md: the
/// paper's tube with the axis refined at the loading roller and the ring
/// refined, against the 3D model of the paper's mesh (CalculiX C3D20R,
/// refine 1: roller 1,698.2 N, σ_yy −63.87 MPa and peeq 5.27e-3 at the
/// contact centre; the stored 3D fields). What the docs claim from it:
/// elements of 1–3.3 mm at the roller bring the roller force within 1.1 %
/// of 3D and u over the tube below 2.1 % (the paper's mesh: −3.45 % and
/// 5.7 %); σ_yy at the contact centre follows the ring, +9 to +15 % with
/// 28 L9 and within 2 % with 52 L9.
#[test]
#[ignore = "validate: slow — three tube meshes of 40,000–108,000 DOF (about 3 min)"]
fn tube_roller_meshes_against_stored_3d() {
    let text = std::fs::read_to_string(root().join("examples/bending_tube_28L9.toml")).unwrap();
    let stored_on = cufem::setup::Model::from_file(&root().join("examples/bending_tube_28L9.toml")).unwrap();
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
        ("axis_3mm", text[..start].to_string() + &axis(&graded_33) + &text[end..]),
        ("axis_1mm", text[..start].to_string() + &axis(&graded_1) + &text[end..]),
        (
            "axis_1mm_52L9",
            (text[..start].to_string() + &axis(&graded_1) + &text[end..]).replace("around = 28", "around = 52"),
        ),
    ];
    for (name, t) in variants {
        let model = cufem::setup::Model::parse(&t).unwrap();
        let s = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
        assert!(s.failure.is_none(), "{:?}", s.failure);
        let view = s.fields(&model);
        let force = 100.0 * (s.contacts.iter().find(|c| c.name == "load").unwrap().force[2] / -1698.2 - 1.0);
        let p = view.sample_point(None, [0.015, 0.125, 0.03]).unwrap();
        let s_yy = 100.0 * (p.stress[1] / -63.8669e6 - 1.0);
        let id = |q: &str| format!("tube_roller.{name}.{q}");
        common::figure(&id("dof"), model.n_dofs() as f64, "", "reported");
        common::figure(&id("force"), force, "%", "|force − 3D| ≤ 1.1 %");
        common::figure(&id("sag"), 100.0 * (p.u[2] / -0.75e-3 - 1.0), "%", "reported (3D: 0.39 % of the travel)");
        common::figure(&id("s_yy"), s_yy, "%", "28 L9: 9 to 15 %; 52 L9: within 2 %");
        common::figure(&id("peeq"), 100.0 * (p.peeq / 5.27e-3 - 1.0), "%", "reported");
        let rows =
            cufem_ccx::verify::compare_stored_on(&stored_on, &model, &view, &stored::field_3d("bending_tube_28L9"))
                .unwrap();
        report(&format!("tube_roller.{name}"), &rows);
        assert!(force.abs() <= 1.1, "{name}: roller force {force:+.2} % from 3D");
        assert!(row(&rows, "body tube", "u").l2_percent < 2.1, "{name}: u over the tube");
        if name.ends_with("52L9") {
            assert!(s_yy.abs() <= 2.0, "{name}: σ_yy {s_yy:+.1} %");
        } else {
            assert!((9.0..=15.5).contains(&s_yy), "{name}: σ_yy {s_yy:+.1} %");
        }
    }
}

/// The table "The cantilevers' rollers under refinement" of
/// docs/cross-check.md: `examples/cantilevers_contact.toml` with both
/// beams' axes refined alike (so that the node-to-node pairs keep
/// matching) and their sections refined, the rollers as shipped
/// (node-to-node) or exact-gap rigid surfaces; roller forces, the force
/// across the interface, and the whole field against the stored 3D fields
/// of the shipped mesh (CalculiX C3D20R, refine 1: 7 in roller 25,769 N,
/// 9 in roller 2,937 N). What the docs claim from it: from 20 B4 on the
/// 7 in roller is within 0.6 % of 3D and von Mises over both plastic zones
/// within 6 %; the 9 in roller does not converge (it falls by 15–25 %
/// under axis refinement); surface rollers move the roller forces by less
/// than 1 %.
#[test]
#[ignore = "validate: slow — seven cantilever meshes of 15,000–123,000 DOF (about 5 min)"]
fn cantilever_meshes_against_stored_3d() {
    let text = std::fs::read_to_string(root().join("examples/cantilevers_contact.toml")).unwrap();
    let stored_on = cufem::setup::Model::from_file(&root().join("examples/cantilevers_contact.toml")).unwrap();
    let (upper, lower) = (
        "axis = { element = \"B4\", from = 0.0, to = 0.254, elements = 10 }",
        "axis = { element = \"B4\", from = 0.0762, to = 0.3302, elements = 10 }",
    );
    let mut forces = std::collections::HashMap::new();
    for (axis, section, surface) in [
        (10, 4, false),
        (10, 4, true),
        (20, 4, false),
        (20, 4, true),
        (40, 4, false),
        (80, 4, false),
        (20, 6, false),
        (40, 6, false),
    ] {
        let elements = format!("elements = {axis} }}");
        let mut t = text
            .replace(upper, &upper.replace("elements = 10 }", &elements))
            .replace(lower, &lower.replace("elements = 10 }", &elements))
            .replace("elements = 4 }", &format!("elements = {section} }}"));
        if surface {
            t = t.replace("radius = 0.0127\n", "radius = 0.0127\nmethod = \"surface\"\n");
        }
        let model = cufem::setup::Model::parse(&t).unwrap();
        let s = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
        assert!(s.failure.is_none(), "{:?}", s.failure);
        let force = |n: &str| s.contacts.iter().find(|c| c.name == n).unwrap().force[2];
        let key = format!("{axis}B4_{section}x{section}{}", if surface { "_surface" } else { "" });
        let id = |q: &str| format!("cantilever_rollers.{key}.{q}");
        let (f7, f9) =
            (100.0 * (force("indenter_7in") / -25_769.0 - 1.0), 100.0 * (force("indenter_9in") / -2_937.2 - 1.0));
        common::figure(&id("dof"), model.n_dofs() as f64, "", "reported");
        common::figure(&id("force_7in"), f7, "%", "from 20 B4 on: within 0.6 % of 3D");
        common::figure(&id("force_9in"), f9, "%", "reported: not converged");
        let view = s.fields(&model);
        for p in &model.probes {
            let at = view.sample_probe(p).unwrap();
            common::figure(&id(&format!("{}.s_yy", p.name)), at.stress[1] / 1e6, "MPa", "reported");
        }
        let rows =
            cufem_ccx::verify::compare_stored_on(&stored_on, &model, &view, &stored::field_3d("cantilevers_contact"))
                .unwrap();
        report(&format!("cantilever_rollers.{key}"), &rows);
        if axis >= 20 {
            assert!(f7.abs() <= 0.6, "{key}: 7 in roller {f7:+.2} %");
            for b in ["upper", "lower"] {
                let vm = row(&rows, &format!("plastic zone {b}"), "von_mises").l2_percent;
                assert!(vm <= 6.0, "{key}: von Mises over the {b} plastic zone {vm} %");
            }
        }
        forces.insert(key, (force("indenter_7in"), force("indenter_9in")));
    }
    for (a, b) in [("10B4_4x4", "10B4_4x4_surface"), ("20B4_4x4", "20B4_4x4_surface")] {
        let ((a7, a9), (b7, b9)) = (forces[a], forces[b]);
        assert!((b7 / a7 - 1.0).abs() < 0.01 && (b9 / a9 - 1.0).abs() < 0.01, "{a} against {b}");
    }
    let nine = |k: &str| forces[k].1;
    for k in ["40B4_4x4", "80B4_4x4", "40B4_6x6"] {
        assert!(nine(k) / nine("10B4_4x4") < 0.85, "{k}: the 9 in roller did not fall under refinement");
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
    let stored = stored::field_3d("bending_compact_4L9");
    let plastic_zone_von_mises = |formulation: &str| {
        let t = text.replacen(
            "material = \"alloy\"\n",
            &format!("material = \"alloy\"\nformulation = \"{formulation}\"\n"),
            1,
        );
        assert!(t.contains("formulation"));
        let model =
            cufem::setup::Model::parse_in(&t, cufem::setup::Limits::machine(), &root().join("examples")).unwrap();
        let s = cufem::analysis::run(&model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
        let rows = cufem_ccx::verify::compare_stored(&model, &s.fields(&model), &stored).unwrap();
        row(&rows, "plastic zone bar", "von_mises").l2_percent
    };
    let (standard, bbar) = (plastic_zone_von_mises("standard"), plastic_zone_von_mises("bbar"));
    eprintln!("von Mises over the plastic zone: standard {standard:.2} %, B-bar {bbar:.2} %");
    assert!(bbar > standard, "B-bar {bbar} % vs standard {standard} %: reconsider the default");
}
