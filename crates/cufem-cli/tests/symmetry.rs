//! Symmetry planes (issue 29): the quarter-model twins of the bending
//! examples (`examples/*_quarter.toml`, the full file with its two
//! symmetry constraints turned into `[[symmetry]]` planes) against the
//! full models they were cut from. The full models hold the same planes as
//! constraints, so both solve the same problem on the same nodes: every
//! field must agree to Newton's tolerance, everywhere — probes, points in
//! the part the planes leave out (reflected), lines across both planes —
//! and the full structure's forces must be the full model's.

#[path = "../../../tests/common/mod.rs"]
mod common;

use std::path::Path;

use cufem::post::{Quantity, Sample};
use cufem::setup::Model;

fn example(name: &str) -> String {
    std::fs::read_to_string(
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("examples").join(format!("{name}.toml")),
    )
    .unwrap()
}

/// Points of the full bar away from the probes: in each quarter of the
/// structure, so three of them lie in the part the planes leave out.
fn extra_probes(text: &str, points: &[[f64; 3]]) -> String {
    let mut t = text.to_string();
    for (k, p) in points.iter().enumerate() {
        t.push_str(&format!("\n[[probes]]\nname = \"extra{k}\"\npoint = [{}, {}, {}]\n", p[0], p[1], p[2]));
    }
    t
}

/// The largest difference between two samples, each quantity relative to
/// its kind's scale (largest |u|, von Mises, largest |strain|, peeq).
fn difference(a: &Sample, b: &Sample, scale: [f64; 4]) -> f64 {
    Quantity::all()
        .into_iter()
        .map(|q| {
            let s = match q {
                Quantity::Displacement(_) => scale[0],
                Quantity::Stress(_) | Quantity::VonMises => scale[1],
                Quantity::Strain(_) => scale[2],
                _ => scale[3].max(1e-12),
            };
            (a.get(q) - b.get(q)).abs() / s
        })
        .fold(0.0, f64::max)
}

/// Runs the full model in the library and the quarter twin through the CLI
/// (both with `extra` probes), and compares every field and force.
fn twin(full: &str, quarter: &str, extra: &[[f64; 3]]) {
    twin_of((full, &example(full)), (quarter, &example(quarter)), extra);
}

