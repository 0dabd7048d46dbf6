//! The rollers of the paper's tube (§4.2) and cantilevers (§4.3) against
//! refined 3D twins (issue 49, item 3): CalculiX C3D20R models made by
//! `cufem verify FILE --refine 1` of quarter (tube) and half (cantilevers)
//! CUF models refined where the stored references were coarse — along the
//! axis at the rollers, and through the tube's wall — so that each
//! reference's own convergence is measured beside it
//! (tests/data/references.toml; the `validate: references` tests below
//! re-make them). Each CUF mesh is then held to the finest twin: the roller
//! forces within the issue's `2 %`, the probes on the roller lines within
//! its `10 %`; where a shipped mesh misses, the measured value is a known
//! limit asserted from both sides (docs/limitations.md).

#[path = "../../../tests/common/mod.rs"]
mod common;
#[path = "stored/mod.rs"]
mod stored;

use std::path::PathBuf;

use cufem::analysis::{Silent, Solution};
use cufem::setup::Model;
use cufem_ccx::verify::FieldRow;

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn read(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).unwrap()
}

fn solve(text: &str) -> (Model, Solution) {
    let model = Model::parse(text).unwrap();
    let solution = cufem::analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    assert!(solution.failure.is_none(), "{:?}", solution.failure);
    (model, solution)
}

/// A 3D twin's values: the roller forces along z on the part modelled (N)
/// and, per probe, σ_yy (Pa) and peeq.
struct Twin {
    forces: &'static [(&'static str, f64)],
    probes: &'static [(&'static str, f64, f64)],
}

/// The tube's quarter, 3D, on the axis graded at the roller (the twin of
/// examples/bending_tube_graded_quarter.toml, 34,815 DOF; docs/validation.md
/// rows `verify.tube_graded_quarter.*`, `bench/validate --steps verify-long`).
const TUBE_GRADED: Twin = Twin { forces: &[("load", -418.654)], probes: &[("contact_centre", -64.7949e6, 5.42024e-3)] };

/// The same with 1 mm B4 at the roller (the twin of
/// bench/tube_quarter_axis_1mm.toml, 54,723 DOF; tests/data/references.toml,
/// tube_quarter_1mm).
const TUBE_1MM: Twin = Twin { forces: &[("load", -418.6434)], probes: &[("contact_centre", -64.6981e6, 5.39991e-3)] };

/// The 1 mm twin with the axis at the support halved (the twin of
/// bench/tube_quarter_axis_1mm_support.toml, 60,411 DOF;
/// tests/data/references.toml, tube_quarter_1mm_support).
const TUBE_1MM_SUPPORT: Twin =
    Twin { forces: &[("load", -417.9706)], probes: &[("contact_centre", -64.5528e6, 5.36636e-3)] };

/// The graded quarter with its section doubled, four C3D20R through the
/// wall (the twin of examples/bending_tube_graded_wall2.toml, 118,803 DOF;
/// tests/data/references.toml, tube_quarter_section_x2).
const TUBE_SECTION_X2: Twin =
    Twin { forces: &[("load", -417.713)], probes: &[("contact_centre", -64.6451e6, 5.48801e-3)] };

/// The cantilevers' half, 3D, 20 B4 per beam (the twin of
/// bench/cantilevers_half_20B4.toml, 60,486 DOF; tests/data/references.toml,
/// cantilevers_half_20B4).
const CANTILEVERS_20: Twin = Twin {
    forces: &[("indenter_7in", -13_025.99), ("indenter_9in", -1_177.311)],
    probes: &[("y_177.8mm", -417.215e6, 9.99242e-3), ("y_228.6mm", -167.34e6, 0.0)],
};

/// The same with 40 B4 per beam (the twin of bench/cantilevers_half_40B4.toml,
/// 120,246 DOF; tests/data/references.toml, cantilevers_half_40B4).
const CANTILEVERS_40: Twin = Twin {
    forces: &[("indenter_7in", -13_032.93), ("indenter_9in", -1_038.878)],
    probes: &[("y_177.8mm", -483.907e6, 1.35933e-2), ("y_228.6mm", -170.061e6, 0.0)],
};

