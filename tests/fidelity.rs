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
    let csv = std::fs::read_to_string(root().join("tests/data").join(format!("{name}_field_3d.csv"))).unwrap();
    let rows = cufem::verify::compare_stored(&model, &solution.fields(&model), &csv).unwrap();
    for r in &rows {
        eprintln!(
            "{name}: {:<28} {:<10} L2 {:6.2} %  max {:6.2} %  ({} points, {} excluded)",
            r.region, r.quantity, r.l2_percent, r.max_percent, r.points, r.excluded
        );
    }
    rows
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
    let bound = |region: &str, q: &str, measured: f64| {
        let r = row(&rows, region, q);
        assert!(r.points > 100 && r.l2_percent <= 1.1 * measured, "{region} {q}: {r:?} (measured {measured} %)");
    };
    bound("body block", "u", 19.02);
    bound("surface punch", "u", 24.36);
    bound("plastic zone block", "von_mises", 7.54);
    bound("plastic zone block", "peeq", 36.40);
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