/// [`twin`] of the models given as (name, text); returns the full model's
/// solution and the twin's output folder.
fn twin_of(
    (full, full_text): (&str, &str),
    (quarter, quarter_text): (&str, &str),
    extra: &[[f64; 3]],
) -> (cufem::analysis::Solution, std::path::PathBuf) {
    let full_model = Model::parse(&extra_probes(full_text, extra)).unwrap();
    let full_solution = cufem::analysis::run(&full_model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    assert!(full_solution.failure.is_none());
    let quarter_model = Model::parse(&extra_probes(quarter_text, extra)).unwrap();
    assert_eq!(quarter_model.symmetry.copies(), 4);
    // the cut body's tolerances and bounds are the whole one's: its size is the body written
    for (a, b) in full_model.mesh.bodies.iter().zip(&quarter_model.mesh.bodies) {
        assert_eq!(a.size(), b.size(), "{full}: body {}", a.name);
    }
    let quarter_solution =
        cufem::analysis::run(&quarter_model, &Default::default(), &mut cufem::analysis::Silent).unwrap();
    let (fv, qv) = (full_solution.fields(&full_model), quarter_solution.fields(&quarter_model));

    // scales from the full model's line along the top
    let line = cufem::post::sample_line(&fv, &full_model.lines[0]);
    let samples: Vec<Sample> = line.iter().filter_map(|s| s.sample).collect();
    let scale = [
        samples.iter().flat_map(|s| s.u.map(f64::abs)).fold(0.0, f64::max),
        samples.iter().map(|s| s.von_mises).fold(0.0, f64::max),
        samples.iter().flat_map(|s| s.strain.map(f64::abs)).fold(0.0, f64::max),
        samples.iter().map(|s| s.peeq).fold(0.0, f64::max),
    ];
    let mut worst: f64 = 0.0;
    for (p, q) in full_model.probes.iter().zip(&quarter_model.probes) {
        let d = difference(&fv.sample_probe(p).unwrap(), &qv.sample_probe(q).unwrap(), scale);
        assert!(d < 1e-6, "{full}: probe {} differs by {d:e}", p.name);
        worst = worst.max(d);
    }
    // the line runs over both halves of the bar, on the plane x = c
    let quarter_line = cufem::post::sample_line(&qv, &quarter_model.lines[0]);
    for (a, b) in line.iter().zip(&quarter_line) {
        let d = difference(&a.sample.unwrap(), &b.sample.unwrap(), scale);
        assert!(d < 1e-6, "{full}: line at s = {} differs by {d:e}", a.s);
        worst = worst.max(d);
    }

    // the twin through the CLI: its summary's full-structure forces
    let (out, summary) = common::run_text("symmetry", quarter, &extra_probes(quarter_text, extra));
    // the probes' displacement history (analysis::recorder's probe_displacements, its
    // own path to the mirror image): the last row is the full model's u
    let history = common::csv_columns(&out.join("history_probes.csv"));
    for p in &full_model.probes {
        let u = fv.sample_probe(p).unwrap().u;
        for (k, c) in ["u_x", "u_y", "u_z"].iter().enumerate() {
            let ours = *history[&format!("{}.{c}", p.name)].last().unwrap();
            assert!((ours - u[k]).abs() < 1e-6 * scale[0], "{full}: {} {c} {ours:e} against {:e}", p.name, u[k]);
        }
    }
    let mut force_worst: f64 = 0.0;
    for c in summary["contact"].as_array().unwrap() {
        let name = c["name"].as_str().unwrap();
        let full_force = full_solution.contacts.iter().find(|f| f.name == name).unwrap().force;
        let peak = full_force.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for k in 0..3 {
            let ours = c["full_structure_force"][k].as_f64().unwrap();
            force_worst = force_worst.max((ours - full_force[k]).abs() / peak);
            // and the summary's force is the quarter's own
            let own = c["force"][k].as_f64().unwrap();
            let quarter = quarter_solution.contacts.iter().find(|f| f.name == name).unwrap().force[k];
            assert!((own - quarter).abs() <= 1e-12 * peak);
        }
    }
    // every indenter's history carries the full structure's force too: its
    // last row is the full model's force, and f_* the quarter's own
    for ind in &quarter_model.indenters {
        let history = common::csv_columns(&out.join(format!("history_{}.csv", ind.name)));
        let full_force = full_solution.contacts.iter().find(|f| f.name == ind.name).unwrap().force;
        let own = quarter_solution.contacts.iter().find(|f| f.name == ind.name).unwrap().force;
        let peak = full_force.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (k, c) in ["x", "y", "z"].iter().enumerate() {
            let (full_col, own_col) =
                (history[&format!("full_f_{c}")].last().unwrap(), history[&format!("f_{c}")].last().unwrap());
            assert!(
                (full_col - full_force[k]).abs() < 1e-6 * peak,
                "{}: full_f_{c} {full_col:e} against {:e}",
                ind.name,
                full_force[k]
            );
            assert!((own_col - own[k]).abs() <= 1e-12 * peak, "{}: f_{c} {own_col:e} against {:e}", ind.name, own[k]);
        }
    }
    // a plane's own reaction has no full-structure force
    let plane = std::fs::read_to_string(out.join("history_symmetry_x.csv")).unwrap();
    assert!(!plane.lines().next().unwrap().contains("full_"), "{}", plane.lines().next().unwrap());
    // the loading roller touches both planes: its full force is 4× the quarter's
    let load = quarter_solution.contacts.iter().find(|c| c.name == "load").unwrap().force[2];
    let full_load = full_solution.contacts.iter().find(|c| c.name == "load").unwrap().force[2];
    assert!((4.0 * load - full_load).abs() < 1e-6 * full_load.abs(), "{load} × 4 against {full_load}");
    assert!(force_worst < 1e-6, "{full}: full-structure force differs by {force_worst:e}");
    eprintln!("{quarter}: fields within {worst:.1e}, forces within {force_worst:.1e} of the full model");
    (full_solution, out)
}

#[test]
fn compact_bar_quarter_equals_the_full_model() {
    // the quarter written on its kept side only (its mirror images are the rest) has the whole bar's size
    let quarter = example("bending_compact_16L9_quarter");
    let kept = quarter
        .replace("x = { from = 0.0, to = 0.01, elements = 4 }", "x = { from = 0.005, to = 0.01, elements = 2 }")
        .replace("from = 0.0, to = 0.25, elements = 10 }", "from = 0.0, to = 0.125, elements = 5 }");
    let (a, b) = (Model::parse(&quarter).unwrap(), Model::parse(&kept).unwrap());
    assert_eq!(a.mesh.n_nodes(), b.mesh.n_nodes());
    assert!((a.mesh.bodies[0].size() / b.mesh.bodies[0].size() - 1.0).abs() < 1e-12);
    // bar x, z ∈ [0, 0.01], y ∈ [0, 0.25]; planes x = 0.005, y = 0.125
    twin(
        "bending_compact_16L9",
        "bending_compact_16L9_quarter",
        &[[0.0075, 0.06, 0.004], [0.0025, 0.06, 0.004], [0.0075, 0.19, 0.0], [0.001, 0.2, 0.009]],
    );
}

#[test]
fn tube_quarter_equals_the_full_model() {
    // tube x, z ∈ [0, 0.03], wall 1.5 mm; planes x = 0.015, y = 0.125
    twin(
        "bending_tube_28L9",
        "bending_tube_28L9_quarter",
        &[[0.0293, 0.06, 0.015], [0.0007, 0.06, 0.015], [0.022, 0.19, 0.0295], [0.005, 0.2, 0.0005]],
    );
}

/// A CSV file's columns by name (`common::csv_columns`).
type Columns = std::collections::HashMap<String, Vec<f64>>;

/// The tool `load`'s (u_z, f_z) in the full model after every increment,
/// and the twin's history_load.csv in `out`.
fn load_histories(full_solution: &cufem::analysis::Solution, out: &Path) -> (Vec<(f64, f64)>, Columns) {
    let a = full_solution
        .history
        .iter()
        .map(|r| r.contact("load").map(|c| (c.displacement[2], c.force[2])).unwrap())
        .collect();
    (a, common::csv_columns(&out.join("history_load.csv")))
}

/// A force-controlled roller across both planes: the springback tube
/// (`bending_tube_springback.toml`, the roller pushed with 1.6 kN, then
/// unloaded to 2 % of it) and its quarter (`common::springback_quarter`),
/// whose roller carries a quarter of the force. Every field of the unloaded
/// state as [`twin`] holds it, and the roller's displacement after every
/// increment of both steps (history_load.csv, the springback is the
/// difference of the two step ends) within `1e-9` of its largest; the
/// quarter's own roller force a quarter of the file's. Mutation: the force
/// not shared (the quarter pushed with the whole 1.6 kN) moves the roller
/// to about four times the displacement and fails.
#[test]
fn a_force_controlled_roller_across_both_planes_carries_the_full_force() {
    let full = example("bending_tube_springback");
    let quarter = common::springback_quarter(&full);
    let (full_solution, out) = twin_of(
        ("bending_tube_springback", &full),
        ("bending_tube_springback_quarter", &quarter),
        &[[0.0293, 0.06, 0.015]],
    );
    let (a, b) = load_histories(&full_solution, &out);
    let peak = a.iter().fold(0.0f64, |m, v| m.max(v.0.abs()));
    assert!(peak > 1e-4, "the roller moves: {peak:e} m");
    assert_eq!(a.len(), b["d_z"].len(), "the same increments");
    for (k, &(x, f)) in a.iter().enumerate() {
        let y = b["d_z"][k];
        assert!((x - y).abs() < 1e-9 * peak, "increment {k}: d_z {y:e} against the full model's {x:e}");
        // converged to the prescribed force: the quarter's is a quarter of it
        let own = b["f_z"][k];
        assert!((4.0 * own - f).abs() < 1e-6 * f.abs(), "increment {k}: f_z {own} × 4 against {f}");
    }
    // `cufem check` says which force the quarter's roller carries
    let text = common::check_output("symmetry", "springback_check", &quarter);
    let share = "force [0.0, 0.0, -400.0] N (its share of the full structure's [0.0, 0.0, -1600.0] N)";
    assert!(text.contains(share), "{text}");
}

/// A drop weight across both planes: the smaller twin of
/// `examples/tube_drop_weight.toml` (`common::coarse_drop_weight` with 12
/// L9 around, 2 kg at 1 m/s on a roller across the tube, the alloy elastic)
/// over its first 1.2 ms (60 steps of 20 µs: the weight pressing the top
/// wall, the supports and the weight in contact) and its quarter
/// (`common::tube_quarter`), whose weight has a quarter of the mass. Every
/// field at the last step as [`twin`] holds it; the weight's displacement
/// after every step within `1e-7` of its largest (the two converge to
/// Newton's tolerance, tightened to `1e-9`, in different numbers of
/// corrections), its force on
/// the quarter a quarter of the whole's; every column of the quarter's
/// energy.csv (kinetic, internal, contact work, the weight's own kinetic
/// energy) a quarter of the whole's. Mutation: the mass not shared (the
/// quarter's weight of 2 kg) drives it four times as hard and fails.
#[test]
fn a_drop_weight_across_both_planes_carries_a_quarter_of_its_mass() {
    let steps = "duration = 6e-3\nincrements = 300";
    let full = common::coarse_drop_weight(&example("tube_drop_weight"));
    assert!(full.contains(steps));
    // two elements along each wall (8 around put one across each): the plane x = 15 mm between them
    let full = full.replace(steps, "duration = 1.2e-3\nincrements = 60").replace("around = 8", "around = 12");
    // elastic: with the alloy's hardening both converge to Newton's tolerance in different numbers of
    // corrections, and at the 23rd step one cuts back where the other does not (their time steps part)
    let (from, to) = (full.find("[materials.plasticity]").unwrap(), full.find("[[bodies]]").unwrap());
    let full = format!("{}{}", &full[..from], &full[to..]);
    // converged far below the comparison's 1e-6 (the default 1e-6 of the residual leaves 4e-6 in the fields)
    let full = full.replace("[solver]\n", "[solver]\nresidual_tolerance = 1e-9\ndisplacement_tolerance = 1e-9\n");
    let quarter = common::tube_quarter(&full);
    let (full_solution, out) =
        twin_of(("tube_drop_weight", &full), ("tube_drop_weight_quarter", &quarter), &[[0.0293, 0.06, 0.015]]);
    let (a, b) = load_histories(&full_solution, &out);
    let (peak, force) = a.iter().fold((0.0f64, 0.0f64), |m, v| (m.0.max(v.0.abs()), m.1.max(v.1.abs())));
    assert!(peak > 1e-4 && force > 100.0, "the weight dents the tube: {peak:e} m, {force} N");
    assert_eq!(a.len(), b["d_z"].len(), "the same steps");
    for (k, &(x, f)) in a.iter().enumerate() {
        let y = b["d_z"][k];
        assert!((x - y).abs() < 1e-7 * peak, "step {k}: d_z {y:e} against the full model's {x:e}");
        assert!((4.0 * b["f_z"][k] - f).abs() < 1e-6 * force, "step {k}: f_z {} × 4 against {f}", b["f_z"][k]);
    }
    // the energies: the quarter's are a quarter of the whole's
    let (whole, _) = common::run_text("symmetry", "tube_drop_weight", &full);
    let scale = common::csv_columns(&whole.join("energy.csv")).values().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.1, "about 0.8 J change hands: {scale} J");
    common::assert_energies_scaled(&whole, &out, 4.0, 1e-7 * scale, true);
    // `cufem check` says which mass the quarter's weight has
    let text = common::check_output("symmetry", "drop_weight_check", &quarter);
    let share = "impactor of 0.5 kg (its share of the full structure's 2 kg) at [0.0, 0.0, -1.0] m/s";
    assert!(text.contains(share), "{text}");
    // a weight pushed by a force too (its weight, say): both are shared
    let pushed =
        quarter.replace("velocity = [0.0, 0.0, -1.0]", "velocity = [0.0, 0.0, -1.0]\nforce = [0.0, 0.0, -20.0]");
    let text = common::check_output("symmetry", "drop_weight_pushed_check", &pushed);
    let share = "at [0.0, 0.0, -1.0] m/s, pushed by force [0.0, 0.0, -5.0] N (its share of the full structure's [0.0, 0.0, -20.0] N)";
    assert!(text.contains(share), "{text}");
}