/// `100 (a / b − 1)`.
fn percent(a: f64, b: f64) -> f64 {
    100.0 * (a / b - 1.0)
}

/// The differences of `model` (its forces scaled by `scale` to the twin's
/// part) from `twin`, as figures `<id>.force_<name>`, `<id>.<probe>.s_yy`
/// and `<id>.<probe>.peeq` (%); returned in that order.
fn against(id: &str, (model, solution): &(Model, Solution), scale: f64, twin: &Twin) -> Vec<(String, f64)> {
    let mut out = Vec::new();
    for &(name, reference) in twin.forces {
        let f = solution.contacts.iter().find(|c| c.name == name).unwrap().force[2] * scale;
        out.push((format!("{id}.force_{name}"), percent(f, reference)));
    }
    let view = solution.fields(model);
    for &(name, s_yy, peeq) in twin.probes {
        let probe = model.probes.iter().find(|p| p.name == name).unwrap();
        let sample = view.sample_probe(probe).unwrap();
        out.push((format!("{id}.{name}.s_yy"), percent(sample.stress[1], s_yy)));
        // a probe that stays elastic in 3D (peeq 0) has no relative peeq difference
        if peeq > 0.0 {
            out.push((format!("{id}.{name}.peeq"), percent(sample.peeq, peeq)));
        }
    }
    out
}

/// The whole field of `run` against the 3D field stored for `bench/<stored>.toml`
/// (its points located by position), each row a figure
/// `<id>.field.<region>.<quantity>` (relative L2, %; `.max`: the largest
/// difference in % of the body's largest 3D value), returned.
fn whole_field(id: &str, (model, solution): &(Model, Solution), stored: &str) -> Vec<FieldRow> {
    let stored_on = Model::from_file(&root().join("bench").join(format!("{stored}.toml"))).unwrap();
    let rows =
        cufem_ccx::verify::compare_stored_on(&stored_on, model, &solution.fields(model), &stored::field_3d(stored))
            .unwrap();
    for r in &rows {
        let at = format!("{id}.field.{}.{}", stored::region_id(&r.region), r.quantity);
        common::figure(&at, r.l2_percent, "%", "reported: relative L2 against the refined 3D twin");
        common::figure(
            &format!("{at}.max"),
            r.max_percent,
            "%",
            "reported: largest difference, % of the largest 3D value",
        );
    }
    rows
}

/// One row of a whole-field comparison.
fn row<'a>(rows: &'a [FieldRow], region: &str, quantity: &str) -> &'a FieldRow {
    rows.iter()
        .find(|r| r.region == region && r.quantity == quantity)
        .unwrap_or_else(|| panic!("no row {region} {quantity}"))
}

/// What a comparison must show: within `±bound` %, or a known limit held
/// in `[low, high]` % (docs/limitations.md).
#[derive(Clone, Copy)]
enum Check {
    Within(f64),
    Known(f64, f64),
}
use Check::{Known, Within};

/// Asserts `value` (%, the figure `id`) against `check`.
fn check(id: &str, value: f64, check: Check) {
    match check {
        Within(bound) => {
            common::figure(id, value, "%", &format!("|difference| ≤ {bound} % (issue 49)"));
            assert!(value.abs() <= bound, "{id}: {value:+.2} % (allowed ±{bound} %)");
        }
        Known(low, high) => common::known_limit(id, value, "%", low, high, id),
    }
}

/// The 3D references' own convergence: each value of `finer` against
/// `coarser` in the order [`against`] gives them, as figures
/// `<id>.<quantity>` (%), each against its `checks`.
fn converged(id: &str, coarser: &Twin, finer: &Twin, checks: &[Check]) {
    let pairs: Vec<_> = coarser
        .forces
        .iter()
        .zip(finer.forces)
        .map(|(a, b)| (format!("force_{}", a.0), a.1, b.1))
        .chain(coarser.probes.iter().zip(finer.probes).flat_map(|(a, b)| {
            let peeq = (a.2 > 0.0).then(|| (format!("{}.peeq", a.0), a.2, b.2));
            std::iter::once((format!("{}.s_yy", a.0), a.1, b.1)).chain(peeq)
        }))
        .collect();
    assert_eq!(pairs.len(), checks.len());
    for ((q, a, b), &c) in pairs.into_iter().zip(checks) {
        check(&format!("{id}.{q}"), percent(b, a), c);
    }
}

