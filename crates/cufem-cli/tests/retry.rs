//! The retry of a failed increment (`solver::stepping`, `Incremental::cautious`)
//! searches along its corrections in a frictionless contact model
//! (`analysis::structure` `searches`): a contact set that cycled at the
//! first touch of a fine axis mesh converges at the same Δλ instead of
//! being cut back again and again.

#[path = "../../../tests/common/mod.rs"]
mod common;

use serde_json::Value;
use std::path::Path;

/// The loading roller's force and the contact centre's σ_yy and peeq.
fn values(s: &Value) -> [f64; 3] {
    let p = s["probes"].as_array().unwrap().iter().find(|p| p["name"] == "contact_centre").unwrap();
    let load = s["contact"].as_array().unwrap().iter().find(|c| c["name"] == "load").unwrap();
    [load["force"][2].as_f64().unwrap(), p["stress"][1].as_f64().unwrap(), p["peeq"].as_f64().unwrap()]
}

/// The tube's quarter with 1 mm B4 at its roller (bench/tube_quarter_axis_1mm.toml,
/// 15,138 DOF) started at Δλ = 1/15: at first touch the node lines 0.33 mm
/// apart under the 10 mm roller leave and re-enter the contact set in turn,
/// the residual stays at 1 and an iterate that lifts the support is
/// singular. Without the search in the retry the increment is cut back five
/// times (to 1/240); with it once, its retry converging at 1/15 in 15
/// iterations (measured with `cufem run`). The first attempt, which never
/// settles nor halves its residual, is given up after 6 corrections
/// (`solver::newton`, an attempt that chatters) instead of running on to 21:
/// 99 evaluations over the run instead of 114. The answer is that of the same
/// file started at 1/240, which converges at once (and grows to 1/15), up to
/// the path of the plastic increments: measured within 0.06 % (force,
/// σ_yy, peeq); held within 0.5 %.
#[test]
fn a_first_touch_that_cycles_is_retried_with_a_line_search() {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let text = std::fs::read_to_string(root.join("bench/tube_quarter_axis_1mm.toml")).unwrap();
    assert!(text.contains("\nincrements = 60\n"));
    let small = common::run_text("retry", "small", &text.replace("increments = 60\n", "increments = 240\n")).1;
    let large = common::run_text("retry", "large", &text.replace("increments = 60\n", "increments = 15\n")).1;
    assert_eq!(small["cutbacks"], 0);
    let cutbacks = large["cutbacks"].as_u64().unwrap();
    assert!(cutbacks <= 1, "{cutbacks} cutbacks at Δλ = 1/15");
    assert!(large["line_searches"].as_u64().unwrap() >= 1);
    let evaluations = large["timings"]["evaluations"].as_u64().unwrap();
    assert!(evaluations <= 105, "{evaluations} evaluations");
    for (name, (a, b)) in ["force", "s_yy", "peeq"].iter().zip(values(&large).into_iter().zip(values(&small))) {
        let d = (a - b) / b;
        println!("{name}: {a:.6e} against {b:.6e} ({:+.3} %)", 100.0 * d);
        assert!(d.abs() <= 5e-3, "{name}: {a:.6e} against {b:.6e} ({:+.3} %)", 100.0 * d);
    }
}