/// A drop weight across a plane on a laminate that delaminates: the first
/// millisecond of `examples/laminate_drop_weight.toml` (400 steps of
/// 2.5 µs: the striker's 0.8 J, the mid-plane's cohesive interface failing
/// in shear, the load drop) and its half across the mid-span plane (the
/// right support left out, the striker carrying half its 0.1 kg). The
/// softening interface makes the two converge in different numbers of
/// corrections (1,267 and 1,249), so they agree to Newton's tolerance, not
/// to round-off: the striker's motion at every step within `1e-4` of its
/// largest (measured `6e-6`); every energy.csv column at the end twice the
/// half's within `1e-3` of the impact energy (measured `1e-4`: the
/// delamination's `0.46073` J against `2 × 0.23040`), the delaminated
/// area twice the half's within a tenth of a percent. The raw contact
/// force is not compared: under the rigid striker it rings and is not a
/// converged quantity (its twice differs by up to 9 % of its peak after
/// the drop; docs/composites.md). Mutation: the half's striker with the
/// whole mass fails.
#[test]
fn a_drop_weight_across_a_plane_delaminates_the_half_as_the_whole() {
    let steps = "duration = 0.006\nincrements = 2400";
    let whole = example("laminate_drop_weight");
    assert!(whole.contains(steps) && whole.contains("mass = 0.1\nvelocity = [0.0, 0.0, -4]"));
    let whole = whole.replace(steps, "duration = 0.001\nincrements = 400");
    let support =
        "[[constraints]]\nname = \"support_right\"\nbody = \"beam\"\nwhere = { y = 0.05, z = 0.0 }\nfix = [\"z\"]\n";
    assert_eq!(whole.matches(support).count(), 1);
    let half = whole.replace(support, "[[symmetry]]\nname = \"mid_span\"\nplane = { y = 0.025 }\nkeep = \"below\"\n");
    let (w, sw) = common::run_text("symmetry", "laminate_drop_weight_whole", &whole);
    let (h, sh) = common::run_text("symmetry", "laminate_drop_weight_half", &half);
    let (hw, hh) =
        (common::csv_columns(&w.join("history_striker.csv")), common::csv_columns(&h.join("history_striker.csv")));
    assert_eq!(hw["d_z"].len(), hh["d_z"].len(), "the same steps");
    let peak = hw["d_z"].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = hw["d_z"].iter().zip(&hh["d_z"]).map(|(a, b)| (a - b).abs() / peak).fold(0.0, f64::max);
    assert!(worst < 1e-4, "the striker's motion differs by {worst:e} of its largest");
    let impact = 0.5 * 0.1 * 4.0 * 4.0;
    common::assert_energies_scaled(&w, &h, 2.0, 1e-3 * impact, false);
    let area = |s: &serde_json::Value| s["delamination"]["area_m2"].as_f64().unwrap();
    assert!(area(&sw) > 1e-4, "the mid-plane delaminates: {} m²", area(&sw));
    assert!((area(&sw) / (2.0 * area(&sh)) - 1.0).abs() < 1e-3, "{} against 2 × {}", area(&sw), area(&sh));
    eprintln!(
        "the striker's motion within {worst:.1e}; delaminated {:.4e} against 2 × {:.4e} m²",
        area(&sw),
        area(&sh)
    );
}