/// One CUF mesh's checks against a twin: the roller forces' and probes'
/// differences in the order [`against`] gives them, then the whole field's
/// u over the body each test names (relative L2).
struct Mesh {
    name: &'static str,
    differences: &'static [Check],
    u_body: Check,
}

/// The stored 3D field a tube mesh's u is held to: the twin with the
/// support refined as the mesh's (`*_support`), else the 1 mm one.
fn tube_field(name: &str) -> &'static str {
    if name.ends_with("_support") { "tube_quarter_axis_1mm_support" } else { "tube_quarter_axis_1mm" }
}

/// The tube's loading roller. The 3D quarter is converged along the axis
/// (1 mm B4 at the roller against the graded mesh's 2–3 mm: the force
/// `0.003 %`, σ_yy and peeq at the contact centre `0.15 %` and `0.38 %`)
/// and through the wall (four C3D20R against two: `0.22 %`, `0.23 %`,
/// `1.25 %`) and, in force and probes, at the support (its axis halved:
/// `−0.16 %`, `−0.22 %`, `−0.62 %`; u over the tube follows the support's
/// mesh on both sides, so a mesh refined there is held to the twin refined
/// alike). Against the
/// 1 mm twin (roller force, σ_yy and peeq at the contact centre, u over
/// the tube): the section doubled on the 1 mm axis meets every criterion of
/// issues 49 and 23 (measured `−0.02 %`, `−2.1 %`, `−5.4 %`, u `1.21 %`);
/// with one L9 through the wall the shipped meshes keep their roller force
/// within `2 %` but for the paper's uniform 28 L9 (`−2.08 %`), and σ_yy at
/// the contact centre is `12`–`16 %` above 3D on the 28 L9 rings, peeq
/// `12 %` off on two meshes, u over the tube `2.2`–`3.8 %` — known limits.
/// The paper's 20 L9 ring is the closest of the shipped meshes (u `1.57
/// %`). The roller force is set by the plastic zone under it: a hardening
/// curve 10 % high fails the doubled section's (`+8.7 %`), while Young's
/// modulus 10 % high moves it by `+1.0 %` only (checked by hand).
#[test]
#[ignore = "validate: slow — eight tube quarters of 9,000–50,000 DOF (about 1.5 min)"]
fn tube_roller_against_the_refined_quarter_twins() {
    // a reference is converged when refining it moves it by at most a
    // quarter of the tolerance it is used for: 0.5 % for the roller force
    // (issue 49: 2 %), 2.5 % for the probes (10 %)
    let quarter = [Within(0.5), Within(2.5), Within(2.5)];
    converged("roller_twins.tube.3d_axis", &TUBE_GRADED, &TUBE_1MM, &quarter);
    converged("roller_twins.tube.3d_section", &TUBE_GRADED, &TUBE_SECTION_X2, &quarter);
    converged("roller_twins.tube.3d_support", &TUBE_1MM, &TUBE_1MM_SUPPORT, &quarter);
    let axis_1mm = read("bench/tube_quarter_axis_1mm.toml");
    let one_through = "thickness = 0.0015, around = 28 }";
    assert!(axis_1mm.contains(one_through));
    let doubled = axis_1mm.replace(one_through, "thickness = 0.0015, through = 2, along_x = 12, along_z = 12 }");
    let text = |name: &str| match name {
        "axis_1mm" => axis_1mm.clone(),
        "axis_1mm_section_x2" => doubled.clone(),
        "graded_wall2" => read("examples/bending_tube_graded_wall2.toml"),
        "graded_around52" => {
            let text = read("examples/bending_tube_graded_quarter.toml");
            assert!(text.contains(one_through));
            text.replace(one_through, "thickness = 0.0015, around = 52 }")
        }
        "graded_wall2_support" => {
            // the axis at the support halved, as `--adapt` splits it
            // (crates/cufem-cli/tests/adapt.rs `tube_adaptive_roller_force`)
            let text = read("examples/bending_tube_graded_wall2.toml");
            let at_support =
                "    { from = 0.0, to = 0.025, elements = 2 },\n    { from = 0.025, to = 0.115, elements = 6 },";
            assert!(text.contains(at_support));
            text.replace(
                at_support,
                "    { from = 0.0, to = 0.0125, elements = 1 },\n    { from = 0.0125, to = 0.025, elements = 2 },\n    \
                 { from = 0.025, to = 0.04, elements = 2 },\n    { from = 0.04, to = 0.115, elements = 5 },",
            )
        }
        _ => read(&format!("examples/bending_tube_{name}_quarter.toml")),
    };
    // (force, σ_yy, peeq at the contact centre), u over the tube: measured
    // in the comment of each known limit's range
    const MESHES: [Mesh; 8] = [
        // −2.08 %, +11.71 %, −2.55 %; u 2.18 %
        Mesh {
            name: "28L9",
            differences: &[Known(-2.15, -2.01), Known(11.36, 12.07), Within(10.0)],
            u_body: Known(2.11, 2.25),
        },
        // −1.11 %, +0.06 %, +12.08 %; u 1.57 %
        Mesh { name: "20L9", differences: &[Within(2.0), Within(10.0), Known(11.71, 12.45)], u_body: Within(2.0) },
        // +0.54 %, +16.17 %, −5.69 %; u 2.66 %
        Mesh {
            name: "graded",
            differences: &[Within(2.0), Known(15.68, 16.67), Within(10.0)],
            u_body: Known(2.58, 2.74),
        },
        // +1.20 %, +13.49 %, −11.82 %; u 3.82 %
        Mesh {
            name: "axis_1mm",
            differences: &[Within(2.0), Known(13.14, 13.96), Known(-12.16, -11.44)],
            u_body: Known(3.70, 3.93),
        },
        // −0.02 %, −2.07 %, −5.38 %; u 1.21 %
        Mesh {
            name: "axis_1mm_section_x2",
            differences: &[Within(2.0), Within(10.0), Within(10.0)],
            u_body: Within(2.0),
        },
        // the shipped graded quarter with two L9 through the wall
        // (examples/bending_tube_graded_wall2.toml): −0.18 %, −1.63 %, −3.12 %
        Mesh { name: "graded_wall2", differences: &[Within(2.0), Within(10.0), Within(10.0)], u_body: Within(2.0) },
        // the graded quarter with twice the elements along the walls, one
        // through them (52 L9 around the ring)
        Mesh { name: "graded_around52", differences: &[Within(2.0), Within(10.0), Within(10.0)], u_body: Within(2.0) },
        // the graded wall2 quarter with the axis at the support halved (7.5 and 6.25 mm B4
        // where the 1 mm twin keeps 12.5 and 10 mm hexahedra), its u held
        // to the twin refined there alike (against the 1 mm twin: 2.12 %;
        // the wall2 mesh against this one: 1.58 %)
        Mesh {
            name: "graded_wall2_support",
            differences: &[Within(2.0), Within(10.0), Within(10.0)],
            u_body: Within(2.0),
        },
    ];
    for mesh in &MESHES {
        let run = solve(&text(mesh.name));
        let id = format!("roller_twins.tube.{}", mesh.name);
        let differences = against(&id, &run, 1.0, &TUBE_1MM);
        assert_eq!(differences.len(), mesh.differences.len());
        for ((id, d), &c) in differences.iter().zip(mesh.differences) {
            check(id, *d, c);
        }
        let rows = whole_field(&id, &run, tube_field(mesh.name));
        check(&format!("{id}.u_over_tube"), row(&rows, "body tube", "u").l2_percent, mesh.u_body);
    }
}