/// The error of a quarter model with `from` replaced by `to`.
fn error_of(from: &str, to: &str) -> String {
    let text = example("bending_compact_16L9_quarter");
    assert!(text.contains(from), "{from}");
    Model::parse(&text.replacen(from, to, 1)).unwrap_err().to_string()
}

#[test]
fn bad_symmetry_planes_are_refused_by_key() {
    // through an element (section elements are 2.5 mm wide)
    let e = error_of("plane = { x = 0.005 }", "plane = { x = 0.006 }");
    assert!(e.contains("symmetry[1].plane") && e.contains("element boundaries"), "{e}");
    // beyond the body: it touches no node
    let e = error_of("plane = { y = 0.125 }", "plane = { y = 0.3 }");
    assert!(e.contains("symmetry[0].plane") && e.contains("through nodes"), "{e}");
    // the whole body on the side left out
    let e = error_of("plane = { y = 0.125 }\nkeep = \"below\"", "plane = { y = 0.0 }\nkeep = \"below\"");
    assert!(e.contains("symmetry[0].plane") && e.contains("side left out"), "{e}");
    let e = error_of("keep = \"below\"\n", "");
    assert!(e.contains("symmetry[0].keep"), "{e}");
    let e = error_of("plane = { y = 0.125 }", "plane = { y = 0.125, x = 0.005 }");
    assert!(e.contains("symmetry[0].plane") && e.contains("exactly one coordinate"), "{e}");
    let e = error_of("plane = { y = 0.125 }", "plane = { x = 0.0 }");
    assert!(e.contains("symmetry[1].plane") && e.contains("another axis"), "{e}");
    // a plane's name is its reaction's: unique among constraints, indenters, contacts
    let e = error_of("name = \"symmetry_x\"", "name = \"load\"");
    assert!(e.contains("load"), "{e}");
}