/// Re-makes the tube's twin with 1 mm B4 at the roller (`cufem verify
/// FILE --refine 1`) and checks it against the values stored above.
#[test]
#[ignore = "validate: references — CalculiX on the tube's quarter with 1 mm B4 at the roller (55,000 DOF, about 12 min)"]
fn the_tube_s_1mm_twin_is_remade() {
    remade("bench/tube_quarter_axis_1mm.toml", &TUBE_1MM);
}

/// Re-makes the tube's twin with the support refined.
#[test]
#[ignore = "validate: references — CalculiX on the tube's quarter with the support refined (60,000 DOF, about 12 min)"]
fn the_tube_s_support_twin_is_remade() {
    remade("bench/tube_quarter_axis_1mm_support.toml", &TUBE_1MM_SUPPORT);
}

/// Re-makes the tube's twin with the section doubled.
#[test]
#[ignore = "validate: references — CalculiX on the tube's quarter with four C3D20R through the wall (119,000 DOF, about 45 min)"]
fn the_tube_s_doubled_section_twin_is_remade() {
    remade("examples/bending_tube_graded_wall2.toml", &TUBE_SECTION_X2);
}

/// Re-makes the cantilevers' twin with 20 B4 per beam.
#[test]
#[ignore = "validate: references — CalculiX on the cantilevers' half with 20 B4 per beam (60,000 DOF, about 13 min)"]
fn the_cantilevers_20b4_twin_is_remade() {
    remade("bench/cantilevers_half_20B4.toml", &CANTILEVERS_20);
}

/// Re-makes the cantilevers' twin with 40 B4 per beam.
#[test]
#[ignore = "validate: references — CalculiX on the cantilevers' half with 40 B4 per beam (120,000 DOF, about 25 min)"]
fn the_cantilevers_40b4_twin_is_remade() {
    remade("bench/cantilevers_half_40B4.toml", &CANTILEVERS_40);
}

/// `cufem verify FILE --refine 1` into a scratch folder: its 3D forces and
/// probes equal `twin`'s within `0.1 %`.
fn remade(file: &str, twin: &Twin) {
    if common::ccx_missing() {
        return;
    }
    let stem = std::path::Path::new(file).file_stem().unwrap().to_str().unwrap();
    let dir = common::scratch_dir("roller_twins", stem);
    let out = common::verify(&dir, "twin", &read(file), 1);
    let table: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("verify/table.json")).unwrap()).unwrap();
    let resultant = |name: &str| {
        let r = table["resultants"].as_array().unwrap().iter().find(|r| r["name"] == name).unwrap();
        r["ccx"][2].as_f64().unwrap()
    };
    let probe = |name: &str, q: &str| {
        let p = table["probes"].as_array().unwrap().iter().find(|p| p["probe"] == name && p["quantity"] == q).unwrap();
        p["ccx"].as_f64().unwrap()
    };
    for &(name, value) in twin.forces {
        let got = resultant(name);
        assert!((got / value - 1.0).abs() < 1e-3, "{file}: {name} {got} N against the stored {value} N");
    }
    for &(name, s_yy, peeq) in twin.probes {
        let (a, b) = (probe(name, "s_yy"), probe(name, "peeq"));
        assert!((a / s_yy - 1.0).abs() < 1e-3, "{file}: {name} σ_yy {a} against the stored {s_yy}");
        assert!((b - peeq).abs() <= 1e-3 * peeq.abs().max(1e-6), "{file}: {name} peeq {b} against the stored {peeq}");
    }
}