#[test]
fn forces_that_a_plane_would_split_are_refused() {
    // a total force on faces across the plane x = 0.005: the kept share is not said
    let load = "\n[[loads]]\nname = \"push\"\nbody = \"bar\"\nwhere = { z = 0.01, y = [0.0, 0.025] }\ntotal_force = [0.0, 0.0, -10.0]\n";
    let text = example("bending_compact_16L9_quarter") + load;
    let e = Model::parse(&text).unwrap_err().to_string();
    assert!(e.contains("loads[0].total_force") && e.contains("symmetry_x"), "{e}");
    // the same as a traction is the kept part's share: accepted
    let text = text.replace("total_force = [0.0, 0.0, -10.0]", "traction = [0.0, 0.0, -1.0e5]");
    let model = Model::parse(&text).unwrap();
    // 5 mm × 25 mm kept of the 10 mm × 25 mm face: 12.5 N of the full 25 N
    let r = model.loads[0].resultant();
    assert!((r[2] + 12.5).abs() < 1e-9, "{r:?}");
}

/// What a plane cannot share: a force-controlled indenter's force or an
/// impactor's velocity along a plane's normal (the tool and its mirror
/// image are one and cannot move both ways), a tool touching a plane it
/// does not cross, one crossing a plane its surface does not reach.
#[test]
fn impactors_and_forces_across_a_plane_are_refused_by_key() {
    let quarter = common::springback_quarter(&example("bending_tube_springback"));
    let pushed = "force = [0.0, 0.0, -1600.0]";
    assert!(quarter.contains(pushed));
    let e = Model::parse(&quarter.replace(pushed, "force = [0.0, 1.0, -1600.0]")).unwrap_err().to_string();
    assert!(e.contains("indenters[2].force") && e.contains("force[1] = 0") && e.contains("symmetry_y"), "{e}");
    // a roller crossing y = 0.125 whose surface stops short of it: no node shares its force
    let short =
        quarter.replace("surface = { z = 0.03, y = [0.075, 0.175] }", "surface = { z = 0.03, y = [0.075, 0.12] }");
    let e = Model::parse(&short).unwrap_err().to_string();
    assert!(e.contains("indenters[2].surface") && e.contains("reaches the plane"), "{e}");
    // a flat punch that ends on the plane x = 0.015 touches it without crossing it
    let cylinder = "shape = \"cylinder\"\nsurface = { z = 0.03, y = [0.075, 0.175] }\naxis = \"x\"\ncenter = [0.015, 0.125, 0.04]\nradius = 0.01\n";
    let punch = "shape = \"flat\"\nsurface = { z = 0.03 }\nnormal = \"-z\"\nposition = 0.03\nx = [0.015, 0.03]\ny = [0.1, 0.15]\n";
    assert!(quarter.contains(cylinder));
    let e = Model::parse(&quarter.replace(cylinder, punch)).unwrap_err().to_string();
    assert!(e.contains("indenters[2].force") && e.contains("touching symmetry plane \"symmetry_x\""), "{e}");
    let thrown = quarter
        .replace("[solver]", "[analysis]\ntype = \"transient\"\nduration = 1e-4\n\n[solver]")
        .replace(pushed, "mass = 1.0\nvelocity = [0.0, 0.0, -1.0]")
        .replace("\n[materials.plasticity]", "\ndensity = 2700.0\n[materials.plasticity]");
    // a weight across both planes carries a quarter of its mass (the drop weight's twin above), but
    // it cannot move along a plane's normal, nor touch a plane it does not cross
    assert!(Model::parse(&thrown).is_ok());
    let e = Model::parse(&thrown.replace("velocity = [0.0, 0.0, -1.0]", "velocity = [0.0, 0.5, -1.0]"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("indenters[2].velocity") && e.contains("velocity[1] = 0") && e.contains("symmetry_y"), "{e}");
    // the quarter's share of a 4e-11 kg weight against the quarter tube's 2.9e-2 kg: below a billionth
    // (the whole weight against the whole tube's 0.115 kg is too); 2e-10 kg is above it either way
    let e = Model::parse(&thrown.replace("mass = 1.0", "mass = 4e-11")).unwrap_err().to_string();
    assert!(e.contains("indenters[2].mass") && e.contains("the part kept carries 1.00e-11 kg"), "{e}");
    assert!(Model::parse(&thrown.replace("mass = 1.0", "mass = 2e-10")).is_ok());
    let e = Model::parse(&thrown.replace(cylinder, punch)).unwrap_err().to_string();
    assert!(e.contains("indenters[2].mass") && e.contains("an impactor touching symmetry plane \"symmetry_x\""), "{e}");
}

#[test]
fn coarse_twins_equal_their_full_models() {
    twin(
        "bending_compact_4L9",
        "bending_compact_4L9_quarter",
        &[[0.0075, 0.06, 0.004], [0.0025, 0.06, 0.004], [0.001, 0.2, 0.009]],
    );
    twin("bending_tube_20L9", "bending_tube_20L9_quarter", &[[0.0293, 0.06, 0.015], [0.005, 0.2, 0.0005]]);
}

#[test]
fn graded_tube_quarter_equals_the_full_model() {
    // the axis graded towards the roller: the plane y = 0.125 between 2 mm elements
    twin(
        "bending_tube_graded",
        "bending_tube_graded_quarter",
        &[[0.0007, 0.124, 0.015], [0.022, 0.126, 0.0295], [0.005, 0.2, 0.0005]],
    );
}