/// The cantilevers' rollers: the shipped 10 B4 per beam (the full model,
/// its forces halved), then the half model with 20, 40 and 80 B4 per beam
/// and the 20 B4 one with its section doubled, against the 3D twin of 40
/// B4 per beam (hexahedra of 2.1 mm along the axis). The 3D reference
/// converges along the axis for the 7 in roller (`+0.05 %` from 20 to 40
/// B4) and σ_yy at the 9 in probe (`+1.6 %`), not for the lightly loaded 9
/// in roller (`−11.8 %`; `−20 %` from 10 to 20 B4) nor for σ_yy and peeq at
/// the 7 in probe, on its roller line (`+16 %`, `+36 %`): known limits of
/// the reference itself. Every CUF mesh's 7 in roller is within `2 %`
/// (measured `−1.02` to `+0.70 %`) and u over the lower beam within `2 %`
/// from 20 B4 on (`1.27`, `0.63`, `0.24 %`; the shipped 10 B4 `4.86 %`, a
/// known limit); the 9 in roller is `+10` to `+62 %` off, falling with the
/// axis elements as the reference's does, and the two probes follow their
/// mesh (σ_yy at the 9 in probe within `10 %` from 40 B4 on) — known limits
/// where not within the issue's `10 %`. A yield stress 10 % high puts the
/// 40 B4 model's 7 in roller at `+8.0 %` and fails it (checked by hand).
#[test]
#[ignore = "validate: slow — five cantilever models of 15,000–65,000 DOF (about 2 min)"]
fn cantilever_rollers_against_the_refined_half_twins() {
    // 7 in, 9 in; σ_yy and peeq at 177.8 mm; σ_yy at 228.6 mm
    // converged: at most a quarter of the tolerance (0.5 % for a force,
    // 2.5 % for a probe), as for the tube; not converged: known limits
    let reference = [Within(0.5), Known(-12.12, -11.40), Known(15.50, 16.47), Known(34.94, 37.11), Within(2.5)];
    converged("roller_twins.cantilevers.3d_axis", &CANTILEVERS_20, &CANTILEVERS_40, &reference);
    let half = read("bench/cantilevers_half_20B4.toml");
    assert_eq!(half.matches("elements = 20 }").count(), 2);
    assert_eq!(half.matches("elements = 4 }").count(), 4);
    let text = |name: &str| match name {
        "10B4" => read("examples/cantilevers_contact.toml"),
        "20B4_section_x2" => half.replace("elements = 4 }", "elements = 8 }"),
        _ => half.replace("elements = 20 }", &format!("elements = {} }}", name.trim_end_matches("B4"))),
    };
    // (7 in, 9 in, σ_yy and peeq at 177.8 mm, σ_yy at 228.6 mm), u over
    // the lower beam: measured in the comment of each known limit's range
    const MESHES: [Mesh; 5] = [
        // +0.70, +61.76, −10.29, −75.66, +14.03 %; u 4.86 %
        Mesh {
            name: "10B4",
            differences: &[
                Within(2.0),
                Known(59.90, 63.62),
                Known(-10.60, -9.98),
                Known(-77.94, -73.39),
                Known(13.60, 14.45),
            ],
            u_body: Known(4.71, 5.01),
        },
        // −0.62, +36.07, −0.87, −66.38, +16.04 %; u 1.27 %
        Mesh {
            name: "20B4",
            differences: &[Within(2.0), Known(34.98, 37.16), Within(10.0), Known(-68.38, -64.38), Known(15.55, 16.52)],
            u_body: Within(2.0),
        },
        // −0.75, +10.19, +13.77, −2.24, −8.35 %; u 0.63 %
        Mesh {
            name: "40B4",
            differences: &[Within(2.0), Known(9.88, 10.50), Known(13.36, 14.19), Within(10.0), Within(10.0)],
            u_body: Within(2.0),
        },
        // −0.65, +12.60, −0.72, +62.97, −0.44 %; u 0.24 %
        Mesh {
            name: "80B4",
            differences: &[Within(2.0), Known(12.22, 12.98), Within(10.0), Known(61.08, 64.86), Within(10.0)],
            u_body: Within(2.0),
        },
        // −1.02, +37.53, +11.97, −63.79, +21.56 %; u 0.88 %
        Mesh {
            name: "20B4_section_x2",
            differences: &[
                Within(2.0),
                Known(36.40, 38.66),
                Known(11.61, 12.33),
                Known(-65.70, -61.87),
                Known(20.90, 22.21),
            ],
            u_body: Within(2.0),
        },
    ];
    for mesh in &MESHES {
        let scale = if mesh.name == "10B4" { 0.5 } else { 1.0 };
        let run = solve(&text(mesh.name));
        let id = format!("roller_twins.cantilevers.{}", mesh.name);
        let differences = against(&id, &run, scale, &CANTILEVERS_40);
        assert_eq!(differences.len(), mesh.differences.len());
        for ((id, d), &c) in differences.iter().zip(mesh.differences) {
            check(id, *d, c);
        }
        let rows = whole_field(&id, &run, "cantilevers_half_40B4");
        check(&format!("{id}.u_over_lower"), row(&rows, "body lower", "u").l2_percent, mesh.u_body);
    }
}
